#!/bin/bash
# Smoke test of the real viewer under a virtual X server: a scripted session (pause, step,
# brush stroke, obstacle move, screenshot, quit) must exit 0 and leave a non-blank PNG in which
# the 2D obstacle is a filled solid.
# Usage: viewer_smoke.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
set +e +o pipefail  # every check below runs and is counted; none stops the script
bin=$rtsph

run_x() {
  # Runs "$@" with a display: xvfb-run if present, else our own Xvfb, else skip.
  if command -v xvfb-run >/dev/null; then
    xvfb-run -a -s "-screen 0 1024x768x24" "$@"
  elif command -v Xvfb >/dev/null; then
    local d=:$((100 + RANDOM % 800))
    Xvfb "$d" -screen 0 1024x768x24 >/dev/null 2>&1 &
    local xpid=$!
    sleep 1
    DISPLAY=$d "$@"
    local rc=$?
    kill "$xpid" 2>/dev/null
    wait "$xpid" 2>/dev/null
    return $rc
  else
    echo "SKIP: neither xvfb-run nor Xvfb is installed"
    exit 0
  fi
}

not_blank() {
  # True if the PNG has more than one distinct pixel value (python3 when present).
  local png=$1
  [ -s "$png" ] || { echo "missing $png"; return 1; }
  if command -v python3 >/dev/null; then
    python3 - "$png" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
pos, idat, w, h = 8, b'', 0, 0
while pos < len(data):
    n, kind = struct.unpack('>I4s', data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b'IHDR':
        w, h, depth, ctype = struct.unpack('>IIBB', body[:10])
        assert depth == 8 and ctype == 6, 'expected RGBA8'
    elif kind == b'IDAT':
        idat += body
    pos += 12 + n
raw = zlib.decompress(idat)
stride = w * 4 + 1
# Filter bytes aside, a blank image decompresses to rows that are all equal after row 0 with
# filter "up" (all zeros) or identical unfiltered rows; count distinct raw rows and bytes.
rows = {raw[y * stride + 1:(y + 1) * stride] for y in range(h)}
values = set(raw[1:stride])
if len(rows) < 3 and len(values) < 8:
    sys.exit(f'{sys.argv[1]}: blank image ({w}x{h})')
print(f'{sys.argv[1]}: {w}x{h}, {len(rows)} distinct rows')
PY
  else
    [ "$(stat -c %s "$png")" -gt 20000 ] || { echo "$png looks blank (small file)"; return 1; }
  fi
}

obstacle_is_solid() {
  # True if the PNG holds a filled patch of the obstacle grey (RenderSettings::obstacle, 158 158
  # 153 where the 2D shading is flat): a solid disc, not a ring of boundary particles.
  command -v python3 >/dev/null || return 0
  python3 - "$1" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], 'rb').read()
pos, idat = 8, b''
while pos < len(data):
    n, kind = struct.unpack('>I4s', data[pos:pos + 8])
    if kind == b'IHDR':
        w, h = struct.unpack('>II', data[pos + 8:pos + 16])
    elif kind == b'IDAT':
        idat += data[pos + 8:pos + 8 + n]
    pos += 12 + n
raw, stride, prev, count = zlib.decompress(idat), w * 4, bytearray(w * 4), 0
for y in range(h):
    f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = row[i - 4] if i >= 4 else 0
        b, c = prev[i], prev[i - 4] if i >= 4 else 0
        if f == 1: row[i] = (row[i] + a) & 255
        elif f == 2: row[i] = (row[i] + b) & 255
        elif f == 3: row[i] = (row[i] + (a + b) // 2) & 255
        elif f == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    count += sum(1 for x in range(0, stride, 4)
                 if abs(row[x] - 158) <= 3 and abs(row[x + 1] - 158) <= 3 and abs(row[x + 2] - 153) <= 3)
    prev = row
print(f'{sys.argv[1]}: {count} obstacle-grey pixels')
sys.exit(0 if count > 300 else 1)
PY
}

fail=0

# 3D dam break: brush strokes on the fluid.
cat >"$work/dam.txt" <<EOS
wait 2
key space            # pause
key n                # single step
sync
drag left shift 0.25 0.55 0.45 0.55 6   # push
drag right shift 0.45 0.6 0.3 0.6 6     # pull
key n
sync
drag left none 0.5 0.5 0.55 0.52 4      # orbit
scroll 1
key 8                # colour by speed
key tab
screenshot $work/dam.png
key f                # particles (the surface is the default)
screenshot $work/dam_particles.png
wait 2
quit
EOS
out=$(timeout 600 bash -c "$(declare -f run_x); run_x \"$bin\" view dam_break_3d --set fluid.spacing=0.05 --paused --size 480x320 --script \"$work/dam.txt\"" 2>&1)
rc=$?
echo "$out"
[ $rc -eq 0 ] || { echo "FAIL: viewer (dam_break_3d) exited with $rc"; fail=1; }
not_blank "$work/dam.png" || fail=1
not_blank "$work/dam_particles.png" || fail=1
if cmp -s "$work/dam.png" "$work/dam_particles.png"; then echo "FAIL: key f did not change the style"; fail=1; fi
echo "$out" | grep -q "style: particles" || { echo "FAIL: key f did not report the style"; fail=1; }

