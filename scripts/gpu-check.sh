#!/usr/bin/env bash
# The GPU check, in under 4 minutes on a machine with a Vulkan GPU (and on lavapipe, so it keeps
# working): lists the devices, runs the device tests on the picked device, then
# `strata-bench fuse` at 1, 2 and 5 cm and prints one JSON line per voxel size.
#
# Usage: scripts/gpu-check.sh [BUILD_DIR]   (default: build/, made by scripts/build.sh)
# Env:   STRATA_DEVICE picks the device (index or name substring); FRAMES (default 60) frames per
#        size; DATA (default ../shared/data/redkitchen) the RGB-D folder.
# Machines without a Vulkan loader: put Debian's libvulkan1 .deb into .gl/ (see the device notes
# in docs/benchmarks.md); it is unpacked here. Where no driver is registered and the NVIDIA ICD
# file exists, VK_DRIVER_FILES points at it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
FRAMES="${FRAMES:-60}"
DATA="${DATA:-$ROOT/../shared/data/redkitchen}"
NVIDIA_ICD=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json

loaders="$(ldconfig -p 2>/dev/null || true)"
if [[ "$loaders" != *libvulkan.so.1* ]]; then
  if compgen -G "$ROOT/.gl/*.deb" > /dev/null; then
    for deb in "$ROOT"/.gl/*.deb; do dpkg -x "$deb" /; done
    ldconfig
  else
    echo "gpu-check: no Vulkan loader (libvulkan.so.1) and no .gl/*.deb to unpack" >&2
    exit 2
  fi
fi
if [ -z "${VK_DRIVER_FILES:-}" ] && [ -f "$NVIDIA_ICD" ]; then export VK_DRIVER_FILES="$NVIDIA_ICD"; fi

echo "== devices" >&2
"$BUILD/bin/strata" devices

echo "== device tests" >&2
tests_status=0
(cd "$BUILD" && timeout 150 ctest -L device -j "$(nproc)" --timeout 120 --output-on-failure > "$BUILD/gpu-check-tests.log" 2>&1) || tests_status=$?
tail -n 4 "$BUILD/gpu-check-tests.log" >&2

echo "== strata-bench fuse ($FRAMES frames a size)" >&2
for voxel in 0.01 0.02 0.05; do
  # One line per size: the report with its line breaks and indentation folded away.
  "$BUILD/bench/strata-bench" fuse --data "$DATA" --voxel-sizes "$voxel" --frames "$FRAMES" \
      --reference-frames 0 2> /dev/null | tr -s ' \n' ' '
  echo
done
exit "$tests_status"
