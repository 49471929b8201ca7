#!/usr/bin/env bash
# Builds the unit test programs with AddressSanitizer + UndefinedBehaviorSanitizer (preset `sanitize`: clang-14,
# build-sanitize/, the tree that also holds the libFuzzer targets) and runs them with CTest. Any sanitizer report
# fails the test that triggered it.
# Usage: scripts/sanitize.sh [TEST_PROGRAM...]   (default: every unit test program)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh --with-fuzzing
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  for d in tests/*/; do
    name=$(basename "$d")
    [[ -f "$d/CMakeLists.txt" && "$name" != bench && "$name" != fuzz && "$name" != notebooks ]] && targets+=("${name}_test")
  done
fi
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Programs left out of a partial run register a placeholder test "<program>_NOT_BUILT": skip those.
ctest --preset sanitize -E '_NOT_BUILT$' 
