#!/usr/bin/env python3
"""A linear standing wave in a 2D tank: how fast rtsph's gravity waves lose their amplitude.

The first sloshing mode of a tank L = 1 m long, water h deep: eta = A cos(kx) sin(wt), k = pi/L,
w^2 = g k tanh(kh) (linear theory; water's own viscosity, in its Stokes layers on the floor and
the end walls, would take about 1-2% of the amplitude each period). The water starts flat, on its lattice, with the mode's velocity field
(u = -A w cosh(ky)/sinh(kh) sin(kx), v = A w sinh(ky)/sinh(kh) cos(kx)); the mode's amplitude
is read from the water's first moment, (2/(L h)) * sum(y cos(kx)) * s^2, which is A sin(wt) for
the exact wave. Prints the largest |amplitude| in each of four periods over the first's.
docs/validation.md, "A standing wave" (session 36). An experiment, not a validate case.

    .venv/bin/python scripts/standing_wave.py dfsph 0.01 [depth] ['{"solver": {...}}']
"""
import json
import math
import sys

import numpy as np

import rtsph


def main() -> None:
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    method = sys.argv[1]
    try:
        s = float(sys.argv[2])
        h = float(sys.argv[3]) if len(sys.argv) > 3 else 0.2
    except ValueError:
        raise ValueError(f"spacing and depth must be numbers in m, got {sys.argv[2:4]}") from None
    if not (0 < s < h <= 1):
        raise ValueError(f"need 0 < spacing < depth <= 1 m, got spacing {s}, depth {h}")
    try:
        patch = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
    except json.JSONDecodeError as e:
        raise ValueError(f"the scene patch (4th argument) is not JSON: {sys.argv[4]!r}: {e}") from None
    if not isinstance(patch, dict):
        raise ValueError(f"the scene patch (4th argument) must be a JSON object, got {sys.argv[4]!r}")
    L, A, g = 1.0, 0.01, 9.81
    k = math.pi / L
    w = math.sqrt(g * k * math.tanh(k * h))
    period = 2 * math.pi / w
    spec = {"name": "standing_wave", "dimension": 2, "domain": {"min": [0, 0], "max": [L, 3 * h]},
            "fluid_blocks": [{"min": [0, 0], "max": [L, h]}], "end_time": 4 * period,
            "fluid": {"spacing": s, "hydrostatic_start": True, **patch.get("fluid", {})},
            "solver": {"method": method, **patch.get("solver", {})}}
    sim = rtsph.Simulation(rtsph.scene(spec), threads=1)
    x = np.asarray(sim.positions, dtype=np.float64)
    v = np.zeros(x.shape, dtype=np.float32)
    v[:, 0] = -A * w * np.cosh(k * x[:, 1]) / math.sinh(k * h) * np.sin(k * x[:, 0])
    v[:, 1] = A * w * np.sinh(k * x[:, 1]) / math.sinh(k * h) * np.cos(k * x[:, 0])
    sim._set_velocities(np.ascontiguousarray(v))
    m0 = float(np.sum(x[:, 1] * np.cos(k * x[:, 0])))
    T, M = [], []

    def record(sim_):
        p = np.asarray(sim_.positions, dtype=np.float64)
        T.append(sim_.time)
        M.append((float(np.sum(p[:, 1] * np.cos(k * p[:, 0]))) - m0) * s * s * 2 / (L * h))
    sim.run(until=4 * period, every=period / 100, callback=record)
    T, M = np.array(T), np.array(M)
    amp = [float(np.max(np.abs(M[(T >= i * period) & (T < (i + 1) * period)]))) for i in range(4)]
    print(f"{method} {json.dumps(patch)} spacing {s} m, depth {h} m, period {period:.3f} s (theory): "
          f"first peak {amp[0] * 1000:.1f} mm (A = {A * 1000:g}), amplitude per period over the first's "
          + ", ".join(f"{a / amp[0]:.2f}" for a in amp))


if __name__ == "__main__":
    try:
        main()
    except ValueError as e:  # a bad argument or scene value (SceneError, JSONDecodeError): one line
        sys.exit(f"standing_wave.py: {e}")
