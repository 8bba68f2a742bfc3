#include "opencl/reaction_formula.hpp"

#include "common/base/errors.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace physarum::opencl {

std::string float_literal(double value) {
  // 9 significant digits round-trip every float; shorter when the value allows it.
  char text[64];
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (static_cast<float>(std::strtod(text, nullptr)) == static_cast<float>(value)) break;
  }
  std::string s = text;
  // "2" is an int in OpenCL C and "2f" does not parse: a float literal needs a '.' or an exponent.
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s + "f";
}

namespace {

// Integer powers up to this magnitude are written as products (see FormulaTranslator::power).
constexpr int kProductPowers = 8;

// The recursive-descent parser; each rule returns the translated text of what it read.
class FormulaTranslator {
 public:
  FormulaTranslator(const std::string& formula, const std::map<std::string, std::string>& names,
                    const std::string& where)
      : text_(formula), names_(names), where_(where) {}

  std::string translate() {
    skip_space();
    if (at_end()) fail(0, "is empty");
    std::string out = sum();
    skip_space();
    if (!at_end()) {
      if (text_[pos_] == ')') fail(pos_, "has a ')' with no matching '('");
      fail(pos_, "has '" + std::string(1, text_[pos_]) + "' where an operator (+ - * / ^) or the end was expected");
    }
    return out;
  }

 private:
  [[noreturn]] void fail(std::size_t position, const std::string& what) const {
    throw InputError(where_ + ": the formula \"" + text_ + "\" " + what + " (at position " +
                     std::to_string(position + 1) + ")");
  }
  bool at_end() const { return pos_ >= text_.size(); }
  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  // True (and consumed) when the next non-space character is c.
  bool accept(char c) {
    skip_space();
    if (!at_end() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }

  std::string sum() {
    std::string out = product();
    for (;;) {
      if (accept('+')) out = "(" + out + " + " + product() + ")";
      else if (accept('-')) out = "(" + out + " - " + product() + ")";
      else return out;
    }
  }

  std::string product() {
    std::string out = unary();
    for (;;) {
      if (accept('*')) out = "(" + out + " * " + unary() + ")";
      else if (accept('/')) out = "(" + out + " / " + unary() + ")";
      else return out;
    }
  }

  std::string unary() {
    if (accept('-')) return "(-" + unary() + ")";
    if (accept('+')) return unary();
    return power();
  }

  std::string power() {
    const std::string base = primary();
    if (!accept('^')) return base;
    skip_space();
    const std::size_t exponent_start = pos_;
    const std::string exponent = unary();
    // An integer literal exponent (optionally negative, as muparser reads "a^-2"): pown.
    const std::string written = trimmed(text_.substr(exponent_start, pos_ - exponent_start));
    int n = 0;
    const char* first = written.data();
    const char* last = first + written.size();
    const auto [end, error] = std::from_chars(first, last, n);
    if (error == std::errc() && end == last) {
      // Small powers as products: PoCL calls pown out of line, which stops its work-group
      // vectoriser; the Gray-Scott step ran 26x slower with pown(v, 2) than with v * v
      // (bench_reaction_diffusion, 10^5 vertices). The compiler evaluates the repeated base once.
      if (n == 0) return "1.0f";
      if (std::abs(n) <= kProductPowers) {
        std::string product = base;
        for (int k = 1; k < std::abs(n); ++k) product += " * " + base;
        return n > 0 ? "(" + product + ")" : "(1.0f / (" + product + "))";
      }
      if (std::abs(n) <= 64) return "pown(" + base + ", " + std::to_string(n) + ")";
    }
    return "pow(" + base + ", " + exponent + ")";
  }

  static std::string trimmed(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    const auto b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
  }

  std::string primary() {
    skip_space();
    if (at_end()) fail(pos_, "ends where an operand was expected");
    const char c = text_[pos_];
    if (c == '(') {
      const std::size_t open = pos_++;
      std::string inner = sum();
      if (!accept(')')) fail(open, "has a '(' that is never closed");
      return "(" + inner + ")";
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name_or_call();
    if (c == ')') fail(pos_, "has ')' where an operand was expected");
    fail(pos_, "has '" + std::string(1, c) + "', which is not part of the formula syntax");
  }

  std::string number() {
    const std::size_t start = pos_;
    char* end = nullptr;
    const double value = std::strtod(text_.c_str() + start, &end);
    const std::size_t length = static_cast<std::size_t>(end - (text_.c_str() + start));
    if (length == 0) fail(start, "has a malformed number");
    pos_ = start + length;
    // strtod also reads "inf", "nan" and hex floats; a formula's numbers are plain decimals.
    for (std::size_t i = start; i < pos_; ++i)
      if (!std::isdigit(static_cast<unsigned char>(text_[i])) && std::string(".eE+-").find(text_[i]) == std::string::npos)
        fail(start, "has a malformed number");
    if (!std::isfinite(value)) fail(start, "has a number out of range");
    return float_literal(value);
  }

  std::string name_or_call() {
    const std::size_t start = pos_;
    while (!at_end() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    const std::string name = text_.substr(start, pos_ - start);
    skip_space();
    if (!at_end() && text_[pos_] == '(') return call(name, start);
    const auto found = names_.find(name);
    if (found == names_.end()) {
      std::string known;
      for (const auto& [n, unused] : names_) known += (known.empty() ? "" : ", ") + n;
      fail(start, "uses the unknown name '" + name + "' (known: " + known + ")");
    }
    return "(" + found->second + ")";
  }

  std::string call(const std::string& name, std::size_t start) {
    static const std::map<std::string, std::pair<std::string, int>> functions = {
        {"exp", {"exp", 1}},   {"log", {"log", 1}},   {"ln", {"log", 1}},   {"sqrt", {"sqrt", 1}},
        {"abs", {"fabs", 1}},  {"sin", {"sin", 1}},   {"cos", {"cos", 1}},  {"tanh", {"tanh", 1}},
        {"min", {"fmin", 2}},  {"max", {"fmax", 2}},
    };
    const auto found = functions.find(name);
    if (found == functions.end())
      fail(start, "calls the unknown function '" + name +
                      "' (known: exp, log, ln, sqrt, abs, sin, cos, tanh, min, max)");
    accept('(');
    std::string out = found->second.first + "(";
    int arguments = 0;
    if (!accept(')')) {
      for (;;) {
        out += (arguments++ ? ", " : "") + sum();
        if (accept(')')) break;
        if (!accept(',')) fail(pos_, "has an argument list of '" + name + "' that is never closed");
      }
    }
    if (arguments != found->second.second)
      fail(start, "calls '" + name + "' with " + std::to_string(arguments) + " argument(s); it takes " +
                      std::to_string(found->second.second));
    return out + ")";
  }

  const std::string& text_;
  const std::map<std::string, std::string>& names_;
  const std::string& where_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string translate_reaction_formula(const std::string& formula, const std::map<std::string, std::string>& names,
                                       const std::string& where) {
  return FormulaTranslator(formula, names, where).translate();
}

}  // namespace physarum::opencl
