// The reaction formulas of the reaction-diffusion contract translated to OpenCL C
// (opencl/reaction_formula.hpp). Two kinds of check: the translation's shape (products for small integer
// powers, the function names OpenCL C has, no '^' left) and errors that name what and where, on the
// host; and what the translated text COMPUTES, on the device: each formula is compiled into a
// one-line kernel and evaluated at random points against the formula written out in C++ by hand
// (Gray-Scott as Pearson 1993 writes it; Turk's model as Eq. 20 of paper 002; precedence cases whose
// values are known by arithmetic). float32 against double with O(1) inputs: 1e-5 relative.
#include "common/base/errors.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/runtime/device_buffer.hpp"
#include "opencl/runtime/kernel_arguments.hpp"
#include "opencl/runtime/program_cache.hpp"
#include "opencl/reaction_formula.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

namespace physarum::opencl {
namespace {

const std::map<std::string, std::string> kGrayScottNames = {{"u", "U"}, {"v", "V"}, {"F", "0.04f"}, {"k", "K"}};

TEST(ReactionFormula, GrayScottTranslatesToProductsAndNoCaret) {
  const std::string ru = translate_reaction_formula("-u*v^2 + F*(1-u)", kGrayScottNames, "u");
  EXPECT_NE(ru.find("((V) * (V))"), std::string::npos) << ru;
  EXPECT_NE(ru.find("(0.04f)"), std::string::npos) << ru;
  EXPECT_EQ(ru.find('^'), std::string::npos) << ru;
  const std::string rv = translate_reaction_formula("u*v^2 - (F+k)*v", kGrayScottNames, "v");
  EXPECT_NE(rv.find("((V) * (V))"), std::string::npos) << rv;
  EXPECT_NE(rv.find("(K)"), std::string::npos) << rv;
}

TEST(ReactionFormula, FunctionsAndPowersMapToOpenCLC) {
  const std::map<std::string, std::string> names = {{"a", "A"}, {"b", "B"}};
  EXPECT_NE(translate_reaction_formula("ln(a)", names, "f").find("log((A))"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("log(a)", names, "f").find("log((A))"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("abs(a)", names, "f").find("fabs((A))"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("min(a, b)", names, "f").find("fmin((A), (B))"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("max(a,b)", names, "f").find("fmax((A), (B))"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("a^-3", names, "f").find("(1.0f / ((A) * (A) * (A)))"), std::string::npos);
  EXPECT_EQ(translate_reaction_formula("a^0", names, "f"), "1.0f");
  EXPECT_NE(translate_reaction_formula("a^12", names, "f").find("pown((A), 12)"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("a^1.5", names, "f").find("pow((A), 1.5f)"), std::string::npos);
  EXPECT_NE(translate_reaction_formula("a^b", names, "f").find("pow((A), (B))"), std::string::npos);
}

TEST(ReactionFormula, FloatLiteralsParseAsFloatsAndRoundTrip) {
  EXPECT_EQ(float_literal(2.0), "2.0f");
  EXPECT_EQ(float_literal(0.04), "0.04f");
  EXPECT_EQ(float_literal(1e-5), "1e-05f");
  const double awkward = 0.1234567891234;
  EXPECT_EQ(std::strtof(float_literal(awkward).c_str(), nullptr), static_cast<float>(awkward));
}

// The message of the InputError `formula` throws ("" when it does not throw).
std::string error_of(const std::string& formula) {
  try {
    translate_reaction_formula(formula, kGrayScottNames, "the reaction of morphogen 'u'");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReactionFormula, ErrorsSayWhatAndWhere) {
  const auto expect = [](const std::string& formula, const std::string& what, int position) {
    const std::string message = error_of(formula);
    EXPECT_NE(message.find(what), std::string::npos) << formula << " -> " << message;
    EXPECT_NE(message.find("position " + std::to_string(position) + ")"), std::string::npos)
        << formula << " -> " << message;
    EXPECT_NE(message.find("morphogen 'u'"), std::string::npos) << message;
  };
  expect("u*v^2 + q", "unknown name 'q'", 9);
  expect("u * foo(v)", "unknown function 'foo'", 5);
  expect("u $ v", "'$'", 3);
  expect("(u + v", "never closed", 1);
  expect("u + v)", "')' with no matching '('", 6);
  expect("u +", "operand", 4);
  expect("min(u)", "with 1 argument(s); it takes 2", 1);
  expect("   ", "is empty", 1);
  expect("u v", "where an operator", 3);
  EXPECT_EQ(error_of("-u*v^2 + F*(1-u)"), "");
}

// ---- what the translated text computes, on the device ----

const ComputeContext& compute() {
  static const ComputeContext c = make_compute_context("");
  return c;
}

// Evaluates the formula over the names u, v, F, k at `points` random points on the device and
// returns the largest relative difference from `expected` (double).
double largest_error(const std::string& formula, const std::function<double(double, double, double, double)>& expected,
                     double lo = 0.1, double hi = 1.9) {
  const std::map<std::string, std::string> names = {{"u", "x[4*i]"}, {"v", "x[4*i+1]"}, {"F", "x[4*i+2]"}, {"k", "x[4*i+3]"}};
  const std::string expression = translate_reaction_formula(formula, names, "test formula");
  const std::string source = "__kernel void evaluate(__global const float* x, __global float* y) {\n"
                             "  const int i = get_global_id(0);\n  y[i] = " + expression + ";\n}\n";
  const cl::Program program = build_program(compute().context, compute().device, "formula test", source);
  cl::Kernel kernel(program, "evaluate");
  constexpr int points = 256;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(static_cast<float>(lo), static_cast<float>(hi));
  std::vector<float> x(4 * points), y(points);
  for (float& value : x) value = uniform(rng);
  const DeviceBuffer xs = upload_buffer(compute(), "x", x, CL_MEM_READ_ONLY, false);
  const DeviceBuffer ys = allocate_buffer(compute(), "y", points * sizeof(float), CL_MEM_WRITE_ONLY, false);
  set_arguments(kernel, xs, ys);
  compute().queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(points));
  compute().queue.enqueueReadBuffer(ys.buffer, CL_TRUE, 0, points * sizeof(float), y.data());
  double worst = 0.0;
  for (int i = 0; i < points; ++i) {
    const double want = expected(x[4 * i], x[4 * i + 1], x[4 * i + 2], x[4 * i + 3]);
    worst = std::max(worst, std::abs(y[i] - want) / std::max(1.0, std::abs(want)));
  }
  return worst;
}

constexpr double kFloatTolerance = 1e-5;

TEST(ReactionFormulaOnDevice, GrayScottComputesPearsonsKinetics) {
  EXPECT_LT(largest_error("-u*v^2 + F*(1-u)", [](double u, double v, double F, double) { return -u * v * v + F * (1 - u); }),
            kFloatTolerance);
  EXPECT_LT(largest_error("u*v^2 - (F+k)*v", [](double u, double v, double F, double k) { return u * v * v - (F + k) * v; }),
            kFloatTolerance);
}

TEST(ReactionFormulaOnDevice, TurksTuringComputesEquation20) {
  // Eq. 20 of paper 002: R_u = rho (alpha - u v), R_v = rho (u v - v - beta); here rho = F,
  // alpha = 16 and beta = k.
  EXPECT_LT(largest_error("F*(16 - u*v)", [](double u, double v, double rho, double) { return rho * (16 - u * v); }),
            kFloatTolerance);
  EXPECT_LT(largest_error("F*(u*v - v - k)",
                          [](double u, double v, double rho, double beta) { return rho * (u * v - v - beta); }),
            kFloatTolerance);
}

TEST(ReactionFormulaOnDevice, PrecedenceAndAssociativityAreMuparsers) {
  // -u^2 = -(u^2); 2^3^2 = 2^9 = 512 (right-associative); left-associative - and /.
  EXPECT_LT(largest_error("-u^2", [](double u, double, double, double) { return -u * u; }), kFloatTolerance);
  EXPECT_LT(largest_error("2^3^2 + 0*u", [](double, double, double, double) { return 512.0; }), kFloatTolerance);
  EXPECT_LT(largest_error("u - v - F", [](double u, double v, double F, double) { return u - v - F; }), kFloatTolerance);
  EXPECT_LT(largest_error("u / v / F", [](double u, double v, double F, double) { return u / v / F; }), kFloatTolerance);
  EXPECT_LT(largest_error("u*-v^2", [](double u, double v, double, double) { return -u * v * v; }), kFloatTolerance);
  EXPECT_LT(largest_error("(u-v)^3 + u^-2 + v^10", [](double u, double v, double, double) {
              return std::pow(u - v, 3) + std::pow(u, -2) + std::pow(v, 10);
            }),
            kFloatTolerance);
  EXPECT_LT(largest_error("exp(-u)*sqrt(v) + tanh(F) - min(u, k) + max(v, k) + abs(u - v)^1.5 + ln(F)",
                          [](double u, double v, double F, double k) {
                            return std::exp(-u) * std::sqrt(v) + std::tanh(F) - std::min(u, k) + std::max(v, k) +
                                   std::pow(std::abs(u - v), 1.5) + std::log(F);
                          }),
            1e-4);
}

}  // namespace
}  // namespace physarum::opencl
