#include "tools/sweep/sweep_collect.hpp"

#include "common/base/atomic_write.hpp"
#include "common/base/errors.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace physarum::cli {
namespace {

namespace fs = std::filesystem;

std::string value_text(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

// Labels of the combinations of axes [first, last): "k=v" for one axis, "k1=v1, k2=v2" for more;
// with_keys false: the values only (column labels, under a title that names the keys: a cell is
// narrower than "key=value").
std::vector<std::string> combination_labels(const std::vector<SweepAxis>& axes, std::size_t first, std::size_t last,
                                            bool with_keys = true) {
  std::vector<std::string> labels{""};
  for (std::size_t a = first; a < last; ++a) {
    std::vector<std::string> next;
    for (const std::string& prefix : labels)
      for (const nlohmann::json& v : axes[a].values)
        next.push_back(prefix + (prefix.empty() ? "" : ", ") + (with_keys ? axes[a].key + "=" : "") + value_text(v));
    labels = std::move(next);
  }
  return labels;
}

// ",FIELD" appended piece by piece ("," + std::string trips a GCC 12 -Wrestrict false positive).
void append_field(std::string& csv, const std::string& value) {
  csv += ',';
  csv += csv_field(value);
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) fields.push_back(f);
  return fields;
}

// The header and the last row of a run's stats.csv (empty when absent).
std::pair<std::vector<std::string>, std::vector<std::string>> final_stats(const fs::path& file) {
  std::ifstream in(file);
  std::string header, line, last;
  if (!std::getline(in, header)) return {};
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return {split_csv_line(header), split_csv_line(last)};
}

// The scalars of a run's analysis.json (`physarum analyze RUN`), nested objects flattened with '_'
// (summary.area.median -> summary_area_median); lists (the spots themselves) are left out.
void flatten_scalars(const nlohmann::ordered_json& j, const std::string& prefix, std::vector<std::string>& keys,
                     std::map<std::string, std::string>& values) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix + it.key();
    if (it.value().is_object()) {
      flatten_scalars(it.value(), key + "_", keys, values);
    } else if (!it.value().is_array()) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
      values[key] = it.value().is_null() ? "" : value_text(it.value());
    }
  }
}

}  // namespace

ContactSheet contact_sheet_for(const SweepPlan& plan, const std::vector<SweepJob>& jobs, int thumbnail) {
  ContactSheet sheet;
  ContactSheetLayout& L = sheet.layout;
  L.thumbnail = thumbnail;
  L.seeds = static_cast<int>(plan.seeds.size());
  if (!plan.csv_keys.empty()) {
    for (int v = 0; v < plan.variant_count(); ++v) {
      std::string label;
      for (std::size_t k = 0; k < plan.csv_keys.size(); ++k)
        label += (k ? ", " : "") + plan.csv_keys[k] + "=" + value_text(plan.csv_rows[static_cast<std::size_t>(v)][k]);
      sheet.row_labels.push_back(label);
    }
    sheet.column_labels = {""};
    sheet.title = "rows: the variants of the CSV";
  } else {
    const std::size_t row_axes = plan.axes.size() / 2;
    sheet.row_labels = combination_labels(plan.axes, 0, row_axes);
    sheet.column_labels = combination_labels(plan.axes, row_axes, plan.axes.size(), false);
    if (plan.axes.empty()) sheet.column_labels = {""};
    std::string rows, columns;
    for (std::size_t a = 0; a < plan.axes.size(); ++a) {
      std::string& names = a < row_axes ? rows : columns;
      names += (names.empty() ? "" : ", ") + plan.axes[a].key;
    }
    sheet.title = (rows.empty() ? std::string() : "rows: " + rows + "    ") + (columns.empty() ? std::string() : "columns: " + columns);
  }
  if (L.seeds > 1) {
    std::string seeds;
    for (std::size_t s = 0; s < plan.seeds.size(); ++s) seeds += (s ? ", " : "") + std::to_string(plan.seeds[s]);
    sheet.title += (sheet.title.empty() ? "" : "    ") + std::string("seeds ") + seeds;
  }
  L.rows = static_cast<int>(sheet.row_labels.size());
  L.columns = static_cast<int>(sheet.column_labels.size());
  L.row_label_width = row_label_width_for(sheet.row_labels);
  sheet.previews.assign(static_cast<std::size_t>(L.rows),
                        std::vector<std::vector<std::string>>(static_cast<std::size_t>(L.columns),
                                                              std::vector<std::string>(static_cast<std::size_t>(L.seeds))));
  for (const SweepJob& job : jobs) {
    const int variant = job.index / L.seeds, seed = job.index % L.seeds;
    const int row = variant / L.columns, column = variant % L.columns;
    if (row >= L.rows) throw InputError(plan.folder + ": jobs.jsonl has more jobs than sweep.json's grid");
    sheet.previews[static_cast<std::size_t>(row)][static_cast<std::size_t>(column)][static_cast<std::size_t>(seed)] =
        job.finished() ? (fs::path(job.out) / "preview.png").string() : std::string();
  }
  return sheet;
}

