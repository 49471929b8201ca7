#!/usr/bin/env bash
# The main job: installs what is missing, builds only the `hrad` command (Release; tests and
# benchmarks build in scripts/test.sh), solves the bundled Cornell box with
# hierarchical radiosity and writes out/cornell_box.ply (leaf mesh, vertex colours, per-element
# radiosity), out/cornell_box.json (the solve report) and out/cornell_box.png (a rendering), then
# prints a summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --target hrad_cli
scene=notebooks_data/scenes/cornell_box.obj
mkdir -p out
build/bin/hrad info "$scene"
build/bin/hrad solve "$scene" --method hierarchical --report out/cornell_box.json --out out/cornell_box.ply
build/bin/hrad render out/cornell_box.ply --out out/cornell_box.png
echo "wrote out/cornell_box.png, out/cornell_box.ply, out/cornell_box.json"
