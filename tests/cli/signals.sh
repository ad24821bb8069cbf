#!/bin/bash
# SIGINT/SIGTERM: `rtsph run` finishes the step in progress, writes a final checkpoint and the
# summary, and exits with 130/143. The checkpoint holds exactly the state a run of the same
# number of steps ends with, and resumes.
# Usage: signals.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"

wait_for_frames() {  # wait_for_frames DIR N
  for _ in $(seq 400); do
    [ -f "$1/index.csv" ] && [ "$(wc -l <"$1/index.csv")" -gt "$2" ] && return 0
    sleep 0.05
  done
  fail "no frames in $1 after 20 s"
}

for sig in INT TERM; do
  case $sig in INT) want=130 ;; TERM) want=143 ;; esac
  for mode in default dir; do
    out=$sig-$mode
    extra=()
    [ "$mode" = dir ] && extra=(--checkpoint-dir "$out/ckpt" --stats-json "$out.json")
    "$rtsph" run dam_break_2d --until 1000 --threads 1 --export "$out" --every 0.01 "${extra[@]}" \
      >"$out.stdout" 2>"$out.stderr" &
    pid=$!
    wait_for_frames "$out" 3
    kill -"$sig" "$pid"
    waitrc "$pid"
    [ "$rc" = "$want" ] || fail "SIG$sig ($mode): exit $rc, expected $want: $(cat "$out.stderr")"
    grep -q "^status  *interrupted" "$out.stdout" || fail "SIG$sig ($mode): no summary: $(cat "$out.stdout")"
    grep -q "stopped by SIG$sig" "$out.stderr" || fail "SIG$sig ($mode): no message: $(cat "$out.stderr")"
    if [ "$mode" = default ]; then
      ckpt=$out/rtsph_interrupted_dam_break_2d.ckpt  # next to the frames
    else
      ckpt=$(ls "$out"/ckpt/ckpt_*.ckpt | tail -1)
      grep -q '"status": "interrupted"' "$out.json" || fail "stats json: $(cat "$out.json")"
    fi
    [ -f "$ckpt" ] || fail "SIG$sig ($mode): no checkpoint $ckpt: $(ls -R "$out")"
    grep -q -- "--resume $ckpt" "$out.stderr" || fail "SIG$sig ($mode): no resume hint: $(cat "$out.stderr")"
    # The interrupted state is exactly the state after that many steps.
    steps=$(sed -n 's/^steps  *//p' "$out.stdout")
    "$rtsph" run dam_break_2d --steps "$steps" --threads 1 --quiet --checkpoint-dir "$out-ref" >/dev/null
    cmp "$ckpt" "$out-ref/$(printf 'ckpt_%09d.ckpt' "$steps")" || fail "SIG$sig ($mode): checkpoint differs from a $steps-step run"
    # ... and it resumes.
    "$rtsph" run --resume "$ckpt" --steps 10 --threads 1 --quiet >/dev/null || fail "SIG$sig ($mode): resume failed"
    echo "SIG$sig ($mode): exit $rc after $steps steps, checkpoint $ckpt matches a $steps-step run and resumes"
  done
done
echo "signals: all checks passed"
