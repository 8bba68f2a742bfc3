#pragma once
// `physarum sweep --collect DIR`: gathers a sweep's finished runs (tools/sweep/sweep_plan.hpp) into
//   DIR/sweep.csv          one row per job, in job order: index, the varied keys' values, seed, out,
//                          status (done; failed: its folder exists without run.json, a run that
//                          stopped, failed or is still running; missing: never started), every scalar of the run's run.json (columns in
//                          the order first met), the run's final stats.csv row as final_<column>, and
//                          where `physarum analyze RUN` has written RUN/analysis.json its scalars as
//                          analysis_<key> (nested keys joined by '_': analysis_summary_area_median);
//   DIR/contact_sheet.png  the previews laid out by the varied keys (tools/sweep/contact_sheet.hpp): with
//                          one key its values are the columns of one row; with two the first key's
//                          values are the rows and the second's the columns; with more, the first
//                          half of the keys (combined, "k1=v1, k2=v2") make the rows and the rest the
//                          columns; rows of a CSV of variants are the sheet's rows. The seeds of a
//                          variant stand side by side in its cell.
// Missing and failed runs stay rows and grey cells, so a partial sweep can be looked at; the command
// then exits 1 and lists them.
#include "tools/sweep/contact_sheet.hpp"
#include "tools/sweep/sweep_plan.hpp"

#include <string>
#include <vector>

namespace physarum::cli {

struct SweepCollection {
  int rows = 0;     // rows of sweep.csv (= jobs)
  int missing = 0;  // jobs without run.json (failed_jobs and missing_jobs together)
  std::vector<int> failed_jobs;   // started (their folder exists) and not finished
  std::vector<int> missing_jobs;  // never started
  ContactSheetLayout layout;
};

// The sheet's grid for a plan: rows, columns, labels and which job sits where (previews[r][c][s]
// is job (r * columns + c) * seeds + s's preview path).
ContactSheet contact_sheet_for(const SweepPlan& plan, const std::vector<SweepJob>& jobs, int thumbnail);

// Writes DIR/sweep.csv and DIR/contact_sheet.png (atomically). InputError when DIR is not a sweep.
SweepCollection collect_sweep(const std::string& folder, int thumbnail);

}  // namespace physarum::cli
