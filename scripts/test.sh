#!/usr/bin/env bash
# Installs what is missing, builds (release preset) and runs the whole test suite, then the
# Python package's tests (scripts/test-python.sh; RTSPH_SKIP_PYTHON=1 skips them).
# Tests run one at a time: each already uses both cores, and OpenMP threads competing for
# cores slow down by an order of magnitude.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
ctest --preset release -j1 "$@"
# The Python package, installed into a fresh virtual environment and tested with pytest.
[ "${RTSPH_SKIP_PYTHON:-0}" = 1 ] || scripts/test-python.sh
