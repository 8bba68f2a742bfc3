#include "api/growth_simulation.hpp"

#include "common/base/errors.hpp"
#include "common/growth/growth_law.hpp"
#include "common/setup/reaction_diffusion_build.hpp"
#include "common/shell/membrane_energy.hpp"
#include "common/shell/sheet_perturbation.hpp"
#include "common/simulation/simulation_state.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

namespace physarum {
namespace {

// The mean rest edge length (over faces, each face's three edges): the perturbation's scale.
double mean_rest_edge(const ShellRestState& rest) {
  double sum = 0.0;
  for (const Eigen::Matrix2d& metric : rest.face_metric)
    for (int c = 0; c < 3; ++c) sum += std::sqrt(rest_edge_length_squared(metric, c));
  return rest.face_metric.empty() ? 0.0 : sum / (3.0 * static_cast<double>(rest.face_metric.size()));
}

double face_mean(const std::vector<double>& values, const std::array<int, 3>& face) {
  return (values[static_cast<size_t>(face[0])] + values[static_cast<size_t>(face[1])] + values[static_cast<size_t>(face[2])]) / 3.0;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  throw std::logic_error("growth: map '" + name + "' is not carried by the sheet");
}

// The paper's start for Gray-Scott when the scene gives none: u = 1, v = 0 everywhere but a small
// disc around the vertex nearest the sheet's centroid, where u = 0, v = 1 (the paper seeds its
// middle vertex; a disc of a few edges survives on any resolution, where one vertex may not).
void seed_centre(ReactionDiffusionSystem& system, const GrowingSheet& sheet) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : sheet.positions) centroid += p;
  centroid /= static_cast<double>(sheet.positions.size());
  size_t centre = 0;
  for (size_t i = 1; i < sheet.positions.size(); ++i)
    if ((sheet.positions[i] - centroid).squaredNorm() < (sheet.positions[centre] - centroid).squaredNorm()) centre = i;
  const double radius = 2.5 * mean_rest_edge(sheet.rest);
  for (size_t i = 0; i < sheet.positions.size(); ++i)
    if ((sheet.positions[i] - sheet.positions[centre]).norm() <= radius && (system.fixed.empty() || !system.fixed[i])) {
      system.initial[0][i] = 0.0;
      system.initial[1][i] = 1.0;
    }
}

bool gives_no_start(const ReactionDiffusionSpec& spec) {
  const ReactionInitialSpec& i = spec.initial;
  return spec.model == "gray-scott" && i.noise == 0.0 && !i.seed_region && !i.spots;
}

// ---- checkpoint layout (SimulationState::model_arrays) ----
enum ModelArray : size_t { kHeader, kPositions, kFaces, kMetrics, kHingeAngles, kInitialArea, kRecords, kMotion, kFirstValues };
constexpr size_t kRecordFields = 12;

std::vector<double> record_numbers(const GrowthStepRecord& r) {
  return {double(r.growth_step), double(r.splits), double(r.vertices), double(r.faces), double(r.newton_iterations),
          double(r.factorizations), r.residual, r.membrane_energy, r.bending_energy, r.rest_area, r.seconds, double(r.pieces)};
}

GrowthStepRecord record_from(const double* x) {
  GrowthStepRecord r;
  r.growth_step = int(x[0]), r.splits = int(x[1]), r.vertices = int(x[2]), r.faces = int(x[3]);
  r.newton_iterations = int(x[4]), r.factorizations = int(x[5]);
  r.residual = x[6], r.membrane_energy = x[7], r.bending_energy = x[8], r.rest_area = x[9], r.seconds = x[10];
  r.pieces = int(x[11]);
  return r;
}

}  // namespace

