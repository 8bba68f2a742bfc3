#!/usr/bin/env bash
# Same bits? Runs every shipped scene on both backends with two builds of `physarum` and compares
# pheromone.ply and stats.csv byte for byte: the check a change that must not change results (a
# refactoring, a speed-up) passes before it lands.
#   tools/same_bits.sh OLD_PHYSARUM NEW_PHYSARUM [STEPS]   (default 60 steps per run)
# Prints one line per file and exits 1 when any differs or a run fails.
set -u
if [ $# -lt 2 ]; then echo "usage: $0 OLD_PHYSARUM NEW_PHYSARUM [STEPS]" >&2; exit 2; fi
old=$(readlink -f "$1"); new=$(readlink -f "$2"); steps=${3:-60}
scenes_dir=$(cd "$(dirname "$0")/scenes" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
status=0
for scene in "$scenes_dir"/*.json "$scenes_dir"/compare/*.json; do
  name=$(basename "$(dirname "$scene")")_$(basename "$scene" .json)
  for backend in reference opencl; do
    for which in old new; do
      exe=$([ $which = old ] && echo "$old" || echo "$new")
      if ! "$exe" run "$scene" --backend $backend --steps "$steps" --out "$work/$which/$name-$backend" \
          > "$work/$which-$name-$backend.log" 2>&1; then
        echo "FAILED  $name $backend ($which): $(tail -1 "$work/$which-$name-$backend.log")"; status=1
      fi
    done
    for f in pheromone.ply stats.csv; do
      if cmp -s "$work/old/$name-$backend/$f" "$work/new/$name-$backend/$f"; then echo "same    $name $backend $f"
      else echo "DIFFERS $name $backend $f"; status=1; fi
    done
  done
done
exit $status
