#!/usr/bin/env bash
# Issue 10 §5's GPU figures in one device call, after scripts/device-pack.sh here:
#   run(command="bash scripts/device-gpu-bench.sh", carry=[".device"], timeout_s=600)
# Unpacks the portable rtsph and the GL loaders, checks that the GPU backend starts through EGL,
# then runs each measurement under its own time limit (so one that hangs or runs long costs
# only its share), logging to $OUT/gpu-bench.log with JSON tables and a frame beside it.
# RTSPH_DEVICE_QUICK=1 runs small sizes only (a check of the script, a minute or two);
# RTSPH_DEVICE_PROFILE=1 the stage tables and iteration counts behind the figures instead.
set -uo pipefail
OUT=${OUT:-/tmp/rtsph-out}
LOG=$OUT/gpu-bench.log
. "$(dirname "$0")/device-common.sh"
export LD_LIBRARY_PATH=/tmp/rtsph/pkg/lib

{ nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader; nproc; uname -r; } 2>&1 | tee -a "$LOG"
step 40 "$R" run dam_break_3d --backend gpu --until 0.01
if [ "${RTSPH_DEVICE_QUICK:-0}" = 1 ]; then
  step 60 "$R" bench --backend gpu --dim 3 --particles 100000 --steps 20
  step 60 "$R" render dam_break_3d --backend gpu --frames 2 --size 1920x1080 --style particles \
    --out "$OUT/frame.png" --time-draw 20
  exit 0
fi
if [ "${RTSPH_DEVICE_PROFILE:-0}" = 1 ]; then
  step 60 "$R" bench --backend gpu --dim 3 --particles 1000000,4000000 --steps 20 --json "$OUT/wcsph_stages.json"
  step 60 "$R" bench --backend gpu --method pbf --dim 3 --particles 250000,1000000 --steps 10 --json "$OUT/pbf_stages.json"
  step 60 "$R" bench --backend gpu --method pbf --dim 3 --particles 250000,1000000 --steps 10 \
    --set solver.pbf.max_density_error=0 --json "$OUT/pbf_fixed_stages.json"
  step 60 "$R" bench --backend gpu --method dfsph --dim 3 --particles 250000,1000000 --steps 10 --json "$OUT/dfsph_stages.json"
  step 60 "$R" bench --backend gpu --realtime --method pbf --dim 3 --json "$OUT/pbf_realtime.json"
  step 60 "$R" bench --backend gpu --realtime --method pbf --dim 3 --set solver.pbf.max_density_error=0 \
    --json "$OUT/pbf_fixed_realtime.json"
  step 60 "$R" bench --backend gpu --realtime --method dfsph --dim 3 --json "$OUT/dfsph_realtime.json"
  exit 0
fi
# WCSPH throughput, full physics (floor 7e8 fluid particle-steps/s at 4M)
step 120 "$R" bench --backend gpu --dim 3 --particles 262144,1000000,4000000 --steps 50 --json "$OUT/wcsph.json"
# PBF real-time capacity (floor 1M fluid particles)
step 120 "$R" bench --backend gpu --realtime --method pbf --dim 3 --json "$OUT/pbf_realtime.json"
# PBF per-stage costs at the sizes the capacity search lands near
step 45 "$R" bench --backend gpu --method pbf --dim 3 --particles 1000000,4000000 --steps 10 --json "$OUT/pbf.json"
# DFSPH throughput and capacity (no target; the device-side stopping test's first figures)
step 60 "$R" bench --backend gpu --method dfsph --dim 3 --particles 250000,1000000 --steps 20 --json "$OUT/dfsph.json"
# Drawing at 2M particles, 1920x1080, spheres, from the solver's buffers (floor 60 fps): the dam
# break's 0.192 m^3 of water at spacing 0.004583 m is 1,994,475 particles (0.00572 m is 1.03M).
step 60 "$R" render dam_break_3d --backend gpu --set fluid.spacing=0.004583 --frames 2 --size 1920x1080 \
  --style particles --out "$OUT/frame_2M.png" --time-draw 200
step 45 "$R" render dam_break_3d --backend gpu --set fluid.spacing=0.004583 --frames 2 --size 1920x1080 \
  --out "$OUT/frame_2M_surface.png" --time-draw 50
