// From a reaction-diffusion scene to the system the backends advance
// (common/setup/reaction_diffusion_build.hpp): the stiffness of each morphogen against the finite-element
// facts it must satisfy, the explicit stability limit against a dense eigen-solve, and the initial
// state and Dirichlet mask against the scene's regions.
#include "reaction_diffusion_scene.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>

namespace physarum {
namespace {

using nlohmann::json;
using testing::load_rd_system;
using testing::vertex_positions;

double quadratic_form(const CsrMatrix& k, const std::vector<double>& u) {
  std::vector<double> ku;
  k.multiply(u, ku);
  double sum = 0.0;
  for (size_t i = 0; i < u.size(); ++i) sum += u[i] * ku[i];
  return sum;
}

json turing_square(json v_entry) {
  return {{"mesh", "shape:square"},
          {"time_step", 0.01},
          {"model", "turing"},
          {"maps", {{"east", {{"direction", {1.0, 0.0, 0.0}}}}}},
          {"morphogens", {{"u", {{"diffusion", 0.18}}}, {"v", v_entry}}}};
}

TEST(ReactionDiffusionBuild, IsotropicStiffnessIsTheRateTimesTheCotanLaplacian) {
  const auto rd = load_rd_system({{"mesh", "shape:sphere"}, {"time_step", 1.0}, {"model", "gray-scott"}});
  const CsrMatrix& l = rd.surface.domain.laplacian;
  for (size_t m = 0; m < 2; ++m) {
    const double rate = m == 0 ? 2e-5 : 1e-5;
    const CsrMatrix& k = rd.system.stiffness[m];
    ASSERT_EQ(k.column, l.column);
    ASSERT_EQ(k.row_start, l.row_start);
    for (size_t e = 0; e < l.value.size(); ++e) ASSERT_NEAR(k.value[e], rate * l.value[e], 1e-12 * rate) << e;
  }
}

TEST(ReactionDiffusionBuild, AnisotropyWithRatioOneIsIsotropic) {
  const auto iso = load_rd_system(turing_square({{"diffusion", 0.0375}}));
  const auto aniso = load_rd_system(turing_square({{"diffusion", 0.0375}, {"anisotropy", {{"direction", "east"}, {"ratio", 1.0}}}}));
  const CsrMatrix& a = iso.system.stiffness[1];
  const CsrMatrix& b = aniso.system.stiffness[1];
  ASSERT_EQ(a.value.size(), b.value.size());
  for (size_t e = 0; e < a.value.size(); ++e) EXPECT_NEAR(a.value[e], b.value[e], 1e-12) << e;
}

TEST(ReactionDiffusionBuild, AnisotropicStiffnessDiffusesAlongAndAcrossAtTheirRates) {
  // On the flat unit square with D = a e_x e_x^T + b e_y e_y^T (a = 0.04 along east, b = ratio a):
  // a linear function has K u = 0 at every interior vertex (it is in the kernel of -div D grad for
  // a constant tensor), and its energy u^T K u = integral of grad u^T D grad u = a (u = x) or b (u = y)
  // over the area 1.
  const double a = 0.04, ratio = 0.25;
  const auto rd = load_rd_system(turing_square({{"diffusion", a}, {"anisotropy", {{"direction", "east"}, {"ratio", ratio}}}}));
  const CsrMatrix& k = rd.system.stiffness[1];
  const auto p = vertex_positions(rd.surface);
  std::vector<double> x, y, diagonal;
  for (const auto& q : p) x.push_back(q.x()), y.push_back(q.y()), diagonal.push_back(0.3 * q.x() - 0.7 * q.y());
  ASSERT_NEAR(rd.surface.domain.total_area, 1.0, 1e-12);
  EXPECT_NEAR(quadratic_form(k, x), a, 1e-12);
  EXPECT_NEAR(quadratic_form(k, y), ratio * a, 1e-12);
  std::vector<double> ku;
  k.multiply(diagonal, ku);
  int interior = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const bool on_boundary = std::min({p[i].x(), 1.0 - p[i].x(), p[i].y(), 1.0 - p[i].y()}) < 1e-9;
    if (on_boundary) continue;
    ++interior;
    EXPECT_NEAR(ku[i], 0.0, 1e-12) << "interior vertex " << i;
  }
  EXPECT_GT(interior, 500);
}

// A ratio map (a sketch's per-region squeeze): r = 0.1 + 0.3 t, t going 0 to 1 across the square
// along x. A face takes its corners' mean, which for a linear r is r at its centroid, so the energy
// of u = y is a times the integral of r over the unit square, 0.25 a exactly (the midpoint rule is
// exact for a linear r), while u = x (along the direction) keeps a.
TEST(ReactionDiffusionBuild, ARatioMapSqueezesEachFaceByItsCornersRatio) {
  const double a = 0.04;
  json scene = turing_square({{"diffusion", a}, {"anisotropy", {{"direction", "east"}, {"ratio", "squeeze"}}}});
  scene["maps"]["t"] = {{"axis", "x"}};
  scene["maps"]["squeeze"] = {{"map", "t"}, {"range", {0.1, 0.4}}};
  const auto rd = load_rd_system(scene);
  const CsrMatrix& k = rd.system.stiffness[1];
  std::vector<double> x, y;
  for (const auto& q : vertex_positions(rd.surface)) x.push_back(q.x()), y.push_back(q.y());
  EXPECT_NEAR(quadratic_form(k, x), a, 1e-12);
  EXPECT_NEAR(quadratic_form(k, y), 0.25 * a, 1e-12);

  // A ratio must be > 0 at every vertex: the map's 0 at the square's left edge is refused.
  scene["maps"]["squeeze"]["range"] = {0.0, 0.4};
  try {
    load_rd_system(scene);
    ADD_FAILURE() << "a ratio of 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("morphogens.v.anisotropy.ratio"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be > 0"), std::string::npos) << e.what();
  }
}

