#pragma once
// Movement (paper Sec. 3.2, Fig. 2b): each step an agent walks the geodesic of length v * dt along
// its heading across the intrinsic faces; at a boundary it reflects (BoundaryRule::Reflect), so it
// never leaves the surface, or, with BoundaryBehaviour::Terminate (Sec. 3.3), stops there
// (BoundaryRule::Stop) to be respawned by the turnover of the same step.
#include "common/surface/surface_domain.hpp"
#include "common/surface/trace.hpp"
#include "common/model/agents.hpp"

#include <vector>

namespace physarum {

// Moves agent `a` by `distance` and updates its face, position and heading. `segments` receives the
// per-face pieces of the path (for deposition). Returns the trace (face crossings, boundary hits).
TraceResult move_agent(const SurfaceDomain& domain, Agents& agents, int a, double distance,
                       std::vector<TraceSegment>& segments, BoundaryRule boundary = BoundaryRule::Reflect);

}  // namespace physarum