GrowthSimulation::GrowthSimulation(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps,
                                   ReactionBackendMaker make)
    : scene_(scene), reaction_scene_(reaction_diffusion_scene(scene)), spec_(*scene_.growth()), make_(std::move(make)) {
  sheet_ = sheet_at_rest(surface.simulated);
  morphogens_ = static_cast<int>(spec_.reaction.morphogens.size());
  sheet_.values.assign(static_cast<size_t>(morphogens_), {});
  layout_ = carry_maps(sheet_, maps, surface.domain);
  if (spec_.growth.stretch)
    if (const auto* name = std::get_if<std::string>(&*spec_.growth.stretch)) {
      const IntrinsicVertexData<double>& s = maps.scalar_map(*name);
      for (size_t i = 0; i < s.size(); ++i)
        if (!(s[i] > 0.0))
          throw InputError(scene_.source + ": key 'growth.stretch': map '" + *name + "' is " + std::to_string(s[i]) +
                           " at vertex " + std::to_string(i) + " (a stretch must be > 0; 1 = no growth)");
    }
  ReactionDiffusionSystem system = build_reaction_diffusion_system(reaction_scene_, surface, maps);
  if (gives_no_start(spec_.reaction)) seed_centre(system, sheet_);
  for (int m = 0; m < morphogens_; ++m) {
    const IntrinsicVertexData<double>& u = system.initial[static_cast<size_t>(m)];
    sheet_.values[static_cast<size_t>(m)].assign(u.begin(), u.end());
  }
  substeps_ = system.substeps;
  surface_ = surface;
  reaction_ = make_(surface_->domain, std::move(system));
  backend_name_ = reaction_->backend_name();
  device_name_ = reaction_->device_name();
  initial_rest_area_ = rest_area(sheet_.rest);
  gauge_face_ = central_face(sheet_.topology, sheet_.positions);
}

GrowthSimulation::~GrowthSimulation() = default;

