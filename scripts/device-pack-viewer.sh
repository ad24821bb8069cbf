#!/usr/bin/env bash
# Packs an X server for `rtsph view` on a GPU machine lent through the `device` tool, into
# .device/x.tar.xz (beside scripts/device-pack.sh's rtsph): that machine has no display, and
# the tool's notes say GLX windows reach its NVIDIA driver through a carried Xvfb with Mesa and
# __GLX_VENDOR_LIBRARY_NAME=nvidia. Xvfb offers GLX only when it can load Mesa's swrast_dri.so
# (without it, glxinfo: "couldn't find RGB GLX visual"), and swrast links LLVM, which links libz3
# and libxml2 (+ ICU, 38 MB): Mesa never calls them, so they are replaced by stubs that define
# the symbols LLVM binds (lazily; xmlFree is data). The pack is ~35 MB; the tool carries 64 MiB.
# Then: run(command="bash scripts/device-viewer.sh", carry=[".device"]).
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
x=$work/x
mkdir -p "$x/bin" "$x/lib" "$x/client" "$x/dri"
cp /usr/bin/Xvfb /usr/bin/xkbcomp /usr/bin/glxinfo "$x/bin/"
cp /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so "$x/dri/"
cp -r /usr/share/X11/xkb "$x/xkb"
# Mesa's GLX client library too: without it glvnd found no GLX visual on that Xvfb even with the
# NVIDIA vendor named; with it, glxinfo and rtsph's window ran on the NVIDIA H200 (2026-11-27).
cp -L /usr/lib/x86_64-linux-gnu/libGLX_mesa.so.0 "$x/lib/"
for b in /usr/bin/Xvfb /usr/bin/xkbcomp /usr/bin/glxinfo /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so \
         /usr/lib/x86_64-linux-gnu/libGLX_mesa.so.0; do
  ldd "$b" | awk '$3 ~ /^\// {print $3}'
done | sort -u | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libGL.so*|libGLX.so*|libGLdispatch*|libEGL*|libOpenGL*) ;;
    libz3.so*|libxml2.so*|libicu*) ;;  # stubbed below
    *) cp -L "$lib" "$x/lib/" ;;
  esac
done
# The X libraries GLFW opens at run time (not in rtsph's ldd, so not in device-pack.sh's pack).
for l in libXxf86vm.so.1 libXi.so.6 libXrandr.so.2 libXcursor.so.1 libXinerama.so.1 libX11-xcb.so.1 \
         libXrender.so.1 libXext.so.6 libXfixes.so.3; do
  cp -L "/lib/x86_64-linux-gnu/$l" "$x/client/"
done
llvm=$(ls "$x"/lib/libLLVM*.so* | head -1)
nm -D --undefined-only "$llvm" | awk '{print $2}' >"$work/undef"
z3=$(readelf -d "$llvm" | sed -n 's/.*Shared library: \[\(libz3[^]]*\)\].*/\1/p')
{ grep '^Z3_' "$work/undef" || true; } | sed 's/.*/void &(void) {}/' >"$work/z3.c"
{ grep '@LIBXML2' "$work/undef" || true; } | sed 's/@.*//' |
  awk '{ if ($1 == "xmlFree") print "void* xmlFree = 0;"; else print "void " $1 "(void) {}" }' >"$work/xml.c"
# One version node per LIBXML2_x.y.z that LLVM names, each inheriting the one before.
{ grep '@LIBXML2' "$work/undef" || true; } | awk -F@ '{n[$2] = n[$2] $1 "; "} END {for (v in n) print v "\t" n[v]}' |
  sort -t. -k2,2n -k3,3n | awk -F'\t' '{printf "%s { global: %s}%s;\n", $1, $2, prev ? " " prev : ""; prev = $1}' \
  >"$work/xml.map"
if [ -n "$z3" ]; then gcc -shared -fPIC -Wl,-soname,"$z3" -o "$x/lib/$z3" "$work/z3.c"; fi
[ -s "$work/xml.map" ] || echo 'LIBXML2_2.4.30 { };' >"$work/xml.map"
gcc -shared -fPIC -Wl,-soname,libxml2.so.2 -Wl,--version-script="$work/xml.map" -o "$x/lib/libxml2.so.2" "$work/xml.c"
mkdir -p .device
tar -C "$work" -cf - x | xz -T0 -6 >.device/x.tar.xz
du -sh .device/x.tar.xz
# scripts/device-pack.sh empties .device: run it first, this after.
