#!/usr/bin/env bash
# The main job: installs what is missing for the `hrad` command alone (tests, benchmarks and plots
# install and build in scripts/test.sh), builds only that command (Release), solves the bundled Cornell box with
# hierarchical radiosity and writes out/cornell_box.ply (leaf mesh, vertex colours, per-element
# radiosity), out/cornell_box.json (the solve report), out/cornell_box.png (the elements'
# radiosity, Gouraud-shaded) and out/cornell_box_gathered.png with out/cornell_box_gathered.exr
# (the picture by final gather at every pixel, and its linear values), then prints a summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --command-only
scene=notebooks_data/scenes/cornell_box.obj
mkdir -p out
build/bin/hrad info "$scene"
build/bin/hrad solve "$scene" --method hierarchical --report out/cornell_box.json --out out/cornell_box.ply
build/bin/hrad render out/cornell_box.ply --out out/cornell_box.png
build/bin/hrad render out/cornell_box.ply --scene "$scene" --final-gather --out out/cornell_box_gathered.png \
  --exr out/cornell_box_gathered.exr
echo "wrote out/cornell_box_gathered.png (final gather), out/cornell_box.png (Gouraud), out/cornell_box_gathered.exr," \
  "out/cornell_box.ply, out/cornell_box.json"
