#!/usr/bin/env bash
# scripts/build.sh [--target T]... [CMAKE_ARGS...]: configures Strata in Release into build/ (the
# CMake arguments are passed through) and builds the named targets, or everything without one.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# ccache (the build's compiler launcher when installed) with paths relative to the clone and the
# working directory out of the hash of debug builds: a clean clone at another path hits the cache
# an earlier clone filled.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$ROOT}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-true}"
# The tests' precompiled header: ccache caches the objects that use it only with these.
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
targets=()
cmake_args=()
while (($#)); do
  case "$1" in
    --target) targets+=(--target "${2:?build.sh: --target needs a name}"); shift 2 ;;
    *) cmake_args+=("$1"); shift ;;
  esac
done
# The Python package is built for Debian's interpreter (python3-dev, pybind11-dev, numpy are its
# packages), not for another python3 that may come first on PATH (pyenv).
if [ -x /usr/bin/python3 ]; then cmake_args=(-DPython_EXECUTABLE=/usr/bin/python3 "${cmake_args[@]}"); fi
cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}"
cmake --build "$ROOT/build" -j "$(nproc)" "${targets[@]}"
