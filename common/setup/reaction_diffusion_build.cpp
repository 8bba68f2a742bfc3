#include "common/setup/reaction_diffusion_build.hpp"

#include "common/base/errors.hpp"
#include "common/reaction_diffusion/reaction_at_start.hpp"
#include "common/scene/scene_fields.hpp"
#include "common/base/random_streams.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace physarum {
namespace {


// A number everywhere, or the map's values; every value finite (and >= 0 when `non_negative`).
IntrinsicVertexData<double> per_vertex(const MapOperand& operand, const EvaluatedMaps& maps, int vertex_count,
                                       const Scene& scene, const std::string& key, bool non_negative) {
  IntrinsicVertexData<double> values =
      std::holds_alternative<double>(operand)
          ? IntrinsicVertexData<double>(static_cast<size_t>(vertex_count), std::get<double>(operand))
          : maps.scalar_map(std::get<std::string>(operand));
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]) || (non_negative && values[i] < 0.0))
      fail_key(scene.source, key, "the value " + ValueRange::number(values[i]) + " at intrinsic vertex " + std::to_string(i) +
                                      (non_negative ? " must be >= 0 (a diffusion rate)" : " must be finite"));
  return values;
}

// Gradients of the three hat functions of face f, in the face's frame: grad(phi_i) is the edge
// opposite corner i turned a quarter counter-clockwise, over twice the area.
std::array<Eigen::Vector2d, 3> hat_gradients(const SurfaceDomain& domain, int f) {
  const auto& p = domain.face_corners[static_cast<size_t>(f)];
  const double twice_area = 2.0 * domain.face_area[static_cast<size_t>(f)];
  std::array<Eigen::Vector2d, 3> g;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d e = p[static_cast<size_t>((i + 2) % 3)] - p[static_cast<size_t>((i + 1) % 3)];
    g[static_cast<size_t>(i)] = Eigen::Vector2d(-e.y(), e.x()) / twice_area;
  }
  return g;
}

// The index of entry (row, col) in the CSR pattern; the pattern is the Laplacian's, which holds
// every pair of vertices sharing a face.
int entry_index(const CsrMatrix& m, int row, int col) {
  for (int k = m.row_start[static_cast<size_t>(row)]; k < m.row_start[static_cast<size_t>(row) + 1]; ++k)
    if (m.column[static_cast<size_t>(k)] == col) return k;
  throw std::logic_error("diffusion_stiffness: entry (" + std::to_string(row) + ", " + std::to_string(col) +
                         ") is not in the Laplacian's pattern");
}

}  // namespace

CsrMatrix diffusion_stiffness(const SurfaceDomain& domain, const IntrinsicVertexData<double>& rate,
                              const IntrinsicFaceData<std::array<double, 2>>* direction,
                              const IntrinsicVertexData<double>* ratio) {
  if (static_cast<int>(rate.size()) != domain.vertex_count || (ratio && static_cast<int>(ratio->size()) != domain.vertex_count))
    throw std::invalid_argument("diffusion_stiffness: one rate (and ratio) per vertex is needed");
  auto face_mean = [](const IntrinsicVertexData<double>& u, const std::array<int, 3>& v) {
    return (u[static_cast<size_t>(v[0])] + u[static_cast<size_t>(v[1])] + u[static_cast<size_t>(v[2])]) / 3.0;
  };
  CsrMatrix k = domain.laplacian;
  std::fill(k.value.begin(), k.value.end(), 0.0);
  for (int f = 0; f < domain.face_count; ++f) {
    const auto& v = domain.face_vertices[static_cast<size_t>(f)];
    const double a = face_mean(rate, v);
    Eigen::Matrix2d tensor = a * Eigen::Matrix2d::Identity();
    if (direction) {
      const auto& d = (*direction)[static_cast<size_t>(f)];
      const Eigen::Vector2d dir(d[0], d[1]);
      const double length = dir.norm();
      if (length > 0.0 && std::isfinite(length)) {
        const Eigen::Vector2d unit = dir / length;
        const Eigen::Matrix2d along = unit * unit.transpose();
        const double across = ratio ? face_mean(*ratio, v) : 1.0;
        tensor = a * along + across * a * (Eigen::Matrix2d::Identity() - along);
      }
    }
    const auto g = hat_gradients(domain, f);
    const double area = domain.face_area[static_cast<size_t>(f)];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        k.value[static_cast<size_t>(entry_index(k, v[static_cast<size_t>(i)], v[static_cast<size_t>(j)]))] +=
            area * g[static_cast<size_t>(i)].dot(tensor * g[static_cast<size_t>(j)]);
  }
  return k;
}

