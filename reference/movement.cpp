#include "reference/movement.hpp"

namespace physarum {

TraceResult move_agent(const SurfaceDomain& domain, Agents& agents, int a, double distance,
                       std::vector<TraceSegment>& segments, BoundaryRule boundary) {
  const TraceResult r =
      trace(domain, agents.face[a], agents.position[a], agents.heading[a], distance, boundary, &segments);
  agents.face[a] = r.face;
  agents.position[a] = r.position;
  agents.heading[a] = r.heading;
  return r;
}

}  // namespace physarum
