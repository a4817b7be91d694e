#!/usr/bin/env bash
# Configures and builds Strata in Release into build/ (extra CMake arguments are passed through).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$ROOT/build" -j "$(nproc)"
