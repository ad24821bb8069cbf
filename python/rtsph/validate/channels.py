"""Viscous flows with exact solutions: Poiseuille and Couette start-up, the Taylor–Green vortex."""
from __future__ import annotations

import math
import time

import numpy as np

import rtsph

from . import _common
from ._common import NO_LAMINAR_VISCOSITY, Result, _finish, _simulation


# --- Poiseuille start-up (Morris, Fox & Zhu 1997) --------------------------------------------
def poiseuille_exact(y, t, L, nu, F):
    v = F / (2 * nu) * y * (L - y)
    for k in range(1, 400, 2):
        v = v - 4 * F * L * L / (nu * math.pi ** 3 * k ** 3) * np.sin(math.pi * y * k / L) * \
            math.exp(-k * k * math.pi ** 2 * nu * t / L ** 2)
    return v




def _poiseuille_run(method, n, threads, times):
    L, nu, F = 1e-3, 1e-6, 2e-4
    d = rtsph.scene("validate_poiseuille_2d").to_dict()  # the built-in scene at L/n, 8 columns
    d["solver"]["method"] = method
    d["fluid"]["spacing"] = L / n
    C = _common.periodic_columns(d["solver"], 8)
    d["domain"]["max"] = [C * L / n, L]
    d["fluid_blocks"][0]["max"] = [C * L / n, L]
    scene = rtsph.scene(d)
    sim = _simulation(scene, threads)
    vmax = F * L * L / (8 * nu)
    worst, profiles = 0.0, []
    for t in times:
        sim.run(until=t)
        y = sim.positions[:, 1].astype(np.float64)
        v = sim.velocities[:, 0].astype(np.float64)
        worst = max(worst, float(np.max(np.abs(v - poiseuille_exact(y, sim.time, L, nu, F)))) / vmax)
        profiles.append((sim.time, y, v))
    return sim, worst, profiles


def poiseuille(method: str, level: str, threads: int) -> Result:
    r = Result(case="poiseuille_2d", method=method, metric="largest |v − v_exact| over all particles and times / v_max",
               tolerance=0.02, reference="Morris, Fox & Zhu 1997, eq. 21 (series solution)",
               setup="plates 1 mm apart, ν = 1e-6 m²/s, F = 2e-4 m/s², periodic in x; profiles at t = 0.0225, "
                     "0.045, 0.1125, 0.225, 1 s")
    if method == "pbf":
        r.applicable, r.notes = False, NO_LAMINAR_VISCOSITY
        return r
    times = (0.0225, 0.045, 0.1125, 0.225, 1.0)
    n = {"quick": 20, "full": 40}[level]
    t0 = time.perf_counter()
    sim, worst, profiles = _poiseuille_run(method, n, threads, times)
    r.error, r.particles, r.wall_s = worst, sim.particle_count, time.perf_counter() - t0
    r.setup += f"; spacing L/{n}"
    series = {"t_s": [], "y_m": [], "v_ms": [], "v_exact_ms": []}
    for t, y, v in profiles:
        series["t_s"] += [t] * len(y)
        series["y_m"] += list(y)
        series["v_ms"] += list(v)
        series["v_exact_ms"] += list(poiseuille_exact(y, t, 1e-3, 1e-6, 2e-4))
    r.series = series
    if level == "full":
        for k in (10, 20, 40):
            r.convergence.append((1e-3 / k, _poiseuille_run(method, k, threads, times)[1]))

    def plot(ax, res):
        t = np.array(res.series["t_s"])
        for tt in sorted(set(res.series["t_s"])):
            m = t == tt
            y = np.array(res.series["y_m"])[m]
            ax.plot(np.array(res.series["v_ms"])[m] * 1e6, y * 1e3, ".", ms=3)
            yy = np.linspace(0, 1e-3, 100)
            ax.plot(poiseuille_exact(yy, tt, 1e-3, 1e-6, 2e-4) * 1e6, yy * 1e3, "k-", lw=0.8)
        ax.set_xlabel("velocity (µm/s)")
        ax.set_ylabel("y (mm)")
    r.plot = plot
    return _finish(r)


