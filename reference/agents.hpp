#pragma once
// The initial state of the agent population (paper Sec. 3.2-3.3), serially: the state itself
// (Agents) and the sampling it uses live in common/ (agents.hpp, domain_sampling.hpp).
#include "common/model/agents.hpp"
#include "common/base/element_data.hpp"
#include "common/surface/surface_domain.hpp"
#include "reference/turnover.hpp"

#include <cstdint>

namespace physarum {

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
//
// Everything above reads the LOCAL values at the agent's spawn point (hazard, so lifetime, and the
// decision period), so with spatially varying maps each agent starts in the steady state of the
// place it stands: no inspection-paradox bias and no start-up transient there either. With a
// SpawnRule the placement follows its spawn density (RandomPurpose::InitialSpawnCorner for the
// in-face corner) and the heading its spawn heading. Agent a draws from the streams of id first_id + a
// (a species' agents after those of the species before it: common/model/species.hpp).
Agents initialise_agents(const SurfaceDomain& domain, const IntrinsicVertexData<double>& hazard_rate,
                         const IntrinsicVertexData<double>& turn_frequency, const IntrinsicVertexData<double>& turn_rate,
                         int count, std::uint32_t seed, const SpawnRule& rule = {}, int first_id = 0);

}  // namespace physarum
