#!/usr/bin/env bash
# `rtsph view` on a GPU machine lent through the `device` tool (issue 10's "rtsph view on a
# machine with a GPU runs the built-in scenes on the GPU, drawn from the GPU buffers"), after
# scripts/device-pack.sh and scripts/device-pack-viewer.sh here:
#   run(command="bash scripts/device-viewer.sh", carry=[".device"], timeout_s=540)
# (each step has its own limit: at most about 500 s in all, usually under 200)
# Starts the carried Xvfb, measures PBF's real-time capacity and the viewer's GPU budget
# headless (pbf_realtime.json), opens each built-in scene in the viewer with the default backend
# (auto: the GPU on a hardware driver) for a few hundred frames with --report, saves a
# screenshot of the default scene, then times drawing 2M particles. Logs to $OUT/viewer.log.
set -uo pipefail
OUT=${OUT:-/tmp/rtsph-out}
LOG=$OUT/viewer.log
. "$(dirname "$0")/device-common.sh"
[ -f .device/x.tar.xz ] || { echo "device-viewer: .device/x.tar.xz is missing: run scripts/device-pack-viewer.sh after scripts/device-pack.sh" | tee -a "$LOG"; exit 1; }
tar -C /tmp -xJf .device/x.tar.xz || exit 1
X=/tmp/x

{ nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader; nproc; } 2>&1 | tee -a "$LOG"
# Xvfb runs xkbcomp and loads swrast_dri.so from the paths Debian built it with.
[ -e /usr/bin/xkbcomp ] || cp "$X/bin/xkbcomp" /usr/bin/xkbcomp
[ -e /usr/share/X11/xkb ] || { mkdir -p /usr/share/X11 && ln -s "$X/xkb" /usr/share/X11/xkb; }
dri=/usr/lib/x86_64-linux-gnu/dri
[ -e $dri/swrast_dri.so ] || { mkdir -p $dri && ln -s "$X/dri/swrast_dri.so" $dri/; }
LD_LIBRARY_PATH=$X/lib setsid "$X/bin/Xvfb" :99 -screen 0 1920x1080x24 -nolisten tcp -xkbdir "$X/xkb" \
  >"$OUT/xvfb.log" 2>&1 &
for _ in $(seq 50); do [ -e /tmp/.X11-unix/X99 ] && break; sleep 0.1; done
export DISPLAY=:99 __GLX_VENDOR_LIBRARY_NAME=nvidia
step 20 env LD_LIBRARY_PATH=$X/lib "$X/bin/glxinfo" -B
step 20 env LD_LIBRARY_PATH=$X/lib __GLX_VENDOR_LIBRARY_NAME=mesa "$X/bin/glxinfo" -B
# $X/lib last: it holds Mesa's GLX client library, without which glvnd found no GLX visual even
# with the NVIDIA vendor named (H200, 2026-11-27); rtsph's own libraries come first.
export LD_LIBRARY_PATH=/tmp/rtsph/pkg/lib:$X/client:$X/lib
# The viewer's budget on this GPU and how its profile keeps up, headless (pbf_realtime.json).
step 60 "$R" bench --backend gpu --realtime --method pbf --dim 3 --json "$OUT/pbf_realtime.json"
printf 'wait 400\nscreenshot %s\nquit\n' "$OUT/view_dam_break_3d.png" >/tmp/shot.txt
step 40 "$R" view --report --script /tmp/shot.txt
step 40 "$R" view dam_break_3d --report --frames 600 --size 1920x1080
for s in $("$R" scenes | awk '{print $1}'); do
  step 20 "$R" view "$s" --report --frames 240
done
# Drawing 2M particles at 1920x1080 headless (EGL), spheres, for the same machine.
step 45 "$R" render dam_break_3d --backend gpu --set fluid.spacing=0.004583 --frames 2 --size 1920x1080 \
  --style particles --out "$OUT/frame_2M.png" --time-draw 200
