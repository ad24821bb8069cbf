#!/usr/bin/env bash
# Installs what is missing, builds (release preset) and runs the whole test suite, then the
# Python package's tests (scripts/test-python.sh) and `rtsph validate --quick --known-failures`
# (RTSPH_SKIP_PYTHON=1 skips both).
# Tests run one at a time: each already uses both cores, and OpenMP threads competing for
# cores slow down by an order of magnitude.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh release
ctest --preset release -j1 "$@"
# The Python package, installed into a fresh virtual environment and tested with pytest; then
# the validation suite at its quick level (17-21 minutes on 2 cores, 91% of it the surface-tension
# drops; docs/performance.md, session 40), held to its tolerances
# except for the known failures python/rtsph/validate/known.py lists, which may not get worse.
# Two one-thread jobs: most quick cases are too small for two solver threads, and the figures
# are the same bits for any thread count.
if [ "${RTSPH_SKIP_PYTHON:-0}" != 1 ]; then
  scripts/test-python.sh
  RTSPH_PYTHON=build/pytest-venv/bin/python build/release/rtsph validate --quick --known-failures \
    --jobs 2 --threads 1 --out build/validate-quick
fi
