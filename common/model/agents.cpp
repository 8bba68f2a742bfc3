#include "common/model/agents.hpp"

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

void Agents::append(const Agents& other) {
  face.insert(face.end(), other.face.begin(), other.face.end());
  position.insert(position.end(), other.position.begin(), other.position.end());
  heading.insert(heading.end(), other.heading.begin(), other.heading.end());
  age.insert(age.end(), other.age.begin(), other.age.end());
  exposure.insert(exposure.end(), other.exposure.begin(), other.exposure.end());
  exposure_threshold.insert(exposure_threshold.end(), other.exposure_threshold.begin(), other.exposure_threshold.end());
  time_since_decision.insert(time_since_decision.end(), other.time_since_decision.begin(), other.time_since_decision.end());
  accumulated_turn.insert(accumulated_turn.end(), other.accumulated_turn.begin(), other.accumulated_turn.end());
}

}  // namespace physarum
