#!/usr/bin/env bash
# Same bits? Runs every shipped scene of every model on both backends with two builds of `physarum`
# and compares the result on the input mesh (pheromone.ply for agents, morphogens.ply for
# reaction-diffusion: run.json's "fields_file"; builds older than that name wrote pheromone.ply for
# both) and stats.csv byte for byte: the check a change that must not change results (a
# refactoring, a speed-up) passes before it lands. cascade_second.json reads cascade_first's result
# from out/cascade_first (as the gallery makes it); it is made there with NEW when absent.
# A growth scene's length is its schedule (--steps is refused): it runs 2 growth steps, and STEPS
# reaction steps where its schedule has them.
#   tools/same_bits.sh OLD_PHYSARUM NEW_PHYSARUM [STEPS]   (default 60 steps per run)
# Prints one line per file and exits 1 when any differs or a run fails.
set -u
if [ $# -lt 2 ]; then echo "usage: $0 OLD_PHYSARUM NEW_PHYSARUM [STEPS]" >&2; exit 2; fi
old=$(readlink -f "$1"); new=$(readlink -f "$2"); steps=${3:-60}
scenes_dir=$(cd "$(dirname "$0")/scenes" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
status=0
# The result file a run wrote on the input mesh.
fields_file() {
  local name
  name=$(sed -n 's/^ *"fields_file": "\([^"]*\)".*/\1/p' "$1/run.json" 2>/dev/null)
  echo "${name:-pheromone.ply}"
}
repo=$(cd "$scenes_dir/../.." && pwd)
if [ ! -f "$repo/out/cascade_first/fields_full.ply" ]; then
  "$new" run "$scenes_dir/cascade_first.json" --out "$repo/out/cascade_first" > "$work/cascade_first.log" 2>&1 ||
    { echo "FAILED  making out/cascade_first: $(tail -1 "$work/cascade_first.log")"; status=1; }
fi
# The run-length flags of a scene.
length_flags() {
  if grep -q '"model": *"growth"' "$1"; then
    echo "--set schedule.growth_steps=2"
    if grep -q '"reaction_steps"' "$1"; then echo "--set schedule.reaction_steps=$steps"; fi
  else
    echo "--steps $steps"
  fi
}
for scene in "$scenes_dir"/*.json "$scenes_dir"/compare/*.json; do
  name=$(basename "$(dirname "$scene")")_$(basename "$scene" .json)
  length=$(length_flags "$scene")
  for backend in reference opencl; do
    for which in old new; do
      exe=$([ $which = old ] && echo "$old" || echo "$new")
      # shellcheck disable=SC2086 # $length is several flags
      if ! "$exe" run "$scene" --backend $backend $length --out "$work/$which/$name-$backend" \
          > "$work/$which-$name-$backend.log" 2>&1; then
        echo "FAILED  $name $backend ($which): $(tail -1 "$work/$which-$name-$backend.log")"; status=1
      fi
    done
    old_fields=$(fields_file "$work/old/$name-$backend") new_fields=$(fields_file "$work/new/$name-$backend")
    for f in fields stats.csv; do
      a=$f b=$f
      [ $f = fields ] && a=$old_fields b=$new_fields
      if cmp -s "$work/old/$name-$backend/$a" "$work/new/$name-$backend/$b"; then echo "same    $name $backend $b"
      else echo "DIFFERS $name $backend $b"; status=1; fi
    done
  done
done
exit $status
