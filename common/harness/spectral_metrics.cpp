#include "common/harness/spectral_metrics.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/input_mesh.hpp"
#include "common/surface/surface_domain.hpp"

#include <Eigen/Geometry>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

namespace physarum {
namespace {

double area_weighted_mean_of(const IntrinsicVertexData<double>& field, const IntrinsicVertexData<double>& mass, double* total_mass) {
  double weighted = 0.0, total = 0.0;
  for (size_t i = 0; i < field.size(); ++i) {
    weighted += mass[i] * field[i];
    total += mass[i];
  }
  if (!(total > 0.0)) throw InputError("spectral metrics: total vertex mass is not > 0");
  if (total_mass) *total_mass = total;
  return weighted / total;
}

}  // namespace

// ---- manifold-harmonic band powers ---------------------------------------------------------------

Eigen::VectorXd manifold_harmonic_coefficients(const Eigenpairs& pairs, const IntrinsicVertexData<double>& mass,
                                               const IntrinsicVertexData<double>& field) {
  const Eigen::Index n = pairs.vectors.rows();
  if (static_cast<Eigen::Index>(mass.size()) != n || static_cast<Eigen::Index>(field.size()) != n)
    throw InputError("manifold harmonics: " + std::to_string(field.size()) + " field values and " +
                     std::to_string(mass.size()) + " masses for eigenvectors of length " + std::to_string(n));
  const Eigen::Map<const Eigen::VectorXd> m(mass.data(), n), u(field.data(), n);
  return pairs.vectors.transpose() * m.cwiseProduct(u);
}

ManifoldHarmonicBands manifold_harmonic_band_powers(const SurfaceDomain& domain, const Eigenpairs& pairs,
                                                    const IntrinsicVertexData<double>& field, int bands) {
  if (bands < 1) throw InputError("manifold harmonics: band count " + std::to_string(bands) + " is not >= 1");
  if (pairs.values.size() == 0 || pairs.vectors.cols() != pairs.values.size())
    throw InputError("manifold harmonics: eigenpairs without eigenvectors");
  if (static_cast<int>(field.size()) != domain.vertex_count)
    throw InputError("manifold harmonics: " + std::to_string(field.size()) + " field values for " +
                     std::to_string(domain.vertex_count) + " vertices");
  const Eigen::VectorXd c = manifold_harmonic_coefficients(pairs, domain.vertex_mass, field);

  ManifoldHarmonicBands r;
  double area = 0.0;
  r.mean = area_weighted_mean_of(field, domain.vertex_mass, &area);
  if (!(r.mean > 0.0))
    throw InputError("manifold harmonics: the field's mean " + std::to_string(r.mean) +
                     " is not > 0, so the band powers cannot be normalised by it");

  const double lambda_max = pairs.values.maxCoeff();
  const double top = std::sqrt(std::max(0.0, lambda_max));
  const double width = top / bands;
  r.edges.resize(bands + 1);
  for (int b = 0; b <= bands; ++b) r.edges[b] = width * b;
  r.edges[bands] = top;
  r.power.assign(bands, 0.0);
  r.modes.assign(bands, 0);
  const double normaliser = area * r.mean * r.mean;
  for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
    const double lambda = pairs.values[k];
    if (!(lambda > 1e-8 * lambda_max)) {
      ++r.constant_modes;
      continue;
    }
    const int b = std::min(bands - 1, static_cast<int>(std::sqrt(lambda) / width));
    r.power[b] += c[k] * c[k] / normaliser;
    ++r.modes[b];
  }
  return r;
}

// ---- radially averaged power spectrum ------------------------------------------------------------

