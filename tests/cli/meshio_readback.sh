#!/bin/bash
# Reads rtsph's PLY frames with meshio, an independent third-party reader, and compares them
# bit for bit with the CSV frames of an identical single-threaded run. meshio is installed with
# pip into a venv beside the binary; without python3-venv or the package registry the test is
# skipped (exit 0 with a message), since it checks interoperability, not rtsph itself.
# Usage: meshio_readback.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
venv=$(dirname "$rtsph")/meshio-venv
skip() { echo "meshio_readback: skipped ($1)"; exit 0; }

if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import meshio, numpy" 2>/dev/null; then
  rm -rf "$venv"
  python3 -m venv "$venv" >/dev/null 2>&1 || skip "python3 -m venv unavailable"
  "$venv/bin/pip" install --quiet --disable-pip-version-check --timeout 30 meshio numpy >/dev/null 2>&1 ||
    { rm -rf "$venv"; skip "pip could not install meshio"; }
fi

# Frames go under frames/: a directory named like a built-in scene in the current directory
# would be taken for the scene.
for scene in dam_break_2d dam_break_3d; do
  for fmt in ply csv; do
    "$rtsph" run "$scene" --until 0.004 --every 0.002 --threads 1 --quiet \
      --export "frames/$scene/$fmt" --format "$fmt" >/dev/null
  done
done

"$venv/bin/python" - "$work/frames" <<'PY'
import os, sys
import meshio, numpy as np
work = sys.argv[1]
for scene, dim in (("dam_break_2d", 2), ("dam_break_3d", 3)):
    index = [l.split(",") for l in open(f"{work}/{scene}/ply/index.csv").read().split("\n")[1:-1]]
    assert len(index) >= 2, index
    for frame, time_s, name in index:
        mesh = meshio.read(f"{work}/{scene}/ply/{name}")
        csv = np.loadtxt(f"{work}/{scene}/csv/{name[:-4]}.csv", delimiter=",", skiprows=1, dtype=np.float32, ndmin=2)
        n = len(csv)
        assert mesh.points.shape == (n, 3), (mesh.points.shape, n)
        pts = mesh.points.astype(np.float32)
        assert np.array_equal(pts[:, :dim], csv[:, :dim]), f"{name}: positions differ"
        if dim == 2:
            assert not pts[:, 2].any(), f"{name}: z is not 0 in 2D"
        pd = mesh.point_data
        vel = np.stack([pd["vx"], pd["vy"], pd["vz"]], axis=1).astype(np.float32)
        assert np.array_equal(vel[:, :dim], csv[:, dim:2 * dim]), f"{name}: velocities differ"
        assert np.array_equal(pd["density"].astype(np.float32), csv[:, 2 * dim]), f"{name}: density differs"
        assert np.array_equal(pd["pressure"].astype(np.float32), csv[:, 2 * dim + 1]), f"{name}: pressure differs"
        assert (np.diff(pd["id"].astype(np.int64)) > 0).all(), f"{name}: ids not ascending"
        print(f"{scene} {name}: {n} particles match (meshio {meshio.__version__})")
PY
echo "meshio_readback: all checks passed"
