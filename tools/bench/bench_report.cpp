#include "tools/bench/bench_report.hpp"

#include "common/base/atomic_write.hpp"
#include "common/output/line_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <utility>

namespace physarum::cli {

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (x[i] < lo || x[i] > hi || !(y[i] > 0)) continue;
    const double a = std::log(x[i]), b = std::log(y[i]);
    n += 1, sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  if (n < 2) return std::nan("");
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

nlohmann::ordered_json to_json(const Row& r) {
  return {{"sweep", r.sweep}, {"surface", r.surface}, {"backend", r.backend}, {"agents", r.agents},
          {"faces", r.faces}, {"vertices", r.vertices}, {"seconds_per_step", r.seconds_per_step},
          {"agent_steps_per_second", r.agent_steps_per_second},
          {"crossings_per_agent_step", r.crossings_per_agent_step}, {"crossings_per_second", r.crossings_per_second}};
}

nlohmann::ordered_json plot(const std::string& path, const std::vector<Row>& rows, const std::string& sweep,
                            Axis axis, Measure measure, const std::string& title) {
  nlohmann::ordered_json slopes = nlohmann::ordered_json::array();
  std::vector<PlotSeries> series;
  const std::array<std::array<float, 3>, 6> colors = {{{0.12f, 0.35f, 0.75f},
                                                        {0.85f, 0.35f, 0.1f},
                                                        {0.2f, 0.6f, 0.2f},
                                                        {0.6f, 0.2f, 0.6f},
                                                        {0.5f, 0.5f, 0.1f},
                                                        {0.1f, 0.6f, 0.6f}}};
  std::vector<std::pair<std::string, std::string>> keys;
  for (const Row& r : rows)
    if (r.sweep == sweep && std::find(keys.begin(), keys.end(), std::make_pair(r.surface, r.backend)) == keys.end())
      keys.emplace_back(r.surface, r.backend);
  for (size_t k = 0; k < keys.size(); ++k) {
    PlotSeries s;
    s.color = colors[k % colors.size()];
    s.dashed = keys[k].second == "reference";
    std::vector<double> x, y;
    for (const Row& r : rows)
      if (r.sweep == sweep && r.surface == keys[k].first && r.backend == keys[k].second) {
        x.push_back(axis == Axis::kAgents ? r.agents : r.faces);
        y.push_back(measure == Measure::kSecondsPerStep ? r.seconds_per_step : r.agent_steps_per_second);
      }
    // The ranges (1e5..1e7 agents, 1e4..1e6 faces); a quick run fits whatever it has.
    double slope = axis == Axis::kAgents ? log_log_slope(x, y, 1e5, 1e7) : log_log_slope(x, y, 1e4, 1e6);
    if (std::isnan(slope)) slope = log_log_slope(x, y, 0.0, 1e300);
    char label[96];
    std::snprintf(label, sizeof label, "%s %s, slope %.2f", keys[k].first.c_str(), keys[k].second.c_str(), slope);
    s.label = label;
    slopes.push_back({{"surface", keys[k].first}, {"backend", keys[k].second}, {"slope", slope}});
    s.x = x;
    s.y = y;
    series.push_back(std::move(s));
  }
  if (series.empty()) return slopes;
  PlotOptions o;
  o.log_x = o.log_y = true;
  o.width = 1000;
  o.title = title;
  o.x_label = axis == Axis::kAgents ? "agents" : "intrinsic faces";
  o.y_label = measure == Measure::kSecondsPerStep ? "seconds per step" : "agent-steps per second";
  write_line_plot_png(path, series, o);
  return slopes;
}

void write_bench_outputs(const std::string& out_dir, const std::vector<Row>& bench_rows,
                         const std::string& agent_surface, int resolution_agents, nlohmann::ordered_json& report) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const Row& r : bench_rows) rows.push_back(to_json(r));
  report["rows"] = rows;
  create_output_folder(out_dir);
  const std::filesystem::path out(out_dir);
  std::ostringstream csv;
  csv << "sweep,surface,backend,agents,faces,vertices,seconds_per_step,agent_steps_per_second,"
         "crossings_per_agent_step,crossings_per_second\n";
  csv.precision(9);
  for (const Row& r : bench_rows)
    csv << r.sweep << "," << r.surface << "," << r.backend << "," << r.agents << "," << r.faces << "," << r.vertices
        << "," << r.seconds_per_step << "," << r.agent_steps_per_second << "," << r.crossings_per_agent_step << ","
        << r.crossings_per_second << "\n";
  write_text_file_atomically((out / "bench.csv").string(), csv.str());
  // Slopes of time per step (those of agent-steps per second follow from them).
  const auto png = [&](const char* name) { return (out / name).string(); };
  const std::string fixed_agents = " (" + std::to_string(resolution_agents) + " agents)";
  report["slopes"] = {
      {"agents", plot(png("agents.png"), bench_rows, "agents", Axis::kAgents, Measure::kSecondsPerStep,
                      "Time per step against agents (" + agent_surface + ")")},
      {"faces", plot(png("faces.png"), bench_rows, "faces", Axis::kFaces, Measure::kSecondsPerStep,
                     "Time per step against intrinsic faces" + fixed_agents)},
      {"faces_scaled", plot(png("faces_scaled.png"), bench_rows, "faces_scaled", Axis::kFaces,
                            Measure::kSecondsPerStep,
                            "Time per step against intrinsic faces, work per face held constant")}};
  plot(png("agents_throughput.png"), bench_rows, "agents", Axis::kAgents, Measure::kAgentStepsPerSecond,
       "Agent-steps per second against agents (" + agent_surface + ")");
  plot(png("faces_throughput.png"), bench_rows, "faces", Axis::kFaces, Measure::kAgentStepsPerSecond,
       "Agent-steps per second against intrinsic faces" + fixed_agents);
  std::printf("fitted log-log slopes of time per step: %s\n", report["slopes"].dump().c_str());
  write_text_file_atomically((out / "bench.json").string(), report.dump(2) + "\n");
  std::printf("wrote %s/{bench.json, bench.csv, agents.png, faces.png, faces_scaled.png, agents_throughput.png, "
              "faces_throughput.png}\n",
              out.string().c_str());
}

}  // namespace physarum::cli