std::vector<Eigen::Vector2d> planar_vertex_coordinates(const SurfaceDomain& domain, const InputMesh& input) {
  if (input.positions.empty() || input.triangles.empty()) throw InputError("planar coordinates: empty input mesh");
  // The plane: through the first vertex, normal = area-weighted sum of the face normals.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = input.positions[0], hi = input.positions[0];
  for (const Eigen::Vector3d& p : input.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (const auto& t : input.triangles)
    normal += (input.positions[t[1]] - input.positions[t[0]]).cross(input.positions[t[2]] - input.positions[t[0]]);
  if (!(normal.norm() > 0.0)) throw InputError("planar coordinates: " + input.source + " has no area");
  normal.normalize();
  const double tolerance = 1e-6 * (hi - lo).norm();
  for (size_t v = 0; v < input.positions.size(); ++v)
    if (std::abs(normal.dot(input.positions[v] - input.positions[0])) > tolerance)
      throw InputError("planar coordinates: " + input.source + " is not flat (vertex " + std::to_string(v) +
                       " lies off the plane of the mesh)");
  // Basis: the coordinate axis least aligned with the normal, projected into the plane, and
  // normal x that. For a plane z = const with upward normal this is exactly (x, y).
  Eigen::Index axis = 0;
  normal.cwiseAbs().minCoeff(&axis);
  Eigen::Vector3d e1 = Eigen::Vector3d::Unit(axis);
  e1 = (e1 - normal * normal.dot(e1)).normalized();
  const Eigen::Vector3d e2 = normal.cross(e1);

  std::vector<Eigen::Vector2d> xy(domain.vertex_count);
  if (static_cast<int>(domain.vertex_location.size()) != domain.vertex_count)
    throw InputError("planar coordinates: the domain has no vertex locations");
  for (int v = 0; v < domain.vertex_count; ++v) {
    const SurfacePoint& s = domain.vertex_location[v];
    if (s.face < 0 || s.face >= input.triangle_count())
      throw InputError("planar coordinates: vertex " + std::to_string(v) + " lies on face " + std::to_string(s.face) +
                       ", not a face of " + input.source);
    const auto& t = input.triangles[s.face];
    const Eigen::Vector3d p = s.barycentric[0] * input.positions[t[0]] + s.barycentric[1] * input.positions[t[1]] +
                              s.barycentric[2] * input.positions[t[2]];
    xy[v] = {e1.dot(p), e2.dot(p)};
  }
  return xy;
}

GridSamples rasterize_planar_field(const std::vector<Eigen::Vector2d>& vertex_xy,
                                   const std::vector<std::array<int, 3>>& faces, const IntrinsicVertexData<double>& field,
                                   int size) {
  if (size < 2) throw InputError("rasterise: grid size " + std::to_string(size) + " is not >= 2");
  if (vertex_xy.size() != field.size() || vertex_xy.empty())
    throw InputError("rasterise: " + std::to_string(field.size()) + " field values for " +
                     std::to_string(vertex_xy.size()) + " vertex positions");
  const int nv = static_cast<int>(vertex_xy.size());
  for (const auto& f : faces)
    for (int v : f)
      if (v < 0 || v >= nv) throw InputError("rasterise: face refers to vertex " + std::to_string(v));

  Eigen::Vector2d lo = vertex_xy[0], hi = vertex_xy[0];
  for (const Eigen::Vector2d& p : vertex_xy) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0.0)) throw InputError("rasterise: the vertices span no area");

  GridSamples g;
  g.size = size;
  g.cell = side / size;
  g.origin = 0.5 * (lo + hi) - Eigen::Vector2d::Constant(0.5 * side);
  g.value.assign(static_cast<size_t>(size) * size, 0.0);
  g.covered.assign(static_cast<size_t>(size) * size, 0);

  for (const auto& f : faces) {
    const Eigen::Vector2d& a = vertex_xy[f[0]];
    const Eigen::Vector2d& b = vertex_xy[f[1]];
    const Eigen::Vector2d& c = vertex_xy[f[2]];
    // Twice the signed area; barycentrics are ratios of such areas, so either orientation works.
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (!(std::abs(area2) > 1e-14 * side * side)) continue;  // degenerate: its edges are covered by neighbours
    const Eigen::Vector2d flo = a.cwiseMin(b).cwiseMin(c), fhi = a.cwiseMax(b).cwiseMax(c);
    // Cells whose centre origin + (i + 1/2) cell lies in [flo, fhi].
    const int i0 = std::max(0, static_cast<int>(std::ceil((flo.x() - g.origin.x()) / g.cell - 0.5)));
    const int i1 = std::min(size - 1, static_cast<int>(std::floor((fhi.x() - g.origin.x()) / g.cell - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((flo.y() - g.origin.y()) / g.cell - 0.5)));
    const int j1 = std::min(size - 1, static_cast<int>(std::floor((fhi.y() - g.origin.y()) / g.cell - 0.5)));
    const double tolerance = -1e-12;  // centres exactly on a shared edge belong to either face
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t idx = static_cast<size_t>(j) * size + i;
        if (g.covered[idx]) continue;
        const Eigen::Vector2d p = g.origin + g.cell * Eigen::Vector2d(i + 0.5, j + 0.5);
        const double wa = ((b - p).x() * (c - p).y() - (b - p).y() * (c - p).x()) / area2;
        const double wb = ((c - p).x() * (a - p).y() - (c - p).y() * (a - p).x()) / area2;
        const double wc = 1.0 - wa - wb;
        if (wa < tolerance || wb < tolerance || wc < tolerance) continue;
        g.value[idx] = wa * field[f[0]] + wb * field[f[1]] + wc * field[f[2]];
        g.covered[idx] = 1;
      }
  }
  return g;
}

