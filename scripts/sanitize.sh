#!/usr/bin/env bash
# scripts/sanitize.sh [build|test|all] [ctest arguments...]: Strata with clang, AddressSanitizer,
# UndefinedBehaviorSanitizer and libFuzzer coverage in build-san/, and the unit and device tests
# run under the sanitizers with the Vulkan validation layer on. Any sanitizer report fails the test
# that triggered it (and so this script).
#   build  configures and builds what the stage is for: the libFuzzer targets (which link every
#          library) and the test programs of scripts/sanitizers/ci-programs.txt, with the programs
#          those tests start; with STRATA_SANITIZE_ALL=1 every unit and device test program.
#   test   runs those test programs, each once with all its cases, or, with ctest arguments
#          after it (e.g. -R Mesh), the selected cases one process each.
#   all    (the default) both.
# CI's stage is the short list of ci-programs.txt, chosen to fit its time; STRATA_SANITIZE_ALL=1
# runs every unit and device test program, the heaviest test cases
# (scripts/sanitizers/heavy-tests.txt) included.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# ccache (the build's compiler launcher when installed) with paths relative to the clone and the
# working directory out of the hash of debug builds: a clean clone at another path hits the cache
# an earlier clone filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
# The tests' precompiled header: ccache caches the objects that use it only with these.
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
BUILD="${STRATA_SANITIZE_BUILD_DIR:-$ROOT/build-san}"
PROGRAMS="$ROOT/scripts/sanitizers/ci-programs.txt"
MODE=all
case "${1:-}" in
  build | test | all) MODE="$1"; shift ;;
esac

build() {
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTRATA_BUILD_FUZZ=ON -DSTRATA_BUILD_BENCH=OFF -DSTRATA_WITH_OPEN3D=OFF -DSTRATA_BUILD_TESTS=ON
  local targets=()
  if [[ "${STRATA_SANITIZE_ALL:-0}" == 1 ]]; then
    while read -r name label _; do
      [[ "$label" == unit || "$label" == device ]] && targets+=("$name")
    done <"$BUILD/strata_tests.txt"
  else
    mapfile -t targets < <(grep -v '^#' "$PROGRAMS" | grep .)
  fi
  for source in "$ROOT"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
  echo "sanitize.sh: building ${#targets[@]} targets (test programs, fuzzers) in $BUILD"
  cmake --build "$BUILD" -j "$(nproc)" --target "${targets[@]}"
}

run_tests() {
  source "$ROOT/scripts/sanitizers/env.sh"
  local exclude="$ROOT/scripts/sanitizers/heavy-tests.txt" programs="$PROGRAMS"
  if [[ "${STRATA_SANITIZE_ALL:-0}" == 1 ]]; then
    exclude=""
    programs=""
  else
    echo "sanitize.sh: the $(grep -vc '^#' "$PROGRAMS") programs of $PROGRAMS, less $(grep -vc '^#' "$exclude") heavy test cases (STRATA_SANITIZE_ALL=1 runs every program and case)"
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
    "$ROOT/scripts/lib/run-test-programs.sh" "$BUILD" 'unit|device' "$exclude" "$programs"
  fi
}

case "$MODE" in
  build) build ;;
  test) run_tests "$@" ;;
  all) build && run_tests "$@" ;;
esac
