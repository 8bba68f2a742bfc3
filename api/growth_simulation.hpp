#pragma once
// The growth model (paper 003) as one more SimulationBackend, so `physarum run`'s one loop, its
// checkpoints and the library's Session drive it like the other models: a reaction–diffusion
// system (either backend, rebuilt on the sheet's rest metric whenever the sheet grew) on a thin
// elastic sheet that grows.
//
// One step() is one step of the scene's schedule (common/scene/scene_growth.hpp): a reaction–
// diffusion step, or a growth step:
//   1. refine: rest edges longer than refine.max_edge are split (common/growth/sheet_refinement.hpp);
//   2. grow: each face's rest metric grows (Eq. 6 or 7 of its mean concentrations, or the
//      prescribed stretch; along and across a direction map when anisotropic);
//   3. dilute (optional): concentrations scaled by old / new rest mass, so amounts are conserved;
//   4. start from the last step's shape moved on by that step's motion (a predictor), nudge the sheet
//      out of its plane (seeded) and solve for static equilibrium (Newton); a solve
//      that does not converge is retried with the step's growth in 2, 4, 8 equal sub-steps.
// A growth step that does not converge even so is undone (the sheet stays the last converged one)
// and the simulation stops: stopped() says why, and later steps do nothing.
//
// The layers are the morphogens, per vertex of the sheet as it is now (their count grows with
// refinement). Checkpoints hold the whole sheet (SimulationState::model_arrays), so a resumed run
// continues bit for bit.
#include "common/growth/face_growth.hpp"
#include "common/growth/sheet_refinement.hpp"
#include "common/reaction_diffusion/reaction_diffusion_system.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/growing_sheet_surface.hpp"
#include "common/shell/shell_equilibrium.hpp"
#include "common/simulation/simulation_backend.hpp"
#include "common/surface/prepared_surface.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// What one growth step did (run.json's per-step records).
struct GrowthStepRecord {
  int growth_step = 0;  // 1-based
  int splits = 0;       // edges split before growing
  int vertices = 0, faces = 0;
  int newton_iterations = 0, factorizations = 0;
  double residual = 0.0;
  double membrane_energy = 0.0, bending_energy = 0.0;  // joules, at equilibrium
  double rest_area = 0.0;                              // m^2, after the step
  double seconds = 0.0;                                // wall time of the step (not restored: a timing)
  int pieces = 1;  // equal sub-steps the growth was applied in (more than 1 when the whole one failed)
};

// A growth step whose solve fails is retried in 2, 4, ... up to this many equal sub-steps.
inline constexpr int kMaxGrowthPieces = 8;

// Builds a reaction–diffusion backend for a domain (the chosen backend and device: api/backend_factory.hpp).
using ReactionBackendMaker = std::function<std::unique_ptr<SimulationBackend>(const SurfaceDomain&, ReactionDiffusionSystem)>;

class GrowthSimulation final : public SimulationBackend {
 public:
  // `scene` a growth scene; `surface` = sheet_surface(initial_sheet(scene)) and `maps` the scene's
  // maps on it (as api/feasible_surface.hpp evaluates them).
  GrowthSimulation(const Scene& scene, const PreparedSurface& surface, const EvaluatedMaps& maps, ReactionBackendMaker make);
  ~GrowthSimulation() override;

  void step() override;
  void finish() override;

  int layer_count() const override;
  int dynamic_layer_count() const override;
  int add_static_layer(const IntrinsicVertexData<double>& values) override;
  IntrinsicVertexData<double> field_values(int layer = 0) const override;
  void set_field(const IntrinsicVertexData<double>& values, int layer = 0) override;
  void fill_field(double value, int layer = 0) override;
  FieldStatistics field_statistics(double U, int layer = 0) const override;

  double time() const override;
  long long steps_taken() const override { return steps_; }
  std::vector<int> agent_faces() const override { return {}; }
  SimulationCounters counters() const override { return {}; }

  SimulationState save_state() const override;
  void restore_state(const SimulationState& state) override;

  std::string backend_name() const override { return backend_name_; }
  std::string device_name() const override { return device_name_; }

  // ---- the growing sheet ----
  const GrowingSheet& sheet() const { return sheet_; }
  // The sheet as a surface now (its current shape; the domain on its rest metric).
  const PreparedSurface& surface() const;
  const std::vector<GrowthStepRecord>& records() const { return records_; }
  int growth_steps_done() const { return static_cast<int>(records_.size()); }
  double initial_rest_area() const { return initial_rest_area_; }
  // Per vertex: the rest area of the tissue around it over what it was at the start (the mean of
  // its faces' ratios, weighted by their rest areas).
  IntrinsicVertexData<double> area_growth() const;
  // Why the run stopped early (a Newton solve that did not converge), or nullopt.
  const std::optional<std::string>& stopped() const { return stopped_; }
  // Wall seconds spent in reaction–diffusion steps (backend rebuilds included), for run.json.
  double reaction_seconds() const { return reaction_seconds_; }
  // Explicit sub-steps per reaction–diffusion step on the current sheet.
  int substeps() const;

 private:
  void grow();
  // Splits the rest edges longer than `max_edge` (the sheet's fields and the last step's motion
  // carried onto new vertices); returns the splits.
  int refine(double max_edge);
  // What stopped() says when growth step `record` could not be solved, with what to change.
  std::string failure_message(const GrowthStepRecord& record) const;
  // Grows the sheet by `growth` in `pieces` equal sub-steps, each solved to equilibrium (the nudge
  // before the first); false when a solve does not converge. Adds the solves to `record`.
  bool grow_in_pieces(const FaceGrowth& growth, int pieces, std::uint32_t growth_step, GrowthStepRecord& record);
  void rebuild_reaction() const;  // the backend on the current sheet, from sheet_.values
  void sync_values_from_backend();
  ShellEquilibrium& equilibrium();
  FaceGrowth face_growth() const;

  Scene scene_;                 // the growth scene
  Scene reaction_scene_;        // its reaction–diffusion system as a scene
  const GrowthSpec& spec_;      // scene_'s
  ReactionBackendMaker make_;
  GrowingSheet sheet_;
  SheetMapLayout layout_;
  int morphogens_ = 0;
  std::string backend_name_, device_name_;
  double initial_rest_area_ = 0.0;

  // The reaction–diffusion backend on the sheet as it is; rebuilt lazily after a growth step.
  mutable std::unique_ptr<SimulationBackend> reaction_;
  mutable std::optional<PreparedSurface> surface_;
  mutable int substeps_ = 1;
  double time_base_ = 0.0;  // simulated seconds before the current backend was built
  std::unique_ptr<ShellEquilibrium> equilibrium_;  // for the current topology
  // The face whose coordinates fix the rigid motion: chosen once on the initial sheet and kept (a
  // split face keeps its index for its first child), so a resumed run gauges as the original did.
  int gauge_face_ = 0;

  // Each vertex's motion in the last growth step (empty before the first): the predictor of the next.
  std::vector<Eigen::Vector3d> motion_;
  long long steps_ = 0;
  double reaction_seconds_ = 0.0;  // a timing, kept through checkpoints like the records' seconds
  std::vector<GrowthStepRecord> records_;
  std::optional<std::string> stopped_;
};

}  // namespace physarum
