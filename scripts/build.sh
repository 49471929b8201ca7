#!/usr/bin/env bash
# Configures and builds hrad in Release into build/ (build/bin/hrad), after installing what is missing.
# Usage: scripts/build.sh [--with-notebooks] [--target TARGET...]   (default: every target, tests and
# benchmarks included; scripts/run.sh builds only --target hrad_cli, the command)
set -euo pipefail
cd "$(dirname "$0")/.."
deps=()
targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --target) shift; targets+=(--target "$1") ;;
    *) deps+=("$1") ;;
  esac
  shift
done
scripts/install_deps.sh "${deps[@]}"
cmake --preset release >/dev/null
cmake --build --preset release "${targets[@]}"
