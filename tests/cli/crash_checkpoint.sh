#!/bin/bash
# Crash safety of checkpoints and of the simulation state:
#  1. `rtsph run --checkpoint-every` killed with SIGKILL at random moments leaves only complete
#     checkpoints under final names (each one loads), every one with its scene file.
#  2. An export or checkpoint directory that fails mid-run (here: replaced by a plain file, which
#     works for root too) stops the run with a clear message and exit code 1, and the state is
#     saved to $TMPDIR and resumes.
# Usage: crash_checkpoint.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"

wait_for() {  # wait_for DIR GLOB N: until DIR holds at least N files matching GLOB
  for _ in $(seq 400); do
    [ "$(find "$1" -maxdepth 1 -name "$2" 2>/dev/null | wc -l)" -ge "$3" ] && return 0
    sleep 0.05
  done
  fail "nothing like $2 in $1 after 20 s"
}

replace_with_file() {  # replace_with_file DIR: DIR becomes a plain file, even if rtsph re-creates it
  # rtsph creates a missing output directory before each write, so it can win the race between
  # removing DIR and creating the file (the run then never fails, and the test hung under load):
  # repeat until a plain file stands there.
  for _ in $(seq 100); do
    [ -f "$1" ] && return 0
    rm -rf "$1" && touch "$1" 2>/dev/null
    [ -f "$1" ] || sleep 0.02
  done
  fail "could not replace $1 with a file"
}

# 1. SIGKILL while checkpointing (3D: ~1.5 MB per checkpoint, one every few steps).
for trial in 1 2 3 4; do
  d=kill$trial
  "$rtsph" run dam_break_3d --set fluid.spacing=0.03 --until 100 --checkpoint-every 0.002 --checkpoint-dir "$d" \
    --threads 1 --quiet >/dev/null 2>&1 &
  pid=$!
  wait_for "$d" "ckpt_*.ckpt" 3
  sleep "0.$((RANDOM % 500))"
  kill -9 "$pid" 2>/dev/null || fail "rtsph exited before it was killed"
  wait "$pid" 2>/dev/null || true
  n=0
  for f in $(ls "$d"/ckpt_*.ckpt | tail -8); do
    ls "${f%.ckpt}".scene-*.json >/dev/null 2>&1 || fail "$f has no scene file"
    "$rtsph" run --resume "$f" --steps 0 --threads 1 --quiet >/dev/null 2>err.txt ||
      fail "$f does not load: $(cat err.txt)"
    n=$((n + 1))
  done
  for f in "$d"/*; do
    case $(basename "$f") in
      ckpt_*.ckpt | ckpt_*.scene-*.json) ;;
      *) fail "unexpected file under a final name: $f" ;;
    esac
  done
  echo "trial $trial: $(ls "$d"/ckpt_*.ckpt | wc -l) checkpoints, the newest $n load; $(ls -A "$d" | grep -c '^\.' || true) temporary file(s) left"
done

# 2. The export directory disappears mid-run (replaced by a file): exit 1, state rescued.
export TMPDIR=$work/tmp
mkdir -p "$TMPDIR"
"$rtsph" run dam_break_2d --until 100 --threads 1 --export out --every 0.005 --quiet >/dev/null 2>err.txt &
pid=$!
wait_for out "frame_*" 5
mv out out.gone && replace_with_file out
waitrc "$pid"
[ "$rc" = 1 ] || fail "export failure: exit $rc, expected 1: $(cat err.txt)"
grep -Eq "export failed: cannot [a-z ]+ 'out/" err.txt || fail "no clear message: $(cat err.txt)"
rescued=$TMPDIR/rtsph_rescue_dam_break_2d.ckpt
[ -f "$rescued" ] || fail "state not rescued to $rescued: $(cat err.txt)"
grep -q "saved to $rescued" err.txt || fail "rescue location not printed: $(cat err.txt)"
"$rtsph" run --resume "$rescued" --steps 5 --threads 1 --quiet >/dev/null || fail "rescued state does not resume"
echo "export failure: exit 1, state saved to \$TMPDIR and resumes: $(head -1 err.txt)"

# 3. The checkpoint directory fails mid-run: the same.
rm -f "$TMPDIR"/*
"$rtsph" run dam_break_2d --until 100 --threads 1 --checkpoint-every 0.01 --checkpoint-dir ck --quiet >/dev/null 2>err.txt &
pid=$!
wait_for ck "ckpt_*.ckpt" 2
replace_with_file ck
waitrc "$pid"
[ "$rc" = 1 ] || fail "checkpoint failure: exit $rc, expected 1: $(cat err.txt)"
[ -f "$rescued" ] || fail "state not rescued: $(cat err.txt)"
"$rtsph" run --resume "$rescued" --steps 5 --threads 1 --quiet >/dev/null || fail "rescued state does not resume"
echo "checkpoint failure: exit 1, state saved to \$TMPDIR: $(head -1 err.txt)"

# 4. An export directory that cannot be created fails before any work, with the path named.
runrc dam_break_2d --steps 5 --threads 1 --quiet --export out/sub
[ "$rc" = 1 ] && grep -q "out/sub" err.txt || fail "uncreatable export dir: exit $rc: $(cat err.txt)"
echo "uncreatable export directory: exit 1: $(cat err.txt)"
echo "crash_checkpoint: all checks passed"
