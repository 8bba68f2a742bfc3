#include "tools/sweep/sweep_plan.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"
#include "common/scene/scene.hpp"
#include "common/scene/scene_overrides.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// Splits at commas that are not inside [], {} or a double-quoted string.
std::vector<std::string> split_top_level(const std::string& text) {
  std::vector<std::string> parts(1);
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '\\' && i + 1 < text.size()) {
        parts.back() += c;
        parts.back() += text[++i];
        continue;
      }
      if (c == '"') quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ',' && depth == 0) {
      parts.emplace_back();
      continue;
    }
    parts.back() += c;
  }
  return parts;
}

std::string trim(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// One CSV line's fields (RFC 4180 quoting).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) f = trim(f);
  return fields;
}

// --set's text for a value: strings as they are (parse_scene_value gives them back as strings),
// everything else as compact JSON.
std::string set_text(const std::string& key, const nlohmann::json& value) {
  return key + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
}

std::uint32_t scene_seed(const std::string& scene) {
  std::ifstream file(scene);
  if (!file) throw InputError(scene + ": cannot open the scene file");
  const nlohmann::json j = nlohmann::json::parse(file, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(scene + ": not a JSON object (a scene file)");
  if (!j.contains("seed")) return 1;
  if (!j["seed"].is_number_unsigned()) throw InputError(scene + ": key 'seed' must be a non-negative integer");
  return j["seed"].get<std::uint32_t>();
}

}  // namespace

bool SweepJob::finished() const { return fs::exists(fs::path(out) / "run.json"); }

bool SweepJob::resumes() const { return !finished() && fs::exists(fs::path(out) / "checkpoint.bin"); }

std::vector<std::string> SweepJob::run_args() const {
  if (resumes()) return {"run", args.at(1), "--resume", out};
  return args;
}

int SweepPlan::variant_count() const {
  if (!csv_keys.empty()) return static_cast<int>(csv_rows.size());
  int n = 1;
  for (const SweepAxis& a : axes) n *= static_cast<int>(a.values.size());
  return n;
}

nlohmann::ordered_json SweepPlan::variant(int v) const {
  nlohmann::ordered_json overrides = nlohmann::ordered_json::object();
  if (!csv_keys.empty()) {
    for (std::size_t k = 0; k < csv_keys.size(); ++k) overrides[csv_keys[k]] = csv_rows.at(static_cast<std::size_t>(v))[k];
    return overrides;
  }
  // Mixed radix, the last axis fastest.
  std::vector<std::size_t> digit(axes.size());
  int rest = v;
  for (std::size_t a = axes.size(); a-- > 0;) {
    const int n = static_cast<int>(axes[a].values.size());
    digit[a] = static_cast<std::size_t>(rest % n);
    rest /= n;
  }
  for (std::size_t a = 0; a < axes.size(); ++a) overrides[axes[a].key] = axes[a].values[digit[a]];
  return overrides;
}

std::vector<std::string> SweepPlan::varied_keys() const {
  if (!csv_keys.empty()) return csv_keys;
  std::vector<std::string> keys;
  for (const SweepAxis& a : axes) keys.push_back(a.key);
  return keys;
}

std::vector<SweepJob> SweepPlan::jobs() const {
  std::vector<SweepJob> jobs;
  for (int v = 0; v < variant_count(); ++v) {
    for (const std::uint32_t seed : seeds) {
      SweepJob job;
      job.index = static_cast<int>(jobs.size());
      job.overrides = variant(v);
      job.seed = seed;
      char name[32];
      std::snprintf(name, sizeof name, "run_%04d", job.index);
      job.out = (fs::path(folder) / name).string();
      job.args = {"run", inputs.scene};
      for (auto it = job.overrides.begin(); it != job.overrides.end(); ++it) {
        job.args.push_back("--set");
        job.args.push_back(set_text(it.key(), inputs.rename(it.value())));
      }
      job.args.push_back("--seed");
      job.args.push_back(std::to_string(seed));
      for (const std::string& option : run_options) job.args.push_back(option);
      job.args.push_back("--out");
      job.args.push_back(name);
      jobs.push_back(std::move(job));
    }
  }
  return jobs;
}

SweepAxis parse_vary(const std::string& text) {
  const std::size_t eq = text.find('=');
  SweepAxis axis;
  axis.key = trim(text.substr(0, eq));
  if (eq == std::string::npos || axis.key.empty())
    throw UsageError("--vary '" + text + "': expected KEY=V1,V2,... (KEY may be nested: maps.ramp.range=[0,1],[0.5,1.5])");
  for (const std::string& part : split_top_level(text.substr(eq + 1))) {
    const std::string value = trim(part);
    if (value.empty()) throw UsageError("--vary '" + text + "': an empty value");
    axis.values.push_back(parse_scene_value(value));
  }
  return axis;
}