namespace {

const char* job_status(const SweepJob& job) {
  if (job.finished()) return "done";
  return fs::exists(job.out) ? "failed" : "missing";
}

}  // namespace

SweepCollection collect_sweep(const std::string& folder, int thumbnail) {
  const SweepPlan plan = read_sweep_plan(folder);
  const std::vector<SweepJob> jobs = read_sweep_jobs(folder);
  SweepCollection result;

  // Every run's scalars, and the union of their keys in the order first met.
  std::vector<std::string> run_keys, stats_keys, analysis_keys;
  std::vector<std::map<std::string, std::string>> run_values(jobs.size()), stats_values(jobs.size()),
      analysis_values(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const fs::path out(jobs[i].out);
    if (!jobs[i].finished()) {
      ++result.missing;
      (fs::exists(out) ? result.failed_jobs : result.missing_jobs).push_back(jobs[i].index);
      continue;
    }
    std::ifstream in(out / "run.json");
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object()) throw InputError((out / "run.json").string() + ": not a JSON object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.value().is_structured()) continue;
      if (std::find(run_keys.begin(), run_keys.end(), it.key()) == run_keys.end()) run_keys.push_back(it.key());
      run_values[i][it.key()] = value_text(it.value());
    }
    const auto [header, last] = final_stats(out / "stats.csv");
    for (std::size_t c = 0; c < header.size() && c < last.size(); ++c) {
      if (std::find(stats_keys.begin(), stats_keys.end(), header[c]) == stats_keys.end()) stats_keys.push_back(header[c]);
      stats_values[i][header[c]] = last[c];
    }
    if (std::ifstream a(out / "analysis.json"); a) {
      const nlohmann::ordered_json analysis = nlohmann::ordered_json::parse(a, nullptr, false);
      if (analysis.is_discarded() || !analysis.is_object())
        throw InputError((out / "analysis.json").string() + ": not a JSON object");
      flatten_scalars(analysis, "", analysis_keys, analysis_values[i]);
    }
  }

  const std::vector<std::string> varied = plan.varied_keys();
  std::string csv = "index";
  for (const std::string& k : varied) append_field(csv, k);
  csv += ",seed,out,status";
  for (const std::string& k : run_keys) append_field(csv, k);
  for (const std::string& k : stats_keys) append_field(csv, std::string("final_") + k);
  for (const std::string& k : analysis_keys) append_field(csv, std::string("analysis_") + k);
  csv += "\n";
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const SweepJob& job = jobs[i];
    csv += std::to_string(job.index);
    for (const std::string& k : varied) append_field(csv, job.overrides.contains(k) ? value_text(job.overrides[k]) : "");
    append_field(csv, std::to_string(job.seed));
    append_field(csv, job.out);
    append_field(csv, job_status(job));
    for (const std::string& k : run_keys) append_field(csv, run_values[i].count(k) ? run_values[i][k] : "");
    for (const std::string& k : stats_keys) append_field(csv, stats_values[i].count(k) ? stats_values[i][k] : "");
    for (const std::string& k : analysis_keys) append_field(csv, analysis_values[i].count(k) ? analysis_values[i][k] : "");
    csv += "\n";
  }
  write_text_file_atomically((fs::path(folder) / "sweep.csv").string(), csv);
  result.rows = static_cast<int>(jobs.size());

  const ContactSheet sheet = contact_sheet_for(plan, jobs, thumbnail);
  write_rgb_png((fs::path(folder) / "contact_sheet.png").string(), draw_contact_sheet(sheet));
  result.layout = sheet.layout;
  return result;
}

}  // namespace physarum::cli