TEST(ReactionDiffusionBuild, ExplicitSubstepsFollowTheDenseStabilityLimit) {
  const auto rd = load_rd_system(turing_square({{"diffusion", 0.0375}}));
  // lambda_max of M^-1 K for the faster morphogen (u, D = 0.18), from a dense symmetric eigen-solve.
  const Eigen::MatrixXd k = Eigen::MatrixXd(rd.system.stiffness[0].to_eigen());
  Eigen::VectorXd s(k.rows());
  for (Eigen::Index i = 0; i < k.rows(); ++i) s[i] = 1.0 / std::sqrt(rd.system.mass[static_cast<size_t>(i)]);
  const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s.asDiagonal() * k * s.asDiagonal()).eigenvalues().maxCoeff();
  const double limit = 2.0 / lambda;
  EXPECT_NEAR(explicit_stability_limit(rd.system), limit, 1e-9 * limit);
  EXPECT_EQ(rd.system.substeps, static_cast<int>(std::ceil(0.01 / (kExplicitSafety * limit))));
  EXPECT_GT(rd.system.substeps, 1);
  EXPECT_EQ(explicit_substeps(0.5 * limit, limit), 1);
  EXPECT_EQ(explicit_substeps(1.01 * limit, limit), 2);
}

TEST(ReactionDiffusionBuild, InitialStateAndDirichletRegionFollowTheirMaps) {
  const json scene = {{"mesh", "shape:square"},
                      {"time_step", 1.0},
                      {"model", "gray-scott"},
                      {"maps",
                       {{"centre", {{"box", {{"min", {0.4, 0.4, -1.0}}, {"max", {0.6, 0.6, 1.0}}}}}},
                        {"left", {{"half_space", {{"point", {0.1, 0.0, 0.0}}, {"normal", {-1.0, 0.0, 0.0}}}}}}}},
                      {"initial", {{"noise", 0.01}, {"seed_region", {{"map", "centre"}, {"values", {{"u", 0.5}, {"v", 0.25}}}}}}},
                      {"dirichlet", {{"map", "left"}, {"values", {{"v", 0.0}}}}}};
  const auto rd = load_rd_system(scene);
  const auto& centre = rd.maps.scalar_map("centre");
  const auto& left = rd.maps.scalar_map("left");
  int seeded = 0, fixed = 0;
  for (size_t i = 0; i < rd.system.mass.size(); ++i) {
    const double u = rd.system.initial[0][i], v = rd.system.initial[1][i];
    if (left[i] >= 0.5) {
      ++fixed;
      EXPECT_EQ(rd.system.fixed[i], 1);
      EXPECT_EQ(v, 0.0);  // the Dirichlet value, exactly (after the noise)
    } else {
      EXPECT_EQ(rd.system.fixed[i], 0);
    }
    if (centre[i] == 1.0 && left[i] < 0.5) {
      ++seeded;
      EXPECT_LE(std::abs(u - 0.5), 0.01);
      EXPECT_LE(std::abs(v - 0.25), 0.01);
    } else if (centre[i] == 0.0 && left[i] < 0.5) {
      EXPECT_LE(std::abs(u - 1.0), 0.01);
      EXPECT_LE(std::abs(v), 0.01);
    }
  }
  EXPECT_GT(seeded, 10);
  EXPECT_GT(fixed, 10);
  // Deterministic in the seed: the same scene gives the same state, another seed another one.
  EXPECT_EQ(load_rd_system(scene).system.initial, rd.system.initial);
  json other = scene;
  other["seed"] = 2;
  EXPECT_NE(load_rd_system(other).system.initial, rd.system.initial);
}

TEST(ReactionDiffusionBuild, ANegativeDiffusionMapIsRefusedAtItsVertex) {
  const json scene = {{"mesh", "shape:square"},
                      {"time_step", 1.0},
                      {"model", "gray-scott"},
                      {"maps", {{"ramp", {{"axis", "x"}}}, {"below", {{"map", "ramp"}, {"range", {-1.0, 1.0}}}}}},
                      {"morphogens", {{"v", {{"diffusion", "below"}}}}}};
  try {
    load_rd_system(scene);
    FAIL() << "accepted a negative diffusion rate";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("morphogens.v.diffusion"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("intrinsic vertex"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace physarum
