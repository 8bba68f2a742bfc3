#pragma once
// The two arms of a `physarum compare`: what each simulates and how one seed of it is run. By
// default the arms are the two backends on one scene (OpenCL against the reference); with
// `--arm K=V[,K=V...]` given twice they are one scene under two settings or discretisations
// (max_circumradius, time_step, agents, integrator, backend, device, ...), so claims such as "the
// pattern no longer changes once the triangulation is fine enough" become commands with verdicts.
//
// Reaction-diffusion scenes are compared the same way (their own metric set; an --arm may set
// integrator, max_circumradius, time_step, backend, device and the like).
//
// An arm's seeds never overlap the other's: arm 0 runs seeds scene.seed + i, arm 1 scene.seed +
// 100000 + i (the reference arm's numbering, which stored statistics depend on).
#include "api/compare/comparison_fields.hpp"
#include "api/comparison.hpp"
#include "common/harness/comparison_metrics.hpp"
#include "common/scene/scene.hpp"
#include "common/setup/scene_maps.hpp"
#include "common/setup/scene_surface.hpp"
#include "common/setup/workload.hpp"
#include "opencl/runtime/compute_context.hpp"
#include "opencl/agent_simulation.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace physarum {

// One --arm: scene keys to override, and the arm's backend and device.
struct ArmSpec {
  std::string label;                                   // the text as given, for reports
  nlohmann::json scene_overrides = nlohmann::json::object();
  std::optional<BackendChoice> backend;                // "backend=reference|opencl"
  std::optional<std::string> device;                   // "device=SPEC"
};

// Parses "key=value[,key=value...]". Values are JSON where they parse as JSON (numbers, true, null)
// and strings otherwise; `backend` and `device` choose the arm's backend and OpenCL device, every
// other key is a scene key (checked when the scene is read). UsageError on malformed text.
ArmSpec parse_arm(const std::string& text);

constexpr std::uint32_t kSecondArmSeedOffset = 100000;

// One arm of a comparison: a scene, the backend that runs it, and how one seed of it is run and
// measured. The agent model and reaction-diffusion systems differ only in that last part (their
// metric sets, common/harness/comparison_metrics.hpp and common/harness/reaction_diffusion_metrics.hpp, and how a
// fresh simulation is built), so it is a function of the arm; the seed numbering, the threads that
// run the seeds (api/compare/seed_runner.hpp) and the verdict (api/compare/comparison.cpp) are shared.
struct Arm {
  std::string label;
  // The arm's scene. Agent model: a parameter given by a map holds its mean over the surface
  // (with_mean_parameters: what U and the metrics' length scales read).
  Scene scene;
  BackendChoice backend = BackendChoice::Reference;
  std::shared_ptr<const PreparedSurface> surface;
  std::vector<MetricInfo> metrics;     // what measure returns, in order, with the margins
  std::vector<std::string> left_out;   // metrics of the documented set this scene cannot judge, and why
  std::optional<opencl::ComputeContext> compute;  // OpenCL arms
  opencl::OpenCLBackendOptions options;        // OpenCL arms: planted faults
  std::uint32_t seed_offset = 0;
  // The steady mean / U the arm's time-discrete model reaches (common/setup/agent_inputs.hpp:
  // expected_mean_over_U) where its continuous mean is U (steady_mean_is_U); unset otherwise.
  std::optional<double> expected_mean_over_U;
  // Builds a fresh simulation of `seeded` (the arm's scene with one seed) on `arm`'s backend, with
  // its planted faults (`compute`: the OpenCL context or queue to run it on, null for the reference),
  // and returns its time-averaged metrics; `final_field` (when given) receives the field the seed
  // ends with (the preview morphogen's, for reaction-diffusion). Safe to call from several threads at once.
  std::function<std::vector<double>(const Arm& arm, const Scene& seeded, const opencl::ComputeContext* compute,
                                    IntrinsicVertexData<double>* final_field)>
      measure;
  // Every seed's final field, for the picture of `compare --out` (api/compare/comparison_fields.hpp);
  // null when no picture is asked for (no field is then read back).
  std::shared_ptr<SeedFields> fields;
  // The colour levels of its field in that picture (the agent model: 0 .. 2 U, as the gallery's
  // previews); unset: the range of the fields.
  std::optional<std::array<double, 2>> field_levels;
  // The harness's own planted fault (kHarnessFault): this arm and the other, on two triangulations,
  // get no common sampling, so only mean and coverage compare them, as before the sampling existed.
  bool common_sampling_withheld = false;
  // Where the arm's preparation tells its user about the surface (its refinement, warnings); none: quiet.
  SurfaceNote log;

  std::uint32_t seed(int index) const { return scene.seed + seed_offset + static_cast<std::uint32_t>(index); }
  // Runs seed `index` from a fresh simulation and returns its time-averaged metrics; an OpenCL arm
  // runs it on `stream` (a queue of its context) when given, else on its context's own queue.
  std::vector<double> run_seed(int index, const opencl::ComputeContext* stream = nullptr) const;
};

struct ArmsRequest {
  std::string scene_path;
  std::vector<ArmSpec> arms;  // none (the two backends) or exactly two
  std::string device;         // default OpenCL device
  std::string fault_build_option;  // planted into every OpenCL arm
  bool reference_only = false;     // --store-reference: only the reference arm is built
  bool withhold_common_sampling = false;  // the harness's planted fault (Arm::common_sampling_withheld)
  bool keep_fields = false;               // keep every seed's final field (Arm::fields), for --out
  SurfaceNote log;                        // the surfaces' notes (Arm::log); none: quiet
};

// The arms in order (0: the arm judged, 1: the arm it is judged against, whose means set relative
// margins). Surfaces that are the same are built once; when the arms differ in surface or agent
// count, the metrics tied to one discretisation are left out (ArmsShare). A reaction-diffusion
// scene gets reaction-diffusion arms: each seed builds the system with its own seed (its noise and
// spots) and is measured by common/harness/reaction_diffusion_metrics.hpp, with the pattern scale of the
// arm judged against. `agents` in an --arm
// without `deposit_rate` rescales the deposit so that U (Eq. 5) stays the scene's, as the paper's
// agent-count study does (Fig. 10c). Throws InputError when the arms' metric sets differ.
std::vector<Arm> make_arms(const ArmsRequest& request);

// ---- shared by the models' arms (api/compare/comparison_model.hpp) ----
// Steps of one seed (burn-in + duration): the run whose work the fail-fast checks estimate.
long long steps_per_seed(const Scene& scene);
// True when two arms' scenes ask for the same surface (built once then).
bool same_surface_keys(const Scene& a, const Scene& b);
// What the arms' metrics can share: one discretisation, or a common sampling of two triangulations
// of one input surface (or why there is none).
ArmsShare arms_share(const std::vector<Arm>& arms, bool same_discretisation);

}  // namespace physarum
