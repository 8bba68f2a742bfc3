#pragma once
// std::visit with one lambda per alternative: `std::visit(overloaded{[](const A&) {...}, [](const B&)
// {...}}, v)`. The places that dispatch on a scene's model use it, so a new model (one more
// alternative of SceneModel) does not compile until each of them says what it does with it.
namespace physarum {

template <class... Lambdas>
struct overloaded : Lambdas... {
  using Lambdas::operator()...;
};
template <class... Lambdas>
overloaded(Lambdas...) -> overloaded<Lambdas...>;

}  // namespace physarum
