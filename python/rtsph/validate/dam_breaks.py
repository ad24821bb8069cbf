"""Dam breaks against experiments: Martin & Moyce 1952 (2D) and MARIN's SPHERIC Test 2 (3D)."""
from __future__ import annotations

import math
import os
import time

import numpy as np

import rtsph

from ._common import G, Result, _finish, _simulation


# --- 2D dam break against Martin & Moyce 1952 -------------------------------------------------
# Martin & Moyce 1952 (Phil. Trans. R. Soc. A 244), surge front of the n² = 2 column, in
# T = t·sqrt(2g/a), Z = x/a; the same points as tests/physics_dam_break_test.cpp.
MARTIN_MOYCE_FRONT = [(0.41, 1.11), (0.84, 1.22), (1.19, 1.44), (1.43, 1.67), (1.63, 1.89),
                      (1.83, 2.11), (1.98, 2.33), (2.20, 2.56), (2.32, 2.78), (2.51, 3.00)]
MAX_CLOCK_OFFSET = 0.3  # T units: ≈ 16 ms at their a = 2.25 in; the experiment's time origin
# Their Table 6: the residual height of the same column at the back wall, H = h/(n²a) against
# τ = t·sqrt(g/a) (n² = 2), as tabulated in a public post-processing script beside their Table
# 2's front (whose first ten points are the ones above, to the digit): the points up to
# τ = 3.44. Later points (H ≤ 0.17 at τ ≥ 4.2) are not compared: by then the surge has come back
# from the far wall of rtsph's 6a tank (their channel was longer).
MARTIN_MOYCE_HEIGHT = [(0.56, 0.94), (0.77, 0.89), (0.93, 0.83), (1.08, 0.78), (1.28, 0.72), (1.46, 0.67),
                       (1.66, 0.61), (1.84, 0.56), (2.00, 0.50), (2.21, 0.44), (2.45, 0.39), (2.70, 0.33),
                       (3.06, 0.28), (3.44, 0.22)]


def _front_errors(T, Z):
    T, Z = np.asarray(T), np.asarray(Z)

    def mean_err(offset):
        return float(np.mean([abs(np.interp(t - offset, T, Z, left=1.0) / z - 1) for t, z in MARTIN_MOYCE_FRONT]))
    offsets = np.arange(0.0, MAX_CLOCK_OFFSET + 1e-9, 0.01)
    errs = [mean_err(o) for o in offsets]
    best = int(np.argmin(errs))
    return errs[0], errs[best], float(offsets[best])


def _height_error(tau, H, offset_tau):
    """Mean relative error of the residual column height against Table 6, on the experiment's
    clock shifted by offset_tau (0 for the case's figure; the front's fitted origin is reported)."""
    tau, H = np.asarray(tau), np.asarray(H)
    return float(np.mean([abs(np.interp(t - offset_tau, tau, H, left=1.0) / h - 1) for t, h in MARTIN_MOYCE_HEIGHT]))


def _dam_break_run(method: str, spacing: float, threads: int):
    a = 1.0
    scale = math.sqrt(2 * G / a)
    sim = _simulation(rtsph.scene("dam_break_2d", {"fluid.spacing": spacing, "solver.method": method}),
                      threads)
    T, Z, H = [], [], []
    # The residual column: the highest particle within a tenth of a (at least two spacings) of
    # the back wall, plus half a spacing (its surface), over the column's initial height n²a.
    wall_band = max(0.1 * a, 2 * spacing)

    def record(s):
        x = s.positions
        T.append(s.time * scale)
        Z.append((float(x[:, 0].max()) + 0.5 * spacing) / a)
        at_wall = x[:, 1][x[:, 0] < wall_band]
        H.append((float(at_wall.max()) + 0.5 * spacing) / (2 * a) if at_wall.size else 0.0)
    t_end = max(2.55 / scale, (MARTIN_MOYCE_HEIGHT[-1][0] + 0.1) / math.sqrt(G / a))
    sim.run(until=t_end, every=0.01 / scale, callback=record)
    return sim, T, Z, H


