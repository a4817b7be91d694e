#!/usr/bin/env bash
# scripts/sanitize.sh [build|test|all] [ctest arguments...]: Strata with clang, AddressSanitizer,
# UndefinedBehaviorSanitizer and libFuzzer coverage in build-san/, and the unit and device tests
# run under the sanitizers with the Vulkan validation layer on. Any sanitizer report fails the test
# that triggered it (and so this script).
#   build  configures and builds what the stage is for: every library (through the test
#          executables labelled unit or device, which link all of them), the programs those tests
#          start, and the libFuzzer targets; not the benchmarks and not the acceptance tests.
#   test   runs the unit and device tests: each test program once with all its cases, or, with
#          ctest arguments after it (e.g. -R Mesh), the selected cases one process each.
#   all    (the default) both.
# The heaviest unit/device tests, listed in scripts/sanitizers/heavy-tests.txt, are left to the
# normal build unless STRATA_SANITIZE_ALL=1.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# ccache (the build's compiler launcher when installed) with paths relative to the clone and the
# working directory out of the hash of debug builds: a clean clone at another path hits the cache
# an earlier clone filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
# The tests' precompiled header: ccache caches the objects that use it only with these.
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
BUILD="${STRATA_SANITIZE_BUILD_DIR:-$ROOT/build-san}"
MODE=all
case "${1:-}" in
  build | test | all) MODE="$1"; shift ;;
esac

build() {
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTRATA_BUILD_FUZZ=ON -DSTRATA_BUILD_BENCH=OFF -DSTRATA_WITH_OPEN3D=OFF -DSTRATA_BUILD_TESTS=ON
  local targets=()
  while read -r name label _; do
    [[ "$label" == unit || "$label" == device ]] && targets+=("$name")
  done <"$BUILD/strata_tests.txt"
  for source in "$ROOT"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
  echo "sanitize.sh: building ${#targets[@]} targets (unit and device tests, fuzzers) in $BUILD"
  cmake --build "$BUILD" -j "$(nproc)" --target "${targets[@]}"
}

run_tests() {
  source "$ROOT/scripts/sanitizers/env.sh"
  local exclude="$ROOT/scripts/sanitizers/heavy-tests.txt"
  if [[ "${STRATA_SANITIZE_ALL:-0}" == 1 ]]; then
    exclude=""
  else
    echo "sanitize.sh: leaving $(grep -vc '^#' "$ROOT/scripts/sanitizers/heavy-tests.txt") heavy tests to the normal build (STRATA_SANITIZE_ALL=1 runs them)"
  fi
  if (($# > 0)); then
    # A selection (ctest arguments): one process per test case, as in the normal build.
    local heavy
    cd "$BUILD"
    if [[ -n "$exclude" ]]; then
      heavy="$(grep -v '^#' "$exclude" | grep . | paste -sd '|')"
      ctest --output-on-failure -j 2 --timeout 900 -L "unit|device" -E "^(${heavy})$" "$@"
    else
      ctest --output-on-failure -j 2 --timeout 900 -L "unit|device" "$@"
    fi
  else
    # Everything: each test program once, all its cases in one process (scripts/lib/
    # run-test-programs.sh says why).
    "$ROOT/scripts/lib/run-test-programs.sh" "$BUILD" 'unit|device' $exclude
  fi
}

case "$MODE" in
  build) build ;;
  test) run_tests "$@" ;;
  all) build && run_tests "$@" ;;
esac
