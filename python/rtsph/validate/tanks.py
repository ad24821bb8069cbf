"""Water at rest in a tank: the hydrostatic pressure profile (2D, 3D) and still water (3D)."""
from __future__ import annotations

import math
import time

import numpy as np

import rtsph

from ._common import G, Result, _finish, _simulation


# --- hydrostatic tank --------------------------------------------------------------------------
# p = ρ0 g (H − y) in a closed tank at rest. The tolerances are the ones the per-method tests use
# (issue 9): DFSPH 1%, PBF 3%, WCSPH 5%, here on the relative L2 error of the whole profile.
HYDRO_TOL = {"full": {"dfsph": 0.01, "pbf": 0.03, "wcsph": 0.05},
             # Ten to twenty layers: the free surface's first layer weighs 5-10% of the profile.
             "quick": {"dfsph": 0.03, "pbf": 0.05, "wcsph": 0.07}}
# The 3D quick spacing: 16 layers (0.0125 m) for the large-step methods, 10 (0.02 m) for WCSPH,
# whose explicit step makes the 16-layer tank cost 46 s against 8 (2026-11-26). PBF needs the 16:
# the clamped λ of its surface layer carries no load, and at 10 layers that layer's share of the
# profile reads 7.6% (4.5% at 14 layers, 3.5% at 16, 3.0% at the full level's 20).
HYDRO_QUICK_3D = {"pbf": 0.0125, "dfsph": 0.0125}