def dam_break(method: str, level: str, threads: int) -> Result:
    spacing = {"quick": 0.05, "full": 0.02}[level]
    t0 = time.perf_counter()
    sim, T, Z, H = _dam_break_run(method, spacing, threads)
    raw, fitted, offset = _front_errors(T, Z)
    tau = [t / math.sqrt(2) for t in T]  # τ = t·sqrt(g/a) = T/√2
    # The front is compared with its time origin fitted (within 16 ms), as the physics test
    # does: the experiment's surge starts late. The height is compared on the experiment's own
    # clock: its early points (τ < 1, the column top's first fall) agree with every method on
    # that clock and would not with the front's origin (docs/validation.md, session 26), so the
    # surge's late start is the front's, not the clock's. The height on the front's clock is
    # reported.
    height = _height_error(tau, H, 0.0)
    height_front_clock = _height_error(tau, H, offset / math.sqrt(2))
    conv = []
    failed = []
    if level == "full":
        for s in (0.04, 0.02, 0.01):
            try:
                _, t, z, h = _dam_break_run(method, s, threads)
                fe = _front_errors(t, z)
                conv.append((s, max(fe[1], _height_error([x / math.sqrt(2) for x in t], h, 0.0))))
            except rtsph.InstabilityError as e:  # reported, and left out of the order
                failed.append(f"spacing {s} m did not finish: {e}")
    r = Result(case="dam_break_2d", method=method,
               metric=("worst of the mean relative errors of the surge front (time origin fitted within 16 ms) and "
                       "of the residual column height (the experiment's clock)"),
               error=max(fitted, height), tolerance=0.05, particles=sim.particle_count,
               wall_s=time.perf_counter() - t0,
               setup=f"1 m × 2 m column in a 6 m tank, spacing {spacing} m",
               reference=("Martin & Moyce 1952, n² = 2 column: surge front (Table 2, as in "
                          "tests/physics_dam_break_test.cpp) and residual height at the back wall (Table 6, τ ≤ 3.44)"),
               notes=(f"front {100 * fitted:.1f}% (raw clock {100 * raw:.1f}%), height {100 * height:.1f}% "
                      f"(on the front's clock {100 * height_front_clock:.1f}%); front's fitted offset ΔT = {offset:.2f}. "
                      + " ".join(failed)),
               series={"T": T, "Z": Z, "tau": tau, "H": H}, convergence=conv,
               extra={"front_error": fitted, "height_error": height, "raw_clock_error": raw,
                      "front_clock_height_error": height_front_clock, "clock_offset_T": offset})

    def plot(ax, res):
        line, = ax.plot(res.series["T"], res.series["Z"], "-", label=f"rtsph {res.method}: front Z")
        off = res.extra.get("clock_offset_T", 0.0)  # the front as compared: its origin fitted
        ax.plot(np.asarray(res.series["T"]) + off, res.series["Z"], ":", color=line.get_color(),
                label=f"front, origin fitted (ΔT = {off:.2f})")
        ax.plot(np.asarray(res.series["tau"]), 4 * np.asarray(res.series["H"]), "--", color=line.get_color(),
                label=f"rtsph {res.method}: 4H against τ")
        ax.plot(*zip(*MARTIN_MOYCE_FRONT), "o", color="k", label="Martin & Moyce 1952")
        ax.plot([p[0] for p in MARTIN_MOYCE_HEIGHT], [4 * p[1] for p in MARTIN_MOYCE_HEIGHT], "s", color="k",
                mfc="none", label="their column height (4H)")
        ax.set_xlim(0, 3.6)
        ax.set_xlabel(r"$T = t\sqrt{2g/a}$ (front), $\tau = t\sqrt{g/a}$ (height)")
        ax.set_ylabel(r"$Z = x/a$, $4H = 4h/(2a)$")
    r.plot = plot
    return _finish(r)


# --- SPHERIC Test 2: a 3D dam break onto a box (Kleefsman et al. 2005) -----------------------
# MARIN's experiment as SPHERIC's benchmark 2: a tank 3.22 m long, 1 m wide and 1 m high; water
# 1.228 m × 1 m × 0.55 m deep against the far wall (x > 1.992 m); a box 0.161 × 0.403 × 0.161 m
# on the floor at x = 0.6635–0.8245 m, centred across the width. Water heights are measured at
# four probes on the centre line: H1 x = 0.496 m and H2 x = 0.992 m on either side of the box,
# H3 x = 1.488 m, H4 x = 2.638 m in the reservoir (Kleefsman et al., J. Comput. Phys. 206, 2005).
# rtsph's axes: x along the tank, y up, z across (the box at z = 0.5 ± 0.2015 m).
# The heights: data/spheric_test2_heights.csv (MARIN's record every 0.02 s; its header says which
# file it comes from and how its columns map to the probes).
SPHERIC_PROBES = {"H1": 0.496, "H2": 0.992, "H3": 1.488, "H4": 2.638}
# Spacings that divide the tank's 1 m width and the water's 0.55 m depth, so the column holds
# MARIN's water (1.8% more at 0.05 m, from its 1.25 m length; 0.2% less at 0.025 m). The 0.04 and
# 0.02 m of sessions 19-35 stood the water 0.56 m deep, 2.8% and 1.2% too much, and the extra
# water's faster slosh hid part of rtsph's lag (docs/validation.md, SPHERIC section, session 36).
SPHERIC_LEVELS = {"quick": 0.05, "full": 0.025}  # spacing (m)
SPHERIC_T_END = 6.0