# --- Couette start-up (Morris, Fox & Zhu 1997) --------------------------------------------------
# Fluid at rest between two plates L apart, periodic in x; at t = 0 the top plate starts moving at
# V0. The scales are the Poiseuille case's: L = 1 mm, ν = 1e-6 m²/s, and V0 = 2.5e-5 m/s, its
# v_max (Re = V0 L/ν = 0.025). The bottom plate is the container's
# wall; the top one is a rectangle obstacle with motion "velocity" that spans the periodic width
# exactly (its samples then lie on the fluid's lattice columns, one period of them, no seam). With
# solver.boundary_layers = 2 the container's walls are two sample rows deep and the plate, four
# spacings thick, four full rows: the row the fluid touches gets a wall's boundary volume (Ψ is
# calibrated for boundary_layers rows; a two-row plate with one layer is under-weighted and read
# 12.6% at L/20, against 9.2%). The obstacle's
# velocity enters the viscous term; unlike the container's walls, its samples get no
# extrapolation through the plate (Morris et al. eqs. 30–31), so its no-slip point is its first
# sample row, half a spacing above the plate's face: the case measures that.
COUETTE_L, COUETTE_NU, COUETTE_V0 = 1e-3, 1e-6, 2.5e-5
COUETTE_TIMES = (0.0225, 0.045, 0.1125, 0.225, 1.0)
COUETTE_N = {"quick": 20, "full": 80}
COUETTE_CONVERGENCE_N = (20, 40, 80)


def couette_exact(y, t, L=COUETTE_L, nu=COUETTE_NU, V0=COUETTE_V0):
    y = np.asarray(y, dtype=np.float64)
    u = V0 * y / L
    for n in range(1, 400):
        decay = math.exp(-nu * n * n * math.pi ** 2 * t / L ** 2)
        if decay < 1e-17:
            break
        u = u + 2 * V0 * (-1) ** n / (n * math.pi) * np.sin(n * math.pi * y / L) * decay
    return u


def _couette_run(method, n, threads):
    L, V0 = COUETTE_L, COUETTE_V0
    s = L / n
    # The plate spans the periodic width exactly: 8 columns, or more for a kernel widened by
    # `validate --set` (its extent must hold three supports).
    C = _common.periodic_columns({}, 8)
    W = C * s
    scene = rtsph.scene({
        "name": "validate_couette_2d", "dimension": 2,
        "domain": {"min": [0.0, 0.0], "max": [W, L + 4 * s], "periodic": "x"}, "gravity": [0.0, 0.0],
        "fluid": {"spacing": s, "viscosity": COUETTE_NU},
        # As validate_poiseuille_2d: no artificial viscosity, c0 = 100 V0.
        "solver": {"method": method, "artificial_viscosity": 0, "speed_of_sound": 100 * V0, "boundary_layers": 2},
        "fluid_blocks": [{"min": [0.0, 0.0], "max": [W, L]}],
        # The plate's face at y = L: raised by 2e-6 spacing so the fluid's top row, exactly half a
        # spacing below it, is not culled as inside the obstacle by rounding.
        "obstacles": [{"shape": "rectangle", "center": [W / 2, L + 2 * s * (1 + 1e-6)], "half_extents": [W / 2, 2 * s],
                       "motion": {"type": "velocity", "velocity": [V0, 0.0]}}]})
    sim = _simulation(scene, threads)
    # C n fluid particles; C × layers × 2 container samples (periodic x: bottom and top walls) and
    # C × 4 in the plate (C = 8 and two layers: 64).
    layers = sim.scene.to_dict()["solver"]["boundary_layers"]
    samples = C * (2 * layers + 4)
    if sim.particle_count != C * n or sim.stats["boundary_particles"] != samples:
        raise RuntimeError(f"couette_2d: {sim.particle_count} fluid particles and {sim.stats['boundary_particles']} "
                           f"boundary samples, expected {C * n} and {samples}")
    worst, profiles = 0.0, []
    for t in COUETTE_TIMES:
        sim.run(until=t)
        y = sim.positions[:, 1].astype(np.float64)
        u = sim.velocities[:, 0].astype(np.float64)
        worst = max(worst, float(np.max(np.abs(u - couette_exact(y, sim.time)))) / V0)
        profiles.append((sim.time, y, u))
    return sim, worst, profiles