void read_variant_csv(const std::string& path, std::vector<std::string>& keys, std::vector<std::vector<nlohmann::json>>& rows) {
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open the CSV of variants");
  std::string line;
  int number = 0;
  keys.clear();
  rows.clear();
  while (std::getline(file, line)) {
    ++number;
    if (trim(line).empty()) continue;
    std::vector<std::string> fields = csv_fields(line);
    if (keys.empty()) {
      for (const std::string& k : fields)
        if (k.empty()) throw InputError(path + ":" + std::to_string(number) + ": an empty key in the header line");
      keys = fields;
      continue;
    }
    if (fields.size() != keys.size())
      throw InputError(path + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) + " fields, the header has " +
                       std::to_string(keys.size()));
    std::vector<nlohmann::json> row;
    for (const std::string& f : fields) {
      if (f.empty()) throw InputError(path + ":" + std::to_string(number) + ": an empty value");
      row.push_back(parse_scene_value(f));
    }
    rows.push_back(std::move(row));
  }
  if (keys.empty()) throw InputError(path + ": empty (the first line names the keys, each further line is a variant)");
  if (rows.empty()) throw InputError(path + ": no variants after the header line");
}

// Refuses a sweep of more than kMaxSweepJobs jobs before anything is expanded: its size is the
// product of the value counts (or the CSV's rows) times the seeds, computed in floating point so a
// product past any integer type is still a number to show.
void check_sweep_size(const SweepPlan& plan, int seeds) {
  double jobs = seeds;
  if (!plan.csv_keys.empty()) jobs *= static_cast<double>(plan.csv_rows.size());
  for (const SweepAxis& a : plan.axes) jobs *= static_cast<double>(a.values.size());
  if (jobs > static_cast<double>(kMaxSweepJobs)) {
    std::ostringstream count;
    count.precision(15);
    count << jobs;
    throw UsageError("a sweep of " + count.str() + " jobs (the values of every --vary multiplied, times --seeds) is more "
                     "than the " + std::to_string(kMaxSweepJobs) + " one sweep plans; split it into several sweeps");
  }
}

SweepPlan make_sweep_plan(const std::string& scene, const std::vector<std::string>& vary, const std::string& csv,
                          int seeds, const std::vector<std::string>& run_options, const std::string& folder) {
  if (seeds < 1) throw UsageError("--seeds " + std::to_string(seeds) + " must be >= 1");
  if (!vary.empty() && !csv.empty()) throw UsageError("--vary and --csv do not go together: give the grid or the rows");
  SweepPlan plan;
  plan.scene_source = absolute(scene);
  plan.folder = absolute(folder);
  plan.run_options = run_options;
  std::set<std::string> seen;
  for (const std::string& text : vary) {
    plan.axes.push_back(parse_vary(text));
    if (!seen.insert(plan.axes.back().key).second) throw UsageError("--vary: key '" + plan.axes.back().key + "' varied twice");
  }
  if (!csv.empty()) {
    read_variant_csv(csv, plan.csv_keys, plan.csv_rows);
    for (const std::string& key : plan.csv_keys)
      if (!seen.insert(key).second) throw InputError(csv + ": key '" + key + "' is a column twice");
  }
  check_sweep_size(plan, seeds);
  const std::uint32_t first = scene_seed(plan.scene_source);
  for (int k = 0; k < seeds; ++k) plan.seeds.push_back(first + static_cast<std::uint32_t>(k));
  plan.inputs = plan_frozen_inputs(plan.scene_source, variant_values(plan));
  return plan;
}

std::vector<nlohmann::json> variant_values(const SweepPlan& plan) {
  std::vector<nlohmann::json> values;
  for (const SweepAxis& a : plan.axes) values.insert(values.end(), a.values.begin(), a.values.end());
  for (const auto& row : plan.csv_rows) values.insert(values.end(), row.begin(), row.end());
  return values;
}

void check_sweep_variants(const SweepPlan& plan) {
  for (int v = 0; v < plan.variant_count(); ++v) {
    const nlohmann::ordered_json overrides = plan.variant(v);
    try {
      load_scene(plan.scene_source, nlohmann::json(overrides));
    } catch (const InputError& e) {
      throw InputError("variant " + std::to_string(v) + " " + overrides.dump() + ": " + e.what());
    }
  }
}

namespace {

nlohmann::ordered_json plan_json(const SweepPlan& plan) {
  nlohmann::ordered_json j;
  j["scene"] = plan.inputs.scene;
  j["axes"] = nlohmann::ordered_json::array();
  for (const SweepAxis& a : plan.axes) j["axes"].push_back({{"key", a.key}, {"values", a.values}});
  j["csv_keys"] = plan.csv_keys;
  j["csv_rows"] = plan.csv_rows;
  j["seeds"] = plan.seeds;
  j["run_options"] = plan.run_options;
  j["jobs"] = plan.variant_count() * static_cast<int>(plan.seeds.size());
  j["inputs"] = plan.inputs.to_json();
  return j;
}

// Why a folder's sweep is not the one being planned: the inputs that differ by name, else the plan.
std::string how_it_differs(const SweepPlan& there, const SweepPlan& planned) {
  std::map<std::string, std::string> hash_of;  // source -> hash, as planned now
  for (const FrozenFile& f : planned.inputs.files) hash_of[f.source] = f.hash;
  std::string changed;
  for (const FrozenFile& f : there.inputs.files) {
    const auto it = hash_of.find(f.source);
    if (it != hash_of.end() && it->second != f.hash) changed += (changed.empty() ? "" : ", ") + f.source;
  }
  if (!changed.empty()) return "changed since it was planned there: " + changed;
  return "its sweep.json or jobs.jsonl differ from this one's";
}

std::string slurp(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream s;
  s << file.rdbuf();
  return s.str();
}

}  // namespace

