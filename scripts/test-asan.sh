#!/usr/bin/env bash
# Builds the asan-ubsan preset (AddressSanitizer + UBSan, leaks checked with tests/lsan.supp)
# and runs the whole test suite under it: GoogleTest executables and tests/cli/*.sh.
#
# - RTSPH_SANITIZER=1 is exported; tests may shorten long runs with it (same checks, fewer
#   steps). The physics validations run in full: about 50 s (hydrostatic) and 25 s (dam break)
#   under ASan on 2 cores.
# - OMP_WAIT_POLICY=passive: spinning OpenMP workers and ASan slow each other down badly when
#   cores are shared.
# - OpenGL tests (RTSPH_ASAN_GL_TESTS) run in a second pass without leak checking: Mesa's
#   drivers are unloaded before LeakSanitizer reports, so their allocations cannot be matched
#   by tests/lsan.supp. ASan and UBSan still check them. Set RTSPH_ASAN_GL_TESTS="" to run
#   them with leak checking.
# - RTSPH_ASAN_EXCLUDE: a ctest regex of tests to skip (default: none).
# Extra arguments go to both ctest passes.
# Usage: scripts/test-asan.sh [ctest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh asan-ubsan
export RTSPH_SANITIZER=1
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
gl="${RTSPH_ASAN_GL_TESTS-RenderGl|ShadersGl|Shader|cli_render_smoke|cli_viewer_smoke}"
exclude="${RTSPH_ASAN_EXCLUDE-}"

# Each test uses both cores already; tests in parallel only compete (see scripts/test.sh).
rc=0
skip="$exclude"
[ -n "$gl" ] && skip="${skip:+$skip|}$gl"
if [ -n "$skip" ]; then
  ctest --preset asan-ubsan -j1 -E "$skip" "$@" || rc=$?
else
  ctest --preset asan-ubsan -j1 "$@" || rc=$?
fi
if [ -n "$gl" ]; then
  echo "test-asan: OpenGL tests, leak checking off (Mesa)" >&2
  args=(-R "$gl")
  [ -n "$exclude" ] && args+=(-E "$exclude")
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" ctest --preset asan-ubsan -j1 "${args[@]}" "$@" || rc=$?
fi
exit "$rc"
