#!/bin/bash
# The GPU backend from the command line, headless through EGL (Mesa llvmpipe in CI): run, bench
# and render with --backend gpu, checkpoints that resume on the other backend, and one clear
# line (exit 2) where the GPU cannot run a scene or the driver has no OpenGL 4.3 compute.
# Usage: gpu_backend.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
set +e +o pipefail
bin=$rtsph
unset DISPLAY WAYLAND_DISPLAY
fail=0
check() { if ! "$@"; then echo "FAIL: $*"; fail=1; fi; }
small=(--set fluid.spacing=0.05)

# run: the header names the backend and its renderer; the summary is written.
"$bin" run dam_break_2d "${small[@]}" --backend gpu --steps 30 --stats-json "$work/g.json" 2>"$work/g.err" >/dev/null
check test $? -eq 0
check grep -q "wcsph, gpu (" "$work/g.err"
check grep -q '"steps": 30' "$work/g.json"
# The scene can ask for the GPU too; --backend overrides it.
"$bin" run dam_break_2d "${small[@]}" --set solver.backend=gpu --steps 5 2>"$work/s.err" >/dev/null
check test $? -eq 0
check grep -q "wcsph, gpu (" "$work/s.err"
"$bin" run dam_break_2d "${small[@]}" --set solver.backend=gpu --backend cpu --steps 5 2>"$work/c.err" >/dev/null
check grep -q "wcsph, cpu)" "$work/c.err"

# A GPU checkpoint resumes on the CPU and the CPU's next one on the GPU.
"$bin" run dam_break_2d "${small[@]}" --backend gpu --steps 30 --checkpoint-dir "$work/ck" --quiet >/dev/null
check test $? -eq 0
check test -s "$work/ck/ckpt_000000030.ckpt"
"$bin" run --resume "$work/ck" --backend cpu --steps 10 --checkpoint-dir "$work/ck" --quiet >/dev/null
check test $? -eq 0
check test -s "$work/ck/ckpt_000000040.ckpt"
"$bin" run --resume "$work/ck" --backend gpu --steps 10 --stats-json "$work/r.json" --quiet >/dev/null
check test $? -eq 0
check grep -q '"steps": 10' "$work/r.json"

# PBF runs on the GPU too.
"$bin" run dam_break_3d --set fluid.spacing=0.05 --set solver.method=pbf --backend gpu --steps 5 --quiet >/dev/null
check test $? -eq 0

# bench and render.
out=$("$bin" bench --backend gpu --dim 2 --particles 400 --steps 5 2>&1)
check test $? -eq 0
check grep -q "backend gpu" <<<"$out"
"$bin" render dam_break_2d "${small[@]}" --backend gpu --out "$work/g.png" --frames 2 --size 96x64 --quiet >/dev/null
check test $? -eq 0
check test -s "$work/g.png"

# The viewer on the GPU backend (under Xvfb when present): steps in the drawing thread's context
# and draws from the GPU's buffers.
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1024x768x24" "$bin" view dam_break_2d "${small[@]}" --backend gpu --frames 20 \
    --size 320x200 --report >"$work/v.out" 2>"$work/v.err"
  check test $? -eq 0
  check grep -q "gpu backend" "$work/v.err"
  check grep -q "20 frames" "$work/v.out"
fi

# DFSPH runs on the GPU too, with the transport velocity as well (in the periodic channel).
"$bin" run dam_break_2d "${small[@]}" --set solver.method=dfsph --backend gpu --steps 5 --quiet >/dev/null 2>"$work/e"
check test $? -eq 0
"$bin" run validate_poiseuille_2d --set solver.method=dfsph --set solver.transport_velocity=1 --backend gpu \
  --steps 3 --quiet >/dev/null 2>"$work/e"
check test $? -eq 0
# Refusal: one line naming the key, exit 2.
"$bin" run dam_break_2d "${small[@]}" --set solver.method=gas --backend gpu --steps 1 2>"$work/e" >/dev/null
rc=$?
check test $rc -eq 2
check test "$(wc -l <"$work/e")" -eq 1
check grep -q "solver.method" "$work/e"
# Periodic axes run on the GPU too (the Poiseuille channel of `rtsph validate`).
"$bin" run validate_poiseuille_2d --backend gpu --steps 20 --quiet >/dev/null 2>"$work/e"
check test $? -eq 0
# A driver without OpenGL 4.3 (Mesa told to offer 3.3).
MESA_GL_VERSION_OVERRIDE=3.3 "$bin" run dam_break_2d "${small[@]}" --backend gpu --steps 1 2>"$work/e" >/dev/null
check test $? -eq 2
check test "$(wc -l <"$work/e")" -eq 1
check grep -q "no OpenGL 4.3" "$work/e"
exit $fail
