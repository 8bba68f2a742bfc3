#!/usr/bin/env bash
# The README's pictures: runs each gallery scene on the OpenCL backend and keeps its preview.png
# under docs/gallery/ (SCENE.png); for spot also its baked texture and a
# re-colouring with the colour map extracted from the shipped exemplar image; the flat sign and disk
# of the control scenes are shown face-on (physarum render's front view), spot_scale from the side.
# The map-tool scenes sea_fan and ginkgo (flat fans) are shown face-on too, and so are the three
# systems of the appendix of 004 (turing_spots, meinhardt_spots, meinhardt_stripes: flat squares).
# Reaction-diffusion: fandisk_gray_scott and petal_stripes keep their
# preview; cascade runs cascade_first, then cascade_second seeded from its fields_full.ply (both
# pictures kept); pearson_map is a sweep of 6 x 6 (F, k) runs collected into one contact sheet
# (about 2 minutes on two cores). sketch runs `physarum sketch` on tools/sketch/examples/four_sizes.png,
# oriented.json, mixed_aspects.json and strokes.json and keeps each sketch as measured beside its grown
# pattern (face-on), cube_orientations.json on shape:cube's UV layout, sphere_marks.json (marks on the
# surface), then layer_big.json with --layer2 layer_small.json, with and without --rosettes,
# each layer in its own colour set, and four_sizes.json on the cow.
# growth_ruffles runs twice, on a 4 mm sheet and on the scene's 1 mm (growth_ruffles_4mm.png,
# growth_ruffles.png).
# Usage: [PHYSARUM=path/to/physarum] tools/make_gallery.sh [SCENE ...] (default: all of them; the
# binary defaults to ./build/physarum).
set -euo pipefail
cd "$(dirname "$0")/.."
physarum=${PHYSARUM:-./build/physarum}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default repulsion torus_backward spot sign branching spot_scale sea_fan ginkgo species gray_scott fandisk_gray_scott petal_stripes petal_turing cascade pearson_map turing_spots meinhardt_spots meinhardt_stripes sketch growth_rings growth_beads growth_interleaved growth_cap growth_saddle growth_anisotropic growth_ruffles)
mkdir -p docs/gallery
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  if [ "$scene" = cascade ]; then
    "$physarum" run tools/scenes/cascade_first.json --backend opencl --out "$work/cascade_first" > /dev/null
    fields="$(cd "$work" && pwd)/cascade_first/fields_full.ply"
    "$physarum" run tools/scenes/cascade_second.json --backend opencl --out "$work/cascade_second" \
      --set "maps.first_u.fields_full=$fields" --set "maps.first_v.fields_full=$fields" > /dev/null
    cp "$work/cascade_first/preview.png" docs/gallery/cascade_first.png
    cp "$work/cascade_second/preview.png" docs/gallery/cascade_second.png
    echo "docs/gallery/cascade_first.png docs/gallery/cascade_second.png"
    continue
  fi
  if [ "$scene" = sketch ]; then
    "$physarum" sketch tools/sketch/examples/four_sizes.png --backend opencl --out "$work/sketch" > /dev/null
    "$physarum" render "$work/sketch" --views 3 --out "$work/sketch/views" > /dev/null
    cp "$work/sketch/sketch.png" docs/gallery/sketch_input.png
    cp "$work/sketch/views/view_front.png" docs/gallery/sketch_result.png
    "$physarum" sketch tools/sketch/examples/oriented.json --backend opencl --out "$work/oriented" > /dev/null
    "$physarum" render "$work/oriented" --views 3 --out "$work/oriented/views" > /dev/null
    cp "$work/oriented/sketch.png" docs/gallery/sketch_oriented_input.png
    cp "$work/oriented/views/view_front.png" docs/gallery/sketch_oriented_result.png
    "$physarum" sketch tools/sketch/examples/mixed_aspects.json --backend opencl --out "$work/mixed" > /dev/null
    "$physarum" render "$work/mixed" --views 3 --out "$work/mixed/views" > /dev/null
    cp "$work/mixed/sketch.png" docs/gallery/sketch_mixed_input.png
    cp "$work/mixed/views/view_front.png" docs/gallery/sketch_mixed_result.png
    "$physarum" sketch tools/sketch/examples/strokes.json --backend opencl --out "$work/strokes" > /dev/null
    "$physarum" render "$work/strokes" --views 3 --out "$work/strokes/views" > /dev/null
    cp "$work/strokes/sketch.png" docs/gallery/sketch_strokes_input.png
    cp "$work/strokes/views/view_front.png" docs/gallery/sketch_strokes_result.png
    "$physarum" sketch tools/sketch/examples/cube_orientations.json --mesh shape:cube --uv --area 1.5 --regions 6 \
      --backend opencl --out "$work/cube" > /dev/null
    cp "$work/cube/sketch.png" docs/gallery/sketch_cube_input.png
    cp "$work/cube/preview.png" docs/gallery/sketch_cube_result.png
    "$physarum" sketch tools/sketch/examples/sphere_marks.json --mesh shape:sphere --area 2 --backend opencl --out "$work/sphere" > /dev/null
    cp "$work/sphere/sketch.png" docs/gallery/sketch_sphere_input.png
    cp "$work/sphere/preview.png" docs/gallery/sketch_sphere_result.png
    # Each layer in its own colour set (--colors): the sketch draws view_front.png itself, composited.
    "$physarum" sketch tools/sketch/examples/layer_big.json --layer2 tools/sketch/examples/layer_small.json \
      --colors '#fbe7c6,#f28c28' '#fbe7c6,#b5179e' --backend opencl --out "$work/layers" > /dev/null
    "$physarum" sketch tools/sketch/examples/layer_big.json --layer2 tools/sketch/examples/layer_small.json --rosettes \
      --colors '#f0c890,#c08040' '#f0c890,#3a2010,#100800' --backend opencl --out "$work/rosettes" > /dev/null
    for mode in layers rosettes; do cp "$work/$mode/view_front.png" "docs/gallery/sketch_${mode}_result.png"; done
    pictures="docs/gallery/sketch_layers_result.png docs/gallery/sketch_rosettes_result.png"
    # Spots of four sizes on a 3D mesh: the window's quadrants over the cow's x/y extent.
    "$physarum" sketch tools/sketch/examples/four_sizes.json --mesh tools/scenes/meshes/spot.obj --area 3 --refine 1 \
      --colors '#1a1a2e,#e94560,#ffd460' --backend opencl --out "$work/cow" > /dev/null
    cp "$work/cow/preview.png" docs/gallery/sketch_cow_result.png
    cp "$work/cow/sketch.png" docs/gallery/sketch_cow_input.png
    pictures="$pictures docs/gallery/sketch_cow_input.png docs/gallery/sketch_cow_result.png"
    cp "$work/layers/sketch.png" docs/gallery/sketch_layers_input.png
    cp "$work/layers/sketch_layer2.png" docs/gallery/sketch_layers_input2.png
    echo "docs/gallery/sketch_input.png docs/gallery/sketch_result.png docs/gallery/sketch_oriented_input.png docs/gallery/sketch_oriented_result.png docs/gallery/sketch_mixed_input.png docs/gallery/sketch_mixed_result.png docs/gallery/sketch_strokes_input.png docs/gallery/sketch_strokes_result.png docs/gallery/sketch_cube_input.png docs/gallery/sketch_cube_result.png docs/gallery/sketch_sphere_input.png docs/gallery/sketch_sphere_result.png docs/gallery/sketch_layers_input.png docs/gallery/sketch_layers_input2.png $pictures"
    continue
  fi
  if [ "$scene" = pearson_map ]; then
    "$physarum" sweep tools/scenes/pearson_map.json --vary parameters.F=0.01,0.018,0.026,0.034,0.042,0.05 \
      --vary parameters.k=0.047,0.051,0.055,0.059,0.063,0.067 --backend opencl --out "$work/pearson_map" --run > /dev/null
    "$physarum" sweep --collect "$work/pearson_map" > /dev/null
    cp "$work/pearson_map/contact_sheet.png" docs/gallery/pearson_map.png
    echo "docs/gallery/pearson_map.png"
    continue
  fi
  if [ "$scene" = growth_interleaved ]; then  # two moments of the growth: the time-lapse's two frames
    "$physarum" run tools/scenes/growth_interleaved.json --backend opencl --frames 2 --out "$work/$scene" > /dev/null
    cp "$work/$scene/frames/frame_0001.png" docs/gallery/growth_interleaved_1.png
    cp "$work/$scene/frames/frame_0002.png" docs/gallery/growth_interleaved_2.png
    echo "docs/gallery/growth_interleaved_1.png docs/gallery/growth_interleaved_2.png"
    continue
  fi
  if [ "$scene" = growth_ruffles ]; then  # the same rim growth on a 4 mm and a 1 mm sheet
    "$physarum" run tools/scenes/growth_ruffles.json --backend opencl --set shell.thickness=0.004 --out "$work/${scene}_4mm" > /dev/null
    "$physarum" run tools/scenes/growth_ruffles.json --backend opencl --out "$work/$scene" > /dev/null
    cp "$work/${scene}_4mm/preview.png" docs/gallery/growth_ruffles_4mm.png
    cp "$work/$scene/preview.png" docs/gallery/growth_ruffles.png
    echo "docs/gallery/growth_ruffles_4mm.png docs/gallery/growth_ruffles.png"
    continue
  fi
  "$physarum" run "tools/scenes/$scene.json" --backend opencl --texture-size 1024 --out "$work/$scene" > /dev/null
  if [ "$scene" = sign ] || [ "$scene" = branching ] || [ "$scene" = sea_fan ] || [ "$scene" = ginkgo ] ||
     [ "$scene" = turing_spots ] || [ "$scene" = meinhardt_spots ] || [ "$scene" = meinhardt_stripes ]; then
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
