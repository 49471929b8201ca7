#!/usr/bin/env bash
# Configures and builds hrad in Release into build/ (build/bin/hrad), after installing what is missing.
# Usage: scripts/build.sh [--command-only] [--with-notebooks] [--target TARGET...]
#   default: every target, tests and benchmarks included; --command-only: the hrad command alone,
#   with only the packages it needs (scripts/run.sh), and the tests left out of the configuration
#   (a later build without it puts them back).
set -euo pipefail
cd "$(dirname "$0")/.."
deps=()
targets=()
tests=ON
while [[ $# -gt 0 ]]; do
  case "$1" in
    --target) shift; targets+=(--target "$1") ;;
    --command-only) tests=OFF; deps+=("$1"); targets+=(--target hrad_cli) ;;
    *) deps+=("$1") ;;
  esac
  shift
done
scripts/install_deps.sh "${deps[@]}"
cmake --preset release -DHRAD_BUILD_TESTS=$tests -DHRAD_BUILD_BENCHMARKS=$tests >/dev/null
cmake --build --preset release "${targets[@]}"