def hydrostatic(dim: int):
    def run(method: str, level: str, threads: int) -> Result:
        W, H = (0.5, 0.25) if dim == 2 else (0.3, 0.2)
        s = {"quick": 0.0125 if dim == 2 else HYDRO_QUICK_3D.get(method, 0.02),
             "full": 0.005 if dim == 2 else 0.01}[level]
        domain_max = [W, 1.5 * H] + ([W] if dim == 3 else [])
        block_max = [W, H] + ([W] if dim == 3 else [])
        scene = rtsph.scene({
            "name": f"validate_hydrostatic_{dim}d", "dimension": dim,
            "domain": {"min": [0.0] * dim, "max": domain_max}, "fluid": {"spacing": s},
            # α damps the start-up slosh so a short run sees the settled state (as the tests).
            "solver": {"method": method, "artificial_viscosity": 0.1},
            "fluid_blocks": [{"min": [0.0] * dim, "max": block_max}]})
        t_end = 1.5 if dim == 2 else 1.0
        sim = _simulation(scene, threads)
        t0 = time.perf_counter()
        sim.run(until=t_end - 0.3)
        # Every step, weighted by its dt: PBF's equivalent pressure (Σλ/Δt²) swings from step to
        # step, and a sample every 10 steps (8 samples over the window) read anything from 4% to
        # 17% depending on where the window ended; every step reads 3.5-5.4% (2026-11-24).
        p_sum = 0.0
        y_sum = 0.0
        w_sum = 0.0
        while sim.time < t_end:
            t_before = sim.time
            sim.step(1)
            w = sim.time - t_before
            p_sum = p_sum + w * sim.pressure.astype(np.float64)
            y_sum = y_sum + w * sim.positions[:, 1].astype(np.float64)
            w_sum += w
        p, y = p_sum / w_sum, y_sum / w_sum
        # The profile: pressure averaged over each horizontal layer one spacing thick (single
        # particles carry acoustic noise), against the hydrostatic pressure there, the weight of
        # the water above per unit floor area: the layers above it and half its own, each
        # particle of mass ρ0 s^d. That is ρ0 g (H − y) at the layer's height for water at ρ0 of
        # depth H, whatever the density (WCSPH's water is compressed) and wherever its surface
        # particles sit. Until session 28 the reference was ρ0 g (H − y) with H the highest
        # particle plus half a spacing, and one particle 0.6 mm higher moved DFSPH's 3D figure
        # from 0.87% to 1.25% (docs/validation.md, session 28).
        rho0 = 1000.0
        layer = np.floor(y / s).astype(int)
        ks = np.unique(layer)
        count = np.array([np.count_nonzero(layer == k) for k in ks])
        above = np.cumsum(count[::-1])[::-1] - count
        lexact = G * rho0 * s ** dim * (above + 0.5 * count) / W ** (dim - 1)
        ly = np.array([y[layer == k].mean() for k in ks])
        lp = np.array([p[layer == k].mean() for k in ks])
        err = float(np.sqrt(np.sum((lp - lexact) ** 2) / np.sum(lexact ** 2)))
        exact = np.interp(y, ly, lexact)
        order = np.argsort(y)
        r = Result(case=f"hydrostatic_{dim}d", method=method,
                   metric="relative L2 error of the layer-averaged pressure profile (time-averaged over the last 0.3 s)",
                   error=err, tolerance=HYDRO_TOL[level][method], particles=sim.particle_count,
                   wall_s=time.perf_counter() - t0,
                   setup=f"{dim}D tank {W} m wide, water {H} m deep, spacing {s} m, α = 0.1, {t_end} s",
                   reference="p = ρ0 g (H − y): the weight of the water above each layer per unit floor area",
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


# --- still water, 3D ------------------------------------------------------------------------
# Water at rest in a closed box. A Cartesian lattice is not SPH's resting arrangement: every
# method rearranges it in the first second (90% of the particles end 0.6-1 spacing from their
# lattice site, measured, whatever the kernel), and a weakly compressible fluid sampled at ρ0
# first settles under its own weight and sloshes (rms 0.07 m/s after 0.25 s). So WCSPH starts
# hydrostatically compressed (fluid.hydrostatic_start), and the bounds are on the state after a
# settling time. The issue names three properties: no drift, no clumping, and bounded kinetic
# energy and density error.
# - Drift is motion of the water, not of single particles: the particles go on rearranging at
#   the particle scale (a particle moves up to 1.2 spacings between t = 1 and 3 s with every
#   method), and that swaps neighbours without moving any water. So the drift is the mean
#   displacement after t_settle over the particles that started in each cube of DRIFT_CELL
#   spacings, the largest over the cubes, bounded by a spacing (session 18: those means are 3-7
#   times what random rearrangement of the same particles would give, so they do see the slow
#   circulations there are). The largest single displacement is reported.
# - Clumping: particles pairing up. The bound: every particle's nearest neighbour at least half
#   a spacing away at the end.
# - Particle shifting (solver.shifting, Lind et al. 2012 with its free-surface treatment) at
#   A = STILL_SHIFTING for the methods that have it: the issue's remedy for particle disorder.
#   Without it WCSPH's top layer pairs up (pressure clamped at 0 holds nothing apart there: a
#   pair 0.47 spacings apart at the quick level), and DFSPH jitters twice as fast against the
#   floor (session 19).
STILL_LEVELS = {"quick": (0.025, 4.0, 1.0), "full": (0.02, 10.0, 2.0)}  # spacing (m), t_end, t_settle (s)
STILL_SHIFTING = {"wcsph": 1.0, "dfsph": 1.0}
# - PBF at the stable Jacobi weight (solver.pbf.omega = 0, session 21): at its default full step
#   the clamped iteration cycles the lattice's stiffest mode and the water never comes to rest
#   (quick 1.76, full 1.93 times the speed bound); the stable weight is PBF's remedy for rest,
#   as shifting is the others' (PBF has no shifting: it doubled PBF's speed, session 20).
STILL_PBF = {"pbf": {"omega": 0.0}}
DRIFT_CELL = 4         # spacings: the cubes the drift is averaged over
CLUMP_DISTANCE = 0.5   # spacings: the nearest neighbour's least distance


def _coherent_drift(x_from: np.ndarray, x_to: np.ndarray, cell: float) -> float:
    """The largest |mean displacement| over the particles starting in each cube of side `cell`."""
    c = np.floor(x_from / cell).astype(np.int64)
    _, inv = np.unique(c, axis=0, return_inverse=True)
    inv = inv.reshape(-1)
    count = np.bincount(inv)
    d = x_to - x_from
    mean = np.stack([np.bincount(inv, weights=d[:, k]) / count for k in range(d.shape[1])], axis=1)
    return float(np.max(np.linalg.norm(mean, axis=1)))


def _nearest_neighbour(x: np.ndarray) -> np.ndarray:
    """Each particle's distance to its nearest other particle (brute force in blocks: a few
    thousand particles)."""
    n = len(x)
    out = np.empty(n)
    for a in range(0, n, 256):
        d2 = np.sum((x[a:a + 256, None, :] - x[None, :, :]) ** 2, axis=-1)
        d2[np.arange(d2.shape[0]), a + np.arange(d2.shape[0])] = np.inf
        out[a:a + 256] = np.sqrt(d2.min(axis=1))
    return out


def still_water(method: str, level: str, threads: int) -> Result:
    # Spacings that divide the 0.4 m box: a gap at a wall would start a slosh.
    s, t_end, t_settle = STILL_LEVELS[level]
    scene = rtsph.scene({
        "name": "validate_still_water_3d", "dimension": 3,
        "domain": {"min": [0, 0, 0], "max": [0.4, 0.4, 0.4]}, "fluid": {"spacing": s, "hydrostatic_start": True},
        "solver": {"method": method, **({"shifting": STILL_SHIFTING[method]} if method in STILL_SHIFTING else {}),
                   **(STILL_PBF if method == "pbf" else {})},
        "fluid_blocks": [{"min": [0, 0, 0], "max": [0.4, 0.24, 0.4]}]})
    sim = _simulation(scene, threads)
    t0 = time.perf_counter()
    x0 = sim.positions.astype(np.float64)
    T, KE, RHO = [], [], []

    def record(s_):
        if T and s_.time == T[-1]:  # the second run() calls it at its start, where the first ended
            return
        T.append(s_.time)
        KE.append(s_.stats["kinetic_energy_j"])
        RHO.append(s_.stats["mean_density_error"])
    sim.run(until=t_settle, every=t_end / 50, callback=record)
    x_settled = sim.positions.astype(np.float64)
    sim.run(until=t_end, every=t_end / 50, callback=record)
    x_end = sim.positions.astype(np.float64)
    single = float(np.max(np.linalg.norm(x_end - x_settled, axis=1))) / s
    drift = _coherent_drift(x_settled, x_end, DRIFT_CELL * s) / s
    from_lattice = float(np.max(np.linalg.norm(x_end - x0, axis=1))) / s
    nn = _nearest_neighbour(x_end) / s
    mass = 1000.0 * 0.4 * 0.24 * 0.4
    v_rms = math.sqrt(2 * KE[-1] / mass)
    # Stated bounds, each a ratio that must stay ≤ 1: rms speed at the end ≤ 1% of the
    # gravity-wave speed sqrt(g H); the water's mean displacement after t_settle in any cube of
    # DRIFT_CELL spacings ≤ one spacing; no two particles closer than CLUMP_DISTANCE spacings at
    # the end; mean compression ≤ 1%.
    v_bound = 0.01 * math.sqrt(G * 0.24)
    ratios = {"speed": v_rms / v_bound, "drift": drift, "clumping": CLUMP_DISTANCE / max(float(nn.min()), 1e-9),
              "density": RHO[-1] / 0.01}
    r = Result(case="still_water_3d", method=method,
               metric=(f"worst of: rms speed / 1% of sqrt(gH), mean displacement after t = {t_settle:g} s over "
                       f"cubes of {DRIFT_CELL} spacings / spacing, {CLUMP_DISTANCE:g} spacing / nearest pair, "
                       "mean compression / 1%"),
               error=max(ratios.values()), tolerance=1.0, particles=sim.particle_count, wall_s=time.perf_counter() - t0,
               setup=(f"0.4 m box, water H = 0.24 m deep, spacing {s} m, {t_end} s at rest, default parameters"
                      + (f" with particle shifting A = {STILL_SHIFTING[method]:g}" if method in STILL_SHIFTING else "")
                      + (" at the stable Jacobi weight (solver.pbf.omega = 0)" if method == "pbf" else "")
                      + f", hydrostatic start (WCSPH); drift measured from t = {t_settle:g} s"),
               reference="rest: no flow, no drift, no clumping",
               notes=(f"rms speed {v_rms:.3g} m/s (bound {v_bound:.3g}); drift after t = {t_settle:g} s "
                      f"{drift:.2f} spacings (a single particle's largest displacement {single:.2f}, from the "
                      f"initial lattice {from_lattice:.2f}); nearest neighbour at the end {nn.min():.3f} spacings at "
                      f"least, {np.percentile(nn, 1):.3f} for the closest 1%; mean density error at the end "
                      f"{100 * RHO[-1]:.3f}%; worst ratio: {max(ratios, key=ratios.get)}"),
               series={"t_s": T, "kinetic_energy_j": KE, "mean_density_error": RHO},
               extra={"v_rms": v_rms, "drift_spacings": drift, "max_displacement_spacings": single,
                      "max_displacement_from_lattice_spacings": from_lattice, "nearest_neighbour_spacings": float(nn.min()),
                      "mean_density_error": RHO[-1], **{f"ratio_{k}": v for k, v in ratios.items()}})

    def plot(ax, res):
        ax.semilogy(res.series["t_s"], np.maximum(res.series["kinetic_energy_j"], 1e-12), "-", label=f"rtsph {res.method}")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("kinetic energy (J)")
    r.plot = plot
    return _finish(r)
