#pragma once
// One reaction term R_m of a reaction–diffusion system, a formula in the morphogen and coefficient
// names (common/reaction_diffusion/reaction_diffusion_system.hpp lists the syntax), parsed by muparser (Debian's
// libmuparser-dev). The functions are restricted to the contract's list (exp, log = natural log,
// sqrt, abs, min, max, sin, cos, tanh) and there are no built-in constants, so a formula that
// passes here means the same on the OpenCL backend, which compiles it into kernel source.
//
// Bad formulas are InputErrors naming the scene key and the position (counted in characters from 1):
//   "scene.json: key 'reaction.u': unknown name 'q' at position 7 of \"u*v - q\""
#include <memory>
#include <string>
#include <vector>

namespace physarum {

// The functions a formula may call.
const std::vector<std::string>& reaction_formula_functions();

class ReactionFormula {
 public:
  // Parses `formula` over `names` (the variables it may use). `where` starts messages (the scene
  // file and key: "scene.json: key 'reaction.u'"). InputError for an unknown name, a syntax error or
  // an operator outside + - * / ^ (comparisons, logic and ?: are refused).
  ReactionFormula(const std::string& formula, const std::vector<std::string>& names, const std::string& where);
  ~ReactionFormula();
  ReactionFormula(ReactionFormula&&) noexcept;
  ReactionFormula& operator=(ReactionFormula&&) noexcept;

  // The value with variable k = values[k] (values.size() == names.size()).
  double evaluate(const std::vector<double>& values) const;

  // Faster repeated use: binds variable k to *addresses[k] once (the addresses must stay valid),
  // then evaluate_bound() reads them.
  void bind(const std::vector<double*>& addresses);
  double evaluate_bound() const;

  // The names the formula actually uses.
  std::vector<std::string> used_names() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace physarum
