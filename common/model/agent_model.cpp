#include "common/model/agent_model.hpp"

#include "common/model/model_parameters.hpp"

namespace physarum {

IntrinsicVertexData<double> hazard_rate_per_vertex(const IntrinsicVertexData<double>& mean_lifetime) {
  IntrinsicVertexData<double> hazard(mean_lifetime.size());
  for (size_t i = 0; i < mean_lifetime.size(); ++i)
    hazard[i] = device_value(parameter_spec(Param::mean_lifetime), mean_lifetime[i]);
  return hazard;
}

}  // namespace physarum
