"""A linear standing wave: does rtsph's water keep a gravity wave's amplitude?"""
from __future__ import annotations

import math
import time

import numpy as np

import rtsph

from ._common import G, Result, _finish, _simulation

# The first sloshing mode of a 2D tank L long with water h deep (session 36, docs/validation.md,
# "A standing wave"): eta = A cos(kx) sin(wt), k = pi/L, w^2 = g k tanh(kh) (linear theory; kA =
# 0.03). The water settles flat (below), then gets the mode's velocity field. The exact wave keeps
# its amplitude; water's own viscosity, in its Stokes layers (sqrt(2 nu/w) = 0.7 mm) on the floor
# and the end walls, takes an estimated 1-2% a period. The case's tolerance, 10% of the amplitude
# over three periods, is a log decrement of ln(1/0.9)/3 per period.
WAVE_L, WAVE_H, WAVE_A = 1.0, 0.2, 0.01
WAVE_LEVELS = {"quick": 0.01, "full": 0.005}  # spacing (m): 20 and 40 layers deep
WAVE_PERIODS = 4
WAVE_TOLERANCE = math.log(1 / 0.9) / 3
# Linear theory's wave moves water at rest, and the lattice the water starts on is not at rest:
# settling onto it releases 0.7-4 J of potential energy (the default kernel and h = 1.3 s), 3 to
# 16 times the wave's 0.245 J, as particle noise of 3-10 cm/s against the wave's 4 cm/s (session
# 37). So the water first settles for WAVE_SETTLE_S with its velocities zeroed every
# WAVE_SETTLE_S / WAVE_SETTLE_ZEROS (the last zeroing just before the wave starts), and the wave is
# imposed on the settled particles.
WAVE_SETTLE_S, WAVE_SETTLE_ZEROS = 2.5, 5


def standing_wave_theory(h: float = WAVE_H, L: float = WAVE_L):
    """(k, w, period) of the first mode by linear theory."""
    k = math.pi / L
    w = math.sqrt(G * k * math.tanh(k * h))
    return k, w, 2 * math.pi / w


def mode_amplitude(positions, k: float, s: float, L: float = WAVE_L, h: float = WAVE_H) -> float:
    """The water's first moment on the mode, (2/(L h)) * sum(y cos(kx)) * s^2 (2D): for a surface
    eta(x) over a flat depth h it is the cosine coefficient of eta plus h's own share (0 for the
    lattice on its whole periods of cos(kx))."""
    p = np.asarray(positions, dtype=np.float64)
    return float(np.sum(p[:, 1] * np.cos(k * p[:, 0]))) * s * s * 2 / (L * h)


def mode_velocity(positions, k: float, w: float, A: float = WAVE_A, h: float = WAVE_H) -> np.ndarray:
    """Linear theory's velocity field of the mode at its zero crossing (float32 rows), the
    gradient of phi = (A w / k) cosh(ky)/sinh(kh) cos(kx): all of the wave's energy is kinetic
    there, (1/4) rho g A^2 L per unit width."""
    x = np.asarray(positions, dtype=np.float64)
    v = np.zeros(x.shape, dtype=np.float32)
    v[:, 0] = -A * w * np.cosh(k * x[:, 1]) / math.sinh(k * h) * np.sin(k * x[:, 0])
    v[:, 1] = A * w * np.sinh(k * x[:, 1]) / math.sinh(k * h) * np.cos(k * x[:, 0])
    return v


