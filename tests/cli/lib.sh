# Shared preamble of the CLI tests. Not a test itself (tests/CMakeLists.txt skips it); each
# script, run as `bash SCRIPT RTSPH_BINARY SOURCE_DIR`, starts with
#   source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
# which turns on `set -euo pipefail`, sets $rtsph (the binary, as an absolute path) and $work (a
# temporary directory, removed on exit), and changes into $work.
#
# Sanitizer builds: ASan, LSan and UBSan write their reports to files (log_path), never to the
# stderr that a test reads, so a test that counts the lines rtsph prints counts rtsph's own. A
# report still fails the test: the sanitizer makes rtsph exit non-zero, and on exit this script
# prints every report that holds an error and fails (reports that only list the suppressions
# used are printed as notes).
if [ $# -lt 1 ]; then
  echo "usage: $(basename "$0") RTSPH_BINARY SOURCE_DIR" >&2
  exit 2
fi
set -euo pipefail
rtsph=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d)
sanitizer_logs=$(mktemp -d)
for _v in ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS; do
  export "$_v=${!_v:+${!_v}:}log_path=$sanitizer_logs/report"
done
unset _v

finish() {  # the EXIT trap: sanitizer reports fail the test; temporary files go
  local rc=$? report
  for report in "$sanitizer_logs"/report.*; do
    [ -e "$report" ] || continue
    if grep -qE 'ERROR: |runtime error|SUMMARY: ' "$report"; then
      echo "FAIL: sanitizer report ($(basename "$report")):"
      rc=1
    else
      echo "note: sanitizer log ($(basename "$report")):"
    fi
    cat "$report"
  done
  rm -rf "$work" "$sanitizer_logs"
  exit $rc
}
trap finish EXIT
cd "$work"

fail() {  # fail MESSAGE...: the test fails with this message
  echo "FAIL: $*"
  exit 1
}

runrc() {  # runrc ARGS...: `rtsph run ARGS`, stdout > out.txt, stderr > err.txt, exit code in $rc
  set +e
  "$rtsph" run "$@" >out.txt 2>err.txt
  rc=$?
  set -e
}

waitrc() {  # waitrc PID: waits for a background job, its exit code in $rc
  set +e
  wait "$1"
  rc=$?
  set -e
}

rtsph_lines() {  # rtsph_lines FILE: how many lines of FILE (rtsph's stderr) rtsph itself wrote
  # For runs that load a GL driver: Mesa and other EGL/GLX vendors write warnings to the same
  # stderr ("libEGL warning: ...", "MESA-LOADER: ...") depending on the machine's devices; those
  # lines are shown, not counted. Every line rtsph writes starts with "rtsph". Where no driver is
  # loaded, count every line (wc -l) instead: sanitizer reports never reach stderr (see above).
  local foreign
  foreign=$(grep -v '^rtsph' "$1" || true)
  [ -z "$foreign" ] || printf 'note: not from rtsph (GL driver?), not counted:\n%s\n' "$foreign" >&2
  grep -c '^rtsph' "$1" || true
}

mesa_egl_vendor() {  # prints libglvnd's vendor file for Mesa's EGL, if there is one: a test that
  # sets __EGL_VENDOR_LIBRARY_FILENAMES to it gets Mesa alone, whatever other EGL vendors (NVIDIA)
  # the machine has
  local f
  for f in /usr/share/glvnd/egl_vendor.d/*mesa*.json /etc/glvnd/egl_vendor.d/*mesa*.json; do
    [ -e "$f" ] && { echo "$f"; return 0; }
  done
  return 0
}
