#!/usr/bin/env bash
# README command 2 (what CI runs): install dependencies, build in Release with warnings as errors,
# run every test on lavapipe with the Vulkan validation layer on, the device tests again with
# staged device memory, then a short list of unit and device test programs under ASan + UBSan, and
# the fuzzers. Tests
# needing ../shared/data skip without it. Ends with a table of every stage's time (also written to
# build/stage-times.json). docs/build.md: what each stage costs and why.
#
#   scripts/run-tests.sh           the whole run, as CI
#   scripts/run-tests.sh --quick   the local loop: build, then the unit and device tests of the
#                                  test executables this build relinked (all of them on a first
#                                  build); no install, no sanitizers, no fuzzing
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
QUICK=0
case "${1:-}" in
  --quick) QUICK=1 ;;
  "") ;;
  *) echo "run-tests.sh: unknown argument '$1' (--quick or nothing)" >&2; exit 2 ;;
esac
export STRATA_STAGE_JSON="$ROOT/build/stage-times.json"
source "$ROOT/scripts/lib/stages.sh"
BUILD="$ROOT/build"
CMAKE_ARGS=(-DSTRATA_BUILD_TESTS=ON -DSTRATA_WERROR=ON)

# The quick loop: test executables whose file changed in this build, labelled unit or device.
quick_tests() {
  local before="$1" changed=() name label path
  while read -r name label path; do
    [[ "$label" == unit || "$label" == device ]] || continue
    [[ -x "$path" ]] || continue
    if ! grep -qxF "$path $(stat -c %Y "$path")" "$before"; then changed+=("$path"); fi
  done <"$BUILD/strata_tests.txt"
  if ((${#changed[@]} == 0)); then
    echo "run-tests.sh --quick: no unit or device test executable changed in this build"
    return 0
  fi
  echo "run-tests.sh --quick: ${#changed[@]} changed test executables: ${changed[*]##*/}"
  # Two at a time (one per core), each with the validation layer on, as ctest runs them.
  printf '%s\n' "${changed[@]}" |
    STRATA_VALIDATION=1 xargs -P 2 -I{} sh -c '"$1" --gtest_brief=1 >"$1.quick.log" 2>&1 &&
      echo "passed: ${1##*/}" || { echo "FAILED: ${1##*/} (log: $1.quick.log)"; tail -40 "$1.quick.log"; exit 1; }' _ {}
}

if ((QUICK)); then
  stage_plan build tests
  snapshot="$(mktemp)"
  trap 'status=$?; rm -f "$snapshot"; stage_table >&2; exit $status' EXIT
  if [[ -f "$BUILD/strata_tests.txt" ]]; then
    while read -r _ _ path; do
      [[ -e "$path" ]] && echo "$path $(stat -c %Y "$path")"
    done <"$BUILD/strata_tests.txt" >"$snapshot"
  fi
  stage build "$ROOT/scripts/build.sh" "${CMAKE_ARGS[@]}"
  stage tests quick_tests "$snapshot"
  exit 0
fi

stage_plan install build unit-device acceptance staged-memory sanitizer-build sanitizer-tests fuzzing
stage install "$ROOT/scripts/install-deps.sh"
stage build "$ROOT/scripts/build.sh" "${CMAKE_ARGS[@]}"
cd "$BUILD"
# The unit and device tests: each test program once, all its cases in one process, two programs
# at a time, validation layer on (4.3 min here, against about 8 min as ctest's one process per
# case: each case paid its program's start and its suite's shared set-up again). Then the
# acceptance runs through ctest, everything but the quarter-hour runs labelled long (`ctest -L
# long` runs them; README "Tests").
stage unit-device "$ROOT/scripts/lib/run-test-programs.sh" "$BUILD" 'unit|device'
stage acceptance ctest --output-on-failure -j 2 --timeout 900 -LE 'long|unit|device'
# The path of a discrete GPU (device-local memory never mapped, every copy staged), tested on
# lavapipe on every change: every device test program again with staged memory.
stage staged-memory env STRATA_DEVICE_MEMORY=staged "$ROOT/scripts/lib/run-test-programs.sh" "$BUILD" device
# Sanitizers: the fuzzers (which link every library) and the short list of test programs in
# scripts/sanitizers/ci-programs.txt built with clang, ASan + UBSan (build-san/) and run under
# them, device memory staged (validation layer on; any report fails). Then every parser of outside
# data fuzzed from its committed corpus within one time budget. The whole unit and device suite
# under the sanitizers is `STRATA_SANITIZE_ALL=1 scripts/sanitize.sh` (over an hour cold here, so
# not in CI's 40 minutes). docs/reliability.md, docs/build.md.
stage sanitizer-build "$ROOT/scripts/sanitize.sh" build
stage sanitizer-tests env STRATA_DEVICE_MEMORY=staged "$ROOT/scripts/sanitize.sh" test
stage fuzzing "$ROOT/scripts/fuzz.sh" --total "${STRATA_FUZZ_TOTAL_SECONDS:-120}"
