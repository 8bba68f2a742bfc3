#pragma once
// The outputs of `physarum bench`: bench.csv, bench.json's rows, and the log-log plots with their
// fitted slopes (agents.png, faces.png, faces_scaled.png, agents_throughput.png,
// faces_throughput.png). The file names and JSON keys are a contract (tests/test_cli_*.cpp).
#include "tools/bench/bench_session.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace physarum::cli {

// Least-squares slope of log(y) against log(x) over the points with lo <= x <= hi.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi);

nlohmann::ordered_json to_json(const Row& r);

// Draws one sweep (a line per surface and backend), seconds per step or agent-steps per second
// against agents or faces, and returns the fitted log-log slopes.
enum class Axis { kAgents, kFaces };
enum class Measure { kSecondsPerStep, kAgentStepsPerSecond };
nlohmann::ordered_json plot(const std::string& path, const std::vector<Row>& rows, const std::string& sweep,
                            Axis axis, Measure measure, const std::string& title);

// Adds "rows" and "slopes" to `report`, writes bench.csv, the plots and bench.json into `out_dir`
// and prints the slopes and what was written.
void write_bench_outputs(const std::string& out_dir, const std::vector<Row>& rows, const std::string& agent_surface,
                         int resolution_agents, nlohmann::ordered_json& report);

}  // namespace physarum::cli
