#include "common/reaction_diffusion/reaction_models.hpp"

namespace physarum {
namespace {
constexpr double kNone = -std::numeric_limits<double>::infinity();
}  // namespace

const std::vector<ReactionModel>& reaction_models() {
  // The defaults are the papers' own values, so a scene naming only the model reproduces a published
  // setting: Pearson's spot regime for Gray-Scott, and the figures of Ringham et al. (2021, `002_…`)
  // for the three flower models.
  static const std::vector<ReactionModel> models = {
      {"gray-scott",
       {"u", "v"},
       {"-u*v^2 + F*(1-u)", "u*v^2 - (F+k)*v"},
       {{"F", 0.04}, {"k", 0.06}},
       {2e-5, 1e-5},
       {1.0, 0.0},
       {kNone, kNone},
       "Pearson 1993 (Science 261), the spot regime F = 0.04, k = 0.06; (1, 0) is the trivial uniform state"},
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
       "Eq. 19 of `002_…` (activator-inhibitor with saturation kappa), Fig. 14's Digitalis parameters"},
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
       "Eq. 20 of `002_…` (Turing 1952 in Turk's form), Fig. 16's Kohleria parameters with alpha = 16"},
      {"activator-substrate",
       {"a", "s"},
       {"rho*s*a^2 + rho_a0 - mu_a*a", "-rho*s*a^2 + rho_s0 - mu_s*s"},
       {{"rho", 1.0}, {"rho_a0", 0.0}, {"mu_a", 0.145}, {"rho_s0", 0.082}, {"mu_s", 0.082}},
       {0.25, 0.5},
       {0.0, 1.0},
       {kNone, kNone},
       "Eq. 22 of `002_…` (Gierer-Meinhardt activator-substrate), Fig. 20's Phalaenopsis parameters"},
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
