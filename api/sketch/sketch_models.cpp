#include "api/sketch/sketch_models.hpp"

#include "common/base/errors.hpp"

namespace physarum {

const std::vector<SketchModel>& sketch_models() {
  // rate_time: the gallery scenes' runs (tools/scenes/turing_spots.json, meinhardt_spots.json) at the
  // models' default rates, after which their spots no longer move; make_training_data.sh runs each
  // training rate for the same rate x time.
  static const std::vector<SketchModel> models = {
      {"turing-spots", "ka", "a", 250.0, "turing_spots.csv"},
      {"meinhardt-spots", "s", "b", 1600.0, "meinhardt_spots.csv"},
      // Stripes: a's; tools/scenes/meinhardt_stripes.json's labyrinth at s = 1 has settled by 3000 s.
      {"meinhardt-stripes", "s", "a", 3000.0, "meinhardt_stripes.csv", true},
  };
  return models;
}

const SketchModel& sketch_model(const std::string& name) {
  std::string known;
  for (const SketchModel& m : sketch_models()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw UsageError("--model " + name + ": not a model a sketch can drive (" + known + ")");
}

std::vector<TrainingRun> training_runs(const SketchModel& model) {
  for (const auto& [name, text] : embedded_training_files())
    if (name == model.training) return read_training_runs(text, "tools/sketch/training/" + name);
  throw InputError("tools/sketch/training/" + model.training + ": not built into this program (run "
                   "tools/sketch/make_training_data.sh " + model.name + " and rebuild)");
}

}  // namespace physarum