def _data_columns(name: str) -> dict:
    """The columns of data/NAME (CSV after '#' comment lines), by header."""
    path = os.path.join(os.path.dirname(__file__), "data", name)
    with open(path) as f:
        lines = [ln.strip() for ln in f if ln.strip() and not ln.startswith("#")]
    head = lines[0].split(",")
    vals = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    return {h: vals[:, i] for i, h in enumerate(head)}


def _spheric_data():
    c = _data_columns("spheric_test2_heights.csv")
    return {"t": c["t_s"], **{k: c[f"{k}_m"] for k in SPHERIC_PROBES}}


# MARIN's pressure sensors P1-P4 on the box's front face (x = 0.8245 m; the experiment's z is
# rtsph's y): 0.471 m across the tank, 0.021 / 0.061 / 0.101 / 0.141 m above the floor. The data
# file holds their first impact only (t = 0.383-0.543 s at ~1 ms; its header says why).
SPHERIC_SENSORS = {"P1": 0.021, "P2": 0.061, "P3": 0.101, "P4": 0.141}
SPHERIC_SENSOR_ACROSS = 0.471
SPHERIC_FACE_X = 0.8245
SPHERIC_IMPACT = (0.383, 0.543)   # s: the window the pressure record covers
SPHERIC_PLATEAU = (0.48, 0.543)   # s: after the impact's peaks, the pressure of the water piled on the face
SPHERIC_ARRIVAL_PA = 1000.0       # a sensor is hit when its pressure first passes this


# A probe reads the depth of water over it: the fluid volume (particles × s³) around its line,
# weighted by a smooth weight w(r) normalised over the plane. Robust to splashes and air, unlike
# the highest particle, and smooth: a square column instead (counting particles inside) jumps by
# a lattice column whenever one crosses its edge (±0.05 m at 0.04 m spacing). The weight is the
# 2D cubic spline of support R = 2.5 spacings (at least 5 cm): over a lattice of still water it
# sums to 0.999-1.003 of the depth wherever the probe sits on the lattice. The cone
# w = 3(1 − r/R)/(πR²) it replaced (session 35) summed to 0.980-1.036, and read 0.578 m over
# 0.56 m of water at H4 at the quick level (test_the_probes_read_still_water_at_its_depth).
def probe_radius(s: float) -> float:
    return max(0.05, 2.5 * s)


def cubic_spline_shape(q):
    """The cubic spline's shape (Monaghan 1992) at q = r/h, support 2h: 1 at q = 0, unnormalised."""
    return 0.25 * np.clip(2.0 - q, 0.0, None) ** 3 - np.clip(1.0 - q, 0.0, None) ** 3


def probe_weight(r, R: float):
    """The cubic spline of support R in the plane, normalised: ∫ w dA = 1 (1/m²)."""
    return cubic_spline_shape(2.0 * np.asarray(r) / R) * (40.0 / (7.0 * math.pi * R * R))


def _spheric_pressures():
    c = _data_columns("spheric_test2_pressures.csv")
    return {"t": c["t_s"], **{k: c[f"{k}_pa"] for k in SPHERIC_SENSORS}}


def _impact_figures(t, p):
    """A sensor's first impact: its peak and when, when it first passes SPHERIC_ARRIVAL_PA, and its
    mean over SPHERIC_PLATEAU (Pa, s)."""
    t, p = np.asarray(t), np.asarray(p)
    w = (t >= SPHERIC_IMPACT[0] - 1e-9) & (t <= SPHERIC_IMPACT[1] + 1e-9)
    tw, pw = t[w], p[w]
    i = int(np.argmax(pw))
    hit = np.nonzero(pw > SPHERIC_ARRIVAL_PA)[0]
    plateau = (tw >= SPHERIC_PLATEAU[0]) & (tw <= SPHERIC_PLATEAU[1])
    return {"peak": float(pw[i]), "t_peak": float(tw[i]), "t_hit": float(tw[hit[0]]) if hit.size else float("nan"),
            "plateau": float(np.mean(pw[plateau])) if plateau.any() else float("nan")}


