#!/usr/bin/env bash
# Packs what a GPU machine lent through the `device` tool needs to run rtsph, into .device/ (git
# ignores it): rtsph built for any x86-64-v3 CPU (the `portable` preset; a -march=native binary
# from this machine may not run there), the shared libraries it links that a bare GPU machine
# lacks (xz-compressed: the tool carries at most 64 MiB), and the glvnd GL loaders (libEGL,
# libGL, libOpenGL), which that machine does not have (shared/notes/gpu-sph-performance.md).
# Then, in one device call:  command "bash scripts/device-gpu-bench.sh", carry [".device"].
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset portable >/dev/null
cmake --build --preset portable --target rtsph
out=.device
rm -rf "$out"
mkdir -p "$out/pkg/bin" "$out/pkg/lib" "$out/gl"
cp build/portable/rtsph "$out/pkg/bin/"
strip "$out/pkg/bin/rtsph"
# Every library ldd names, but glibc's own (the GPU machine's is newer) and the GL loaders (they
# must be the machine's glvnd, which dispatches to its NVIDIA driver).
ldd build/portable/rtsph | awk '$3 ~ /^\// {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libGL*|libEGL*|libOpenGL*|libGLX*) ;;
    *) cp -L "$lib" "$out/pkg/lib/" ;;
  esac
done
tar -C "$out" -cJf "$out/rtsph-device.tar.xz" pkg
rm -rf "$out/pkg"
(cd "$out/gl" && apt-get download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null)
du -sh "$out" "$out"/*
