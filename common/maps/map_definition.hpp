#pragma once
// Named surface maps (paper Sec. 3.3; the scene's "maps" key, docs/maps.md "Surface maps"): what
// each map IS, parsed and checked once from the scene file into a small typed tree,
// before any surface exists, so that a bad map is refused before anything is built or written.
// Evaluating the maps on a surface is common/maps/map_evaluation.hpp.
//
// A map is SCALAR (one value per intrinsic vertex, interpolated across faces) or VECTOR (one tangent
// vector per intrinsic face, in that face's own 2D frame). Each source below is one JSON shape:
//   scalar sources
//     5.0                                         a constant
//     {"ply": FILE, "property": NAME}             a per-vertex property of a PLY on the input mesh
//     {"fields_full": FILE, "property": NAME}     a property of an earlier run's fields_full.ply, read
//                                                  exactly at every intrinsic vertex: the run must be on
//                                                  the same surface (mesh, scale_to_area,
//                                                  max_circumradius, min_angle), which is checked
//                                                  (cascaded patterns: a stage seeded from the last)
//     {"texture": FILE, "channel": "r|g|b|a|luma"} an image, sampled through the input's UVs
//     {"sphere": {"center": [x,y,z], "radius": r}, "falloff": w}     regions: 1 inside, 0 outside,
//     {"box": {"min": [x,y,z], "max": [x,y,z]}, "falloff": w}        smooth over w outside when
//     {"half_space": {"point": [x,y,z], "normal": [x,y,z]}, "falloff": w}   falloff is given
//     {"segments": {"points": [[[x,y,z], [x,y,z]], ...], "radius": r}, "falloff": w}  within r of a segment
//     {"axis": "x|y|z"}                           0..1 along that axis of the input's bounding box
//   arithmetic (an OPERAND is a scalar map's name or a number)
//     {"map": OPERAND, "range": [lo, hi]}         lo + (hi - lo) * value
//     {"invert": OPERAND}                         1 - value
//     {"threshold": OPERAND, "at": t}             1 where value >= t, else 0
//     {"clamp": OPERAND, "min": a, "max": b}      value limited to [a, b] (either bound optional)
//     {"sum": [OPERAND, ...]}, {"product": [...]}, {"min": [...]}, {"max": [...]}
//   map tools
//     {"geodesic_distance": {"from": SEEDS}, "method": "heat|fmm", "time_factor": m}
//                                                 distance along the surface to the nearest seed
//                                                 (common/map_tools/geodesic_distance_source.hpp; SEEDS: seed_set.hpp)
//   map tools on the intrinsic triangulation (common/map_tools/surface_diffusion.hpp, laplace_interpolation.hpp,
//   elevation_proxy.hpp, surface_gradient.hpp say what each computes and in which units)
//     {"diffuse": OPERAND, "time": T, "steps": n}  backward-Euler heat flow for time T (scene m^2), n steps (1)
//     {"laplace": [{"region": NAME, "value": v}, ...]}  harmonic between regions held at values; a
//                                                  region is a scalar map's vertices with value >= 0.5
//     {"elevation": {"time": t, "steps": n}}       0..1 height over a volume-preserving smoothed copy
//                                                  (t in units of the squared bounding-box diagonal)
//     {"slope": NAME}                              |gradient| per vertex (area-weighted face mean)
//   vector sources
//     {"gradient": NAME, "normalize": bool}       the FE gradient per face (unit length, or zero
//                                                  where flat, when normalize is true; default false)
//     {"direction": [x, y, z]}                    a constant direction, projected into every face
//     {"toward": [x, y, z]}, {"away_from": [...]}  unit directions from each face toward (away from) a
//                                                  point, projected into the face (Fig. 8's bias to a sink)
//     {"ply": FILE, "face_property": NAME}        per-face NAME_x, NAME_y, NAME_z of a PLY
// Coordinates are the INPUT mesh's own (before scale_to_area). File paths are relative to the scene
// file's folder (or absolute). Maps may name each other in any order; they are sorted so that every
// map comes after the maps it reads, and a cycle is an error.
//
// Adding a source kind (the map tools: geodesic distance, Laplace, diffusion, gradient) is one row
// of the source table in map_definition.cpp, one alternative of MapSource, and one case in
// map_evaluation.cpp (std::visit refuses to compile while the case is missing).
#include "common/map_tools/geodesic_distance_source.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace physarum {

enum class MapKind { Scalar, Vector };
const char* to_string(MapKind kind);

// A number, or the name of a scalar map.
using MapOperand = std::variant<double, std::string>;

