"""Rayleigh's oscillating droplet: a 2D drop stretched into an ellipse oscillates at mode 2 with the
σ(γ) the static drop calibrated (drops.py)."""
from __future__ import annotations

import math
import time

import numpy as np

from ._common import Result, _finish, _simulation
from .drops import (DROPLET_GAMMA, DROPLET_LEVELS, DROPLET_NU, DROPLET_R1, _droplet_scene, _kernel_text, _seeded_s,
                    _semi_axes, _track_semi_axes, calibrate_sigma)

OSC_STRETCH = 1.1            # semi-axes 1.1·R and R/1.1 (area kept)
OSC_NU = 1e-4                # m²/s: light damping while the period is measured
OSC_LEVELS = {"quick": 2.0, "full": 3.0}  # s of free oscillation
OSC_REST_S = 1.5             # s more with ν = DROPLET_NU[2] (a live change) to bring it to rest
PERIOD_TOL, CIRCULARITY_MIN = 0.15, 0.98


def oscillating_droplet(method: str, level: str, threads: int) -> Result:
    R = DROPLET_R1[2]
    s, _ = DROPLET_LEVELS[2][level]
    t_osc = OSC_LEVELS[level]
    t0 = time.perf_counter()
    cal = calibrate_sigma(method, 2, level, threads)
    sigma = cal["sigma"]
    rho0 = 1000.0
    omega2 = 6 * sigma / (rho0 * R ** 3) if sigma > 0 else float("nan")
    period_ref = 2 * math.pi / math.sqrt(omega2) if omega2 > 0 else float("nan")
    sim = _simulation(_droplet_scene(method, 2, R, s, OSC_NU, "validate_oscillating_droplet_2d", level, OSC_STRETCH),
                      threads)
    T, AX, AY = _track_semi_axes(sim, until=t_osc, every=0.005)
    # Period from the crossings of a_x − a_y through its mean (mode 2: the axes swap each half
    # period; the mean is 0 for a drop that relaxes to a circle, and a shape that locks short of
    # round still gives the period of what it does).
    e = AX - AY
    e = e - float(np.mean(e))
    cross = [T[i] - e[i] * (T[i + 1] - T[i]) / (e[i + 1] - e[i]) for i in range(len(e) - 1) if e[i] * e[i + 1] < 0]
    period = 2 * float(np.mean(np.diff(cross))) if len(cross) >= 3 else float("nan")
    # Then to rest: viscosity raised live (the viewer's slider) and the shape measured.
    sim.set_parameter("fluid.viscosity", DROPLET_NU[2])
    sim.run(until=t_osc + OSC_REST_S)
    a, b, _, _ = _semi_axes(sim.positions.astype(np.float64))
    circ = b / a
    period_err = abs(period / period_ref - 1) if np.isfinite(period) else float("inf")
    worst = max(period_err / PERIOD_TOL, max(0.0, 1 - circ) / (1 - CIRCULARITY_MIN))
    r = Result(case="oscillating_droplet_2d", method=method,
               metric="worst of: period error / 15%, (1 − circularity at rest) / 0.02",
               error=worst, tolerance=1.0, particles=sim.particle_count,
               wall_s=time.perf_counter() - t0 + _seeded_s(cal),
               setup=(f"2D drop R = {R} m stretched to semi-axes {OSC_STRETCH}·R and R/{OSC_STRETCH}, zero gravity, "
                      f"spacing {s} m, {_kernel_text(method, 2, level)}, γ = {DROPLET_GAMMA}, ν = {OSC_NU} m²/s for {t_osc} s, then ν = "
                      f"{DROPLET_NU[2]} m²/s for {OSC_REST_S} s to rest"),
               reference="Rayleigh's mode 2: ω² = 6σ/(ρR³), σ from the static 2D droplet's calibration",
               notes=(f"σ = {sigma:.4g} N/m (static droplet at R = {R} m): predicted period {period_ref:.4g} s, "
                      f"measured {period:.4g} s ({100 * (period / period_ref - 1):+.1f}%, {len(cross)} axis "
                      f"crossings); circularity b/a at rest {circ:.4f} (bound {CIRCULARITY_MIN})"),
               series={"t_s": list(T), "a_x_m": list(AX), "a_y_m": list(AY)},
               extra={"period_s": period, "period_predicted_s": period_ref, "period_error": period_err,
                      "circularity_at_rest": circ, "sigma": sigma})

    def plot(ax, res):
        ax.plot(res.series["t_s"], np.array(res.series["a_x_m"]) / R, "-", label=f"{res.method}: a_x/R")
        ax.plot(res.series["t_s"], np.array(res.series["a_y_m"]) / R, "--", label=f"{res.method}: a_y/R")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("semi-axis / R")
    r.plot = plot
    return _finish(r)