def couette(method: str, level: str, threads: int) -> Result:
    r = Result(case="couette_2d", method=method, metric="largest |u − u_exact| over all particles and times / V0",
               tolerance=0.02, reference="Morris, Fox & Zhu 1997, start-up Couette flow (series solution)",
               setup=("plates 1 mm apart, bottom at rest (container wall), top a rectangle obstacle moving at "
                      "V0 = 2.5e-5 m/s, ν = 1e-6 m²/s, periodic in x, c0 = 100 V0, no artificial viscosity, 2 boundary "
                      "layers; profiles at t = 0.0225, 0.045, 0.1125, 0.225, 1 s"))
    if method == "pbf":
        r.applicable, r.notes = False, NO_LAMINAR_VISCOSITY
        return r
    n = COUETTE_N[level]
    t0 = time.perf_counter()
    sim, worst, profiles = _couette_run(method, n, threads)
    r.error, r.particles = worst, sim.particle_count
    r.setup += f"; spacing L/{n}"
    series = {"t_s": [], "y_m": [], "u_ms": [], "u_exact_ms": []}
    for t, y, u in profiles:
        series["t_s"] += [t] * len(y)
        series["y_m"] += list(y)
        series["u_ms"] += list(u)
        series["u_exact_ms"] += list(couette_exact(y, t))
    r.series = series
    t_end, y_end, u_end = profiles[-1]
    top = y_end > COUETTE_L - COUETTE_L / n
    s = COUETTE_L / n
    r.extra = {"top_row_u_over_v0": float(np.mean(u_end[top]) / COUETTE_V0),
               "top_row_exact_over_v0": float(couette_exact([COUETTE_L - s / 2], t_end)[0] / COUETTE_V0)}
    r.notes = (f"top fluid row at t = {t_end:g} s: u = {r.extra['top_row_u_over_v0']:.4f} V0 (exact "
               f"{r.extra['top_row_exact_over_v0']:.4f}; no slip at the obstacle's first sample row, half a spacing "
               f"above the plate, would give {(1 - s / (2 * COUETTE_L)) / (1 + s / (2 * COUETTE_L)):.4f}). The plate's "
               "samples carry its nearest face's normal and their depth below it, so the viscous term extrapolates "
               "their velocity through the face as for the container's walls.")
    if level == "full":
        for k in COUETTE_CONVERGENCE_N:
            r.convergence.append((COUETTE_L / k, worst if k == n else _couette_run(method, k, threads)[1]))
    r.wall_s = time.perf_counter() - t0

    def plot(ax, res):
        t = np.array(res.series["t_s"])
        yy = np.linspace(0, COUETTE_L, 100)
        for tt in sorted(set(res.series["t_s"])):
            m = t == tt
            ax.plot(np.array(res.series["u_ms"])[m] * 1e6, np.array(res.series["y_m"])[m] * 1e3, ".", ms=3)
            ax.plot(couette_exact(yy, tt) * 1e6, yy * 1e3, "k-", lw=0.8)
        ax.set_xlabel("velocity (µm/s)")
        ax.set_ylabel("y (mm)")
    r.plot = plot
    return _finish(r)


# --- Taylor–Green vortex, Re = 100 ------------------------------------------------------------
# The transport-velocity formulation (Adami, Hu & Adams 2013; solver.transport_velocity = 1, their
# and PySPH's background pressure p_b = ρ0 c0²) keeps the particle arrangement uniform where the
# vortex strains it; without it the lattice disorders within 0.2 s and the disorder dissipates
# the vortex 2.6-4x too fast (docs/validation.md). The kernel is Wendland C2 with h = 2 spacings
# (about 50 neighbours in 2D): Wendland kernels have no pairing instability (Dehnen & Aly 2012),
# and the cubic spline at h = spacing (12 neighbours) with TVF still lost a third of the
# amplitude in the first 0.3 s.
#
# DFSPH also shifts its particles (Lind et al. 2012 with Skillen et al. 2013's coefficient, A = 1:
# solver.shifting's value steady on still water; A = 2 heats it, shifting.cpp). Its density solve
# turns whatever the arrangement does to the kernel sums into velocity: while the strained lattice
# first rearranges (t ≈ 0.1-0.3 s) each solve's impulse takes amplitude from the vortex, the more
# the tighter the solve (at 120², tolerance 1%, 0.1%, 0.01%: 2.2%, 5.4%, 13.5% off the decay rate,
# the last at its sweep cap), and after it the decay runs at the exact rate. Shifting keeps the
# arrangement uniform without a velocity, so the solve has less to turn: 1.0% at 120² (0.5: 2.6%,
# 2: 0.06%), 0.21% at 160². WCSPH has no such solve (0.06% without shifting, 0.46% with it), so
# it runs without (session 50, docs/validation.md). RTSPH_VALIDATE_SHIFTING sets A for both.
_TG_SHIFTING_ENV = __import__("os").environ.get("RTSPH_VALIDATE_SHIFTING")
TG_SHIFTING = {"wcsph": 0.0, "dfsph": 1.0}


def _tg_shifting(method: str) -> float:
    return float(_TG_SHIFTING_ENV) if _TG_SHIFTING_ENV is not None else TG_SHIFTING.get(method, 0.0)


