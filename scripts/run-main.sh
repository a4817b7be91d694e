#!/usr/bin/env bash
# README command 1: install dependencies, build in Release what the main job needs (the `strata`
# program and its libraries; no tests, benchmarks or LCM nodes), run it. With no argument it runs
# the multi-session demo on the shipped room; arguments go to `strata` (e.g. `fuse DIR`).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/install-deps.sh"
"$ROOT/scripts/build.sh" --target strata -DSTRATA_BUILD_TESTS=OFF
"$ROOT/build/bin/strata" "$@"
