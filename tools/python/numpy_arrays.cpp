#include "tools/python/numpy_arrays.hpp"

#include <cmath>
#include <stdexcept>

namespace physarum::python {

namespace {

template <class T>
nb::ndarray<nb::numpy, T> owning_array(std::vector<T>&& values, size_t columns) {
  auto* owned = new std::vector<T>(std::move(values));
  nb::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  const size_t rows = columns > 0 ? owned->size() / columns : 0;
  if (columns == 1) {
    const size_t shape[1] = {rows};
    return nb::ndarray<nb::numpy, T>(owned->data(), 1, shape, owner);
  }
  const size_t shape[2] = {rows, columns};
  return nb::ndarray<nb::numpy, T>(owned->data(), 2, shape, owner);
}

}  // namespace

DoubleArray to_numpy(std::vector<double>&& values, size_t columns) { return owning_array(std::move(values), columns); }
Int64Array to_numpy(std::vector<std::int64_t>&& values, size_t columns) { return owning_array(std::move(values), columns); }

nb::tuple mesh_arrays(const InputMesh& mesh) {
  std::vector<double> V;
  V.reserve(3 * mesh.positions.size());
  for (const auto& p : mesh.positions) V.insert(V.end(), {p.x(), p.y(), p.z()});
  std::vector<std::int64_t> F;
  F.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) F.insert(F.end(), {t[0], t[1], t[2]});
  return nb::make_tuple(to_numpy(std::move(V), 3), to_numpy(std::move(F), 3));
}

std::vector<double> finite_values(const nb::handle& array, const std::string& argument, long long length) {
  nb::ndarray<double, nb::ndim<1>, nb::device::cpu> values;
  if (!nb::try_cast(array, values))
    throw nb::value_error((argument + ": expected a 1-D array of real numbers").c_str());
  if (length >= 0 && static_cast<long long>(values.shape(0)) != length)
    throw nb::value_error((argument + ": expected " + std::to_string(length) + " values, got " +
                           std::to_string(values.shape(0)))
                              .c_str());
  std::vector<double> out(values.shape(0));
  const auto view = values.view();
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = view(i);
    if (!std::isfinite(out[i]))
      throw nb::value_error((argument + ": value " + std::to_string(i) + " is not finite").c_str());
  }
  return out;
}

}  // namespace physarum::python
