#!/usr/bin/env bash
# The README's pictures: runs each gallery scene on the OpenCL backend and keeps its preview.png
# under docs/gallery/ (SCENE.png); for spot (needs ../shared/meshes) also its baked texture and a
# re-colouring with the colour map extracted from the shipped exemplar image; the flat sign and disk
# of the control scenes are shown face-on (physarum render's front view), spot_scale from the side.
# The map-tool scenes sea_fan and ginkgo (flat fans) are shown face-on too.
# Usage: [PHYSARUM=path/to/physarum] tools/make_gallery.sh [SCENE ...] (default: all of them; the
# binary defaults to ./build/physarum).
set -euo pipefail
cd "$(dirname "$0")/.."
physarum=${PHYSARUM:-./build/physarum}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default repulsion torus_backward spot sign branching spot_scale sea_fan ginkgo species gray_scott)
mkdir -p docs/gallery
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  "$physarum" run "tools/scenes/$scene.json" --backend opencl --texture-size 1024 --out "$work/$scene" > /dev/null
  if [ "$scene" = sign ] || [ "$scene" = branching ] || [ "$scene" = sea_fan ] || [ "$scene" = ginkgo ]; then
    "$physarum" render "$work/$scene" --views 3 --out "$work/$scene/views" > /dev/null
    cp "$work/$scene/views/view_front.png" "docs/gallery/$scene.png"
  elif [ "$scene" = spot_scale ]; then
    "$physarum" render "$work/$scene" --views 3 --out "$work/$scene/views" > /dev/null
    cp "$work/$scene/views/view_side.png" "docs/gallery/$scene.png"
  else
    cp "$work/$scene/preview.png" "docs/gallery/$scene.png"
  fi
  echo "docs/gallery/$scene.png"
  if [ "$scene" = spot ]; then
    cp "$work/spot/texture.png" docs/gallery/spot_texture.png
    "$physarum" render "$work/spot" --colormap tools/colormaps/lichen_from_exemplar.json --views 1 --out "$work/lichen" > /dev/null
    cp "$work/lichen/preview.png" docs/gallery/spot_lichen.png
    echo "docs/gallery/spot_texture.png docs/gallery/spot_lichen.png"
  fi
done
