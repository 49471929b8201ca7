#!/usr/bin/env bash
# Builds the libFuzzer targets in the sanitizer tree (preset `sanitize`: clang-14, ASan + UBSan, build-sanitize/,
# shared with scripts/sanitize.sh) and runs each for SECONDS (default 60)
# from its seed corpus in tests/fuzz/corpus/<target>/. New inputs go to a scratch folder, not the repo.
# A finding leaves crash-* files in build-sanitize/findings/ and exits non-zero. An input running over 60 s counts
# as a hang (the kernel's worst cases take ~0.1 s uninstrumented, seconds under ASan on a loaded machine).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
scripts/install_deps.sh --with-fuzzing
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  for f in tests/fuzz/*_fuzzer.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
cmake --preset sanitize >/dev/null
cmake --build --preset sanitize --target "${targets[@]}"
mkdir -p build-sanitize/findings
status=0
for t in "${targets[@]}"; do
  name=${t%_fuzzer}
  work=$(mktemp -d)
  cp -r "tests/fuzz/corpus/$name/." "$work/" 2>/dev/null || true
  echo "fuzz: $t for ${seconds}s" >&2
  if ! build-sanitize/bin/"$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 -print_final_stats=1 \
       -artifact_prefix=build-sanitize/findings/"$name"- "$work" 2> build-sanitize/findings/"$name".log; then
    echo "fuzz: $t FOUND A PROBLEM: see build-sanitize/findings/$name.log" >&2
    tail -30 build-sanitize/findings/"$name".log >&2
    status=1
  fi
  grep -E "stat::number_of_executed_units|Done [0-9]+ runs" build-sanitize/findings/"$name".log >&2 || true
  rm -rf "$work"
done
exit $status
