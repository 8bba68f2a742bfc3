// `physarum analyze RUN_DIR [--field NAME] [--threshold T] [--below] [--min-area A] [--direction MAP.ply NAME] [--out DIR]`:
// pattern analysis of a finished run (issue 21). The field is read back from the run's finest result
// (RUN_DIR/fields_full.ply: every intrinsic vertex, exact values; else pheromone.ply on the input
// mesh), segmented into spots and stripes and measured (common/pattern/pattern_analysis.hpp):
//   DIR/analysis.json  per region area, centre, aspect ratio, orientation, stripe width; spacing of
//                      neighbouring spots; summary statistics
//   DIR/analysis.png   histograms of spot area, spacing and aspect ratio
// The field defaults to run.json's "preview_morphogen" (a reaction-diffusion run's shown morphogen)
// when it records one, else "pheromone". Everything is read and analysed before DIR is touched, and
// both files are written under temporary names and renamed, so a bad run folder writes nothing.
#include "api/tools/run_analysis.hpp"
#include "common/base/atomic_write.hpp"
#include "common/output/pattern_histograms.hpp"
#include "tools/commands.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

struct AnalyzeOptions : PatternAnalysisRequest {
  std::string run_dir;
  std::string out;  // "" = RUN_DIR
};

int run_analyze(const AnalyzeOptions& o) {
  // ---- read and analyse everything first ----
  const RunAnalysis run = analyze_run_folder(o.run_dir, o);
  const PatternAnalysis& analysis = run.analysis;
  const nlohmann::json& j = run.json;
  const fs::path run_dir(o.run_dir);

  std::vector<HistogramPanel> panels(3);
  panels[0] = {"spot area (" + std::to_string(j["spot_count"].get<int>()) + " spots)", "area", {}};
  panels[1] = {"neighbour spacing (" + std::to_string(analysis.pairs.size()) + " pairs)", "geodesic distance", {}};
  panels[2] = {"aspect ratio", "major / minor axis", {}};
  for (const AnalysedRegion& r : analysis.regions) {
    if (!r.is_stripe) panels[0].values.push_back(r.area);
    panels[2].values.push_back(r.shape.aspect_ratio);
  }
  for (const SpotPair& p : analysis.pairs) panels[1].values.push_back(p.distance);

  // ---- then write ----
  const fs::path out = o.out.empty() ? run_dir : fs::path(o.out);
  create_output_folder(out.string());
  write_text_file_atomically((out / "analysis.json").string(), j.dump(2) + "\n");
  write_histograms_png((out / "analysis.png").string(), panels);

  const auto& spacing = j["spacing"];
  const auto& width = j["stripe_width"];
  std::cout << "analyze: " << run.field << " from " << run.source << ", threshold " << analysis.threshold
            << ": " << j["spot_count"] << " spots, " << j["stripe_count"] << " stripes; spacing "
            << (spacing["mean"].is_null() ? std::string("-") : spacing["mean"].dump()) << " (" << spacing["count"]
            << " pairs), stripe width " << (width["mean"].is_null() ? std::string("-") : width["mean"].dump())
            << "; wrote " << out.string() << "/{analysis.json, analysis.png}\n";
  return 0;
}

}  // namespace

Command add_analyze_command(CLI::App& parent) {
  auto options = std::make_shared<AnalyzeOptions>();
  CLI::App* app = parent.add_subcommand(
      "analyze",
      "Pattern analysis of a finished run: spots, stripes and their spacing\n"
      "Pattern analysis of a finished run: segments the spots and stripes of a field (the part above a threshold) "
      "on the surface and writes DIR/analysis.json (per spot area, centre, aspect ratio, orientation; spacing of "
      "neighbouring spots; stripe width) and DIR/analysis.png (histograms). Example: physarum analyze out --field v");
  app->footer("Exit codes: 0 success, 1 bad input (a missing run folder or field, a field with nothing above the "
              "threshold; nothing is written), 2 usage error.");
  app->add_option("run_dir", options->run_dir, "Output folder of `physarum run`")->required();
  app->add_option("--field", options->field,
                  "Vertex property to analyse (default: run.json's preview_morphogen, else pheromone)");
  app->add_option("--threshold", options->threshold,
                  "Regions are where the field exceeds T (default: its area-weighted mean + 0.5 standard deviations)");
  app->add_flag("--below", options->below,
               "Segment where the field is BELOW the threshold (default threshold: mean - 0.5 standard deviations): "
               "the cells between a network's strands, the gaps between stripes");
  app->add_option("--min-area", options->min_area,
                  "Leave out regions smaller than this area (mesh units squared; specks of noise at the threshold)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app->add_option("--direction", options->direction,
                  "MAP.ply NAME: a vector map (face properties NAME_x, NAME_y, NAME_z, as `physarum map` writes) to "
                  "measure each spot's orientation against")
      ->expected(2);
  app->add_option("--out", options->out, "Output folder (default: RUN_DIR)");
  return Command{app, [options] { return run_analyze(*options); }};
}

}  // namespace physarum::cli
