#include "tools/python/numpy_arrays.hpp"

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

}  // namespace physarum::python
