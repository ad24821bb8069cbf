#!/bin/bash
# The surface formats from the command line (issue 11 §5): `--format vdb|obj|ply-mesh` write one
# file per frame listed in index.csv, leave no temporary files, and resume like the particle
# formats (0 → 2T straight and 0 → T + --resume → 2T give byte-identical meshes and the same
# index); a 2D scene and bad surface options are refused with one line naming the option and
# value, exit code 2, before anything is written.
# Usage: surface_export.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
# dam_break_3d at a coarse spacing: 10 x 20 x 15 = 3000 particles. Meshing dominates the run
# time (at the default 0.4 x spacing voxel, 1.2 s a frame against 0.25 s for the whole
# simulation); half a spacing halves it, and nothing checked here depends on the voxel.
small=(dam_break_3d --set fluid.spacing=0.04 --threads 1 --quiet --voxel-size 0.02)

for fmt in vdb obj ply-mesh; do
  "$rtsph" run "${small[@]}" --until 0.1 --every 0.05 --export "out/$fmt" --format "$fmt" >/dev/null
  ext=${fmt%-mesh}
  [ "$(tail -n +2 "out/$fmt/index.csv" | cut -d, -f3 | tr '\n' ' ')" = \
    "frame_000000.$ext frame_000001.$ext frame_000002.$ext " ] || fail "$fmt: index.csv: $(cat "out/$fmt/index.csv")"
  for f in $(tail -n +2 "out/$fmt/index.csv" | cut -d, -f3); do
    [ -s "out/$fmt/$f" ] || fail "$fmt: $f missing or empty"
  done
  ! ls -A "out/$fmt" | grep -q '^\.' || fail "$fmt: temporary files left: $(ls -A "out/$fmt")"
  echo "$fmt: $(ls "out/$fmt" | grep -c frame_) frames, $(du -b "out/$fmt/frame_000002.$ext" | cut -f1) bytes at t = 0.1 s"
done
head -c 4 out/vdb/frame_000000.vdb | od -An -tx1 | grep -q '20 42 44 56' || fail "vdb: no OpenVDB magic number"
grep -q '^f [0-9]*//[0-9]* ' out/obj/frame_000001.obj || fail "obj: no faces"
head -c 400 out/ply-mesh/frame_000001.ply | grep -q 'element face' || fail "ply-mesh: no face element"

# Resume: frames after the checkpoint are rewritten to the same bytes (the surface is a function
# of the particles, and OpenVDB's operations used here do not depend on thread scheduling).
for fmt in obj vdb; do
  "$rtsph" run "${small[@]}" --until 0.1 --every 0.05 --checkpoint-every 0.05 --checkpoint-dir "r/$fmt/c1" \
    --export "r/$fmt/straight" --format "$fmt" >/dev/null
  "$rtsph" run "${small[@]}" --until 0.05 --every 0.05 --checkpoint-every 0.05 --checkpoint-dir "r/$fmt/c2" \
    --export "r/$fmt/resumed" --format "$fmt" >/dev/null
  "$rtsph" run --resume "r/$fmt/c2" --until 0.1 --every 0.05 --threads 1 --quiet --voxel-size 0.02 --export "r/$fmt/resumed" \
    --format "$fmt" >/dev/null
  cmp "r/$fmt/straight/index.csv" "r/$fmt/resumed/index.csv" || fail "$fmt: index.csv differs after resume"
done
for f in r/obj/straight/frame_*; do
  cmp "$f" "r/obj/resumed/$(basename "$f")" || fail "obj: $(basename "$f") differs after resume"
done
# A .vdb holds a random file UUID, so its bytes differ between writes; its grids are compared
# in tests/io_surface_vdb_test.cpp. Here: same frames, same sizes.
for f in r/vdb/straight/frame_*; do
  [ "$(stat -c %s "$f")" = "$(stat -c %s "r/vdb/resumed/$(basename "$f")")" ] ||
    fail "vdb: $(basename "$f") has another size after resume"
done
echo "resume: obj frames byte-identical, vdb frames of the same size, index.csv identical"

expect_refused() {  # expect_refused PATTERN ARGS...
  local pattern=$1; shift
  runrc "$@" --until 0.01 --export refused --quiet
  [ "$rc" = 2 ] || fail "run $* exited $rc, expected 2: $(cat err.txt)"
  grep -q -- "$pattern" err.txt || fail "run $*: no '$pattern' in: $(cat err.txt)"
  [ "$(wc -l <err.txt)" = 1 ] || fail "run $*: message is not one line: $(cat err.txt)"
  [ ! -e refused ] || fail "run $*: wrote into the export directory"
  echo "refused ($*): $(cat err.txt)"
}
expect_refused "--format vdb: surfaces are 3D only and the scene is 2D" dam_break_2d --format vdb
expect_refused "--format obj: surfaces are 3D only" hydrostatic_2d --format obj
expect_refused "--voxel-size 0.05 m: must be between" dam_break_3d --format obj --voxel-size 0.05
expect_refused "--voxel-size -1: must be a positive length" dam_break_3d --format vdb --voxel-size -1
expect_refused "--voxel-size 1e-05 m" dam_break_3d --format vdb --voxel-size 1e-5
expect_refused "--adaptivity 2: must be between 0 and 1" dam_break_3d --format ply-mesh --adaptivity 2
expect_refused "--surface-radius 0.5: must be between" dam_break_3d --format vdb --surface-radius 0.5
expect_refused "unknown output format 'xyz' (valid: csv," dam_break_2d --format xyz
echo "surface_export: all checks passed"
