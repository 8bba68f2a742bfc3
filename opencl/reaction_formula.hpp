#pragma once
// A reaction formula of the reaction-diffusion contract (common/reaction_diffusion/reaction_diffusion_system.hpp: the
// muparser syntax the reference evaluates) rewritten as an OpenCL C float expression, so the device
// evaluates the user's kinetics inline in the step kernel, compiled, with no interpreter on the
// device. The host parses the formula once (recursive descent here is fine: it never runs in a
// kernel) and prints it back fully parenthesised, so the OpenCL compiler cannot read it with other
// precedences than the parser did.
//
// Grammar (muparser's, as the contract lists it), loosest binding first:
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?            right-associative: a^b^c = a^(b^c); -a^2 = -(a^2)
//   primary := number | name | name '(' sum (',' sum)* ')' | '(' sum ')'
// Functions: exp, log and ln (natural), sqrt, abs, sin, cos, tanh (one argument), min, max (two).
// `^` with an integer literal exponent becomes a product of the base with itself (magnitude <= 8;
// 1 / product for a negative one; 1 for 0): PoCL runs pown as an out-of-line call that stops its
// vectoriser, and a product is defined for a negative base as muparser's std::pow is. Magnitudes
// 9 .. 64 become pown; any other exponent becomes pow.
#include <map>
#include <string>

namespace physarum::opencl {

// `formula` with every name replaced by its entry in `names` (a kernel variable, a coefficient read
// or a literal; each is parenthesised in the output) and numbers written as float literals.
// `where` names the formula in messages (e.g. "reaction of morphogen 'u'"). Throws InputError
// saying what is wrong and at which character position (1-based) of the formula: an unknown name or
// function, a wrong argument count, a character that is not part of the syntax, an unbalanced
// parenthesis, a missing operand, or an empty formula.
std::string translate_reaction_formula(const std::string& formula, const std::map<std::string, std::string>& names,
                                       const std::string& where);

// A double as an OpenCL C float literal that rounds to the same float ("0.04f", "1e-05f", "2.0f").
std::string float_literal(double value);

}  // namespace physarum::opencl