double largest_diffusion_eigenvalue(const CsrMatrix& stiffness, const IntrinsicVertexData<double>& mass) {
  const int n = stiffness.rows;
  if (n == 0) return 0.0;
  // S = M^-1/2 K M^-1/2 is symmetric and similar to M^-1 K: same eigenvalues, and Lanczos applies.
  Eigen::SparseMatrix<double> s = stiffness.to_eigen();
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) scale[i] = 1.0 / std::sqrt(mass[static_cast<size_t>(i)]);
  s = scale.asDiagonal() * s * scale.asDiagonal();
  if (s.norm() == 0.0) return 0.0;
  if (n <= 3) return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(s)).eigenvalues().maxCoeff();
  Spectra::SparseSymMatProd<double> op(s);
  Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double>> solver(op, 1, std::min(n, 24));
  solver.init();
  solver.compute(Spectra::SortRule::LargestAlge, 1000, 1e-10);
  if (solver.info() == Spectra::CompInfo::Successful) return solver.eigenvalues()[0];
  // Lanczos can stall where the top of the spectrum is a tight cluster (an anisotropy whose
  // direction turns abruptly: a sketch's crossing orientations). Gershgorin's bound, the largest
  // absolute row sum, is never below the largest eigenvalue: a step under it is stable, at the
  // price of a few more sub-steps.
  double bound = 0.0;
  for (int row = 0; row < s.outerSize(); ++row) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(s, row); it; ++it) sum += std::abs(it.value());
    bound = std::max(bound, sum);
  }
  return bound;
}

double explicit_stability_limit(const ReactionDiffusionSystem& system) {
  double largest = 0.0;
  for (const CsrMatrix& k : system.stiffness) largest = std::max(largest, largest_diffusion_eigenvalue(k, system.mass));
  return largest > 0.0 ? 2.0 / largest : std::numeric_limits<double>::infinity();
}

int explicit_substeps(double time_step, double stability_limit) {
  if (!std::isfinite(stability_limit)) return 1;
  const double n = std::ceil(time_step / (kExplicitSafety * stability_limit));
  if (n > 1e7)
    throw InputError("reaction-diffusion: the time step " + ValueRange::number(time_step) + " s needs " +
                     ValueRange::number(n) + " explicit sub-steps (stability limit " + ValueRange::number(stability_limit) +
                     " s); use \"integrator\": \"imex\" or a smaller time_step");
  return std::max(1, static_cast<int>(n));
}

