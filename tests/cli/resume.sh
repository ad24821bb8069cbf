#!/bin/bash
# `rtsph run --resume`: running 0 → 2T straight and 0 → T, then resuming to 2T, give the same
# bytes (final checkpoint, exported frames, index); damaged, truncated or mismatched
# checkpoints are refused with a one-line message and exit code 2.
# Usage: resume.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
run() { "$rtsph" run "$@" --threads 1 --quiet >/dev/null; }
newest() { ls "$1"/ckpt_*.ckpt | tail -1; }

check_scene() {  # check_scene SCENE T 2T FORMAT
  local scene=$1 t=$2 t2=$3 fmt=$4
  local d=w_$scene
  mkdir "$d"
  run "$scene" --until "$t2" --checkpoint-every "$t" --checkpoint-dir "$d/straight" --export "$d/fs" --format "$fmt" --every 0.02
  run "$scene" --until "$t" --checkpoint-every "$t" --checkpoint-dir "$d/half" --export "$d/fr" --format "$fmt" --every 0.02
  # Resume from the directory (newest checkpoint), scene taken from the file next to it.
  run --resume "$d/half" --until "$t2" --checkpoint-every "$t" --checkpoint-dir "$d/resumed" --export "$d/fr" \
    --format "$fmt" --every 0.02
  local s r
  s=$(newest "$d/straight"); r=$(newest "$d/resumed")
  [ "$(basename "$s")" = "$(basename "$r")" ] || fail "$scene: final steps differ: $s vs $r"
  cmp "$s" "$r" || fail "$scene: final checkpoints differ"
  # The checkpoint at T is the same file in both runs.
  cmp "$(newest "$d/half")" "$d/straight/$(basename "$(newest "$d/half")")" || fail "$scene: checkpoints at T differ"
  cmp "$d/fs/index.csv" "$d/fr/index.csv" || fail "$scene: index.csv differs"
  local n=0
  for f in "$d"/fs/frame_*; do
    cmp "$f" "$d/fr/$(basename "$f")" || fail "$scene: $(basename "$f") differs"
    n=$((n + 1))
  done
  [ -f "$d/fs/frames.pvd" ] && { cmp "$d/fs/frames.pvd" "$d/fr/frames.pvd" || fail "$scene: frames.pvd differs"; }
  # Naming the scene explicitly gives the same result.
  run "$scene" --resume "$(newest "$d/half")" --until "$t2" --checkpoint-dir "$d/named"
  cmp "$s" "$(newest "$d/named")" || fail "$scene: resuming with SCENE named differs"
  echo "$scene: final checkpoint $(basename "$s") ($(stat -c %s "$s") bytes) and $n frames bitwise identical"
}

# Under a sanitizer (RTSPH_SANITIZER=1) over half the time: the same comparisons, fewer steps.
if [ "${RTSPH_SANITIZER:-0}" = 0 ]; then
  check_scene dam_break_2d 0.1 0.2 vtk
  check_scene nozzle_moving_obstacle_2d 0.15 0.3 csv
else
  check_scene dam_break_2d 0.06 0.12 vtk
  check_scene nozzle_moving_obstacle_2d 0.08 0.16 csv
fi

# Refusals: exit code 2 and one line naming the checkpoint.
good=$(newest w_dam_break_2d/half)
expect_refused() {  # expect_refused PATTERN ARGS...
  local pattern=$1; shift
  runrc "$@" --threads 1 --quiet
  [ "$rc" = 2 ] || fail "run $* exited $rc, expected 2: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "run $*: no '$pattern' in: $(cat err.txt)"
  [ "$(wc -l <err.txt)" = 1 ] || fail "run $*: message is not one line: $(cat err.txt)"
  echo "refused ($*): $(cat err.txt)"
}
mkdir bad
cp "$good" bad/trunc.ckpt
cp "$good" bad/corrupt.ckpt
scene_json=$(ls "${good%.ckpt}".scene-*.json)
hash=${scene_json##*.scene-}
cp "$scene_json" "bad/trunc.scene-$hash"
cp "$scene_json" "bad/corrupt.scene-$hash"
size=$(stat -c %s "$good")
truncate -s $((size / 2)) bad/trunc.ckpt
printf '\x5a' | dd of=bad/corrupt.ckpt bs=1 seek=$((size / 3)) conv=notrunc status=none
cp "$good" bad/alone.ckpt
echo "not a checkpoint" >bad/text.ckpt
expect_refused "truncated" --resume bad/trunc.ckpt
expect_refused "checksum mismatch" --resume bad/corrupt.ckpt
expect_refused "bad magic" --resume bad/text.ckpt
expect_refused "scene file .* is missing" --resume bad/alone.ckpt
expect_refused "scene hash mismatch" hydrostatic_2d --resume "$good"
expect_refused "scene hash mismatch" dam_break_2d --set fluid.spacing=0.03 --resume "$good"
expect_refused "dimension mismatch" dam_break_3d --resume "$good"
expect_refused "cannot open" --resume bad/missing.ckpt
expect_refused "set fluid.spacing=0.01: fluid.spacing is fixed by the checkpoint.s scene; .*can only change fluid.viscosity, .*solver.time_step.dt, .* and end_time" --resume "$good" --set fluid.viscosity=0.001 --set fluid.spacing=0.01
expect_refused "set gravity=0,-5: gravity is fixed" --resume "$good" --set gravity=0,-5  # c0 was derived from it
expect_refused "no ckpt_" --resume bad
expect_refused "until 0.001 s is before the checkpoint.s time" --resume "$good" --until 0.001
# Live parameters (and end_time) may change on resume.
run --resume "$good" --set fluid.viscosity=2e-6 --set solver.time_step.mode=fixed --set solver.time_step.dt=2e-4 \
  --set end_time=5 --steps 3
echo "resume: all checks passed"