void write_sweep_plan(const SweepPlan& plan) {
  const fs::path dir(plan.folder);
  const std::string plan_text = plan_json(plan).dump(2) + "\n";
  std::string jobs_text;
  for (const SweepJob& job : plan.jobs()) {
    nlohmann::ordered_json line;
    line["index"] = job.index;
    line["overrides"] = job.overrides;
    line["seed"] = job.seed;
    line["out"] = fs::path(job.out).filename().string();
    line["args"] = job.args;
    jobs_text += line.dump() + "\n";
  }
  if (fs::exists(dir / "sweep.json")) {
    if (slurp(dir / "sweep.json") != plan_text || slurp(dir / "jobs.jsonl") != jobs_text)
      throw InputError(plan.folder + " already holds another sweep (" + how_it_differs(read_sweep_plan(plan.folder), plan) +
                       "); choose another --out, or remove it");
    return;  // the same sweep: keep it, its finished runs are skipped
  }
  create_output_folder(plan.folder);
  create_output_folder((dir / "logs").string());
  write_frozen_inputs(plan.inputs, plan.folder);
  write_text_file_atomically((dir / "jobs.jsonl").string(), jobs_text);
  // Last: a folder with sweep.json is a complete plan.
  write_text_file_atomically((dir / "sweep.json").string(), plan_text);
}

SweepPlan read_sweep_plan(const std::string& folder) {
  const fs::path path = fs::path(folder) / "sweep.json";
  std::ifstream file(path);
  if (!file) throw InputError(folder + ": not a sweep folder (no sweep.json; create one with physarum sweep SCENE.json --vary ... --out DIR)");
  try {
    const nlohmann::json j = nlohmann::json::parse(file);
    SweepPlan plan;
    // A sweep planned before inputs were frozen names its scene absolutely and has nothing to check.
    if (j.contains("inputs")) plan.inputs = FrozenInputs::from_json(j.at("inputs"), path.string());
    else plan.inputs.scene = j.at("scene").get<std::string>();
    for (const nlohmann::json& a : j.at("axes"))
      plan.axes.push_back({a.at("key").get<std::string>(), a.at("values").get<std::vector<nlohmann::json>>()});
    plan.csv_keys = j.at("csv_keys").get<std::vector<std::string>>();
    plan.csv_rows = j.at("csv_rows").get<std::vector<std::vector<nlohmann::json>>>();
    plan.seeds = j.at("seeds").get<std::vector<std::uint32_t>>();
    plan.run_options = j.at("run_options").get<std::vector<std::string>>();
    plan.folder = absolute(folder);
    return plan;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string() + ": unreadable: " + e.what());
  }
}

std::vector<SweepJob> read_sweep_jobs(const std::string& folder) {
  const fs::path path = fs::path(folder) / "jobs.jsonl";
  std::ifstream file(path);
  if (!file) throw InputError(folder + ": not a sweep folder (no jobs.jsonl)");
  std::vector<SweepJob> jobs;
  std::string line;
  int number = 0;
  while (std::getline(file, line)) {
    ++number;
    if (trim(line).empty()) continue;
    try {
      const nlohmann::ordered_json j = nlohmann::ordered_json::parse(line);
      SweepJob job;
      job.index = j.at("index").get<int>();
      job.overrides = j.at("overrides");
      job.seed = j.at("seed").get<std::uint32_t>();
      job.out = (fs::path(absolute(folder)) / j.at("out").get<std::string>()).lexically_normal().string();
      job.args = j.at("args").get<std::vector<std::string>>();
      if (job.index != static_cast<int>(jobs.size()))
        throw InputError(path.string() + ":" + std::to_string(number) + ": job index " + std::to_string(job.index) +
                         ", expected " + std::to_string(jobs.size()) + " (line i holds job i)");
      jobs.push_back(std::move(job));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(path.string() + ":" + std::to_string(number) + ": " + e.what());
    }
  }
  return jobs;
}

std::string shell_command(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& w : words) {
    if (!line.empty()) line += ' ';
    const bool plain = !w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./:=+@%,") == std::string::npos;
    if (plain) {
      line += w;
      continue;
    }
    line += '\'';
    for (const char c : w) {
      if (c == '\'') line += "'\\''";
      else line += c;
    }
    line += '\'';
  }
  return line;
}

}  // namespace physarum::cli