RadialSpectrum radial_power_spectrum(const GridSamples& grid) {
  const int n = grid.size;
  const size_t cells = static_cast<size_t>(n) * n;
  if (n < 2 || grid.value.size() != cells || grid.covered.size() != cells)
    throw InputError("radial spectrum: malformed grid");
  double sum = 0.0;
  size_t covered = 0;
  for (size_t i = 0; i < cells; ++i)
    if (grid.covered[i]) {
      sum += grid.value[i];
      ++covered;
    }
  if (covered == 0) throw InputError("radial spectrum: no grid cell lies on the mesh");
  RadialSpectrum r;
  r.mean = sum / covered;
  r.side = grid.cell * n;
  if (!(r.mean > 0.0))
    throw InputError("radial spectrum: the field's mean " + std::to_string(r.mean) +
                     " is not > 0, so the spectrum cannot be normalised by it");

  // Rows (along x) then columns (along y), complex to complex.
  std::vector<std::complex<double>> data(cells);
  for (size_t i = 0; i < cells; ++i) data[i] = grid.covered[i] ? grid.value[i] - r.mean : 0.0;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(n), out(n);
  for (int j = 0; j < n; ++j) {
    std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(j) * n, n, in.begin());
    fft.fwd(out.data(), in.data(), n);
    std::copy_n(out.begin(), n, data.begin() + static_cast<std::ptrdiff_t>(j) * n);
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) in[j] = data[static_cast<size_t>(j) * n + i];
    fft.fwd(out.data(), in.data(), n);
    for (int j = 0; j < n; ++j) data[static_cast<size_t>(j) * n + i] = out[j];
  }

  const double normaliser = static_cast<double>(cells) * static_cast<double>(cells) * r.mean * r.mean;
  const int half = n / 2;
  const int max_radius = static_cast<int>(std::lround(std::sqrt(2.0) * half)) + 1;
  r.power.assign(max_radius + 1, 0.0);
  r.count.assign(max_radius + 1, 0);
  for (int j = 0; j < n; ++j) {
    const int ky = j < n - half ? j : j - n;  // FFT order: 0, 1, ..., then the negative frequencies
    for (int i = 0; i < n; ++i) {
      const int kx = i < n - half ? i : i - n;
      const int radius = static_cast<int>(std::lround(std::sqrt(static_cast<double>(kx * kx + ky * ky))));
      r.power[radius] += std::norm(data[static_cast<size_t>(j) * n + i]) / normaliser;
      ++r.count[radius];
    }
  }
  while (!r.count.empty() && r.count.back() == 0) {
    r.count.pop_back();
    r.power.pop_back();
  }
  for (size_t k = 0; k < r.power.size(); ++k)
    if (r.count[k] > 0) r.power[k] /= r.count[k];
  return r;
}

RadialSpectrum radial_power_spectrum(const std::vector<Eigen::Vector2d>& vertex_xy,
                                     const std::vector<std::array<int, 3>>& faces, const IntrinsicVertexData<double>& field,
                                     int size) {
  return radial_power_spectrum(rasterize_planar_field(vertex_xy, faces, field, size));
}

// ---- agent density -------------------------------------------------------------------------------

AgentDensityDispersion agent_density_dispersion(const std::vector<int>& agent_face,
                                                const IntrinsicFaceData<double>& face_area) {
  if (agent_face.empty()) throw InputError("agent density: no agents");
  const int faces = static_cast<int>(face_area.size());
  double total_area = 0.0;
  for (int f = 0; f < faces; ++f) {
    if (!(face_area[f] > 0.0))
      throw InputError("agent density: face " + std::to_string(f) + " has area " + std::to_string(face_area[f]) +
                       ", not > 0");
    total_area += face_area[f];
  }
  std::vector<double> count(faces, 0.0);
  for (int f : agent_face) {
    if (f < 0 || f >= faces)
      throw InputError("agent density: agent on face " + std::to_string(f) + " of " + std::to_string(faces));
    count[f] += 1.0;
  }
  const double agents = static_cast<double>(agent_face.size());
  // sum_f p_f (n_f / (N p_f) - 1)^2 with p_f = A_f / A.
  double d = 0.0;
  for (int f = 0; f < faces; ++f) {
    const double p = face_area[f] / total_area;
    const double relative = count[f] / (agents * p) - 1.0;
    d += p * relative * relative;
  }
  AgentDensityDispersion r;
  r.dispersion = d;
  r.uniform_expectation = (faces - 1) / agents;
  return r;
}

}  // namespace physarum
