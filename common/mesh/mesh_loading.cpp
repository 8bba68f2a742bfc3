#include "common/mesh/mesh_loading.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/mesh_file_reader.hpp"
#include "common/mesh/mesh_repair.hpp"
#include "common/mesh/shapes.hpp"

namespace physarum {

InputMesh load_mesh(const std::string& spec) {
  constexpr std::string_view shape_prefix = "shape:";
  const bool is_shape = spec.starts_with(shape_prefix);
  const PolygonSoup soup = is_shape ? make_shape_soup(spec.substr(shape_prefix.size())) : read_polygon_soup(spec);
  // Shapes go through the same repair and validation as files, so a construction mistake cannot
  // slip through silently.
  try {
    return repair_polygon_soup(soup, spec);
  } catch (const InputError&) {
    // Text readers stumble over "nan" or "inf" and report something else (a missing face, a
    // shifted index); name the real cause when there is one.
    if (!is_shape)
      if (const std::string non_finite = find_non_finite_number(spec); !non_finite.empty()) throw InputError(spec + ": " + non_finite);
    throw;
  }
}

}  // namespace physarum
