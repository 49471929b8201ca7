#!/usr/bin/env bash
# Installs what is missing, builds (Release) and runs the whole test suite with CTest.
# Exits non-zero when any test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh --with-notebooks
ctest --preset release
