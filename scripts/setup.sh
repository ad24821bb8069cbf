#!/usr/bin/env bash
# Installs the Debian packages rtsph needs (only the missing ones), then configures and builds.
# Idempotent: a second run installs nothing and rebuilds incrementally.
# Usage: scripts/setup.sh [preset]   (default preset: release)
#        scripts/setup.sh --packages-only   (install the missing packages, build nothing)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"

pkgs=(build-essential cmake ninja-build pkg-config libepoxy-dev libegl-dev libgl1-mesa-dri
      libegl-mesa0 libglfw3-dev libglm-dev libimgui-dev libstb-dev xvfb xauth
      nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev libfmt-dev ffmpeg
      glslang-tools ccache mesa-utils python3-venv python3-dev
      libopenvdb-dev libboost-iostreams-dev)
# libopenvdb-dev brings TBB, Blosc and Imath; Debian's FindOpenVDB.cmake also requires
# Boost.Iostreams (delayed loading), which the package does not depend on.
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
[ "$preset" = --packages-only ] && exit 0

# Paths relative to the clone, so a fresh clone elsewhere (CI) hits the same cache entries.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset"
