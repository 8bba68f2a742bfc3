#pragma once
// A tag naming a model's spec type, for the one function of a model's scene part that has no spec to
// take yet: read_model(ModelTag<Spec>{}, ...) (common/scene/scene_models.hpp).
namespace physarum {

template <class Spec>
struct ModelTag {};

}  // namespace physarum
