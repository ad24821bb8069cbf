#!/bin/bash
# Kills `rtsph run --export` with SIGKILL at random moments and checks that every visible frame
# file, index.csv and frames.pvd is complete: writes are atomic (temp file + fsync + rename), so
# a crash may lose the frame in progress but never leaves a partial one under a final name.
# Usage: crash_export.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
if ! command -v python3 >/dev/null; then
  echo "crash_export: skipped (python3 not found, needed to parse the output)"
  exit 0
fi

check() {  # check DIR FORMAT
  python3 - "$1" "$2" <<'PY'
import os, re, struct, sys, xml.etree.ElementTree as ET
d, fmt = sys.argv[1], sys.argv[2]
ext = {"csv": "csv", "vtk": "vtp", "ply": "ply"}[fmt]

def check_csv(path):
    lines = open(path).read().split("\n")
    assert lines[-1] == "", "missing final newline"
    header = lines[0].split(",")
    assert header[:2] == ["x", "y"], header
    for row in lines[1:-1]:
        vals = [float(v) for v in row.split(",")]
        assert len(vals) == len(header), row

def check_vtp(path):
    data = open(path, "rb").read()
    assert data.endswith(b"</AppendedData>\n</VTKFile>\n"), "file does not end with </VTKFile>"
    head, _, rest = data.partition(b'<AppendedData encoding="raw">')
    base = len(head) + len('<AppendedData encoding="raw">') + rest.index(b"_") + 1
    n = int(re.search(rb'NumberOfPoints="(\d+)"', head).group(1))
    for m in re.finditer(rb'<DataArray type="(\w+)" Name="(\w+)"(?: NumberOfComponents="(\d)")? format="appended" offset="(\d+)"', head):
        size = {b"Float32": 4, b"UInt32": 4, b"Int32": 4}[m.group(1)]
        comps = int(m.group(3) or 1)
        at = base + int(m.group(4))
        (nbytes,) = struct.unpack_from("<Q", data, at)
        assert nbytes == n * comps * size, (m.group(2), nbytes)
        assert at + 8 + nbytes <= len(data), "array runs past the end"

def check_ply(path):
    data = open(path, "rb").read()
    head, sep, body = data.partition(b"end_header\n")
    assert sep, "no end_header"
    n = int(re.search(rb"element vertex (\d+)", head).group(1))
    props = len(re.findall(rb"\nproperty ", head))
    assert len(body) == n * 4 * props, (len(body), n, props)

checker = {"csv": check_csv, "vtp": check_vtp, "ply": check_ply}[ext]
visible = sorted(f for f in os.listdir(d) if f.startswith("frame_"))
for f in visible:
    assert f.endswith("." + ext), f
    try:
        checker(os.path.join(d, f))
    except Exception as e:
        sys.exit(f"FAIL {d}/{f}: incomplete or corrupt: {e!r}")
lines = open(os.path.join(d, "index.csv")).read().split("\n")
assert lines[0] == "frame,time_s,file" and lines[-1] == "", "index.csv malformed"
listed = [l.split(",")[2] for l in lines[1:-1]]
assert [int(l.split(",")[0]) for l in lines[1:-1]] == list(range(len(listed))), "frames not 0..n-1"
missing = set(listed) - set(visible)
assert not missing, f"index lists missing files {missing}"
if ext == "vtp":
    files = [e.get("file") for e in ET.parse(os.path.join(d, "frames.pvd")).getroot().iter("DataSet")]
    assert files[: len(listed)] == listed or listed[: len(files)] == files, "frames.pvd disagrees with index.csv"
print(f"{d}: {len(visible)} complete frame files, {len(listed)} indexed")
PY
}

for fmt in csv vtk ply; do
  for trial in 1 2 3; do
    out="$work/$fmt$trial"
    "$rtsph" run dam_break_2d --until 100 --every 0.002 --export "$out" --format "$fmt" --quiet \
      --threads 1 >/dev/null 2>&1 &
    pid=$!
    # Wait for a few frames, then kill at a random moment within the next 0.3 s.
    for _ in $(seq 200); do
      [ -f "$out/index.csv" ] && [ "$(wc -l <"$out/index.csv")" -ge 4 ] && break
      sleep 0.05
    done
    sleep "0.$((RANDOM % 300))"
    kill -9 "$pid" 2>/dev/null || fail "rtsph exited before it was killed"
    wait "$pid" 2>/dev/null || true
    check "$out" "$fmt"
  done
done
echo "crash_export: all checks passed"
