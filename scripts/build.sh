#!/usr/bin/env bash
# Configures and builds hrad in Release into build/ (build/bin/hrad), after installing what is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh "$@"
cmake --preset release >/dev/null
cmake --build --preset release
