#!/usr/bin/env bash
# Builds Strata with clang, AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer coverage into
# build-san/ and runs the unit and device tests under the sanitizers with the Vulkan validation layer
# on. Any sanitizer report fails the test that triggered it (and so this script). The multi-minute
# acceptance runs are left to the normal build, and so are the heaviest unit/device tests listed in
# scripts/sanitizers/heavy-tests.txt unless STRATA_SANITIZE_ALL=1. Extra arguments go to ctest
# (e.g. -R Mesh).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# ccache (the build's compiler launcher when installed) with paths relative to the clone and the
# working directory out of the hash of debug builds: a clean clone at another path hits the cache
# an earlier clone filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
BUILD="${STRATA_SANITIZE_BUILD_DIR:-$ROOT/build-san}"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTRATA_BUILD_FUZZ=ON -DSTRATA_BUILD_BENCH=OFF -DSTRATA_WITH_OPEN3D=OFF -DSTRATA_BUILD_TESTS=ON
cmake --build "$BUILD" -j "$(nproc)"
source "$ROOT/scripts/sanitizers/env.sh"
cd "$BUILD"
exclude=()
if [[ "${STRATA_SANITIZE_ALL:-0}" != 1 ]]; then
  heavy="$(grep -v '^#' "$ROOT/scripts/sanitizers/heavy-tests.txt" | grep . | paste -sd '|')"
  exclude=(-E "^(${heavy})$")  # "." in a name matches itself too
  echo "sanitize.sh: leaving $(grep -vc '^#' "$ROOT/scripts/sanitizers/heavy-tests.txt") heavy tests to the normal build (STRATA_SANITIZE_ALL=1 runs them)"
fi
ctest --output-on-failure -j 2 --timeout 900 -L "unit|device" "${exclude[@]}" "$@"
