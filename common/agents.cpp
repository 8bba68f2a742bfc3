#include "common/agents.hpp"

namespace physarum {

void Agents::resize(int n) {
  const auto size = static_cast<size_t>(n);
  face.resize(size);
  position.resize(size);
  heading.resize(size);
  age.resize(size);
  exposure.resize(size);
  exposure_threshold.resize(size);
  time_since_decision.resize(size);
  accumulated_turn.resize(size);
}

}  // namespace physarum
