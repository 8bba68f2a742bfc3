#include "api/tools/run_analysis.hpp"

#include "common/base/errors.hpp"
#include "common/mesh/ply_reader.hpp"
#include "common/pattern/face_direction_field.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace physarum {
namespace {

namespace fs = std::filesystem;

// What run.json says of the files: the field the pictures show ("preview_morphogen" of
// reaction-diffusion runs) and the name of the result on the input mesh ("fields_file": pheromone.ply
// or morphogens.ply; runs before the key wrote pheromone.ply).
struct RunHints {
  std::optional<std::string> preview_morphogen;
  std::string fields_file = "pheromone.ply";
};

RunHints run_hints(const fs::path& run_dir) {
  const fs::path path = run_dir / "run.json";
  std::ifstream in(path);
  RunHints hints;
  if (!in) return hints;  // the PLY files are what the analysis needs; run.json is optional
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string() + ": not valid JSON: " + e.what());
  }
  if (j.contains("preview_morphogen") && j["preview_morphogen"].is_string())
    hints.preview_morphogen = j["preview_morphogen"].get<std::string>();
  if (j.contains("fields_file") && j["fields_file"].is_string()) hints.fields_file = j["fields_file"].get<std::string>();
  return hints;
}

// The direction map: face properties NAME_x, NAME_y, NAME_z (as `physarum map` writes vector maps).
FaceDirectionField read_direction_field(const std::string& path, const std::string& name) {
  PlyFields ply = read_ply_fields(path);
  FaceDirectionField field;
  const std::vector<double>& x = ply.face_property(name + "_x");
  const std::vector<double>& y = ply.face_property(name + "_y");
  const std::vector<double>& z = ply.face_property(name + "_z");
  for (size_t f = 0; f < x.size(); ++f) {
    field.directions.emplace_back(x[f], y[f], z[f]);
    if (!field.directions.back().allFinite())
      throw InputError(path + ": direction " + name + " is not finite at face " + std::to_string(f));
  }
  field.mesh = std::move(ply.mesh);
  return field;
}

}  // namespace

RunAnalysis analyze_field(const InputMesh& mesh, const InputVertexData<double>& values, const std::string& name,
                          const PatternAnalysisRequest& request) {
  if (request.threshold && !std::isfinite(*request.threshold)) throw UsageError("--threshold must be a finite number");
  if (!request.direction.empty() && request.direction.size() != 2)
    throw UsageError("--direction takes two values: MAP.ply NAME");
  std::optional<FaceDirectionField> direction;
  if (!request.direction.empty()) direction = read_direction_field(request.direction[0], request.direction[1]);
  PatternAnalysisOptions options;
  options.threshold = request.threshold;
  options.below = request.below;
  options.min_area = request.min_area;
  options.direction = direction ? &*direction : nullptr;
  RunAnalysis r;
  r.analysis = analyze_pattern(mesh, values, options);
  r.json = pattern_analysis_json(r.analysis, name);
  r.field = name;
  if (direction) r.json["direction"] = {{"map", request.direction[0]}, {"name", request.direction[1]}};
  return r;
}

RunAnalysis analyze_run_folder(const std::string& folder, const PatternAnalysisRequest& request) {
  const fs::path run_dir(folder);
  if (!fs::is_directory(run_dir)) throw InputError(run_dir.string() + ": no such folder (give a `physarum run` output folder)");
  const RunHints hints = run_hints(run_dir);
  fs::path source = run_dir / "fields_full.ply";
  if (!fs::exists(source)) source = run_dir / hints.fields_file;
  if (!fs::exists(source)) throw InputError(run_dir.string() + ": has neither fields_full.ply nor " + hints.fields_file);
  const PlyFields ply = read_ply_fields(source.string());
  const std::string name = request.field.empty() ? hints.preview_morphogen.value_or("pheromone") : request.field;
  RunAnalysis r = analyze_field(ply.mesh, InputVertexData<double>(ply.property(name)), name, request);
  r.source = source.filename().string();
  r.json["source"] = r.source;
  return r;
}

}  // namespace physarum
