#!/bin/bash
# Reads the surface meshes (`--format obj` and `ply-mesh`) of a resting cubic block with trimesh,
# an independent third-party reader: watertight, consistently wound, outward (positive volume),
# enclosed volume within 5 % of the block's, bounding box within one spacing of the block's,
# and (obj) the file's vertex normals on the outer side of trimesh's own face normals. trimesh is
# installed with pip into a venv beside the binary; without python3-venv or the package registry
# the test is skipped (exit 0 with a message), as cli_meshio_readback is.
# Usage: surface_trimesh.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
venv=$(dirname "$rtsph")/trimesh-venv
skip() { echo "surface_trimesh: skipped ($1)"; exit 0; }

if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import trimesh, numpy" 2>/dev/null; then
  rm -rf "$venv"
  python3 -m venv "$venv" >/dev/null 2>&1 || skip "python3 -m venv unavailable"
  "$venv/bin/pip" install --quiet --disable-pip-version-check --timeout 30 trimesh numpy >/dev/null 2>&1 ||
    { rm -rf "$venv"; skip "pip could not install trimesh"; }
fi

# A cube of water, 16 spacings on a side (4096 particles), at rest on the floor of a tank as wide.
cat >block.json <<'JSON'
{
  "name": "resting_block_3d",
  "dimension": 3,
  "domain": {"min": [0, 0, 0], "max": [0.32, 0.48, 0.32]},
  "fluid": {"spacing": 0.02},
  "fluid_blocks": [{"min": [0, 0, 0], "max": [0.32, 0.32, 0.32]}],
  "end_time": 0.1
}
JSON
for fmt in obj ply-mesh; do
  "$rtsph" run block.json --until 0.1 --every 0.1 --threads 2 --quiet --export "out/$fmt" --format "$fmt" >/dev/null
done

"$venv/bin/python" - "$work/out" <<'PY'
import sys
import numpy as np, trimesh
out, side, spacing = sys.argv[1], 0.32, 0.02
for fmt in ("obj", "ply-mesh"):
    rows = [l.split(",") for l in open(f"{out}/{fmt}/index.csv").read().split("\n")[1:-1]]
    assert [r[0] for r in rows] == ["0", "1"], rows
    for frame, time_s, name in rows:
        # process=False: the mesh exactly as written, no vertex merging or repair.
        m = trimesh.load(f"{out}/{fmt}/{name}", process=False, force="mesh")
        assert len(m.faces) > 1000, (name, len(m.faces))
        assert m.is_watertight, f"{fmt} {name}: not watertight"
        assert m.is_winding_consistent, f"{fmt} {name}: winding not consistent"
        volume, block = m.volume, side ** 3
        err = volume / block - 1
        assert abs(err) < 0.05, f"{fmt} {name}: volume {volume} vs {block}"
        off = np.abs(m.bounds - np.array([[0, 0, 0], [side, side, side]])).max()
        assert off < spacing, f"{fmt} {name}: bounds {m.bounds.tolist()}"
        if fmt == "obj":
            # The normals written in the file (parsed here: trimesh would recompute its own)
            # against trimesh's face normals from the winding: every corner on the outer side.
            lines = open(f"{out}/{fmt}/{name}").read().split("\n")
            v = np.array([l.split()[1:] for l in lines if l.startswith("v ")], dtype=float)
            vn = np.array([l.split()[1:] for l in lines if l.startswith("vn ")], dtype=float)
            assert np.array_equal(v, np.asarray(m.vertices)), f"{name}: trimesh reordered the vertices"
            assert np.allclose(np.linalg.norm(vn, axis=1), 1, atol=1e-3), f"{name}: normals not unit"
            dots = np.einsum("fkj,fj->fk", vn[m.faces], m.face_normals)
            assert (dots > 0).all(), f"{name}: {(dots <= 0).sum()} corner normals point inward"
        print(f"{fmt} {name} (t = {float(time_s):.3g} s): {len(m.vertices)} vertices, {len(m.faces)} faces, "
              f"watertight, volume {volume:.6g} m3 ({100 * err:+.2f} % of the block), bounds within "
              f"{off / spacing:.3f} spacing (trimesh {trimesh.__version__})")
PY
echo "surface_trimesh: all checks passed"
