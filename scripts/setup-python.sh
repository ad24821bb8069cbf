#!/usr/bin/env bash
# The Python package: a virtual environment with what `import rtsph` and its examples need
# (numpy, matplotlib, pytest; nanobind and scikit-build-core to build it), then `pip install .`.
# Installs the Debian packages it needs first (python3-venv, python3-dev, and the C++ build's).
# Usage: scripts/setup-python.sh [VENV]   (default: .venv in the clone)
#        then: VENV/bin/python -c "import rtsph"   (or: source VENV/bin/activate)
# RTSPH_PIP_EDITABLE=1 installs in editable mode (pip install -e .) for development.
set -euo pipefail
cd "$(dirname "$0")/.."
venv="${1:-.venv}"
scripts/setup.sh --packages-only
if [ ! -x "$venv/bin/python" ]; then
  # The system Python: the Debian packages above provide its venv module and headers.
  /usr/bin/python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q --upgrade pip
# The build backend and binding generator are installed here, not in an isolated build
# environment, so a rebuild needs no download (--no-build-isolation below).
"$venv/bin/python" -m pip install -q "numpy>=1.21" "matplotlib>=3.5" "pytest>=7" \
  "nanobind>=2.0" "scikit-build-core>=0.10" ninja
# ccache hits across clones, as in scripts/setup.sh: paths relative to the clone.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
editable=()
[ "${RTSPH_PIP_EDITABLE:-0}" = 1 ] && editable=(-e)
"$venv/bin/python" -m pip install -q --no-build-isolation "${editable[@]}" .
echo "setup-python: rtsph installed in $venv ($("$venv/bin/python" -c 'import rtsph, sys; print(rtsph.__file__)'))"