namespace {

// "parameter_noise": each listed coefficient's value at vertex v gets a + a uniform draw from [-a, a],
// from the vertex's own stream, so the draws do not depend on the order of the coefficients' keys.
void add_parameter_noise(const ReactionDiffusionSpec& spec, std::uint32_t seed, ReactionDiffusionSystem& system) {
  for (const auto& [name, amplitude] : spec.parameter_noise) {
    if (amplitude == 0.0) continue;
    const auto c = std::find(system.coefficient_names.begin(), system.coefficient_names.end(), name);
    const auto index = static_cast<std::uint32_t>(c - system.coefficient_names.begin());
    IntrinsicVertexData<double>& values = system.coefficients[index];
    for (size_t v = 0; v < values.size(); ++v)
      values[v] += amplitude * (2.0 * first_uniform(random_words(seed, static_cast<std::uint32_t>(v), 0,
                                                                 static_cast<std::uint32_t>(RandomPurpose::ReactionParameterNoise),
                                                                 index)) -
                                1.0);
  }
}

// Blends `values` (morphogen -> value) into the initial state at `vertex` with weight w: x <- (1 - w) x + w value.
void blend_initial(const ReactionDiffusionSpec& spec, const MorphogenValues& values, size_t vertex, double weight,
                   ReactionDiffusionSystem& system) {
  for (const auto& [name, value] : values) {
    double& x = system.initial[static_cast<size_t>(spec.morphogen_index(name))][vertex];
    x = (1.0 - weight) * x + weight * value;
  }
}

// Whether a Dirichlet region holds vertex v (noise and spots leave it alone).
bool is_held(const ReactionDiffusionSystem& system, size_t v) { return !system.fixed.empty() && system.fixed[v] != 0; }

// initial.spots: `count` centres drawn by area (one random stream per spot), each setting the spot's
// values on the free vertices within `radius` (straight-line, on the simulated surface).
void seed_spots(const ReactionDiffusionSpec& spec, std::uint32_t seed, const PreparedSurface& surface,
                ReactionDiffusionSystem& system) {
  const SurfaceDomain& domain = surface.domain;
  const int n = domain.vertex_count;
  // Positions of the intrinsic vertices on the simulated (scaled) surface, for the spot radius.
  std::vector<Eigen::Vector3d> position(static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) {
    const SurfacePoint& p = domain.vertex_location[static_cast<size_t>(v)];
    const auto& t = surface.simulated.triangles[static_cast<size_t>(p.face)];
    position[static_cast<size_t>(v)] = p.barycentric[0] * surface.simulated.positions[static_cast<size_t>(t[0])] +
                                       p.barycentric[1] * surface.simulated.positions[static_cast<size_t>(t[1])] +
                                       p.barycentric[2] * surface.simulated.positions[static_cast<size_t>(t[2])];
  }
  std::vector<double> cumulative(static_cast<size_t>(n));
  double total = 0.0;
  for (size_t v = 0; v < static_cast<size_t>(n); ++v) cumulative[v] = total += domain.vertex_mass[v];
  const double r2 = spec.initial.spots->radius * spec.initial.spots->radius;
  for (int s = 0; s < spec.initial.spots->count; ++s) {
    const double u = first_uniform(random_words(seed, static_cast<std::uint32_t>(s), 0,
                                                static_cast<std::uint32_t>(RandomPurpose::ReactionSpot)));
    const size_t centre = static_cast<size_t>(
        std::min<std::ptrdiff_t>(std::lower_bound(cumulative.begin(), cumulative.end(), u * total) - cumulative.begin(), n - 1));
    for (size_t v = 0; v < static_cast<size_t>(n); ++v)
      if (!is_held(system, v) && (position[v] - position[centre]).squaredNorm() <= r2)
        blend_initial(spec, spec.initial.spots->values, v, 1.0, system);
  }
}

}  // namespace

