#!/usr/bin/env bash
# Configures and builds Strata in Release into build/ (extra CMake arguments are passed through).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# ccache (the build's compiler launcher when installed) with paths relative to the clone and the
# working directory out of the hash of debug builds: a clean clone at another path hits the cache
# an earlier clone filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$ROOT/build" -j "$(nproc)"
