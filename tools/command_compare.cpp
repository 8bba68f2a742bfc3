// `physarum compare`: the differential harness's command line (api/comparison.hpp does the work).
#include "api/comparison.hpp"
#include "opencl/planted_faults.hpp"
#include "tools/commands.hpp"

#include <memory>
#include <string>

namespace physarum::cli {

Command add_compare_command(CLI::App& parent) {
  auto options = std::make_shared<ComparisonRequest>();
  CLI::App* app = parent.add_subcommand(
      "compare",
      "Differential harness: do two arms (the backends, or two --arm settings) simulate the same thing?\n"
      "Differential harness: decide whether two arms (the OpenCL backend and the reference, or one scene under two "
      "--arm settings) simulate the same thing (prints a JSON verdict; exit 0 equivalent, 3 different, "
      "4 inconclusive, 1 bad input, 2 usage error)");
  app->add_option("scene", options->scene, "Scene file (JSON); compare_* keys set the run length and margins")
      ->required();
  app->add_option("--arm", options->arms,
                  "An arm as scene overrides, key=value[,key=value...] (plus backend=reference|opencl, "
                  "device=SPEC); give it twice. Default: OpenCL against the reference");
  app->add_option("--max-seeds,--seeds", options->max_seeds,
                  "Seeds per arm at most (default: compare_seeds of the scene, else 64); the sequential test stops "
                  "earlier when it can. With --store-reference: the seeds stored (default 100)");
  app->add_option("--jobs", options->jobs, "Worker threads for reference seeds (default: the cores)");
  app->add_option("--device", options->device, "OpenCL device: index from `physarum devices` or a name substring");
  std::string faults;
  for (const opencl::PlantedFault& f : opencl::planted_faults()) faults += std::string("\n  ") + f.name + ": " + f.what;
  faults += std::string("\n  ") + kHarnessFault +
            ": the harness's own: two triangulations compared by mean and coverage only (no common sampling)";
  app->add_option("--fault", options->fault, "Plant a deliberate bug in the OpenCL kernels (or the harness):" + faults);
  app->add_option("--out", options->out, "Folder for verdict.json, seed_metrics.csv and spectra.png");
  app->add_option("--reference-stats", options->reference_stats,
                  "Stored per-seed reference metrics to use instead of running the reference arm");
  app->add_option("--reference-seeds", options->reference_seeds,
                  "Fresh reference seeds run against --reference-stats to detect drift")
      ->capture_default_str();
  app->add_option("--store-reference", options->store_reference,
                  "Run only the reference (--seeds of them) and store its per-seed metrics in this file");
  return Command{app, [options] { return run_comparison(*options); }};
}

}  // namespace physarum::cli