def standing_wave(method: str, level: str, threads: int) -> Result:
    s = WAVE_LEVELS[level]
    k, w, period = standing_wave_theory()
    r = Result(case="standing_wave_2d", method=method,
               metric="log decrement per period of the mode's amplitude, ln(a1/a4)/3 (a_i: the largest |amplitude| "
                      "in the i-th period)",
               tolerance=WAVE_TOLERANCE,
               reference=f"linear theory: the first mode keeps its amplitude, period 2π/sqrt(gk tanh kh) = {period:.3f} s",
               setup=(f"2D tank {WAVE_L:g} m long, water {WAVE_H:g} m deep, spacing {s} m ({round(WAVE_H / s)} layers), "
                      f"settled for {WAVE_SETTLE_S:g} s (velocities zeroed every {WAVE_SETTLE_S / WAVE_SETTLE_ZEROS:g} s), "
                      f"then given the first mode's velocity field for A = {WAVE_A * 100:g} cm; default "
                      f"parameters (hydrostatic start), {WAVE_PERIODS} periods"))
    scene = rtsph.scene({
        "name": "validate_standing_wave_2d", "dimension": 2,
        "domain": {"min": [0, 0], "max": [WAVE_L, 3 * WAVE_H]},
        "fluid": {"spacing": s, "hydrostatic_start": True}, "solver": {"method": method},
        "fluid_blocks": [{"min": [0, 0], "max": [WAVE_L, WAVE_H]}],
        "end_time": WAVE_SETTLE_S + WAVE_PERIODS * period})
    sim = _simulation(scene, threads)
    t0 = time.perf_counter()
    n = sim.particle_count
    rest = np.zeros((n, 2), dtype=np.float32)
    for z in range(WAVE_SETTLE_ZEROS):
        sim.run(until=(z + 1) * WAVE_SETTLE_S / WAVE_SETTLE_ZEROS)
        v_settle = np.asarray(sim.velocities, dtype=np.float64)
        sim._set_velocities(rest)
    residual = float(np.sqrt(np.mean(np.sum(v_settle * v_settle, axis=1))))  # before the last zeroing
    x = np.asarray(sim.positions, dtype=np.float64)
    v = mode_velocity(x, k, w)
    sim._set_velocities(np.ascontiguousarray(v))
    m0, start = mode_amplitude(x, k, s), sim.time
    # The energy budget tells a damped wave (the water's energy goes) from a scattered one (it
    # stays, as particle noise; session 39). Equal masses: per unit mass, over the imposed wave's.
    y0, e0 = float(np.sum(x[:, 1])), 0.5 * float(np.sum(v.astype(np.float64) ** 2))
    T, M, E = [], [], []

    def record(sim_):
        T.append(sim_.time - start)
        p_ = np.asarray(sim_.positions, dtype=np.float64)
        M.append(mode_amplitude(p_, k, s) - m0)
        v_ = np.asarray(sim_.velocities, dtype=np.float64)
        E.append((0.5 * float(np.sum(v_ * v_)) + G * (float(np.sum(p_[:, 1])) - y0)) / e0)
    sim.run(until=start + WAVE_PERIODS * period, every=period / 50, callback=record)
    Ta, Ma, Ea = np.array(T), np.abs(np.array(M)), np.array(E)
    in_period = [(Ta >= i * period - 1e-9) & (Ta < (i + 1) * period - 1e-9) for i in range(WAVE_PERIODS)]
    amp = [float(np.max(Ma[m])) for m in in_period]
    energy = [float(np.mean(Ea[m])) for m in in_period]
    r.error = math.log(amp[0] / max(amp[-1], 1e-12)) / (WAVE_PERIODS - 1)
    r.particles, r.wall_s = sim.particle_count, time.perf_counter() - t0
    kept = [a / amp[0] for a in amp]
    r.notes = (f"first peak {1000 * amp[0]:.1f} mm (A = {1000 * WAVE_A:g}); the amplitude in each period over the "
               f"first's: " + ", ".join(f"{a:.2f}" for a in kept) + f" (the tolerance keeps 0.90 after three); "
               f"the water's mechanical energy, mean in each period, over the imposed wave's: "
               + ", ".join(f"{e:.2f}" for e in energy) + " (the exact wave keeps 1; energy that stays while "
               f"the amplitude falls has become particle noise); "
               f"the settled water's rms speed before its last zeroing {100 * residual:.2f} cm/s (the wave's "
               f"surface speed {100 * WAVE_A * w:.1f} cm/s)")
    r.series = {"t_s": T, "amplitude_m": M, "theory_m": [WAVE_A * math.sin(w * t) for t in T],
                "energy_over_wave": E}
    r.extra = {**{f"kept_period_{i + 1}": a for i, a in enumerate(kept)},
               **{f"energy_period_{i + 1}": e for i, e in enumerate(energy)}, "first_peak_m": amp[0],
               "settled_rms_speed_m_s": residual}

    def plot(ax, res):
        t = np.asarray(res.series["t_s"])
        ax.plot(t, 1000 * np.asarray(res.series["amplitude_m"]), "-", label=f"rtsph {res.method}")
        ax.plot(t, 1000 * np.asarray(res.series["theory_m"]), "k--", lw=0.8, label="linear theory")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("the first mode's amplitude (mm)")
    r.plot = plot
    return _finish(r)
