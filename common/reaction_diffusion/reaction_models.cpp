#include "common/reaction_diffusion/reaction_models.hpp"

namespace physarum {
namespace {
constexpr double kNone = -std::numeric_limits<double>::infinity();
}  // namespace

const std::vector<ReactionModel>& reaction_models() {
  // The defaults are the papers' own values, so a scene naming only the model reproduces a published
  // setting: Pearson's spot regime for Gray-Scott, and the figures of Ringham et al. (2021, `002_…`)
  // for the three flower models.
  // Turk's and Meinhardt's random factor: beta varies by +-0.1 from cell to cell.
  const std::vector<std::pair<std::string, double>> beta_noise = {{"beta", 0.1}};
  static const std::vector<ReactionModel> models = {
      {"gray-scott",
       {"u", "v"},
       {"-u*v^2 + F*(1-u)", "u*v^2 - (F+k)*v"},
       {{"F", 0.04}, {"k", 0.06}},
       {2e-5, 1e-5},
       {1.0, 0.0},
       {kNone, kNone},
       "Pearson 1993 (Science 261), the spot regime F = 0.04, k = 0.06; (1, 0) is the trivial uniform state",
       {}},
      {"gierer-meinhardt",
       {"a", "h"},
       {"rho_a*a^2/(h + kappa) + rho_a0 - mu_a*a", "rho_h*a^2 + rho_h0 - mu_h*h"},
       {{"rho_a", 0.05}, {"rho_a0", 0.0125}, {"kappa", 0.001}, {"mu_a", 0.05}, {"rho_h", 0.05}, {"rho_h0", 0.0},
        {"mu_h", 0.08}},
       {4.0e-5, 1.5e-3},
       // Near the uniform steady state of these defaults (kappa neglected: a = (rho_a mu_h / rho_h +
       // rho_a0) / mu_a = 1.85, h = rho_h a^2 / mu_h = 2.14).
       {1.85, 2.14},
       {kNone, kNone},
       "Eq. 19 of `002_…` (activator-inhibitor with saturation kappa), Fig. 14's Digitalis parameters",
       {}},
      {"turing",
       {"u", "v"},
       {"rho*(alpha - u*v)", "rho*(u*v - v - beta)"},
       {{"rho", 0.035}, {"alpha", 16.0}, {"beta", 12.0}},
       {0.18, 0.0375},
       // The uniform steady state: u v = alpha and v = alpha - beta.
       {4.0, 4.0},
       // v >= 0, as Turk clamps it (Turk 1991, "Generating textures on arbitrary surfaces using
       // reaction-diffusion"): Eq. 20 alone pulls v below zero where it is small (its rate at v = 0
       // is -rho*beta), and from there the pattern's troughs run away without bound.
       {kNone, 0.0},
       "Eq. 20 of `002_…` (Turing 1952 in Turk's form), Fig. 16's Kohleria parameters with alpha = 16",
       {}},
      {"activator-substrate",
       {"a", "s"},
       {"rho*s*a^2 + rho_a0 - mu_a*a", "-rho*s*a^2 + rho_s0 - mu_s*s"},
       {{"rho", 1.0}, {"rho_a0", 0.0}, {"mu_a", 0.145}, {"rho_s0", 0.082}, {"mu_s", 0.082}},
       {0.25, 0.5},
       {0.0, 1.0},
       {kNone, kNone},
       "Eq. 22 of `002_…` (Gierer-Meinhardt activator-substrate), Fig. 20's Phalaenopsis parameters",
       {}},
      // The three systems of the appendix of `004_…` (Phan & Grimm), in Turk's grid units taken as a
      // 1 cm cell and a 1 s time unit: a grid diffusion rate D is D x 1e-4 m^2/s here, so the patterns
      // have the sizes Turk's and Ready's grids give on a patch of 1 cm cells. The appendix's
      // "speed" multiplies the reaction and the diffusion alike: it is the time step.
      {"turing-spots",
       {"a", "b"},
       {"ka*(16 - a*b)", "ka*(a*b - b - beta)"},
       {{"ka", 0.0625}, {"beta", 12.0}},
       {0.5e-4, 0.125e-4},
       // The uniform steady state for beta = 12: a b = 16, b = a b - beta = 4.
       {4.0, 4.0},
       {kNone, 0.0},  // b >= 0, as Turk clamps it (see "turing")
       "appendix 8.1 of `004_…` (Turk 1991's Turing spots), s = 1/16, D_a = 1/2, D_b = 1/8 per cell, beta = 12 +- 0.1",
       beta_noise},
      {"meinhardt-spots",
       {"a", "b"},
       {"s*(0.01*a^2*beta/b - a*p1 + p3)", "s*(0.01*a^2*beta - b*p2 + p3)"},
       {{"s", 0.2}, {"p1", 0.03}, {"p2", 0.04}, {"p3", 0.0}, {"beta", 1.0}},
       {0.01e-4, 0.2e-4},
       // The uniform steady state for beta = 1, p3 = 0: b = 0.01 a^2 / p2 and then a = p2 / p1.
       {0.04 / 0.03, 0.01 * (0.04 / 0.03) * (0.04 / 0.03) / 0.04},
       {kNone, kNone},
       "appendix 8.2 of `004_…` (Meinhardt 1982's spots, Turk's values), s = 0.2, p1 = 0.03, p2 = 0.04, p3 = 0, "
       "D_a = 0.01, D_b = 0.2 per cell, beta = 1 +- 0.1",
       beta_noise},
      {"meinhardt-stripes",
       {"a", "b", "c", "d", "e"},
       // s multiplies every reaction term (1 in the appendix): the rate a sketch's stripe width sets,
       // as s does in meinhardt-spots. Last in the list, so the other coefficients keep their places.
       {"s*(0.01*a^2*e*beta/c - a*k_ab)", "s*(0.01*b^2*d/c - b*k_ab)", "s*(0.01*a^2*e*beta + 0.01*b^2*d - c*k_c)",
        "s*(a - d)*k_de", "s*(b - e)*k_de"},
       {{"k_ab", 0.04}, {"k_c", 0.06}, {"k_de", 0.04}, {"beta", 1.0}, {"s", 1.0}},
       // c does not diffuse (the appendix gives it no diffusion term).
       {0.005e-4, 0.005e-4, 0.0, 0.4e-4, 0.4e-4},
       // The symmetric uniform steady state for beta = 1: d = a, e = b, c = 0.01 a b / k_ab and
       // a + b = k_c / k_ab; a = b = k_c / (2 k_ab) = 0.75, c = 0.01 a^2 / k_ab = 0.140625.
       {0.75, 0.75, 0.140625, 0.75, 0.75},
       {kNone, kNone, kNone, kNone, kNone},
       "appendix 8.3 of `004_…` (Meinhardt 1982's five-morphogen stripes, Turk's values), k_ab = 0.04, "
       "k_c = 0.06, k_de = 0.04, D_a = D_b = 0.005, D_d = D_e = 0.4 per cell, beta = 1 +- 0.1, s = 1 (a rate on every term)",
       beta_noise},
  };
  return models;
}

const ReactionModel* find_reaction_model(std::string_view name) {
  for (const ReactionModel& m : reaction_models())
    if (m.name == name) return &m;
  return nullptr;
}

std::string reaction_model_names() {
  std::string names;
  for (const ReactionModel& m : reaction_models()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

}  // namespace physarum
