#!/bin/bash
# Registered only in leak-checked builds (cmake/sanitizers.cmake). The mechanism that keeps GL
# driver leaks from failing tests (tests/lsan.supp, with driver modules kept loaded by
# tests/support/keep_modules_loaded.cpp) must not hide leaks in rtsph's own code: lsan_leak_helper
# creates and destroys a headless GL context as rtsph does, then leaks 4321 bytes from
# rtsph::test_support::leak_on_purpose. Under the suite's LSAN_OPTIONS, LeakSanitizer must report
# exactly that leak and fail the process: once with the machine's GL, once with every EGL probe
# failing (MESA_GL_VERSION_OVERRIDE=3.3: the driver is loaded and unloaded for each platform and
# device, the case of issue 15).
# It also checks that no pattern in the suppressions file matches rtsph's own functions or source
# files (a pattern matches any substring of a frame's module, function or file: "dri" would hide
# every leak under Wcsph::drift).
# Usage: lsan_reports_own_leak.sh LSAN_LEAK_HELPER RTSPH_BINARY
set -u
helper=$1
rtsph=$2
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case "${LSAN_OPTIONS:-}" in
  *suppressions=*) echo "LSAN_OPTIONS=$LSAN_OPTIONS" ;;
  *) echo "FAIL: LSAN_OPTIONS names no suppressions file; run through ctest --preset asan-ubsan"
     exit 1 ;;
esac
fail=0

supp=$(sed -n 's/^\(.*:\)\{0,1\}suppressions=\([^:]*\).*/\2/p' <<<"$LSAN_OPTIONS")
own=$( (nm -C --defined-only "$rtsph" | cut -d' ' -f3- | grep -F 'rtsph::'
        cd "$src" && find src apps -name '*.cpp' -o -name '*.h') | sort -u)
[ -n "$own" ] || { echo "FAIL: cannot list rtsph's functions (nm) and files"; fail=1; }
while IFS= read -r line; do
  case $line in leak:?*) pattern=${line#leak:} ;; *) continue ;; esac
  # LeakSanitizer's templates: substring, * any run, ^ and $ anchors.
  regex=$(sed -e 's/[][\.+?(){}|]/\\&/g' -e 's/\*/.*/g' <<<"$pattern")
  hits=$(grep -E -- "$regex" <<<"$own" | head -3 | cut -c1-160)
  [ -z "$hits" ] || { echo "FAIL: suppression 'leak:$pattern' matches rtsph's own code:"; echo "$hits"; fail=1; }
done <"${supp:-/dev/null}"
echo "checked the patterns of ${supp:-?} against $(wc -l <<<"$own") functions and files of rtsph"

for mode in default no-gl43; do
  echo "== $mode"
  if [ $mode = no-gl43 ]; then
    MESA_GL_VERSION_OVERRIDE=3.3 "$helper" >"$work/out" 2>"$work/err"
  else
    "$helper" >"$work/out" 2>"$work/err"
  fi
  rc=$?
  cat "$work/out" "$work/err"
  echo "(exit code $rc)"
  bad() { echo "FAIL ($mode): $*"; fail=1; }
  [ $rc -ne 0 ] || bad "the helper exited 0: the leak did not fail it"
  grep -q "ERROR: LeakSanitizer: detected memory leaks" "$work/err" || bad "no leak report"
  # Exactly one leak reported, ours: the driver's are all suppressed.
  leaks=$(grep -cE '^(Direct|Indirect) leak of' "$work/err")
  [ "$leaks" -eq 1 ] || bad "$leaks leak reports, expected exactly 1 (the deliberate one)"
  grep -q '^Direct leak of 4321 byte(s) in 1 object(s)' "$work/err" ||
    bad "the deliberate 4321-byte leak is not reported"
  # Its allocation stack names the function that leaked (symbolised: rtsph's own code).
  awk '/^Direct leak of 4321 byte/ {on = 1; next} on && /^$/ {exit} on' "$work/err" |
    grep -q 'rtsph::test_support::leak_on_purpose' ||
    bad "the leak's stack does not name rtsph::test_support::leak_on_purpose"
  grep -q 'SUMMARY: AddressSanitizer: 4321 byte(s) leaked in 1 allocation(s)' "$work/err" ||
    bad "the summary is not exactly the deliberate leak"
done
[ $fail -eq 0 ] && echo "LeakSanitizer reports rtsph's own leak, and no leak of the GL driver"
exit $fail
