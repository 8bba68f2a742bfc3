#!/usr/bin/env bash
# Speed unchanged? Two builds of `physarum` measured in alternating order (ABBA pairs, so the drift
# of a shared machine and the order of the runs cancel): the default scene's agent-steps/s (run.json,
# 1000 steps) and `physarum bench --quick`'s paper case seconds. Each pair also runs OLD a second
# time, so the noise of OLD against itself is printed beside NEW against OLD.
#   tools/speed_ab.sh OLD_PHYSARUM NEW_PHYSARUM [PAIRS]   (default 20 scene pairs, 6 bench pairs)
set -eu
if [ $# -lt 2 ]; then echo "usage: $0 OLD_PHYSARUM NEW_PHYSARUM [PAIRS]" >&2; exit 2; fi
old=$(readlink -f "$1"); new=$(readlink -f "$2"); pairs=${3:-20}
scene=$(cd "$(dirname "$0")/scenes" && pwd)/default.json
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
scene_speed() {  # agent-steps per second (higher is faster)
  "$1" run "$scene" --steps 1000 --out "$work/run" > /dev/null 2>&1
  python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['agent_steps_per_second'])" "$work/run/run.json"
}
paper_speed() {  # 1 / the paper case's seconds (higher is faster)
  (cd "$work" && "$1" bench --quick 2>&1) | sed -n 's/^paper case: .*: \([0-9.]*\) s (the paper.*/\1/p' |
    python3 -c "import sys; print(1.0 / float(sys.stdin.read()))"
}
measure() {  # FUNCTION PAIRS: lines "old new old_again"
  for p in $(seq 1 "$2"); do
    if [ $((p % 2)) = 1 ]; then a=$($1 "$old"); b=$($1 "$new"); else b=$($1 "$new"); a=$($1 "$old"); fi
    echo "$a $b $($1 "$old")"
  done
}
summary() {  # NAME < lines
  python3 -c "
import statistics as st, sys
rows = [[float(x) for x in line.split()] for line in sys.stdin]
print(f'{sys.argv[1]}: {len(rows)} pairs, median speed new/old {st.median(b / a for a, b, c in rows):.3f}, '
      f'old/old {st.median(c / a for a, b, c in rows):.3f}')" "$1"
}
measure scene_speed "$pairs" | summary "default scene, agent-steps/s"
measure paper_speed $(( (pairs + 2) / 3 )) | summary "bench --quick paper case, 1/s"
