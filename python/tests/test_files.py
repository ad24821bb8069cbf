"""Checkpoints, exports and pictures: the CLI's formats, bit for bit where it matters."""
import csv
import subprocess

import numpy as np
import pytest

import rtsph


def test_python_run_matches_the_cli_bit_for_bit(tank, cli, tmp_path):
    # The same scene, steps and threads through `rtsph run` and through Python: the two final
    # checkpoints (every state array, the time, the step count) are byte-identical files.
    subprocess.run([cli, "run", "hydrostatic_2d", "--set", "fluid.spacing=0.05", "--steps", "60", "--threads", "2",
                    "--checkpoint-every", "1000", "--checkpoint-dir", str(tmp_path / "cli"), "--quiet"],
                   check=True, capture_output=True, cwd=tmp_path)
    sim = rtsph.Simulation(tank, threads=2).step(60)
    sim.save_checkpoint(tmp_path / "py.ckpt")
    assert (tmp_path / "py.ckpt").read_bytes() == (tmp_path / "cli" / "ckpt_000000060.ckpt").read_bytes()


@pytest.mark.parametrize("method", ["wcsph", "pbf", "dfsph"])
def test_checkpoint_resumes_bit_for_bit(tank, tmp_path, method):
    scene = tank.with_overrides({"solver.method": method})
    straight = rtsph.Simulation(scene, threads=2).step(25)
    sim = rtsph.Simulation(scene, threads=2).step(10)
    sim.save_checkpoint(tmp_path / "a.ckpt")
    resumed = rtsph.Simulation.from_checkpoint(tmp_path / "a.ckpt", threads=1)
    assert resumed.step_count == 10 and resumed.scene == scene
    resumed.step(15)
    assert np.array_equal(resumed.positions, straight.positions)
    assert np.array_equal(resumed.velocities, straight.velocities)
    assert resumed.time == straight.time


def test_damaged_checkpoint_raises_one_line(tank, tmp_path):
    rtsph.Simulation(tank, threads=1).step(2).save_checkpoint(tmp_path / "a.ckpt")
    data = bytearray((tmp_path / "a.ckpt").read_bytes())
    data[len(data) // 2] ^= 0xFF
    (tmp_path / "a.ckpt").write_bytes(bytes(data))
    with pytest.raises(rtsph.CheckpointError, match="a.ckpt") as e:
        rtsph.Simulation.from_checkpoint(tmp_path / "a.ckpt")
    assert "\n" not in str(e.value)
    with pytest.raises(rtsph.CheckpointError):
        rtsph.Simulation.from_checkpoint(tmp_path / "missing.ckpt")


def test_export_writes_the_cli_frames(tank, tmp_path):
    sim = rtsph.Simulation(tank, threads=1)
    first = sim.export(tmp_path / "out", format="csv")
    sim.step(5)
    second = sim.export(tmp_path / "out", format="csv")
    assert first.endswith("frame_000000.csv") and second.endswith("frame_000001.csv")
    with open(tmp_path / "out" / "index.csv") as f:
        rows = list(csv.DictReader(f))
    assert [r["frame"] for r in rows] == ["0", "1"]
    assert float(rows[1]["time_s"]) == pytest.approx(sim.time)
    data = np.genfromtxt(second, delimiter=",", names=True)
    # Rows in id order, exact floats: the file holds the arrays the API returns.
    assert np.array_equal(np.stack([data["x"], data["y"]], axis=1).astype(np.float32), sim.positions)
    vtk = sim.export(tmp_path / "vtk")
    assert vtk.endswith("frame_000000.vtp") and (tmp_path / "vtk" / "frames.pvd").exists()  # ParaView opens the .pvd
    with pytest.raises(ValueError, match="unknown output format 'xls'"):  # a bad argument, not an I/O error
        sim.export(tmp_path / "bad", format="xls")
    assert not (tmp_path / "bad").exists()


def test_render_returns_a_picture_of_the_water(tank, tmp_path):
    sim = rtsph.Simulation(tank, threads=1)
    img = rtsph.render(sim, size=(160, 120), color="solid", style="particles")
    assert img.shape == (120, 160, 4) and img.dtype == np.uint8
    # Not blank: the water's colour covers part of the frame, the background the rest.
    colours, counts = np.unique(img.reshape(-1, 4), axis=0, return_counts=True)
    assert len(colours) > 2 and counts.max() < img.shape[0] * img.shape[1]
    again = rtsph.render(sim, tmp_path / "f.png", size=(160, 120), color="solid", style="particles")
    assert np.array_equal(img, again)
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # A file it cannot write is an I/O error with the system's reason, as export's is.
    with pytest.raises(rtsph.IoError, match="No such file or directory"):
        rtsph.render(sim, tmp_path / "no" / "f.png", size=(32, 32))
    assert rtsph.render(sim, size=(32, 32), color="log_density").shape == (32, 32, 4)
    with pytest.raises(ValueError, match="PNG"):  # not PNG bytes under another name
        rtsph.render(sim, tmp_path / "f.jpg", size=(32, 32))
    assert not (tmp_path / "f.jpg").exists()
    with pytest.raises(ValueError, match="color"):
        rtsph.render(sim, color="plaid")
    with pytest.raises(ValueError, match="style"):
        rtsph.render(sim, style="oil")
    # The default style is the water surface: a picture too, and not the particles' one.
    surface = rtsph.render(sim, size=(160, 120))
    assert surface.shape == img.shape and len(np.unique(surface.reshape(-1, 4), axis=0)) > 2
    assert not np.array_equal(surface, img)


def test_export_surface_mesh_from_python(dam3d, tmp_path):
    # The surface formats take their voxel size from the scene's spacing, as `rtsph run` does: the
    # OBJ of the resting column is a closed mesh around the fluid's bounding box.
    sim = rtsph.Simulation(dam3d, threads=1)
    path = sim.export(tmp_path / "mesh", format="obj")
    assert path.endswith("frame_000000.obj")
    verts = np.array([[float(t) for t in line.split()[1:4]] for line in open(path) if line.startswith("v ")])
    assert len(verts) > 100
    lo, hi = sim.positions.min(axis=0), sim.positions.max(axis=0)
    spacing = dam3d.to_dict()["fluid"]["spacing"]
    assert np.all(verts.min(axis=0) > lo - 1.5 * spacing) and np.all(verts.max(axis=0) < hi + 1.5 * spacing)
    with pytest.raises(ValueError, match="3D only"):  # one line, as the CLI's refusal
        rtsph.Simulation(rtsph.scene("dam_break_2d", {"fluid.spacing": 0.1}), threads=1).export(tmp_path / "m2", format="obj")