ReactionDiffusionSystem build_reaction_diffusion_system(const Scene& scene, const PreparedSurface& surface,
                                                        const EvaluatedMaps& maps) {
  if (!scene.reaction_diffusion()) throw std::logic_error("build_reaction_diffusion_system: not a reaction-diffusion scene");
  const ReactionDiffusionSpec& spec = *scene.reaction_diffusion();
  const SurfaceDomain& domain = surface.domain;
  const int n = domain.vertex_count;
  const size_t count = spec.morphogens.size();
  ReactionDiffusionSystem system;
  system.reaction = spec.reaction;
  for (const MorphogenSpec& m : spec.morphogens) system.morphogens.push_back(m.name);
  for (const auto& [name, value] : spec.coefficients) {
    system.coefficient_names.push_back(name);
    system.coefficients.push_back(per_vertex(value, maps, n, scene, "parameters." + name, false));
  }
  add_parameter_noise(spec, scene.seed, system);
  system.mass = domain.vertex_mass;
  for (const MorphogenSpec& m : spec.morphogens) {
    const IntrinsicVertexData<double> rate = per_vertex(m.diffusion, maps, n, scene, "morphogens." + m.name + ".diffusion", true);
    if (m.anisotropy) {
      const std::string key = "morphogens." + m.name + ".anisotropy.ratio";
      const IntrinsicVertexData<double> ratio = per_vertex(m.anisotropy->ratio, maps, n, scene, key, false);
      for (size_t i = 0; i < ratio.size(); ++i)
        if (!(ratio[i] > 0.0))
          fail_key(scene.source, key, "the value " + ValueRange::number(ratio[i]) + " at intrinsic vertex " + std::to_string(i) +
                                          " must be > 0 (the rate across the direction over the rate along it)");
      system.stiffness.push_back(diffusion_stiffness(domain, rate, &maps.vector_map(m.anisotropy->direction), &ratio));
    } else
      system.stiffness.push_back(diffusion_stiffness(domain, rate));
  }

  // ---- initial state and floors ----
  for (const MorphogenSpec& m : spec.morphogens) {
    system.initial.push_back(per_vertex(m.initial, maps, n, scene, "morphogens." + m.name + ".initial", false));
    system.minimum.push_back(m.minimum);
  }
  auto set_value = [&](const MorphogenValues& values, size_t vertex, double weight) {
    blend_initial(spec, values, vertex, weight, system);
  };
  // The held vertices first: noise skips them, so a held vertex keeps exactly its initial (or given)
  // value — a cascade's frozen layer is the earlier run's, bit for bit.
  if (spec.dirichlet) {
    const IntrinsicVertexData<double>& region = maps.scalar_map(spec.dirichlet->map);
    system.fixed.assign(static_cast<size_t>(n), 0);
    for (size_t v = 0; v < static_cast<size_t>(n); ++v) system.fixed[v] = region[v] >= 0.5 ? 1 : 0;
  }
  auto held = [&](size_t v) { return is_held(system, v); };
  if (spec.initial.seed_region) {
    const IntrinsicVertexData<double>& w = maps.scalar_map(spec.initial.seed_region->map);
    for (size_t i = 0; i < static_cast<size_t>(n); ++i)
      if (!held(i)) set_value(spec.initial.seed_region->values, i, std::clamp(w[i], 0.0, 1.0));
  }
  if (spec.initial.spots) seed_spots(spec, scene.seed, surface, system);
  if (spec.initial.noise > 0.0)
    for (size_t m = 0; m < count; ++m)
      for (size_t v = 0; v < static_cast<size_t>(n); ++v)
        if (!held(v))
          system.initial[m][v] += spec.initial.noise *
                                  (2.0 * first_uniform(random_words(scene.seed, static_cast<std::uint32_t>(v), 0,
                                                                    static_cast<std::uint32_t>(RandomPurpose::ReactionNoise),
                                                                    static_cast<std::uint32_t>(m))) - 1.0);
  if (spec.dirichlet)
    for (size_t v = 0; v < static_cast<size_t>(n); ++v)
      if (held(v)) set_value(spec.dirichlet->values, v, 1.0);

  std::vector<std::string> where;
  for (const MorphogenSpec& m : spec.morphogens)
    where.push_back(scene_where(scene.source) +
                    (spec.model == "custom" ? ": key 'reaction." + m.name + "'"
                                            : ": key 'model' (\"" + spec.model + "\"), the reaction of '" + m.name + "'"));
  check_reactions_finite_at_start(system, where);

  // ---- time ----
  system.integrator = spec.integrator;
  system.time_step = scene.time_step;
  system.substeps = spec.integrator == Integrator::Forward
                        ? explicit_substeps(scene.time_step, explicit_stability_limit(system))
                        : 1;
  return system;
}

}  // namespace physarum