def spheric_heights_plot(ax, res):
    """The four probes' water heights against MARIN's (a report panel; module level, so a saved
    run's CSV can be drawn again)."""
    data = _spheric_data()
    w = data["t"] <= SPHERIC_T_END + 1e-9
    color = None  # one colour per method, taken from its first line
    for i, k in enumerate(SPHERIC_PROBES):
        off = 0.6 * i
        line, = ax.plot(res.series["t_s"], np.asarray(res.series[f"{k}_m"]) + off, "-", lw=0.9,
                        label=f"rtsph {res.method}", **({} if color is None else {"color": color}))
        color = line.get_color() if color is None else color
        ax.plot(data["t"][w], data[k][w] + off, "k-", lw=0.6, label="MARIN (SPHERIC Test 2)")
        ax.text(6.05, off + 0.02, k, fontsize=8)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("water height (m), probes offset by 0.6 m")


def spheric_pressures_plot(ax, res):
    """P1 and P3 on the box's front face over the first impact, against MARIN's sensors."""
    exp_p = _spheric_pressures()
    t = np.asarray([v for v in res.series["t_impact_s"] if v is not None])
    color = None
    for k, style in (("P1", "-"), ("P3", "--")):
        line, = ax.plot(t, np.asarray(res.series[f"{k}_pa"][:len(t)]) / 1e3, style, lw=0.9,
                        label=f"rtsph {res.method} {k}", **({} if color is None else {"color": color}))
        color = line.get_color() if color is None else color
        ax.plot(exp_p["t"], exp_p[k] / 1e3, "k" + style, lw=0.7, label=f"MARIN {k}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("pressure on the box's front face (kPa)")
    ax.set_title("first impact: P1 (0.021 m), P3 (0.101 m)")


def spheric_test2(method: str, level: str, threads: int) -> Result:
    s = SPHERIC_LEVELS[level]
    r = Result(case="spheric_test2_3d", method=method,
               metric="largest of the four probes' mean absolute height error over 0–6 s (m)",
               tolerance=0.03, reference="MARIN's water heights at H1–H4 (SPHERIC Test 2, Kleefsman et al. 2005)",
               setup=(f"3.22 × 1 × 1 m tank, water 1.228 × 1 × 0.55 m (in whole spacings: {round(1.228 / s) * s:.3g} × 1 × "
                      f"{round(0.55 / s) * s:.3g} m), box 0.161 × 0.403 × 0.161 m at "
                      f"x = 0.6635 m; spacing {s} m, default parameters, 6 s; height = fluid volume around the "
                      f"probe, weighted by the 2D cubic spline of support {probe_radius(s):g} m normalised over the plane"))
    data = _spheric_data()
    # The column in whole spacings against the far wall. The lattice starts half a spacing inside
    # the block, so a length that is not a whole number of spacings puts its last column too
    # close to the wall (0.8 cm instead of 2 cm at 0.04 m spacing: 1.228/0.04 = 30.7). The wall
    # pushes that column off, and the slosh reached H4 as a 4–5 cm bump in the first 0.3 s. The
    # dam face moves by less than half a spacing; the depth is exact (SPHERIC_LEVELS).
    length, depth = round(1.228 / s) * s, round(0.55 / s) * s
    scene = rtsph.scene({
        "name": "validate_spheric_test2_3d", "dimension": 3,
        "domain": {"min": [0, 0, 0], "max": [3.22, 1.0, 1.0]}, "fluid": {"spacing": s},
        "solver": {"method": method},
        "fluid_blocks": [{"min": [3.22 - length, 0, 0], "max": [3.22, depth, 1.0]}],
        "obstacles": [{"shape": "box", "center": [0.744, 0.0805, 0.5], "half_extents": [0.0805, 0.0805, 0.2015]}],
        "end_time": SPHERIC_T_END})
    sim = _simulation(scene, threads)
    t0 = time.perf_counter()
    R = probe_radius(s)
    # Pressure on the box's front face (the side the water hits, x = 0.8245 m): the mean pressure
    # of the fluid within 1.5 spacings of it, below 0.08 m and within 0.1 m of the centre line.
    # And at MARIN's sensors P1-P4: the Shepard (kernel-weighted) mean of the fluid's pressure
    # around the point half a spacing in front of each sensor, W with h = spacing (support 2h); 0
    # while no particle is in reach (dry).
    T, H, PF = [], {k: [] for k in SPHERIC_PROBES}, []
    TS, PS = [], {k: [] for k in SPHERIC_SENSORS}
    sig = 1.0 / (math.pi * s ** 3)

    next_record = [0.02 * math.ceil(SPHERIC_IMPACT[0] / 0.02 - 1e-9)]

    def sensors(sim_):
        if sim_.time >= next_record[0] - 1e-9:  # the heights go on at their 0.02 s through the window
            record(sim_)
            next_record[0] += 0.02
        x = sim_.positions
        p = sim_.pressure
        TS.append(sim_.time)
        near = np.abs(x[:, 0] - SPHERIC_FACE_X - 0.5 * s) < 2 * s
        xn, pn = x[near], p[near]
        for k, y in SPHERIC_SENSORS.items():
            q = np.sqrt((xn[:, 0] - SPHERIC_FACE_X - 0.5 * s) ** 2 + (xn[:, 1] - y) ** 2
                        + (xn[:, 2] - SPHERIC_SENSOR_ACROSS) ** 2) / s
            w = sig * cubic_spline_shape(q)
            PS[k].append(float(np.sum(w * pn) / np.sum(w)) if np.sum(w) > 0 else 0.0)

    def record(sim_):
        x = sim_.positions
        T.append(sim_.time)
        for k, px in SPHERIC_PROBES.items():
            H[k].append(float(np.sum(probe_weight(np.hypot(x[:, 0] - px, x[:, 2] - 0.5), R))) * s ** 3)
        front = (x[:, 0] > 0.8245) & (x[:, 0] < 0.8245 + 1.5 * s) & (x[:, 1] < 0.08) & (np.abs(x[:, 2] - 0.5) < 0.1)
        PF.append(float(np.mean(sim_.pressure[front])) if front.any() else 0.0)
    # run() calls its callback at its start too: the first call records t = 0.
    sim.run(until=SPHERIC_IMPACT[0], every=0.02, callback=record)
    sim.run(until=SPHERIC_IMPACT[1], every=0.001, callback=sensors)  # the impact at MARIN's ~1 ms
    sim.run(until=SPHERIC_T_END, every=0.02, callback=record)
    errs = {}
    window = data["t"] <= SPHERIC_T_END + 1e-9  # MARIN's record runs on to 7.38 s
    for k in SPHERIC_PROBES:
        hs = np.interp(data["t"][window], T, H[k])
        errs[k] = float(np.mean(np.abs(hs - data[k][window])))
    r.error = max(errs.values())
    r.particles, r.wall_s = sim.particle_count, time.perf_counter() - t0
    # The first impact at P1-P4 against MARIN's record: reported, not toleranced (the issue asks
    # for the heights within 3 cm and the pressures reported).
    exp_p = _spheric_pressures()
    impact = {k: (_impact_figures(exp_p["t"], exp_p[k]), _impact_figures(TS, PS[k])) for k in SPHERIC_SENSORS}
    r.notes = ("mean absolute height error " + ", ".join(f"{k} {100 * e:.1f} cm" for k, e in errs.items())
               + "; first impact on the box's front face, MARIN / rtsph: "
               + "; ".join(f"{k} hit at {e['t_hit']:.3f} / {m['t_hit']:.3f} s, peak {e['peak'] / 1e3:.1f} / "
                           f"{m['peak'] / 1e3:.1f} kPa, then {e['plateau'] / 1e3:.1f} / {m['plateau'] / 1e3:.1f} kPa"
                           for k, (e, m) in impact.items())
               + f" (t = {SPHERIC_PLATEAU[0]:g}-{SPHERIC_PLATEAU[1]:g} s); reported, not compared with a tolerance")
    r.series = {"t_s": T, **{f"{k}_m": H[k] for k in SPHERIC_PROBES}, "p_front_pa": PF,
                "t_impact_s": TS, **{f"{k}_pa": PS[k] for k in SPHERIC_SENSORS}}
    r.extra = {**{f"mae_{k}_m": e for k, e in errs.items()},
               **{f"{k}_{f}_{who}": v for k, pair in impact.items() for who, fig in zip(("marin", "rtsph"), pair)
                  for f, v in fig.items()}}

    r.plot, r.side_plot = spheric_heights_plot, spheric_pressures_plot
    return _finish(r)
