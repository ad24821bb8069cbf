#!/usr/bin/env bash
# Builds the asan-ubsan preset (AddressSanitizer + UBSan, leaks checked with tests/lsan.supp)
# and runs the whole test suite under it: GoogleTest executables and tests/cli/*.sh.
#
# - Leaks inside the GL driver are suppressed by module name; the build keeps driver modules
#   loaded until exit so that LeakSanitizer can name them (cmake/sanitizers.cmake), and the test
#   lsan_reports_own_leak checks that a leak in rtsph's own code is still reported.
# - The CLI tests send sanitizer reports to files (tests/cli/lib.sh), so that counting the lines
#   rtsph prints is not thrown off; any report with an error still fails the test and is printed.
# - RTSPH_SANITIZER=1 is exported; tests may shorten long runs with it (same checks, fewer
#   steps; tests/run_checkpoint_test.cpp does). The physics validations run in full: about
#   50 s (hydrostatic) and 25 s (dam break) under ASan on 2 cores; the whole suite about 6 min
#   after a first build of ~25 min (cli_render_smoke took 200-360 s of it while plain `rtsph`'s
#   headless video ran WCSPH; it runs PBF since 2026-11-26, session 17).
# - RTSPH_ASAN_EXCLUDE: a ctest regex of tests to skip (default: none).
# Extra arguments go to ctest.
# Usage: scripts/test-asan.sh [ctest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh asan-ubsan
export RTSPH_SANITIZER=1
exclude="${RTSPH_ASAN_EXCLUDE:-}"
# Each test uses both cores already; tests in parallel only compete (see scripts/test.sh).
if [ -n "$exclude" ]; then
  exec ctest --preset asan-ubsan -j1 -E "$exclude" "$@"
fi
exec ctest --preset asan-ubsan -j1 "$@"
