#!/usr/bin/env bash
# The training data of the sketch's inverse map (common/sketch/inverse_map.hpp; 004 Sec. 5.2.1):
# MODEL's training scene (tools/sketch/training/MODEL.json: a 1 m square at the model's 1 cm cells)
# is swept over its reaction rate with `physarum sweep`, every run is measured with
# `physarum analyze`, `physarum sweep --collect` gathers them, and the columns the map reads go to
# tools/sketch/training/MODEL.csv, headed by this command, the commit and the date.
#
# Each run lasts the same time in the model's own units (rate x time = RATE_TIME): the pattern
# depends on D / rate alone (time scaled by the rate), so the runs differ only in how many mesh
# cells and how much of the square the pattern's length spans: what the training records.
#
# The stripe system is trained the same way on its stripes' width (stripe_width: the mean over its
# stripes of area / centre-line length, common/pattern/stripe_width.hpp); the spot columns of its
# rows are whatever spots its labyrinth leaves, and are not read.
#
# Usage: [PHYSARUM=path/to/physarum] tools/sketch/make_training_data.sh turing-spots|meinhardt-spots|meinhardt-stripes [WORK_DIR]
# (about 4, 4 and 12 minutes on two cores with PoCL).
set -euo pipefail
cd "$(dirname "$0")/../.."
physarum=${PHYSARUM:-./build/physarum}
model=${1:?usage: make_training_data.sh turing-spots|meinhardt-spots|meinhardt-stripes [WORK_DIR]}
work=${2:-$(mktemp -d)}
case "$model" in
  # field: the morphogen whose high values are the spots; rates: the sweep (geometric steps);
  # rate_time: rate x simulated time of every run (the gallery scene's run at its default rate).
  turing-spots) key=ka; field=a; rate_time=250
    rates="0.025 0.032 0.04 0.05 0.0625 0.08 0.1 0.125 0.16 0.2 0.25" ;;
  meinhardt-spots) key=s; field=b; rate_time=1600
    rates="0.08 0.1 0.125 0.16 0.2 0.25 0.32 0.4 0.5 0.63 0.8 1.0" ;;
  # Above s = 1 the stripes are under three mesh cells wide at the training's resolution.
  meinhardt-stripes) key=s; field=a; rate_time=3000
    rates="0.12 0.15 0.19 0.25 0.32 0.4 0.5 0.63 0.8 1.0" ;;
  *) echo "make_training_data.sh: unknown model '$model' (turing-spots, meinhardt-spots, meinhardt-stripes)" >&2; exit 2 ;;
esac
scene="tools/sketch/training/${model//-/_}.json"
out="tools/sketch/training/${model//-/_}.csv"
mkdir -p "$work"
variants="$work/variants.csv"
echo "parameters.$key,steps" > "$variants"
for r in $rates; do echo "$r,$(awk -v r="$r" -v t="$rate_time" 'BEGIN { printf "%d", t / r + 0.5 }')"; done >> "$variants"
"$physarum" sweep "$scene" --csv "$variants" --seeds 2 --backend opencl --out "$work/sweep" --run --jobs 1 > /dev/null
for run in "$work"/sweep/run_*; do "$physarum" analyze "$run" --field "$field" > /dev/null; done
"$physarum" sweep --collect "$work/sweep" > /dev/null
{
  echo "# Training data of the sketch's inverse map for $model: one row per run."
  echo "# command: tools/sketch/make_training_data.sh $model"
  echo "# commit: $(git rev-parse HEAD 2>/dev/null || echo unknown)   date: $(date -u +%Y-%m-%d)"
  echo "# scene: $scene, rate key parameters.$key, rate x time = $rate_time, 2 seeds per rate"
  echo "# spot_area: median area of the spots clear of the boundary (m^2); spacing: median distance"
  echo "# between neighbouring spot centres (m); spots: their count; stripe_width: the stripes' mean width (m);"
  echo "# stripes: their count; field: $field above its mean + 0.5 sd"
  echo "rate,seed,steps,spots,spot_area,spacing,stripes,stripe_width"
  # sweep.csv quotes fields with commas (the device's name): read it as CSV.
  python3 - "$work/sweep/sweep.csv" "parameters.$key" <<'PY'
import csv, sys
for row in csv.DictReader(open(sys.argv[1])):
    if row["status"] == "done":
        print(",".join(row[k] for k in (sys.argv[2], "seed", "steps", "analysis_spot_count",
                                        "analysis_summary_interior_spot_area_median", "analysis_spacing_median",
                                        "analysis_stripe_count", "analysis_stripe_width_mean")))
PY
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "$out"
