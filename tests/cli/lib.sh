# Shared preamble of the CLI tests. Not a test itself (tests/CMakeLists.txt skips it); each
# script, run as `bash SCRIPT RTSPH_BINARY SOURCE_DIR`, starts with
#   source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
# which turns on `set -euo pipefail`, sets $rtsph (the binary, as an absolute path) and $work (a
# temporary directory, removed on exit), and changes into $work.
if [ $# -lt 1 ]; then
  echo "usage: $(basename "$0") RTSPH_BINARY SOURCE_DIR" >&2
  exit 2
fi
set -euo pipefail
rtsph=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
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
