#!/usr/bin/env bash
# Prints a short description of the machine, for CI logs and bug reports: CPU model, SIMD level
# and core count, free disk, Mesa version, /dev/dri nodes, and what EGL finds on each platform
# (eglinfo, package mesa-utils, installed by scripts/setup.sh). Best effort: never fails, prints
# "?" for whatever it cannot find out.
# Usage: scripts/machine-info.sh [PREFIX]   (each line starts with PREFIX, default "machine: ")
p=${1-machine: }

cpu=$(sed -n 's/^model name[[:space:]]*: *//p' /proc/cpuinfo 2>/dev/null | head -1)
simd=$(grep -m1 -owE 'avx512f|avx2|avx|sse4_2' /proc/cpuinfo 2>/dev/null | sort -u | paste -sd' ')
echo "${p}CPU ${cpu:-?}; $(nproc 2>/dev/null || echo '?') cores; SIMD ${simd:-?}"

mesa=$(dpkg-query -W -f='${Version}' libegl-mesa0 2>/dev/null)
dri=$(ls /dev/dri 2>/dev/null | tr '\n' ' ')
# Free disk where the build goes: a link failing with "No space left on device" (the CI run of
# 2026-11-27, at 787 s) reads from here.
disk=$(df -h --output=avail,size . 2>/dev/null | tail -1 | awk '{print $1 " free of " $2}')
echo "${p}disk: ${disk:-?} at $PWD"

echo "${p}Mesa ${mesa:-? (libegl-mesa0 not installed)}; /dev/dri: ${dri:-none}"

if ! command -v eglinfo >/dev/null; then
  echo "${p}EGL: ? (eglinfo not installed: package mesa-utils)"
  exit 0
fi
# One line per platform ("gbm: no display", "surfaceless: Mesa Project, EGL 1.5, driver swrast")
# and one per device of the device platform, with its device extensions (software, DRM).
egl=$(timeout 60 env -u DISPLAY -u WAYLAND_DISPLAY eglinfo 2>/dev/null)
[ -n "$egl" ] || { echo "${p}EGL: ? (eglinfo printed nothing)"; exit 0; }
awk -v p="$p" '
  function flush() {
    if (name != "") print p "EGL " name (exts == "" ? "" : " [" exts "]") ": " (info == "" ? "?" : info)
    name = ""; info = ""; exts = ""; inext = 0
  }
  /^[A-Za-z0-9]+ platform:$/ { flush(); plat = tolower($1); name = plat; next }
  plat == "" { next }
  /^Device #[0-9]+:/ {
    if (name == plat && info == "") name = ""  # the platform line: its devices follow
    flush(); name = "device " $2; sub(/:$/, "", name); next
  }
  /^EGL device extensions string:/ { inext = 1; next }
  inext && /^    / { for (i = 1; i <= NF; i++) exts = exts (exts == "" ? "" : " ") $i; next }
  { inext = 0 }
  /eglInitialize failed|eglGetPlatformDisplay failed|no devices/ { info = "no display"; next }
  /^EGL vendor string:/ { sub(/^EGL vendor string: */, ""); vendor = $0; next }
  /^EGL version string:/ { sub(/^EGL version string: */, ""); info = vendor ", EGL " $0; next }
  /^EGL driver name:/ { info = info ", driver " $NF; next }
  END { flush() }' <<<"$egl" || true
exit 0
