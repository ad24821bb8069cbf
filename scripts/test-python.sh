#!/usr/bin/env bash
# The Python package's tests (python/tests, pytest) in a fresh virtual environment, as a user
# would install it: build/pytest-venv is recreated, rtsph is installed into it with pip, and
# pytest runs against the installed package (not the source tree). scripts/test.sh calls this.
# RTSPH_BINARY: the CLI the bit-for-bit comparison runs (default build/release/rtsph).
# Extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=build/pytest-venv
rm -rf "$venv"
scripts/setup-python.sh "$venv"
export RTSPH_BINARY="${RTSPH_BINARY:-$PWD/build/release/rtsph}"
# From another directory, so `import rtsph` finds the installed package, not python/rtsph.
cd "$(mktemp -d)"
set +e
"$OLDPWD/$venv/bin/python" -m pytest -q -p no:cacheprovider "$OLDPWD/python/tests" "$@"
rc=$?
set -e
# pytest's 5 means no test was collected: a broken suite, never a pass.
if [ "$rc" -eq 5 ]; then echo "test-python: pytest collected no tests" >&2; exit 1; fi
exit "$rc"
