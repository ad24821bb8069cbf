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
#   steps; tests/run_checkpoint_test.cpp and tests/cli/resume.sh do).
# - The long physics validations are skipped here (LONG_PHYSICS below): each runs seconds of
#   simulated time to compare against an analytic or experimental answer, which is what the
#   release build's run checks; under ASan they took 25-70 s each, about 10 of the 24 minutes
#   of the suite in the CI run of 2026-11-27 (docs/performance.md), and their code paths all run
#   here through shorter tests of the same method, kernel and backend (the same tanks in 3D
#   with PBF and DFSPH, the other dam breaks and toy stars, the GPU methods' comparisons; DFSPH's
#   pressure stabilisation in GpuBackend.PressureStabilisationAsOnTheCpu's CPU run).
# - RTSPH_ASAN_EXCLUDE: a ctest regex of tests to skip instead (default: LONG_PHYSICS; set it
#   to a regex that matches nothing, e.g. '^$', to run everything).
# Extra arguments go to ctest.
# Usage: scripts/test-asan.sh [ctest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh asan-ubsan
export RTSPH_SANITIZER=1
LONG_PHYSICS='^(GpuBackend\.(Wcsph|Pbf|Dfsph)TankSettlesToRhoGH|Hydrostatic\.Tank(2D|3D)SettlesToRhoGH'
LONG_PHYSICS+='|TransportVelocity\.TaylorGreenDecaysAtTheViscousRate|Gas\.ToyStarOscillatesAtItsAnalyticFrequencies'
LONG_PHYSICS+='|Gas\.PolytropeRelaxesToLaneEmden|Methods/DamBreak2D\.SurgeFrontFollowsMartinMoyce/wcsph'
LONG_PHYSICS+='|PressureStabilisation\.FixesTheLayerAlternatingPressure'
LONG_PHYSICS+='|Methods/WallsHold\.DamBreakPutsNothingBack/dam_break_(2d|3d)_wcsph'
LONG_PHYSICS+='|All/GpuMethods\.DamBreakFollowsTheCpuFor200Steps/"dfsph")( |$)'
exclude="${RTSPH_ASAN_EXCLUDE-$LONG_PHYSICS}"
# (Parameterised tests carry " # GetParam() = ..." in their names, hence "( |$)".) Each test
# uses both cores already; tests in parallel only compete (see scripts/test.sh).
exec ctest --preset asan-ubsan -j1 -E "$exclude" "$@"