# 2D scene with an obstacle: Ctrl-drag and q/w a/s keys move it.
cat >"$work/obst.txt" <<EOS
wait 2
key space
drag left ctrl 0.35 0.7 0.45 0.6 5
key w
key s
key n
sync
key 6
screenshot $work/obst.png
key v                # record a few frames
wait 4
key v
wait 1
key esc
EOS
out=$(cd "$work" && timeout 600 bash -c "$(declare -f run_x); run_x \"$bin\" view nozzle_obstacle_2d --size 480x320 --script \"$work/obst.txt\"" 2>&1)
rc=$?
echo "$out"
[ $rc -eq 0 ] || { echo "FAIL: viewer (nozzle_obstacle_2d) exited with $rc"; fail=1; }
not_blank "$work/obst.png" || fail=1
obstacle_is_solid "$work/obst.png" || { echo "FAIL: the obstacle is not drawn as a filled solid"; fail=1; }
echo "$out" | grep -q "no obstacles" && { echo "FAIL: obstacle not found"; fail=1; }
# The recording went to an MP4 (ffmpeg on PATH) or a PNG folder, and the viewer said which.
if command -v ffmpeg >/dev/null; then
  ls "$work"/rtsph_nozzle_obstacle_2d_*.mp4 >/dev/null 2>&1 || { echo "FAIL: no MP4 recording"; fail=1; }
  echo "$out" | grep -q "recording MP4" || { echo "FAIL: recording message"; fail=1; }
else
  ls "$work"/rtsph_nozzle_obstacle_2d_*_frames/frame_000000.png >/dev/null 2>&1 || { echo "FAIL: no PNG recording"; fail=1; }
fi

# The real-time profile's budget: measured on this machine by default (a line says so), or
# given with --realtime-rate (no measurement; the reference machine's rate gives its 10,350
# particles for the 3D dam break on one solver thread).
out=$(timeout 120 bash -c "$(declare -f run_x); run_x \"$bin\" view --threads 1 --frames 2" 2>&1)
echo "$out" | grep -q "this machine steps .* fluid particle-substeps/s per solver thread" ||
  { echo "FAIL: no measurement line"; echo "$out"; fail=1; }
echo "$out" | grep -q "measured on this machine)" || { echo "FAIL: profile does not name the measured rate"; fail=1; }
out=$(timeout 120 bash -c "$(declare -f run_x); run_x \"$bin\" view --threads 1 --realtime-rate 1.26e6 --frames 2" 2>&1)
echo "$out" | grep -q "this machine steps" && { echo "FAIL: measured despite --realtime-rate"; fail=1; }
echo "$out" | grep -q "10350 fluid particles at most.*--realtime-rate)" ||
  { echo "FAIL: --realtime-rate 1.26e6 not the reference budget:"; echo "$out"; fail=1; }

# On the GPU backend the budget is the GPU's own (here llvmpipe's, which keeps few particles in
# real time): probed at a few sizes, and the profile names it.
out=$(timeout 300 bash -c "$(declare -f run_x); run_x \"$bin\" view --backend gpu --frames 2" 2>&1)
echo "$out" | grep -q "this GPU keeps [0-9]* fluid particles of dam_break_3d in real time (PBF substeps of [0-9]* particles" ||
  { echo "FAIL: no GPU measurement line"; echo "$out"; fail=1; }
echo "$out" | grep -q "this machine steps" && { echo "FAIL: the CPU was measured for the GPU backend"; fail=1; }
echo "$out" | grep -q "(3D, pbf, gpu backend)" || { echo "FAIL: not on the GPU backend:"; echo "$out"; fail=1; }
echo "$out" | grep -q "measured on this GPU)" || { echo "FAIL: profile does not name the GPU's rate"; fail=1; }

# No OpenGL 4.3 (Mesa told to offer 3.3): one line on stderr, non-zero exit.
out=$(MESA_GL_VERSION_OVERRIDE=3.3 timeout 120 bash -c "$(declare -f run_x); run_x \"$bin\" view dam_break_2d --frames 3" 2>&1)
rc=$?
echo "$out"
[ $rc -ne 0 ] || { echo "FAIL: viewer without GL 4.3 exited 0"; fail=1; }
echo "$out" | grep -q "OpenGL 4.3" || { echo "FAIL: no GL 4.3 message"; fail=1; }

# A bad script is refused with one line and a non-zero exit, before any window opens.
echo "jump 3" >"$work/bad.txt"
if env -u DISPLAY -u WAYLAND_DISPLAY "$bin" view dam_break_2d --script "$work/bad.txt" 2>"$work/err"; then
  echo "FAIL: bad script accepted"; fail=1
fi
grep -q "bad.txt:1: unknown command 'jump'" "$work/err" || { echo "FAIL: bad script message:"; cat "$work/err"; fail=1; }
# Without a display: one clear line and a non-zero exit.
if env -u DISPLAY -u WAYLAND_DISPLAY "$bin" view dam_break_2d 2>"$work/err"; then
  echo "FAIL: view without a display exited 0"; fail=1
fi
[ "$(wc -l <"$work/err")" -eq 1 ] || { echo "FAIL: expected one line on stderr:"; cat "$work/err"; fail=1; }
cat "$work/err"

[ $fail -eq 0 ] && echo "viewer smoke test passed"
exit $fail
