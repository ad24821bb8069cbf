"""The validation cases. Each takes (method, level, threads) and returns a Result.

Levels: "quick" (coarse, for CI: the whole suite in a few minutes on two cores) and "full"
(the report's resolution, with a convergence study where the issue asks for one).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

import rtsph

G = 9.81


@dataclass
class Result:
    case: str
    method: str
    metric: str                 # what the error measures
    error: float = float("nan")
    tolerance: float = float("nan")
    passed: bool = False
    applicable: bool = True     # False: the method has no model for this case (reason in notes)
    setup: str = ""
    reference: str = ""
    notes: str = ""
    particles: int = 0
    wall_s: float = 0.0
    series: Dict[str, List[float]] = field(default_factory=dict)  # columns of the case's CSV
    plot: Optional[Callable] = None                                 # plot(ax, result)
    convergence: List[Tuple[float, float]] = field(default_factory=list)  # (spacing, error)
    extra: Dict[str, float] = field(default_factory=dict)           # other figures for the summary


def _finish(r: Result) -> Result:
    r.passed = bool(r.applicable and np.isfinite(r.error) and r.error <= r.tolerance)
    return r


def _order(conv: List[Tuple[float, float]]) -> float:
    """Observed order of convergence: slope of log(error) against log(spacing)."""
    h = np.log([c[0] for c in conv])
    e = np.log([max(c[1], 1e-300) for c in conv])
    return float(np.polyfit(h, e, 1)[0]) if len(conv) >= 2 else float("nan")


# --- hydrostatic tank --------------------------------------------------------------------------
# p = ρ0 g (H − y) in a closed tank at rest. The tolerances are the ones the per-method tests use
# (issue 9): DFSPH 1%, PBF 3%, WCSPH 5%, here on the relative L2 error of the whole profile.
HYDRO_TOL = {"full": {"dfsph": 0.01, "pbf": 0.03, "wcsph": 0.05},
             # Ten to twenty layers: the free surface's first layer weighs 5-10% of the profile.
             "quick": {"dfsph": 0.03, "pbf": 0.05, "wcsph": 0.07}}


def hydrostatic(dim: int):
    def run(method: str, level: str, threads: int) -> Result:
        W, H = (0.5, 0.25) if dim == 2 else (0.3, 0.2)
        s = {"quick": 0.0125 if dim == 2 else 0.02, "full": 0.005 if dim == 2 else 0.01}[level]
        domain_max = [W, 1.5 * H] + ([W] if dim == 3 else [])
        block_max = [W, H] + ([W] if dim == 3 else [])
        scene = rtsph.scene({
            "name": f"validate_hydrostatic_{dim}d", "dimension": dim,
            "domain": {"min": [0.0] * dim, "max": domain_max}, "fluid": {"spacing": s},
            # α damps the start-up slosh so a short run sees the settled state (as the tests).
            "solver": {"method": method, "artificial_viscosity": 0.1},
            "fluid_blocks": [{"min": [0.0] * dim, "max": block_max}]})
        t_end = 1.5 if dim == 2 else 1.0
        sim = rtsph.Simulation(scene, threads=threads)
        t0 = time.perf_counter()
        sim.run(until=t_end - 0.3)
        p_sum = None
        y_sum = None
        k = 0
        while sim.time < t_end:
            sim.step(10)
            p = sim.pressure.astype(np.float64)
            y = sim.positions[:, 1].astype(np.float64)
            p_sum = p if p_sum is None else p_sum + p
            y_sum = y if y_sum is None else y_sum + y
            k += 1
        p, y = p_sum / k, y_sum / k
        surface = float(sim.positions[:, 1].max()) + 0.5 * s
        rho0 = 1000.0
        # The profile: pressure averaged over each horizontal layer one spacing thick, against
        # the exact value at the layer's mean height (single particles carry acoustic noise).
        layer = np.floor(y / s).astype(int)
        ly = np.array([y[layer == k].mean() for k in np.unique(layer)])
        lp = np.array([p[layer == k].mean() for k in np.unique(layer)])
        lexact = rho0 * G * (surface - ly)
        err = float(np.sqrt(np.sum((lp - lexact) ** 2) / np.sum(lexact ** 2)))
        exact = rho0 * G * (surface - y)
        order = np.argsort(y)
        r = Result(case=f"hydrostatic_{dim}d", method=method,
                   metric="relative L2 error of the layer-averaged pressure profile (time-averaged over the last 0.3 s)",
                   error=err, tolerance=HYDRO_TOL[level][method], particles=sim.particle_count,
                   wall_s=time.perf_counter() - t0,
                   setup=f"{dim}D tank {W} m wide, water {H} m deep, spacing {s} m, α = 0.1, {t_end} s",
                   reference="p = ρ0 g (H − y), H the free surface (top particle + half a spacing)",
                   series={"y_m": list(y[order]), "p_pa": list(p[order]), "p_exact_pa": list(exact[order])},
                   extra={"kinetic_energy_j": sim.stats["kinetic_energy_j"]})

        def plot(ax, res):
            ax.plot(np.array(res.series["p_pa"]) / 1e3, res.series["y_m"], ".", ms=2, label=f"rtsph {res.method}")
            ax.plot(np.array(res.series["p_exact_pa"]) / 1e3, res.series["y_m"], "-", label="ρ0 g (H − y)")
            ax.set_xlabel("pressure (kPa)")
            ax.set_ylabel("height y (m)")
        r.plot = plot
        return _finish(r)
    return run


# --- 2D dam break against Martin & Moyce 1952 -------------------------------------------------
# Martin & Moyce 1952 (Phil. Trans. R. Soc. A 244), surge front of the n² = 2 column, in
# T = t·sqrt(2g/a), Z = x/a; the same points as tests/physics_dam_break_test.cpp.
MARTIN_MOYCE_FRONT = [(0.41, 1.11), (0.84, 1.22), (1.19, 1.44), (1.43, 1.67), (1.63, 1.89),
                      (1.83, 2.11), (1.98, 2.33), (2.20, 2.56), (2.32, 2.78), (2.51, 3.00)]
MAX_CLOCK_OFFSET = 0.3  # T units: ≈ 16 ms at their a = 2.25 in; the experiment's time origin


def _front_errors(T, Z):
    T, Z = np.asarray(T), np.asarray(Z)

    def mean_err(offset):
        return float(np.mean([abs(np.interp(t - offset, T, Z, left=1.0) / z - 1) for t, z in MARTIN_MOYCE_FRONT]))
    offsets = np.arange(0.0, MAX_CLOCK_OFFSET + 1e-9, 0.01)
    errs = [mean_err(o) for o in offsets]
    best = int(np.argmin(errs))
    return errs[0], errs[best], float(offsets[best])


def _dam_break_run(method: str, spacing: float, threads: int):
    a = 1.0
    scale = math.sqrt(2 * G / a)
    sim = rtsph.Simulation(rtsph.scene("dam_break_2d", {"fluid.spacing": spacing, "solver.method": method}),
                           threads=threads)
    T, Z = [], []

    def record(s):
        T.append(s.time * scale)
        Z.append((float(s.positions[:, 0].max()) + 0.5 * spacing) / a)
    sim.run(until=2.55 / scale, every=0.01 / scale, callback=record)
    return sim, T, Z


def dam_break(method: str, level: str, threads: int) -> Result:
    spacing = {"quick": 0.05, "full": 0.02}[level]
    t0 = time.perf_counter()
    sim, T, Z = _dam_break_run(method, spacing, threads)
    raw, fitted, offset = _front_errors(T, Z)
    conv = []
    failed = []
    if level == "full":
        for s in (0.04, 0.02, 0.01):
            try:
                _, t, z = _dam_break_run(method, s, threads)
                conv.append((s, _front_errors(t, z)[1]))
            except rtsph.InstabilityError as e:  # reported, and left out of the order
                failed.append(f"spacing {s} m did not finish: {e}")
    r = Result(case="dam_break_2d", method=method,
               metric="mean relative error of the surge front, clock origin fitted within 16 ms",
               error=fitted, tolerance=0.05, particles=sim.particle_count, wall_s=time.perf_counter() - t0,
               setup=f"1 m × 2 m column in a 6 m tank, spacing {spacing} m",
               reference="Martin & Moyce 1952, surge front of the n² = 2 column (as in tests/physics_dam_break_test.cpp)",
               notes=(f"raw clock: {100 * raw:.1f}%; fitted offset ΔT = {offset:.2f}. "
                      "The residual column height (their Table 6) is not compared yet: its data is not sourced. "
                      + " ".join(failed)),
               series={"T": T, "Z": Z}, convergence=conv, extra={"raw_clock_error": raw, "clock_offset_T": offset})

    def plot(ax, res):
        ax.plot(res.series["T"], res.series["Z"], "-", label=f"rtsph {res.method}")
        ax.plot(*zip(*MARTIN_MOYCE_FRONT), "o", label="Martin & Moyce 1952")
        ax.set_xlabel(r"$T = t\sqrt{2g/a}$")
        ax.set_ylabel(r"$Z = x/a$")
    r.plot = plot
    return _finish(r)


# --- Poiseuille start-up (Morris, Fox & Zhu 1997) --------------------------------------------
def poiseuille_exact(y, t, L, nu, F):
    v = F / (2 * nu) * y * (L - y)
    for k in range(1, 400, 2):
        v = v - 4 * F * L * L / (nu * math.pi ** 3 * k ** 3) * np.sin(math.pi * y * k / L) * \
            math.exp(-k * k * math.pi ** 2 * nu * t / L ** 2)
    return v


NO_LAMINAR_VISCOSITY = ("PBF has no laminar viscosity ν (its XSPH term smooths velocities without one), "
                        "so this viscous case does not apply.")


def _poiseuille_run(method, n, threads, times):
    L, nu, F = 1e-3, 1e-6, 2e-4
    d = rtsph.scene("validate_poiseuille_2d").to_dict()  # the built-in scene at L/n, 8 columns
    d["solver"]["method"] = method
    d["fluid"]["spacing"] = L / n
    d["domain"]["max"] = [8 * L / n, L]
    d["fluid_blocks"][0]["max"] = [8 * L / n, L]
    scene = rtsph.scene(d)
    sim = rtsph.Simulation(scene, threads=threads)
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


# --- Taylor–Green vortex, Re = 100 ------------------------------------------------------------
def _taylor_green_run(method, n, threads):
    Re, U, L = 100.0, 1.0, 1.0
    s = L / n
    scene = rtsph.scene({
        "name": "validate_taylor_green_2d", "dimension": 2,
        "domain": {"min": [0, 0], "max": [L, L], "periodic": "xy"}, "gravity": [0, 0],
        "fluid": {"spacing": s, "viscosity": U * L / Re},
        # Negative pressures carry the vortex's low-pressure cores: no clamping.
        "solver": {"method": method, "artificial_viscosity": 0, "speed_of_sound": 10 * U,
                   "clamp_negative_pressure": False},
        "fluid_blocks": [{"min": [0, 0], "max": [L, L]}]})
    sim = rtsph.Simulation(scene, threads=threads)
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
               setup="1 m periodic square, U = 1 m/s, Re = 100, c0 = 10 U, no artificial viscosity")
    if method == "pbf":
        r.applicable, r.notes = False, NO_LAMINAR_VISCOSITY
        return r
    n = {"quick": 30, "full": 50}[level]
    t0 = time.perf_counter()
    sim, T, A, rate, exact = _taylor_green_run(method, n, threads)
    r.error, r.particles, r.wall_s = abs(rate / exact - 1), sim.particle_count, time.perf_counter() - t0
    r.setup += f", {n}×{n} particles"
    r.series = {"t_s": T, "amplitude_ms": A, "exact_ms": [math.exp(-exact * t) for t in T]}
    r.extra = {"decay_rate": rate, "exact_rate": exact}
    r.notes = ("No particle shifting or transport-velocity correction yet (Lind 2012, Adami 2013): "
               "the lattice disorders as it turns, which adds dissipation.")
    if level == "full":
        for k in (25, 50, 100):
            _, _, _, rt, ex = _taylor_green_run(method, k, threads)
            r.convergence.append((1.0 / k, abs(rt / ex - 1)))

    def plot(ax, res):
        ax.semilogy(res.series["t_s"], res.series["amplitude_ms"], "-", label=f"rtsph {res.method}")
        ax.semilogy(res.series["t_s"], res.series["exact_ms"], "k--", label="exp(−8π²t/Re)")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("velocity amplitude (m/s)")
    r.plot = plot
    return _finish(r)


# --- still water, 3D ------------------------------------------------------------------------
def still_water(method: str, level: str, threads: int) -> Result:
    # Spacings that divide the 0.4 m box: a gap at a wall would start a slosh.
    s, t_end = {"quick": (0.025, 2.0), "full": (0.02, 10.0)}[level]
    scene = rtsph.scene({
        "name": "validate_still_water_3d", "dimension": 3,
        "domain": {"min": [0, 0, 0], "max": [0.4, 0.4, 0.4]}, "fluid": {"spacing": s},
        "solver": {"method": method},
        "fluid_blocks": [{"min": [0, 0, 0], "max": [0.4, 0.24, 0.4]}]})
    sim = rtsph.Simulation(scene, threads=threads)
    t0 = time.perf_counter()
    x0 = sim.positions.astype(np.float64)
    T, KE, RHO = [], [], []

    def record(s_):
        T.append(s_.time)
        KE.append(s_.stats["kinetic_energy_j"])
        RHO.append(s_.stats["mean_density_error"])
    sim.run(until=t_end, every=t_end / 50, callback=record)
    drift = float(np.max(np.linalg.norm(sim.positions - x0, axis=1))) / s
    mass = 1000.0 * 0.4 * 0.24 * 0.4
    v_rms = math.sqrt(2 * KE[-1] / mass)
    # Stated bounds, each a ratio that must stay ≤ 1: rms speed at the end ≤ 1% of the
    # gravity-wave speed sqrt(g H); no particle further than one spacing from where it started;
    # mean compression ≤ 1%.
    v_bound = 0.01 * math.sqrt(G * 0.24)
    ratios = {"speed": v_rms / v_bound, "drift": drift, "density": RHO[-1] / 0.01}
    r = Result(case="still_water_3d", method=method,
               metric="worst of: rms speed / 1% of sqrt(gH), displacement / spacing, mean compression / 1%",
               error=max(ratios.values()), tolerance=1.0, particles=sim.particle_count, wall_s=time.perf_counter() - t0,
               setup=f"0.4 m box, water H = 0.24 m deep, spacing {s} m, {t_end} s at rest, default parameters",
               reference="rest: no flow, no drift, no clumping",
               notes=(f"rms speed {v_rms:.3g} m/s (bound {v_bound:.3g}); largest displacement {drift:.2f} spacings; "
                      f"mean density error at the end {100 * RHO[-1]:.3f}%"),
               series={"t_s": T, "kinetic_energy_j": KE, "mean_density_error": RHO},
               extra={"v_rms": v_rms, "max_displacement_spacings": drift, "mean_density_error": RHO[-1]})

    def plot(ax, res):
        ax.semilogy(res.series["t_s"], np.maximum(res.series["kinetic_energy_j"], 1e-12), "-", label=f"rtsph {res.method}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("kinetic energy (J)")
    r.plot = plot
    return _finish(r)


CASES: Dict[str, Callable[[str, str, int], Result]] = {
    "hydrostatic_2d": hydrostatic(2),
    "hydrostatic_3d": hydrostatic(3),
    "dam_break_2d": dam_break,
    "poiseuille_2d": poiseuille,
    "taylor_green_2d": taylor_green,
    "still_water_3d": still_water,
}


def run_case(name: str, method: str, level: str, threads: int) -> Result:
    t0 = time.perf_counter()
    try:
        r = CASES[name](method, level, threads)
    except (rtsph.InstabilityError, RuntimeError, ValueError) as e:
        # A case the method cannot run (the instability guard tripped, a solve gave up) fails
        # with the engine's diagnostic; the rest of the suite goes on.
        return Result(case=name, method=method, metric="(did not finish)", error=float("inf"), tolerance=0.0,
                      notes=f"{type(e).__name__}: {e}", wall_s=time.perf_counter() - t0)
    if r.convergence:
        r.extra["observed_order"] = _order(r.convergence)
    return r
