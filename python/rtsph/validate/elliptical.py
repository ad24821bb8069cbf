"""Monaghan's elliptical drop: a free 2D disc strained into an ellipse, against incompressible theory."""
from __future__ import annotations

import math
import time

import numpy as np

import rtsph

from ._common import Result, _finish, _simulation
from .drops import _ball_blocks, _track_semi_axes


# --- elliptical drop (Monaghan 1994) -----------------------------------------------------------
# A 2D disc of radius R, no gravity, free surface in open space, started with the straining flow
# u = −A0 x, v = A0 y (Monaghan 1994, J. Comput. Phys. 110; PySPH's elliptical_drop example).
# Incompressible inviscid theory keeps the field linear, u = −A(t) x, v = A(t) y, and the drop an
# ellipse with semi-axes a (x), b (y): a' = −A a, b' = A b (so a b = R²). With
# p = P0(t)(1 − x²/a² − y²/b²) (zero on the surface), Euler's Du/Dt = −∇p/ρ reads
#   x: (−A' + A²) x = 2 P0 x/(ρ a²),   y: (A' + A²) y = 2 P0 y/(ρ b²),
# whose sum gives P0 = ρ A² a² b²/(a² + b²) and whose difference dA/dt = A² (a² − b²)/(a² + b²).
# The drop's semi-axes are measured from the particles' second moments, each normalised by its own
# value at t = 0 (b = R √(⟨y²⟩/⟨y²⟩₀)): exact for an affine motion, so the lattice's staircase
# disc is no error. The run starts at p = 0 (the lattice's density), not at the P0 = 5 MPa of the
# theory, as PySPH's example does.
ELL_A0, ELL_R, ELL_T = 100.0, 1.0, 0.008   # 1/s, m, s
ELL_C0 = 1400.0      # m/s: 14× the largest speed A0·R (Mach 0.07; PySPH's choice, about water's 1,480)
ELL_SPACING = {"quick": 0.0125, "full": 0.00625}   # R/80 and R/160
ELL_CONVERGENCE = (0.025, 0.0125, 0.00625)
ELL_SAMPLE = ELL_T / 40        # s between measurements
ELL_PBF_STEP = ELL_SAMPLE      # PBF's frame step (its default 1/60 s is twice the whole case)


def elliptical_drop_exact(times, A0=ELL_A0, R=ELL_R):
    """(A, a, b) of the incompressible drop at each of the ascending `times`, RK4 at ≤ 1 µs steps."""
    def f(y):
        A, a, b = y
        return np.array([A * A * (a * a - b * b) / (a * a + b * b), -A * a, A * b])
    y, t, out = np.array([A0, R, R], dtype=np.float64), 0.0, []
    for t_next in times:
        n = max(1, int(math.ceil((t_next - t) / 1e-6)))
        h = (t_next - t) / n
        for _ in range(n):
            k1 = f(y)
            k2 = f(y + 0.5 * h * k1)
            k3 = f(y + 0.5 * h * k2)
            k4 = f(y + h * k3)
            y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t = t_next
        out.append(y.copy())
    return np.array(out).reshape(-1, 3)


def _elliptical_drop_run(method, s, threads):
    R = ELL_R
    solver = {"method": method, "speed_of_sound": ELL_C0}
    if method == "pbf":
        solver["pbf"] = {"time_step": ELL_PBF_STEP}
    scene = rtsph.scene({
        "name": "validate_elliptical_drop_2d", "dimension": 2,
        # Open space: no walls; the box only bounds the neighbour grid (b reaches 2 R, a R/2).
        "domain": {"min": [-1.5 * R, -2.5 * R], "max": [1.5 * R, 2.5 * R], "open": True},
        "gravity": [0.0, 0.0], "fluid": {"spacing": s}, "solver": solver,
        "fluid_blocks": _ball_blocks(2, R, s)})
    sim = _simulation(scene, threads)
    x = sim.positions.astype(np.float64)
    c = x.mean(0)
    sim.set_velocities(np.stack([-ELL_A0 * (x[:, 0] - c[0]), ELL_A0 * (x[:, 1] - c[1])], 1))
    T, AX, AY = _track_semi_axes(sim, until=ELL_T, every=ELL_SAMPLE)
    a = np.array(AX) / AX[0] * R
    b = np.array(AY) / AY[0] * R
    ex = elliptical_drop_exact(T)
    b_err = float(np.max(np.abs(b / ex[:, 2] - 1)))
    a_err = float(np.max(np.abs(a / ex[:, 1] - 1)))
    return sim, T, a, b, ex, b_err, a_err


def elliptical_drop(method: str, level: str, threads: int) -> Result:
    s = ELL_SPACING[level]
    t0 = time.perf_counter()
    sim, T, a, b, ex, b_err, a_err = _elliptical_drop_run(method, s, threads)
    pbf = (f"; PBF: frame step {ELL_PBF_STEP:g} s (4 substeps), its defaults otherwise (XSPH c = 0.01, "
           "s_corr k = 0.1; α does not apply)" if method == "pbf" else "")
    r = Result(case="elliptical_drop_2d", method=method,
               metric="largest relative error of the semi-major axis b(t) over t ∈ [0, 8 ms]",
               error=b_err, tolerance=0.02, particles=sim.particle_count, wall_s=time.perf_counter() - t0,
               setup=(f"2D disc R = {ELL_R:g} m, no gravity, open space (no walls), u = −A0 x, v = A0 y with "
                      f"A0 = {ELL_A0:g} 1/s, {ELL_T * 1e3:g} ms; c0 = {ELL_C0:g} m/s, cubic spline h = spacing, "
                      f"α = 0.02, negative pressure clamped (the defaults); spacing {s} m (R/{ELL_R / s:.0f})" + pbf),
               reference=("Monaghan 1994: incompressible ellipse, a' = −A a, b' = A b, "
                          "dA/dt = A² (a² − b²)/(a² + b²) (RK4)"),
               notes=(f"at t = {1e3 * T[-1]:.3f} ms: b = {b[-1]:.4f} m (exact {ex[-1, 2]:.4f}), a = {a[-1]:.4f} m "
                      f"(exact {ex[-1, 1]:.4f}); the minor axis's largest error {100 * a_err:.2f}% (not bounded); area a·b/R² = "
                      f"{a[-1] * b[-1] / ELL_R ** 2:.4f} at the end (incompressible: 1). Semi-axes from the second "
                      "moments, each normalised by its t = 0 value."),
               series={"t_s": list(T), "b_m": list(b), "b_exact_m": list(ex[:, 2]), "a_m": list(a),
                       "a_exact_m": list(ex[:, 1])},
               extra={"a_error": a_err, "b_end_m": float(b[-1]), "a_end_m": float(a[-1]),
                      "area_ratio_end": float(a[-1] * b[-1] / ELL_R ** 2)})
    if level == "full":
        for sc in ELL_CONVERGENCE:
            r.convergence.append((sc, b_err if sc == s else _elliptical_drop_run(method, sc, threads)[5]))
        r.wall_s = time.perf_counter() - t0

    def plot(ax, res):
        t = np.array(res.series["t_s"]) * 1e3
        ax.plot(t, res.series["b_m"], ".", ms=4, label=f"{res.method}: b")
        ax.plot(t, res.series["a_m"], "x", ms=4, label=f"{res.method}: a")
        ax.plot(t, res.series["b_exact_m"], "k-", lw=0.8, label="incompressible theory")
        ax.plot(t, res.series["a_exact_m"], "k-", lw=0.8)
        ax.set_xlabel("t (ms)")
        ax.set_ylabel("semi-axis (m)")
    r.plot = plot
    return _finish(r)