void GrowthSimulation::step() {
  if (stopped_) return;
  ++steps_;
  if (spec_.schedule.is_growth_step(steps_)) {
    grow();
    if (stopped_) --steps_;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  if (!reaction_) rebuild_reaction();
  reaction_->step();
  reaction_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A device backend enqueues its steps: the time they take shows where the host waits for them, so
// that wait counts as reaction–diffusion time too (here and where a growth step reads the fields).
void GrowthSimulation::finish() {
  if (!reaction_) return;
  const auto start = std::chrono::steady_clock::now();
  reaction_->finish();
  reaction_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void GrowthSimulation::rebuild_reaction() const {
  if (!surface_) surface_ = sheet_surface(sheet_, scene_.mesh);
  ReactionDiffusionSystem system =
      build_reaction_diffusion_system(reaction_scene_, *surface_, sheet_maps(sheet_, layout_, surface_->domain));
  for (int m = 0; m < morphogens_; ++m) system.initial[static_cast<size_t>(m)] = IntrinsicVertexData<double>(sheet_.values[static_cast<size_t>(m)]);
  substeps_ = system.substeps;
  reaction_ = make_(surface_->domain, std::move(system));
}

void GrowthSimulation::sync_values_from_backend() {
  if (!reaction_) return;
  for (int m = 0; m < morphogens_; ++m) {
    const IntrinsicVertexData<double> u = reaction_->field_values(m);
    sheet_.values[static_cast<size_t>(m)].assign(u.begin(), u.end());
  }
}

ShellEquilibrium& GrowthSimulation::equilibrium() {
  if (!equilibrium_) equilibrium_ = std::make_unique<ShellEquilibrium>(sheet_.topology, spec_.shell.material, gauge_face_);
  return *equilibrium_;
}

FaceGrowth GrowthSimulation::face_growth() const {
  const GrowthRuleSpec& rule = spec_.growth;
  const auto& faces = sheet_.topology.faces;
  FaceGrowth g;
  const double per_step = 1.0 / spec_.schedule.growth_steps;
  const std::vector<double>* stretch_map = nullptr;
  if (rule.stretch)
    if (const auto* name = std::get_if<std::string>(&*rule.stretch))
      stretch_map = &sheet_.values[static_cast<size_t>(layout_.first_value + index_of(layout_.scalar, *name))];
  // A prescribed isotropic stretch map grows each edge by the map along it, so neighbouring faces
  // keep agreeing on their shared edge and the rest state approximates the map's metric (per face,
  // a shared edge would get two rest lengths: a strain of the map's gradient times the edge length
  // that no shape relieves, which outweighs the bending of a thin sheet).
  if (stretch_map && !rule.anisotropy) {
    g.edge = edge_stretches(sheet_.topology, *stretch_map, per_step);
    return g;
  }
  g.along.resize(faces.size());
  g.across.resize(faces.size());
  const std::vector<double>& a = sheet_.values[static_cast<size_t>(spec_.reaction.morphogen_index(rule.a))];
  const std::vector<double>& b = sheet_.values[static_cast<size_t>(spec_.reaction.morphogen_index(rule.b))];
  for (size_t f = 0; f < faces.size(); ++f) {
    double along = 1.0;
    if (rule.stretch) along = std::pow(stretch_map ? face_mean(*stretch_map, faces[f]) : std::get<double>(*rule.stretch), per_step);
    else along = growth_stretch(rule.law, face_mean(a, faces[f]), face_mean(b, faces[f]));
    g.along[f] = along;
    g.across[f] = rule.anisotropy ? 1.0 + rule.anisotropy->across * (along - 1.0) : along;
  }
  if (rule.anisotropy) g.direction = sheet_.directions[static_cast<size_t>(index_of(layout_.vector, rule.anisotropy->direction))];
  return g;
}

namespace {

// `growth` with every factor raised to 1 / pieces: one of `pieces` equal sub-steps of it.
FaceGrowth piece_of(const FaceGrowth& growth, int pieces) {
  FaceGrowth piece = growth;
  for (double& x : piece.along) x = std::pow(x, 1.0 / pieces);
  for (double& x : piece.across) x = std::pow(x, 1.0 / pieces);
  for (auto& stretches : piece.edge)
    for (double& x : stretches) x = std::pow(x, 1.0 / pieces);
  return piece;
}

}  // namespace

bool GrowthSimulation::grow_in_pieces(const FaceGrowth& growth, int pieces, std::uint32_t growth_step, GrowthStepRecord& record) {
  const FaceGrowth piece = piece_of(growth, pieces);
  for (int k = 0; k < pieces; ++k) {
    grow_faces(sheet_.rest, piece);
    if (k == 0)
      perturb_out_of_plane(sheet_.topology, sheet_.positions, spec_.shell.perturbation * mean_rest_edge(sheet_.rest),
                           scene_.seed, growth_step);
    const NewtonReport report = equilibrium().solve(sheet_.positions, sheet_.rest, spec_.shell.newton);
    record.newton_iterations += report.iterations;
    record.factorizations += report.factorizations;
    record.residual = report.residual();
    record.membrane_energy = report.energy.membrane;
    record.bending_energy = report.energy.bending;
    if (!report.converged) return false;
  }
  return true;
}

std::string GrowthSimulation::failure_message(const GrowthStepRecord& record) const {
  std::ostringstream why;
  why << scene_.source << ": growth step " << record.growth_step << " of " << spec_.schedule.growth_steps
      << ": Newton's method did not reach equilibrium, not even in " << kMaxGrowthPieces << " sub-steps of "
      << spec_.shell.newton.max_iterations << " iterations each (residual " << record.residual << ", tolerance "
      << spec_.shell.newton.tolerance
      << "). Grow less per step: a smaller \"growth.rate\" (or stretch), more \"schedule.growth_steps\", or a larger "
         "\"shell.max_iterations\"; the outputs hold the last converged shape (after growth step "
      << record.growth_step - 1 << ")";
  return why.str();
}

int GrowthSimulation::refine(double max_edge) {
  // The last step's motion rides along as three more values (a new vertex moves as its edge's middle).
  const bool moving = !motion_.empty();
  if (moving)
    for (int c = 0; c < 3; ++c) {
      std::vector<double> component;
      for (const Eigen::Vector3d& d : motion_) component.push_back(d[c]);
      sheet_.values.push_back(std::move(component));
    }
  const int splits = refine_sheet(sheet_, max_edge);
  if (splits > 0) equilibrium_.reset();
  if (moving) {
    const size_t first = sheet_.values.size() - 3;
    motion_.assign(sheet_.positions.size(), Eigen::Vector3d::Zero());
    for (size_t i = 0; i < motion_.size(); ++i)
      motion_[i] = {sheet_.values[first][i], sheet_.values[first + 1][i], sheet_.values[first + 2][i]};
    sheet_.values.resize(first);
  }
  return splits;
}

void GrowthSimulation::grow() {
  finish();
  const auto start = std::chrono::steady_clock::now();
  sync_values_from_backend();
  const GrowingSheet before = sheet_;
  const std::vector<Eigen::Vector3d> motion_before = motion_;
  GrowthStepRecord record;
  record.growth_step = growth_steps_done() + 1;
  if (spec_.max_edge) record.splits = refine(*spec_.max_edge);
  // The predictor: the sheet starts where the last step's motion would carry it (growth steps change
  // the shape smoothly, and Newton then starts near the answer).
  const std::vector<Eigen::Vector3d> start_positions = sheet_.positions;
  for (size_t i = 0; i < motion_.size(); ++i) sheet_.positions[i] += motion_[i];
  const std::vector<double> old_mass = rest_vertex_masses(sheet_.topology, sheet_.rest);
  const FaceGrowth growth = face_growth();
  // A growth step the solve cannot follow is retried in 2, 4, ... equal sub-steps (each starting
  // from the last one's equilibrium): a sheet about to fold may need the smaller increments.
  const GrowingSheet refined = sheet_;
  bool converged = false;
  for (int pieces = 1; pieces <= kMaxGrowthPieces && !converged; pieces *= 2) {
    sheet_ = refined;
    if (pieces > 1) sheet_.positions = start_positions;  // a retry starts where the last step ended
    record.pieces = pieces;
    converged = grow_in_pieces(growth, pieces, static_cast<std::uint32_t>(record.growth_step), record);
  }
  if (!converged) {
    stopped_ = failure_message(record);
    sheet_ = before;
    motion_ = motion_before;
    equilibrium_.reset();
    return;
  }
  if (spec_.dilute) {
    const std::vector<double> new_mass = rest_vertex_masses(sheet_.topology, sheet_.rest);
    for (int m = 0; m < morphogens_; ++m) dilute(sheet_.values[static_cast<size_t>(m)], old_mass, new_mass);
  }
  motion_.resize(sheet_.positions.size());
  for (size_t i = 0; i < motion_.size(); ++i) motion_[i] = sheet_.positions[i] - start_positions[i];
  record.vertices = sheet_.topology.vertex_count;
  record.faces = static_cast<int>(sheet_.topology.faces.size());
  record.rest_area = rest_area(sheet_.rest);
  record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  records_.push_back(record);
  // The reaction–diffusion backend and the surface are the old sheet's now.
  if (reaction_) time_base_ += reaction_->time();
  reaction_.reset();
  surface_.reset();
}

const PreparedSurface& GrowthSimulation::surface() const {
  if (!surface_) surface_ = sheet_surface(sheet_, scene_.mesh);
  return *surface_;
}

int GrowthSimulation::substeps() const { return substeps_; }

IntrinsicVertexData<double> GrowthSimulation::area_growth() const {
  const size_t n = static_cast<size_t>(sheet_.topology.vertex_count);
  std::vector<double> weighted(n, 0.0), weight(n, 0.0);
  for (size_t f = 0; f < sheet_.topology.faces.size(); ++f) {
    const double area = metric_area(sheet_.rest.face_metric[f]);
    const double ratio = area / sheet_.initial_area[f];
    for (const int v : sheet_.topology.faces[f]) {
      weighted[static_cast<size_t>(v)] += area * ratio;
      weight[static_cast<size_t>(v)] += area;
    }
  }
  IntrinsicVertexData<double> growth(n, 1.0);
  for (size_t i = 0; i < n; ++i)
    if (weight[i] > 0.0) growth[i] = weighted[i] / weight[i];
  return growth;
}

// ---- layers ----
int GrowthSimulation::layer_count() const { return morphogens_; }
int GrowthSimulation::dynamic_layer_count() const { return morphogens_; }

int GrowthSimulation::add_static_layer(const IntrinsicVertexData<double>&) {
  throw InputError("growth simulation: add_static_layer: the growth model has no static layers");
}

IntrinsicVertexData<double> GrowthSimulation::field_values(int layer) const {
  check_layer_index(layer, morphogens_, "growth simulation", "field_values");
  if (reaction_) return reaction_->field_values(layer);
  return IntrinsicVertexData<double>(sheet_.values[static_cast<size_t>(layer)]);
}

void GrowthSimulation::set_field(const IntrinsicVertexData<double>& values, int layer) {
  if (!reaction_) rebuild_reaction();
  reaction_->set_field(values, layer);
}

void GrowthSimulation::fill_field(double value, int layer) {
  if (!reaction_) rebuild_reaction();
  reaction_->fill_field(value, layer);
}

FieldStatistics GrowthSimulation::field_statistics(double U, int layer) const {
  if (!reaction_) rebuild_reaction();
  return reaction_->field_statistics(U, layer);
}

double GrowthSimulation::time() const { return time_base_ + (reaction_ ? reaction_->time() : 0.0); }

// ---- checkpoints ----
SimulationState GrowthSimulation::save_state() const {
  SimulationState state;
  state.steps_taken = steps_;
  state.time = time();
  for (int m = 0; m < morphogens_; ++m) state.layers.push_back(field_values(m));
  const double inner_time = reaction_ ? reaction_->time() : 0.0;
  const double inner_steps = reaction_ ? static_cast<double>(reaction_->steps_taken()) : 0.0;
  std::vector<std::vector<double>>& a = state.model_arrays;
  a.resize(kFirstValues);
  a[kHeader] = {time_base_, inner_time, inner_steps, double(gauge_face_), double(sheet_.topology.vertex_count),
                double(sheet_.values.size()), double(sheet_.directions.size()), reaction_seconds_};
  for (const Eigen::Vector3d& p : sheet_.positions) a[kPositions].insert(a[kPositions].end(), {p.x(), p.y(), p.z()});
  for (const auto& f : sheet_.topology.faces) a[kFaces].insert(a[kFaces].end(), {double(f[0]), double(f[1]), double(f[2])});
  for (const Eigen::Matrix2d& g : sheet_.rest.face_metric) a[kMetrics].insert(a[kMetrics].end(), {g(0, 0), g(0, 1), g(1, 1)});
  a[kHingeAngles] = sheet_.rest.hinge_angle;
  a[kInitialArea] = sheet_.initial_area;
  for (const GrowthStepRecord& r : records_) {
    const std::vector<double> x = record_numbers(r);
    a[kRecords].insert(a[kRecords].end(), x.begin(), x.end());
  }
  for (const Eigen::Vector3d& d : motion_) a[kMotion].insert(a[kMotion].end(), {d.x(), d.y(), d.z()});
  for (size_t v = static_cast<size_t>(morphogens_); v < sheet_.values.size(); ++v) a.push_back(sheet_.values[v]);
  for (const std::vector<Eigen::Vector2d>& field : sheet_.directions) {
    std::vector<double> flat;
    for (const Eigen::Vector2d& d : field) flat.insert(flat.end(), {d.x(), d.y()});
    a.push_back(std::move(flat));
  }
  return state;
}

void GrowthSimulation::restore_state(const SimulationState& state) {
  const std::string who = "growth simulation: restore_state";
  const auto& a = state.model_arrays;
  if (a.size() < kFirstValues || a[kHeader].size() != 8)
    throw InputError(who + ": the state holds no growing sheet (a checkpoint of another model?)");
  const auto& h = a[kHeader];
  const size_t n = static_cast<size_t>(h[4]), values = static_cast<size_t>(h[5]), directions = static_cast<size_t>(h[6]);
  const size_t faces = a[kFaces].size() / 3;
  if (values != sheet_.values.size() || directions != sheet_.directions.size() ||
      a.size() != kFirstValues + (values - static_cast<size_t>(morphogens_)) + directions ||
      a[kPositions].size() != 3 * n || a[kMetrics].size() != 3 * faces || a[kInitialArea].size() != faces ||
      a[kRecords].size() % kRecordFields != 0 || state.layers.size() != static_cast<size_t>(morphogens_) ||
      (!a[kMotion].empty() && a[kMotion].size() != 3 * n))
    throw InputError(who + ": the sheet's arrays do not fit this scene's growth model");
  GrowingSheet sheet;
  std::vector<std::array<int, 3>> triangles(faces);
  for (size_t f = 0; f < faces; ++f)
    for (int c = 0; c < 3; ++c) {
      const double v = a[kFaces][3 * f + c];
      if (!(v >= 0 && v < double(n))) throw InputError(who + ": face " + std::to_string(f) + " uses a vertex that does not exist");
      triangles[f][c] = static_cast<int>(v);
    }
  sheet.topology = build_shell_topology(static_cast<int>(n), triangles);
  if (a[kHingeAngles].size() != sheet.topology.hinges.size()) throw InputError(who + ": the rest angles do not fit the sheet");
  for (size_t i = 0; i < n; ++i) sheet.positions.emplace_back(a[kPositions][3 * i], a[kPositions][3 * i + 1], a[kPositions][3 * i + 2]);
  for (size_t f = 0; f < faces; ++f) {
    Eigen::Matrix2d g;
    g << a[kMetrics][3 * f], a[kMetrics][3 * f + 1], a[kMetrics][3 * f + 1], a[kMetrics][3 * f + 2];
    sheet.rest.face_metric.push_back(g);
  }
  sheet.rest.hinge_angle = a[kHingeAngles];
  sheet.initial_area = a[kInitialArea];
  for (const IntrinsicVertexData<double>& layer : state.layers) {
    if (layer.size() != n) throw InputError(who + ": a morphogen layer does not have one value per vertex of the sheet");
    sheet.values.emplace_back(layer.begin(), layer.end());
  }
  size_t next = kFirstValues;
  for (size_t v = static_cast<size_t>(morphogens_); v < values; ++v, ++next) {
    if (a[next].size() != n) throw InputError(who + ": a carried map does not have one value per vertex of the sheet");
    sheet.values.push_back(a[next]);
  }
  for (size_t d = 0; d < directions; ++d, ++next) {
    if (a[next].size() != 2 * faces) throw InputError(who + ": a carried direction map does not have one vector per face");
    std::vector<Eigen::Vector2d> field;
    for (size_t f = 0; f < faces; ++f) field.emplace_back(a[next][2 * f], a[next][2 * f + 1]);
    sheet.directions.push_back(std::move(field));
  }
  std::vector<GrowthStepRecord> records;
  for (size_t r = 0; r < a[kRecords].size(); r += kRecordFields) records.push_back(record_from(&a[kRecords][r]));

  sheet_ = std::move(sheet);
  records_ = std::move(records);
  motion_.clear();
  for (size_t i = 0; i < a[kMotion].size(); i += 3) motion_.emplace_back(a[kMotion][i], a[kMotion][i + 1], a[kMotion][i + 2]);
  time_base_ = h[0];
  reaction_seconds_ = h[7];
  gauge_face_ = static_cast<int>(h[3]);
  steps_ = state.steps_taken;
  stopped_.reset();
  equilibrium_.reset();
  reaction_.reset();
  surface_.reset();
  rebuild_reaction();
  SimulationState inner;
  inner.time = h[1];
  inner.steps_taken = static_cast<long long>(h[2]);
  inner.layers = state.layers;
  reaction_->restore_state(inner);
}

}  // namespace physarum
