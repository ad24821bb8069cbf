"""The GIL is released while stepping; Ctrl-C stops a run cleanly."""
import _thread
import threading
import time

import numpy as np
import pytest

import rtsph


def _scene():
    return rtsph.scene("dam_break_2d", {"fluid.spacing": 0.03})  # about 2,200 particles


def test_two_simulations_in_two_threads(report):
    steps = 400
    # Sequential: one after the other, one solver thread each.
    t0 = time.perf_counter()
    seq = [rtsph.Simulation(_scene(), threads=1).step(steps) for _ in range(2)]
    sequential_s = time.perf_counter() - t0

    sims = [rtsph.Simulation(_scene(), threads=1) for _ in range(2)]
    errors = []

    def work(sim):
        try:
            sim.step(steps)
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(s,)) for s in sims]
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    parallel_s = time.perf_counter() - t0
    assert not errors
    # Same results as the sequential runs, bit for bit.
    for a, b in zip(seq, sims):
        assert np.array_equal(a.positions, b.positions)
    # Speed is reported, not asserted (the machine is shared and noisy).
    report(f"two simulations of {steps} steps: sequential {sequential_s:.3f} s, in two Python threads "
           f"{parallel_s:.3f} s, speed-up {sequential_s / parallel_s:.2f}x")


def test_one_simulation_from_two_threads_is_serialised():
    # Stepping the same simulation from two threads must not race: both calls complete and the
    # step count is their sum.
    sim = rtsph.Simulation(rtsph.scene("hydrostatic_2d", {"fluid.spacing": 0.05}), threads=1)
    threads = [threading.Thread(target=sim.step, args=(50,)) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert sim.step_count == 100


def test_ctrl_c_stops_a_run_and_leaves_it_usable():
    sim = rtsph.Simulation(_scene(), threads=1)
    timer = threading.Timer(0.3, _thread.interrupt_main)  # what Ctrl-C does: SIGINT to the main thread
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        sim.run(until=1000.0)
    timer.join()
    t = sim.time
    assert 0 < t < 1000.0
    sim.step(3)
    assert sim.time > t and np.isfinite(sim.positions).all()


def test_run_calls_back_on_schedule(tmp_path):
    sim = rtsph.Simulation(rtsph.scene("hydrostatic_2d", {"fluid.spacing": 0.05}), threads=1)
    times = []
    sim.run(until=0.05, every=0.01, callback=lambda s: times.append(s.time))
    assert times[0] == 0.0 and len(times) == 6
    for k, t in enumerate(times[1:], start=1):
        assert k * 0.01 <= t + 1e-12 < k * 0.01 + sim.stats["dt_s"] * 1.5 + 1e-12
    assert sim.time >= 0.05