TG_TRANSPORT_VELOCITY = 1.0
TG_KERNEL, TG_H = "wendland_c2", 2.0
# The resolution resolves the lattice's first rearrangement (t ≈ 0.1-0.2 s), which costs DFSPH's
# large steps amplitude at coarse spacings: 10.7% at 40², 7.6% at 80², 7.7% at 100², 3.7% at
# 120², 0.57% at 160² (WCSPH 0.16-1.1% throughout; docs/validation.md). The full level's run is
# the convergence study's finest.
TG_N = {"quick": 120, "full": 160}
TG_CONVERGENCE_N = (40, 80, 160)


def _taylor_green_run(method, n, threads):
    Re, U, L = 100.0, 1.0, 1.0
    s = L / n
    scene = rtsph.scene({
        "name": "validate_taylor_green_2d", "dimension": 2,
        "domain": {"min": [0, 0], "max": [L, L], "periodic": "xy"}, "gravity": [0, 0],
        "fluid": {"spacing": s, "viscosity": U * L / Re},
        # Negative pressures carry the vortex's low-pressure cores: no clamping.
        "solver": {"method": method, "artificial_viscosity": 0, "speed_of_sound": 10 * U,
                   "clamp_negative_pressure": False, "shifting": _tg_shifting(method),
                   "transport_velocity": TG_TRANSPORT_VELOCITY, "kernel": TG_KERNEL, "smoothing_ratio": TG_H},
        "fluid_blocks": [{"min": [0, 0], "max": [L, L]}]})
    sim = _simulation(scene, threads)
    x = sim.positions.astype(np.float64)
    k = 2 * math.pi / L
    v = np.stack([-U * np.cos(k * x[:, 0]) * np.sin(k * x[:, 1]), U * np.sin(k * x[:, 0]) * np.cos(k * x[:, 1])], 1)
    sim.set_velocities(v)
    T, A = [], []

    def record(s_):
        vv = s_.velocities.astype(np.float64)
        T.append(s_.time)
        A.append(math.sqrt(2 * np.mean(np.sum(vv * vv, axis=1))))  # = U e^{-bt} for the exact field
    sim.run(until=1.0, every=0.02, callback=record)
    rate = -np.polyfit(T, np.log(A), 1)[0]
    exact = 8 * math.pi ** 2 / Re  # 2νk² with k = 2π/L
    return sim, T, A, rate, exact


def taylor_green(method: str, level: str, threads: int) -> Result:
    r = Result(case="taylor_green_2d", method=method, metric="relative error of the amplitude's decay rate over t ∈ [0, 1] s",
               tolerance=0.05, reference="exact decay exp(−8π² t/Re) of the velocity amplitude",
               setup=(f"1 m periodic square, U = 1 m/s, Re = 100, c0 = 10 U, no artificial viscosity, "
                      f"transport velocity p_b = {TG_TRANSPORT_VELOCITY:g} ρ0 c0², {TG_KERNEL} h = {TG_H:g} spacings"))
    if method == "pbf":
        r.applicable, r.notes = False, NO_LAMINAR_VISCOSITY
        return r
    if _tg_shifting(method) > 0:
        r.setup += f", particle shifting A = {_tg_shifting(method):g}"
    n = TG_N[level]
    t0 = time.perf_counter()
    sim, T, A, rate, exact = _taylor_green_run(method, n, threads)
    r.error, r.particles, r.wall_s = abs(rate / exact - 1), sim.particle_count, time.perf_counter() - t0
    r.setup += f", {n}×{n} particles"
    r.series = {"t_s": T, "amplitude_ms": A, "exact_ms": [math.exp(-exact * t) for t in T]}
    r.extra = {"decay_rate": rate, "exact_rate": exact}
    r.notes = (f"Transport-velocity formulation (Adami et al. 2013) with its momentum correction; particle "
               f"shifting A = {_tg_shifting(method):g}. The run starts at p = 0 (the lattice's density), not at the "
               "vortex's pressure field.")
    if level == "full":
        for k in TG_CONVERGENCE_N:
            if k == n:
                r.convergence.append((1.0 / k, r.error))  # the run above
                continue
            _, _, _, rt, ex = _taylor_green_run(method, k, threads)
            r.convergence.append((1.0 / k, abs(rt / ex - 1)))

    def plot(ax, res):
        ax.semilogy(res.series["t_s"], res.series["amplitude_ms"], "-", label=f"rtsph {res.method}")
        ax.semilogy(res.series["t_s"], res.series["exact_ms"], "k--", label="exp(−8π²t/Re)")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("velocity amplitude (m/s)")
    r.plot = plot
    return _finish(r)
