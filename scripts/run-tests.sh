#!/usr/bin/env bash
# README command 2: install dependencies, build in Release with warnings as errors, run every test
# on lavapipe with the Vulkan validation layer on. Tests needing ../shared/data skip without it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/install-deps.sh"
"$ROOT/scripts/build.sh" -DSTRATA_BUILD_TESTS=ON -DSTRATA_WERROR=ON
cd "$ROOT/build"
# Everything but the quarter-hour runs labelled long (`ctest -L long` runs them; README "Tests").
ctest --output-on-failure -j 2 --timeout 900 -LE long
# The path of a discrete GPU (device-local memory never mapped, every copy staged), tested here on
# lavapipe on every change.
STRATA_DEVICE_MEMORY=staged ctest --output-on-failure -j 2 --timeout 900 -L device
# Sanitizers: everything rebuilt with clang, ASan + UBSan (build-san/), the unit and device tests
# again under them (validation layer on; any report fails). Then every parser of outside data
# fuzzed from its committed corpus for a bounded time (STRATA_FUZZ_SECONDS per target, 15 by
# default). The acceptance runs are left to the build above. docs/reliability.md.
"$ROOT/scripts/sanitize.sh"
"$ROOT/scripts/fuzz.sh" "${STRATA_FUZZ_SECONDS:-15}"
