#!/usr/bin/env bash
# Installs what is missing, builds (release preset) and runs the whole test suite.
# Tests run one at a time: each already uses both cores, and OpenMP threads competing for
# cores slow down by an order of magnitude.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
ctest --preset release -j1 "$@"
