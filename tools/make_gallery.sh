#!/usr/bin/env bash
# The README's pictures: runs each gallery scene on the OpenCL backend and keeps its preview.png
# under docs/gallery/ (SCENE.png). Usage: tools/make_gallery.sh [SCENE ...] (default: all of them).
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(default repulsion torus_backward)
mkdir -p docs/gallery
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  ./build/physarum run "tools/scenes/$scene.json" --backend opencl --out "$work/$scene" > /dev/null
  cp "$work/$scene/preview.png" "docs/gallery/$scene.png"
  echo "docs/gallery/$scene.png"
done
