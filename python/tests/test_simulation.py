"""Stepping, arrays in id order, validated writes, live parameters, the instability guard."""
import numpy as np
import pytest

import rtsph


def test_arrays_have_documented_shapes_and_dtypes(tank, dam3d):
    for scene, d in ((tank, 2), (dam3d, 3)):
        sim = rtsph.Simulation(scene, threads=1)
        sim.step(2)
        n = sim.particle_count
        assert n > 0
        assert sim.positions.shape == (n, d) and sim.positions.dtype == np.float32
        assert sim.velocities.shape == (n, d) and sim.velocities.dtype == np.float32
        assert sim.density.shape == (n,) and sim.density.dtype == np.float32
        assert sim.pressure.shape == (n,) and sim.pressure.dtype == np.float32
        assert sim.time > 0 and sim.dt > 0 and sim.step_count == 2
        assert sim.stats["fluid_particles"] == n and sim.stats["dimension"] == d


def test_arrays_are_independent_copies(tank):
    sim = rtsph.Simulation(tank, threads=1)
    x0 = sim.positions
    x0_copy = x0.copy()
    sim.step(20)
    assert np.array_equal(x0, x0_copy)  # not a view into memory the step reordered
    assert not np.array_equal(sim.positions, x0)


def test_rows_follow_particle_ids():
    # A dam break moves particles far, and the solver re-sorts memory every step; rows in id
    # order move continuously: no row jumps by more than what dt·|v|max allows.
    sim = rtsph.Simulation(rtsph.scene("dam_break_2d", {"fluid.spacing": 0.1}), threads=1)
    sim.step(5)
    for _ in range(20):
        before = sim.positions
        sim.step(1)
        jump = np.linalg.norm(sim.positions - before, axis=1).max()
        assert jump <= 1.01 * sim.dt * sim.stats["max_speed"] + 1e-6


@pytest.mark.parametrize("method", ["wcsph", "pbf", "dfsph"])
def test_writing_the_state_back_changes_nothing(method):
    # set_positions/set_velocities with the arrays just read must leave the run bit-identical:
    # the rows are mapped back to the right particles and the re-sort keeps the memory order.
    scene = rtsph.scene("dam_break_2d", {"fluid.spacing": 0.1, "solver.method": method})
    a = rtsph.Simulation(scene, threads=2)
    b = rtsph.Simulation(scene, threads=2)
    a.step(30)
    b.step(30)
    b.set_positions(b.positions)
    b.set_velocities(b.velocities)
    a.step(40)
    b.step(40)
    assert np.array_equal(a.positions, b.positions)
    assert np.array_equal(a.velocities, b.velocities)


def test_set_velocities_and_positions_take_effect(tank):
    sim = rtsph.Simulation(tank, threads=1)
    v = np.zeros((sim.particle_count, 2), np.float64)
    v[:, 0] = 0.25  # float64 is accepted and converted
    sim.set_velocities(v)
    assert np.array_equal(sim.velocities, v.astype(np.float32))
    x = sim.positions
    x[:, 1] += 0.01  # lift the whole block by 1 cm
    sim.set_positions(x)
    assert np.allclose(sim.positions, x)
    sim.step(1)  # stepping from the edited state works
    assert np.isfinite(sim.positions).all()


@pytest.mark.parametrize("bad, error", [
    (np.zeros((3, 2), np.float32), ValueError),          # wrong N
    (np.zeros((200, 3), np.float32), ValueError),        # wrong D
    (np.zeros(400, np.float32), ValueError),             # not 2-D
    (np.zeros((200, 2), np.int32), TypeError),           # not floats
    (np.full((200, 2), np.nan, np.float32), ValueError), # not finite
])
def test_bad_writes_raise(tank, bad, error):
    sim = rtsph.Simulation(tank, threads=1)
    before = sim.positions
    with pytest.raises(error):
        sim.set_positions(bad)
    with pytest.raises(error):
        sim.set_velocities(bad)
    assert np.array_equal(sim.positions, before)


@pytest.mark.parametrize("call, message", [
    (lambda sim: sim.step(-1), "n must be >= 0"),
    (lambda sim: sim.run(until=float("nan")), "until must be a time"),
    (lambda sim: sim.run(until=0.01, every=0), "every must be positive"),
])
def test_bad_run_arguments_raise_and_leave_the_state(tank, call, message):
    sim = rtsph.Simulation(tank, threads=1)
    with pytest.raises(ValueError, match=message):
        call(sim)
    assert sim.time == 0 and sim.step_count == 0


def test_live_parameters(tank):
    sim = rtsph.Simulation(tank, threads=1)
    sim.set_parameter("fluid.viscosity", 1e-3)
    assert sim.scene.to_dict()["fluid"]["viscosity"] == 1e-3
    with pytest.raises(ValueError, match="not a live parameter"):
        sim.set_parameter("fluid.spacing", 0.01)
    with pytest.raises(rtsph.SceneError, match="fluid.viscosity"):
        sim.set_parameter("fluid.viscosity", -1.0)
    with pytest.raises(rtsph.SceneError, match="no_such"):
        sim.set_parameter("no_such.parameter", 1)


def test_gravity_off_leaves_a_resting_tank_at_rest(tank):
    sim = rtsph.Simulation(tank, threads=1)
    sim.set_gravity([0.0, 0.0])
    sim.set_velocities(np.zeros((sim.particle_count, 2)))
    sim.step(5)
    # The tank is at rest with hydrostatic pressure; without gravity that pressure pushes the
    # water up, so the centre of mass must rise, where with gravity it stays.
    with_g = rtsph.Simulation(tank, threads=1).step(5)
    assert sim.positions[:, 1].mean() > with_g.positions[:, 1].mean()
    with pytest.raises(ValueError):
        sim.set_gravity([0.0])


def test_obstacles_move(tmp_path):
    sim = rtsph.Simulation(rtsph.scene("nozzle_obstacle_2d", {"fluid.spacing": 0.05}), threads=1)
    c = sim.obstacle_center(0)
    sim.move_obstacle(0, [c[0] + 0.01, c[1]])
    sim.step(1)
    assert sim.obstacle_center(0)[0] == pytest.approx(c[0] + 0.01)
    with pytest.raises(IndexError):
        sim.move_obstacle(5, [0.0, 0.0])


def test_instability_raises_with_the_cli_diagnostic(tank):
    sim = rtsph.Simulation(tank.with_overrides({"solver.time_step.mode": "fixed", "solver.time_step.dt": 0.05}),
                           threads=1)
    with pytest.raises(rtsph.InstabilityError, match="step"):
        sim.step(200)


def test_unknown_backend_and_auto(tank):
    with pytest.raises(ValueError, match="backend"):
        rtsph.Simulation(tank, backend="quantum")
    assert rtsph.Simulation(tank, backend="auto").backend == "cpu"  # as for `rtsph run` (GPU: test_gpu_backend.py)


def test_every_method_steps_in_2d_and_3d(tank, dam3d):
    for scene in (tank, dam3d):
        for method in rtsph.solver_methods():
            sim = rtsph.Simulation(scene.with_overrides({"solver.method": method}), threads=1)
            sim.step(3)
            assert sim.stats["method"] == method
            assert np.isfinite(sim.positions).all()
