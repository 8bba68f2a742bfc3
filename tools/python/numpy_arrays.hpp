#pragma once
// The module's one place where engine containers become numpy arrays: results are handed over
// without a copy (the vector moves into the array's owner). Arguments are checked on the Python side
// (physarum/_arrays.py), with messages naming the argument.
#include "common/mesh/input_mesh.hpp"

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <vector>

namespace physarum::python {

namespace nb = nanobind;

using DoubleArray = nb::ndarray<nb::numpy, double>;
using Int64Array = nb::ndarray<nb::numpy, std::int64_t>;

// An (n,) or (n, columns) float64 array owning `values` (moved, not copied).
DoubleArray to_numpy(std::vector<double>&& values, size_t columns = 1);
// An (n, columns) int64 array owning `values`.
Int64Array to_numpy(std::vector<std::int64_t>&& values, size_t columns);

// A mesh as the pair (V: (n, 3) float64, F: (m, 3) int64).
nb::tuple mesh_arrays(const InputMesh& mesh);

}  // namespace physarum::python
