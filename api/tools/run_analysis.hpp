#pragma once
// Pattern analysis of a run (issue 21; the measures are common/pattern/pattern_analysis.hpp): the
// field read back from a finished run's folder (its finest result: fields_full.ply, every intrinsic
// vertex with exact values; else the fields file on the input mesh), or a field on a mesh in memory
// (a running Session's), segmented into spots and stripes and measured. `physarum analyze` writes
// the JSON as analysis.json with its histograms; the Python module's analyze() returns it.
#include "common/mesh/input_mesh.hpp"
#include "common/pattern/pattern_analysis.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace physarum {

struct PatternAnalysisRequest {
  std::string field;                   // "" = run.json's "preview_morphogen" when it records one, else "pheromone"
  std::optional<double> threshold;     // none: the area-weighted mean + 0.5 std (- 0.5 std with `below`)
  bool below = false;                  // segment where the field is below the threshold
  double min_area = 0.0;               // leave out smaller regions
  std::vector<std::string> direction;  // {MAP.ply, NAME} (a vector map's face properties NAME_x, ...) or empty
};

struct RunAnalysis {
  PatternAnalysis analysis;
  nlohmann::json json;  // analysis.json: per region area, centre, aspect, orientation, stripe width; spacing; summaries
  std::string field;    // the field analysed
  std::string source;   // the file it was read from ("" for a field in memory)
};

// A finished run's folder. InputError naming the folder, file or field when one is missing or unreadable.
RunAnalysis analyze_run_folder(const std::string& run_dir, const PatternAnalysisRequest& request);

// `values` per vertex of `mesh`, named `name` in the JSON.
RunAnalysis analyze_field(const InputMesh& mesh, const InputVertexData<double>& values, const std::string& name,
                          const PatternAnalysisRequest& request);

}  // namespace physarum
