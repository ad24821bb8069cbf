# Sourced by the device scripts (device-gpu-bench.sh, device-viewer.sh) with LOG set: brings a
# bare GPU machine glvnd's GL loaders, unpacks scripts/device-pack.sh's rtsph into /tmp/rtsph
# (R is its binary), defines step, and names the NVIDIA EGL vendor file where glvnd's default
# search misses it (the device tool's README).
mkdir -p "$(dirname "$LOG")"
# (grep reads all of ldconfig's output: with -q it could stop early, and under pipefail the
# writer's SIGPIPE would read as "not found" and unpack over the machine's own loaders.)
if ! ldconfig -p | grep 'libEGL.so.1 ' >/dev/null; then  # a bare GPU machine: bring glvnd's loaders
  for f in .device/gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
[ -f .device/rtsph-device.tar.xz ] || { echo "device: .device/rtsph-device.tar.xz is missing: run scripts/device-pack.sh" | tee -a "$LOG"; exit 1; }
mkdir -p /tmp/rtsph
tar -C /tmp/rtsph -xJf .device/rtsph-device.tar.xz || exit 1
R=/tmp/rtsph/pkg/bin/rtsph

step() {  # step LIMIT_S COMMAND...: run it under a time limit, log its output and exit status
  local limit=$1
  shift
  echo "== $(date -u +%T) $* (limit ${limit} s)" | tee -a "$LOG"
  timeout "$limit" "$@" 2>&1 | tee -a "$LOG"
  echo "== exit ${PIPESTATUS[0]}" | tee -a "$LOG"
}

if ! LD_LIBRARY_PATH=/tmp/rtsph/pkg/lib timeout 30 "$R" run dam_break_3d --backend gpu --until 0.001 --quiet >/dev/null 2>&1; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
