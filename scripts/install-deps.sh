#!/usr/bin/env bash
# Installs every build, test and run dependency of Strata from Debian 12 packages.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
PACKAGES=(
  cmake ninja-build g++ pkg-config ccache git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libeigen3-dev libopencv-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev libembree-dev
  liblcm-dev liblcm-bin libglib2.0-dev iproute2 util-linux
  clang libclang-rt-14-dev llvm lld
  libceres-dev
  libsqlite3-dev
  libhnswlib-dev
  libpcl-dev
  libompl-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pil
  libboost-dev chromium fonts-dejavu-core
)
# Node.js and npm for the viewer page's packages: Debian's, unless the machine has its own.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then PACKAGES+=(nodejs npm); fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "strata: installing ${missing[*]}" >&2
  $SUDO apt-get update
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "strata: all Debian dependencies already installed" >&2
fi
# The viewer page's packages (three.js, esbuild, playwright-core), exactly as web/package-lock.json
# pins them; nothing else is downloaded (playwright-core drives Debian's chromium).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ ! -f "$ROOT/web/node_modules/.package-lock.json" ] ||
   ! cmp -s "$ROOT/web/package-lock.json" "$ROOT/web/node_modules/.strata-lock"; then
  echo "strata: npm ci in web/" >&2
  (cd "$ROOT/web" && npm ci --no-audit --no-fund --loglevel=error)
  cp "$ROOT/web/package-lock.json" "$ROOT/web/node_modules/.strata-lock"
else
  echo "strata: web/ npm packages already installed" >&2
fi
