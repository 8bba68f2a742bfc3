#include "common/reaction_diffusion/reaction_formula.hpp"

#include "common/base/errors.hpp"

#include <muParser.h>

#include <algorithm>
#include <cmath>

namespace physarum {
namespace {

double natural_log(double x) { return std::log(x); }
double exp_(double x) { return std::exp(x); }
double sqrt_(double x) { return std::sqrt(x); }
double abs_(double x) { return std::fabs(x); }
double sin_(double x) { return std::sin(x); }
double cos_(double x) { return std::cos(x); }
double tanh_(double x) { return std::tanh(x); }
double min_(double a, double b) { return std::min(a, b); }
double max_(double a, double b) { return std::max(a, b); }

// Only what both backends evaluate the same way: muparser's own defaults include functions
// (log2, rint, sum, avg, ...) and constants (_pi, _e) the OpenCL side does not translate.
void define_functions(mu::Parser& p) {
  p.ClearFun();
  p.ClearConst();
  p.DefineFun("exp", exp_);
  p.DefineFun("log", natural_log);
  p.DefineFun("sqrt", sqrt_);
  p.DefineFun("abs", abs_);
  p.DefineFun("min", min_);
  p.DefineFun("max", max_);
  p.DefineFun("sin", sin_);
  p.DefineFun("cos", cos_);
  p.DefineFun("tanh", tanh_);
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

}  // namespace

const std::vector<std::string>& reaction_formula_functions() {
  static const std::vector<std::string> names = {"exp", "log", "sqrt", "abs", "min", "max", "sin", "cos", "tanh"};
  return names;
}

struct ReactionFormula::State {
  mu::Parser parser;
  std::vector<double> scratch;  // the variables' storage for evaluate()
  std::vector<std::string> names;
  bool bound_to_scratch = true;
};

ReactionFormula::ReactionFormula(const std::string& formula, const std::vector<std::string>& names,
                                 const std::string& where)
    : state_(std::make_unique<State>()) {
  const std::string shown = quoted(formula);
  // muparser also knows comparisons, logic and the ternary operator; R_m is arithmetic only (the
  // contract's syntax), so they are refused before muparser sees them.
  const size_t bad = formula.find_first_of("<>=!&|?:");
  if (bad != std::string::npos)
    throw InputError(where + ": '" + std::string(1, formula[bad]) + "' at position " + std::to_string(bad + 1) +
                     " of " + shown + " is not allowed (use + - * / ^, parentheses and " +
                     "exp, log, sqrt, abs, min, max, sin, cos, tanh)");
  if (formula.find_first_not_of(" \t") == std::string::npos) throw InputError(where + ": the formula is empty");
  State& s = *state_;
  s.names = names;
  s.scratch.assign(names.size(), 0.0);
  try {
    define_functions(s.parser);
    for (size_t k = 0; k < names.size(); ++k) s.parser.DefineVar(names[k], &s.scratch[k]);
    s.parser.SetExpr(formula);
    s.parser.Eval();  // parses now, so errors surface here and not mid-run
  } catch (const mu::Parser::exception_type& e) {
    const std::string position = std::to_string(e.GetPos() + 1);
    const std::string token = e.GetToken();
    switch (e.GetCode()) {
      case mu::ecUNASSIGNABLE_TOKEN:
      case mu::ecUNEXPECTED_FUN:
        throw InputError(where + ": unknown name '" + token + "' at position " + position + " of " + shown +
                         " (known: the morphogens and coefficients, and exp, log, sqrt, abs, min, max, sin, cos, tanh)");
      default:
        throw InputError(where + ": syntax error at position " + position + " of " + shown + " (muparser: " +
                         e.GetMsg() + ")");
    }
  }
}

ReactionFormula::~ReactionFormula() = default;
ReactionFormula::ReactionFormula(ReactionFormula&&) noexcept = default;
ReactionFormula& ReactionFormula::operator=(ReactionFormula&&) noexcept = default;

double ReactionFormula::evaluate(const std::vector<double>& values) const {
  State& s = *state_;
  if (values.size() != s.names.size()) throw std::invalid_argument("ReactionFormula::evaluate: wrong value count");
  if (!s.bound_to_scratch) {
    for (size_t k = 0; k < s.names.size(); ++k) s.parser.DefineVar(s.names[k], &s.scratch[k]);
    s.bound_to_scratch = true;
  }
  std::copy(values.begin(), values.end(), s.scratch.begin());
  return s.parser.Eval();
}

void ReactionFormula::bind(const std::vector<double*>& addresses) {
  State& s = *state_;
  if (addresses.size() != s.names.size()) throw std::invalid_argument("ReactionFormula::bind: wrong address count");
  for (size_t k = 0; k < s.names.size(); ++k) s.parser.DefineVar(s.names[k], addresses[k]);
  s.bound_to_scratch = false;
}

double ReactionFormula::evaluate_bound() const { return state_->parser.Eval(); }

std::vector<std::string> ReactionFormula::used_names() const {
  std::vector<std::string> used;
  for (const auto& [name, address] : state_->parser.GetUsedVar()) used.push_back(name);
  return used;
}

}  // namespace physarum