struct ConstantSource {
  double value = 0.0;
};
struct PlyVertexSource {
  std::string path;  // resolved
  std::string property;
};
struct FieldsFullSource {
  std::string path;  // resolved: an earlier run's fields_full.ply
  std::string property;
};
enum class TextureChannel { Red, Green, Blue, Alpha, Luma };
struct TextureSource {
  std::string path;  // resolved
  TextureChannel channel = TextureChannel::Red;
};
struct SphereRegion {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};
struct BoxRegion {
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
};
// The side the normal points into is inside: {x : (x - point) . normal >= 0}.
struct HalfSpaceRegion {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit length
};
// Thick polylines: the points within `radius` of any segment (a sketch's initiator cells, 004 Sec. 5.4).
struct SegmentsRegion {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  double radius = 0.0;
};
struct RegionSource {
  std::variant<SphereRegion, BoxRegion, HalfSpaceRegion, SegmentsRegion> region;
  double falloff = 0.0;  // 0: a sharp edge; w > 0: 1 - smoothstep(d / w) at distance d outside
};
struct AxisRampSource {
  int axis = 0;  // 0 = x, 1 = y, 2 = z
};
struct RangeSource {
  MapOperand operand;
  double low = 0.0, high = 1.0;
};
struct InvertSource {
  MapOperand operand;
};
struct ThresholdSource {
  MapOperand operand;
  double at = 0.5;
};
struct ClampSource {
  MapOperand operand;
  std::optional<double> low, high;
};
enum class CombineOperation { Sum, Product, Min, Max };
struct CombineSource {
  CombineOperation operation = CombineOperation::Sum;
  std::vector<MapOperand> operands;  // at least one
};
struct DirectionSource {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // in input coordinates, any length
};
struct RadialSource {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // in input coordinates
  bool toward = true;                                // false: away from the point
};
struct PlyFaceVectorSource {
  std::string path;      // resolved
  std::string property;  // NAME: the file has NAME_x, NAME_y, NAME_z per face
};

// ---- map tools (paper Sec. 3.3) ----
struct DiffuseSource {
  MapOperand operand;
  double time = 0.0;  // > 0, in the domain's m^2
  int steps = 1;      // >= 1
};
struct LaplaceRegion {
  std::string region;  // a scalar map: its vertices with value >= 0.5 are held at `value`
  double value = 0.0;
};
struct LaplaceSource {
  std::vector<LaplaceRegion> regions;  // at least one
  std::vector<std::string> map_dependencies() const {
    std::vector<std::string> names;
    for (const LaplaceRegion& r : regions) names.push_back(r.region);
    return names;
  }
};
struct ElevationSource {
  double time = 0.0;  // > 0, in units of the squared bounding-box diagonal
  int steps = 1;      // >= 1
};
struct SlopeSource {
  MapOperand operand;  // always a map name
};
struct GradientSource {
  MapOperand operand;  // always a map name
  bool normalize = false;
};

using MapSource = std::variant<ConstantSource, PlyVertexSource, FieldsFullSource, TextureSource, RegionSource, AxisRampSource,
                               RangeSource, InvertSource, ThresholdSource, ClampSource, CombineSource,
                               DirectionSource, RadialSource, PlyFaceVectorSource, GeodesicDistanceSource,
                               DiffuseSource, LaplaceSource, ElevationSource, SlopeSource, GradientSource>;

struct MapDefinition {
  std::string name;
  MapKind kind = MapKind::Scalar;
  MapSource source;
  // The names of the maps this one reads (operands that are names, and the maps a map tool's
  // map_dependencies() names), in the order given.
  std::vector<std::string> dependencies() const;
};

// A scene's maps, every map after the maps it reads.
class MapSet {
 public:
  MapSet() = default;
  explicit MapSet(std::vector<MapDefinition> ordered) : maps_(std::move(ordered)) {}

  const std::vector<MapDefinition>& in_dependency_order() const { return maps_; }
  bool empty() const { return maps_.empty(); }
  // nullptr when there is no map of that name.
  const MapDefinition* find(const std::string& name) const;

 private:
  std::vector<MapDefinition> maps_;
};

// Parses the "maps" object of a scene. `folder` is the scene file's folder (relative file paths are
// resolved against it); `where` starts every message (the scene file). InputError naming
// "key 'maps': map 'NAME'" and the problem for: a value that is no known source (the known ones
// are listed), a missing or malformed field, an unknown field, a file that does not exist, an
// operand that names no map or a vector map, a map name that cannot be a PLY property, and a
// dependency cycle (shown as a -> b -> a).
MapSet parse_maps(const nlohmann::json& maps, const std::string& folder, const std::string& where);

}  // namespace physarum
