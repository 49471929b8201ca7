#!/usr/bin/env bash
# The main job: installs what is missing, builds (Release), solves the bundled Cornell box and
# writes out/cornell_box.png, out/cornell_box.ply and out/cornell_box.json, then prints a summary.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
scene=notebooks_data/scenes/cornell_box.obj
mkdir -p out
build/bin/hrad info "$scene"
build/bin/hrad info "$scene" --json > out/cornell_box.scene.json.tmp && mv out/cornell_box.scene.json.tmp out/cornell_box.scene.json
