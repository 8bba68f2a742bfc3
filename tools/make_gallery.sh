#!/usr/bin/env bash
# The README's pictures: runs each gallery scene on the OpenCL backend and keeps its preview.png
# under docs/gallery/ (SCENE.png); for spot (needs ../shared/meshes) also its baked texture and a
# re-colouring with the colour map extracted from the shipped exemplar image; the flat sign and disk
# of the control scenes are shown face-on (physarum render's front view), spot_scale from the side.
# Usage: tools/make_gallery.sh [SCENE ...] (default: all of them).
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default repulsion torus_backward spot sign branching spot_scale)
mkdir -p docs/gallery
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  ./build/physarum run "tools/scenes/$scene.json" --backend opencl --texture-size 1024 --out "$work/$scene" > /dev/null
  if [ "$scene" = sign ] || [ "$scene" = branching ]; then
    ./build/physarum render "$work/$scene" --views 3 --out "$work/$scene/views" > /dev/null
    cp "$work/$scene/views/view_front.png" "docs/gallery/$scene.png"
  elif [ "$scene" = spot_scale ]; then
    ./build/physarum render "$work/$scene" --views 3 --out "$work/$scene/views" > /dev/null
    cp "$work/$scene/views/view_side.png" "docs/gallery/$scene.png"
  else
    cp "$work/$scene/preview.png" "docs/gallery/$scene.png"
  fi
  echo "docs/gallery/$scene.png"
  if [ "$scene" = spot ]; then
    cp "$work/spot/texture.png" docs/gallery/spot_texture.png
    ./build/physarum render "$work/spot" --colormap tools/colormaps/lichen_from_exemplar.json --views 1 --out "$work/lichen" > /dev/null
    cp "$work/lichen/preview.png" docs/gallery/spot_lichen.png
    echo "docs/gallery/spot_texture.png docs/gallery/spot_lichen.png"
  fi
done
