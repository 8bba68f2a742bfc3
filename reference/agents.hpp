#pragma once
// The agent population of the extended slime-mold model (paper Sec. 3.2, Table 1), stored as a
// structure of arrays (one array per attribute, index = agent id), and its initial state.
//
// An agent lives on one intrinsic face at a time; its position and heading are expressed in that
// face's own 2D frame (surface_domain.hpp). Headings are unit vectors; since every face frame is an
// isometric, counter-clockwise layout, a positive rotation turns the agent to its left.
#include "common/philox.hpp"
#include "common/surface_domain.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace physarum {

struct Agents {
  std::vector<int> face;                      // intrinsic face the agent is on
  std::vector<Eigen::Vector2d> position;      // in that face's frame
  std::vector<Eigen::Vector2d> heading;       // unit vector in that face's frame
  std::vector<double> age;                    // a: seconds since the agent (re)spawned
  std::vector<double> exposure;               // lambda: age normalised by the local mean lifetime
  std::vector<double> exposure_threshold;     // lambda_t: the agent turns over once lambda >= lambda_t
  std::vector<double> time_since_decision;    // seconds since the last turn decision (carries the remainder)
  std::vector<double> accumulated_turn;       // radians of turn_rate integrated since the last decision

  int count() const { return static_cast<int>(face.size()); }
  void resize(int n);
};

// A point on the surface: a face and a position in its frame.
struct FacePoint {
  int face = -1;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
};

// A point uniformly distributed over the surface (with density proportional to the domain's face
// sampler weights): the face from the alias table (two uniforms of `face_choice`), then a uniform
// point inside it by the square-root trick (two uniforms of `in_face`): with s = sqrt(r1), the point
// (1 - s) A + s (1 - r2) B + s r2 C has constant density over triangle ABC.
FacePoint sample_surface_point(const SurfaceDomain& domain, const PhiloxWords& face_choice, const PhiloxWords& in_face);

// A uniformly distributed unit direction from one uniform u in (0, 1): angle 2 pi u.
Eigen::Vector2d heading_from_uniform(double u);

// Exponentially distributed exposure with mean 1 from one uniform u in (0, 1): -ln(u).
double exponential_exposure(double u);

// Linear (barycentric) interpolation of a per-vertex field at a point of face `face` (paper
// Sec. 3.3: scalar maps live at vertices and are interpolated across faces).
double interpolate_vertex_field(const SurfaceDomain& domain, const std::vector<double>& vertex_values, int face,
                                const Eigen::Vector2d& position);

// Places `count` agents uniformly over the surface (face sampler weights) with uniform random
// headings, and draws each agent's age and exposure from the steady state of the turnover process
// (paper Sec. 3.3). Random numbers: RandomPurpose::InitialPlacement / InitialState at step 0.
//
// Why steady state, and how the inspection paradox is avoided: an agent observed at a random moment
// of a population in steady state is more likely to be one with a LONG lifetime (long lives cover
// more moments), so its total lifetime is not Exp(1) in exposure but length-biased (Gamma(2, 1),
// mean 2). Drawing a fresh threshold lambda_t ~ Exp(1) and placing the exposure somewhere below it
// would make the initial agents die too early and leave too few old, depositing agents. Instead,
// because exponential decay is memoryless, the elapsed exposure of an observed agent is Exp(1) (the
// stationary age distribution under a constant hazard) and its REMAINING exposure is an independent
// Exp(1), exactly like a newborn's; the threshold is their sum [Ros10, ch. 7.7]:
//     lambda = -ln X1,   lambda_t = lambda + (-ln X2),   age = lambda * tau(x)
// with 1/tau(x) the hazard rate (turnover.hpp) interpolated at the agent's position. With a constant
// tau the age is Exp(tau), so the depositing fraction P(age >= t_a) = exp(-t_a / tau) is that of
// Eq. 5 from the first step on.
//
// Where the hazard is 0 (no turnover: tau infinite) lifetimes are infinite and there is no
// steady-state age: the agent starts newborn (age 0, exposure 0) and its threshold is +infinity.
//
// Decision clocks start at a uniform phase of the local decision period 1/f(x) (with the turn
// omega(x) accumulated over that time), as in a population that has been running for a while.
Agents initialise_agents(const SurfaceDomain& domain, const std::vector<double>& hazard_rate,
                         const std::vector<double>& turn_frequency, const std::vector<double>& turn_rate, int count,
                         std::uint32_t seed);

}  // namespace physarum
