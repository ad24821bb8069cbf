"""rtsph validate's cases: the tools each case measures with read known inputs right (the lattice
drops, the virial pressure, the probes, the standing wave's mode, the reference solutions)."""
import math

import numpy as np
import pytest

from rtsph import validate

pytestmark = pytest.mark.usefixtures("validate_context")


# The droplet cases' measuring tools (rtsph.validate.cases): the lattice ball has the ball's
# volume, and the Irving–Kirkwood pressure of the SPH pressure force reads the EOS pressure in a
# uniform lattice (within the kernel sums' 2%), so the mechanical jump is measured on p's scale.
@pytest.mark.parametrize("dim", [2, 3])
def test_ball_blocks_fill_the_ball(dim):
    import math
    from rtsph.validate.cases import _ball_blocks
    s, R = 0.005, 0.05
    count = sum(round((b["max"][0] - b["min"][0]) / s) for b in _ball_blocks(dim, R, s))
    volume = math.pi * R * R if dim == 2 else 4 / 3 * math.pi * R ** 3
    assert abs(count * s ** dim / volume - 1) < 0.02
    ellipse = sum(round((b["max"][0] - b["min"][0]) / s) for b in _ball_blocks(2, R, s, 1.1))
    assert abs(ellipse * s * s / (math.pi * R * R) - 1) < 0.03  # semi-axes 1.1 R and R/1.1


# The static drops' lattice draws: draw 0 is the centred lattice, the others shift it under the
# ball by distinct fractions of a spacing, and every draw still fills the ball.
@pytest.mark.parametrize("dim", [2, 3])
def test_lattice_draws_shift_the_lattice_and_fill_the_ball(dim):
    import math
    from rtsph.validate.drops import _ball_blocks, _draw_offset
    s, R = 0.005, 0.05
    assert _draw_offset(0, dim, s) == [0.0] * dim
    offsets = [tuple(_draw_offset(k, dim, s)) for k in range(32)]
    assert len(set(offsets)) == 32 and all(0 <= v < s for o in offsets for v in o)
    volume = math.pi * R * R if dim == 2 else 4 / 3 * math.pi * R ** 3
    for o in offsets[1:4]:
        blocks = _ball_blocks(dim, R, s, offset=o)
        count = sum(round((b["max"][0] - b["min"][0]) / s) for b in blocks)
        assert abs(count * s ** dim / volume - 1) < 0.02
        for b in blocks:  # every block on the shifted lattice: its corners at k·s + offset
            for a in range(dim):
                assert abs((b["min"][a] - o[a]) / s - round((b["min"][a] - o[a]) / s)) < 1e-9


# The draws each method's drops take, (R1, R2): the quick level halves them only where a method's
# draws agree (drops.QUICK_HALVED, docs/validation.md "Half the draws"); the full level keeps
# every draw (DFSPH's 2D R2 apart); the oscillating drop calibrates on its static drop's R1 draws.
def test_the_quick_level_halves_only_the_listed_draws():
    from rtsph.validate import drops
    quick = {(2, "wcsph"): (4, 2), (2, "pbf"): (4, 2), (2, "dfsph"): (4, 2),
             (3, "wcsph"): (4, 1), (3, "pbf"): (4, 1), (3, "dfsph"): (4, 1)}
    full = {(2, "wcsph"): (8, 4), (2, "pbf"): (8, 4), (2, "dfsph"): (8, 2),
            (3, "wcsph"): (4, 1), (3, "pbf"): (4, 1), (3, "dfsph"): (4, 1)}
    for (dim, m), draws in quick.items():
        assert drops._draws(m, dim, "quick") == draws and drops._draws(m, dim, "full") == full[(dim, m)]
        static = drops.draw_keys(f"static_droplet_{dim}d", m, "quick")
        assert len(static) == sum(draws)
        if dim == 2:
            osc = drops.draw_keys("oscillating_droplet_2d", m, "quick")
            assert len(osc) == draws[0] and all(k in static for k in osc)


# A drop's pressure sample is the mean over consecutive steps (DFSPH's step pressure cycles at
# rest): each particle's mean of what stepping one by one reads, the simulation left on the last
# of those steps. Two runs of the same scene give the same bits, so one steps by hand.
def test_drop_pressure_samples_are_means_over_consecutive_steps():
    import rtsph
    from rtsph.validate.drops import _droplet_scene, _mean_pressure_and_density
    scene = _droplet_scene("dfsph", 2, 0.02, 0.005, 0.01, "t", "quick")
    by_hand, sampled = rtsph.Simulation(scene, threads=1), rtsph.Simulation(scene, threads=1)
    by_hand.step(5)
    sampled.step(5)
    p, rho = [by_hand.pressure.astype(np.float64)], [by_hand.density.astype(np.float64)]
    for _ in range(3):
        by_hand.step()
        p.append(by_hand.pressure.astype(np.float64))
        rho.append(by_hand.density.astype(np.float64))
    mp, mrho = _mean_pressure_and_density(sampled, 4)
    assert sampled.step_count == by_hand.step_count == 8
    assert np.ptp(np.array(p), axis=0).max() > 0  # the steps differ, so the mean is not one of them
    np.testing.assert_allclose(mp, np.mean(p, axis=0), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(mrho, np.mean(rho, axis=0), rtol=1e-6)


# The pressure force's virial on a uniform lattice at uniform p is p times the lattice's kernel
# moment (ρ/d) Σⱼ (m/ρ) r² |G|, 1 to within the kernel's discretisation: so each kernel's gradient
# is the solver's (a wrong normalisation or exponent reads far off).
@pytest.mark.parametrize("dim,kernel,ratio", [(2, "cubic_spline", 1.0), (3, "cubic_spline", 1.0),
                                              (2, "wendland_c2", 2.0), (3, "wendland_c2", 2.0)])
def test_virial_pressure_of_a_uniform_lattice_is_the_eos_pressure(dim, kernel, ratio):
    import numpy as np
    from rtsph.validate.cases import _virial_pressures
    s, n = 0.005, 8 if ratio == 1.0 else 12
    grid = np.stack(np.meshgrid(*[np.arange(-n, n) * s] * dim, indexing="ij"), -1).reshape(-1, dim)
    inner = np.nonzero(np.linalg.norm(grid, axis=1) < 2 * s)[0]
    rho, p = np.full(len(grid), 1000.0), np.full(len(grid), 100.0)
    vp, vc = _virial_pressures(grid, rho, p, inner, ratio * s, 1000.0 * s ** dim, 1.0, dim, kernel=kernel)
    assert abs(vp / 100.0 - 1) < 0.03
    assert vc < 0  # cohesion is a tension in the bulk
    vp0, vc0 = _virial_pressures(grid, rho, p, inner, ratio * s, 1000.0 * s ** dim, 0.0, dim, kernel=kernel)
    assert vc0 == 0 and vp0 == vp
    with pytest.raises(ValueError):
        _virial_pressures(grid, rho, p, inner, s, 1000.0 * s ** dim, 1.0, dim, kernel="gaussian")


# Still water's measures (rtsph.validate.tanks): drift is the water's motion, the mean over the
# particles starting in each cube, so a uniform shift reads in full and neighbours trading places
# read nothing; the nearest neighbour of a lattice is its spacing.
def test_still_water_drift_is_the_waters_not_a_particles():
    from rtsph.validate.tanks import _coherent_drift, _nearest_neighbour
    s, n = 0.025, 8
    grid = np.stack(np.meshgrid(*[(np.arange(n) + 0.5) * s] * 3, indexing="ij"), -1).reshape(-1, 3)
    shifted = grid + np.array([0.3 * s, 0.0, -0.4 * s])
    assert abs(_coherent_drift(grid, shifted, 4 * s) / s - 0.5) < 1e-9
    # Every particle trades places with its x neighbour (a move of a whole spacing each): the
    # mean over each cube of 4 spacings (an even number of columns) does not move.
    swapped = grid.copy()
    swapped[:, 0] += np.where(np.floor(grid[:, 0] / s) % 2 == 0, s, -s)
    assert np.max(np.linalg.norm(swapped - grid, axis=1)) / s == pytest.approx(1.0)
    assert _coherent_drift(grid, swapped, 4 * s) < 1e-12
    nn = _nearest_neighbour(grid) / s
    assert np.allclose(nn, 1.0)
    clumped = grid.copy()
    clumped[0] = clumped[1] + np.array([0.0, 0.0, -0.3 * s])  # particle 0 onto its neighbour
    assert _nearest_neighbour(clumped).min() / s == pytest.approx(0.3)


# The two issue-13 cases' references and scenes: the incompressible ellipse keeps its area and
# starts as the free strain b = R e^{A0 t}; the Couette series starts at rest and ends linear.
def test_elliptical_drop_reference():
    import numpy as np
    from rtsph.validate.cases import elliptical_drop_exact
    t = np.array([0.0, 1e-5, 0.004, 0.008])
    A, a, b = elliptical_drop_exact(t).T
    assert np.allclose(a * b, 1.0, atol=1e-9)
    assert abs(b[1] / np.exp(100.0 * 1e-5) - 1) < 1e-6 and A[0] == 100.0
    assert 1.99 < b[-1] < 2.01 and np.all(np.diff(A) < 0)


def test_couette_reference():
    import numpy as np
    from rtsph.validate.cases import couette_exact
    y = np.linspace(0.1e-3, 0.9e-3, 9)
    assert np.max(np.abs(couette_exact(y, 0.0))) < 0.01 * 2.5e-5
    assert np.allclose(couette_exact(y, 10.0), 2.5e-5 * y / 1e-3, rtol=1e-9)


def test_issue_13_cases_run():
    r = validate.CASES["elliptical_drop_2d"]("dfsph", "quick", 2)
    assert r.passed and r.tolerance == 0.02 and list(r.series)[:3] == ["t_s", "b_m", "b_exact_m"]
    # The plate drags the fluid (with its top row culled it did not: 92%), with no slip on its
    # face (0.085%; on its first sample row, half a spacing above the face, it was 9.2%).
    r = validate.CASES["couette_2d"]("wcsph", "quick", 2)
    assert r.passed and r.error < 0.005 and r.particles == 160
    assert not validate.CASES["couette_2d"]("pbf", "quick", 2).applicable


def test_the_channels_widen_for_a_wider_kernel(monkeypatch):
    """Poiseuille's and Couette's periodic channel is 8 columns at the cases' own kernels, and as
    many as three of a kernel's supports need when `validate --set` widens it (the scene check
    refuses a periodic extent under three supports: both cases were n/a at Wendland C2, h = 1.5 s)."""
    from rtsph.validate import _common, cases
    assert _common.periodic_columns({}, 8) == 8  # the cubic spline at h = s: 6.0006 spacings
    wide = {"solver.kernel": "wendland_c2", "solver.smoothing_ratio": "1.5", "solver.boundary_layers": "3"}
    monkeypatch.setattr(_common, "_OVERRIDES", wide)
    assert _common.periodic_columns({}, 8) == 10  # 9.0009 spacings
    monkeypatch.setattr(_common, "_OVERRIDES", dict(wide, **{"solver.smoothing_ratio": "2"}))
    assert _common.periodic_columns({}, 8) == 13
    monkeypatch.setattr(_common, "_OVERRIDES", wide)
    for case in ("couette_2d", "poiseuille_2d"):
        r = cases.CASES[case]("dfsph", "quick", 2)
        assert r.applicable and r.metric != "(did not finish)" and r.particles == 10 * 20, (case, r.notes)


def test_a_case_the_engine_cannot_build_says_why(monkeypatch):
    """A case whose scene the installed engine rejects (an older build that lacks a newer
    parameter) fails with the engine's message and the fix, not with a bare inf."""
    import rtsph
    from rtsph.validate import cases

    def old_engine(method, level, threads):
        return rtsph.scene("dam_break_2d", {"solver.no_such_parameter": 1})
    monkeypatch.setitem(cases.CASES, "old_engine", old_engine)
    r = cases.run_case("old_engine", "wcsph", "quick", 1)
    assert r.metric == "(did not finish)" and not r.passed
    assert "unknown key" in r.notes and "scripts/setup-python.sh" in r.notes


def test_the_column_height_metric_reads_the_table():
    # Martin & Moyce's own points read back exactly; a column 10% higher everywhere reads 10%;
    # a clock shift moves the comparison along τ.
    from rtsph.validate.cases import MARTIN_MOYCE_HEIGHT, _height_error
    tau = [0.0] + [p[0] for p in MARTIN_MOYCE_HEIGHT]
    H = [1.0] + [p[1] for p in MARTIN_MOYCE_HEIGHT]
    assert _height_error(tau, H, 0.0) == pytest.approx(0.0, abs=1e-12)
    assert _height_error(tau, [1.1 * h for h in H], 0.0) == pytest.approx(0.1, rel=1e-9)
    assert _height_error(tau, H, 0.2) > 0.02


def test_the_spheric_heights_are_in_probe_order():
    # The water starts beyond x = 1.992 m and runs toward x = 0, so it reaches H3 (1.488 m),
    # then H2 (0.992 m), then H1 (0.496 m); H4 (2.638 m) starts inside the column, 0.55 m deep.
    from rtsph.validate.cases import _spheric_data
    d = _spheric_data()
    assert d["t"][0] == 0.0 and d["t"][-1] >= 5.9
    wet = {k: float(d["t"][np.argmax(d[k] > 0.02)]) for k in ("H1", "H2", "H3")}
    assert wet["H3"] < wet["H2"] < wet["H1"]
    assert abs(d["H4"][0] - 0.55) < 0.01


def test_the_spheric_pressures_are_the_front_face_sensors_bottom_up():
    # P1-P4 sit 0.021 ... 0.141 m up the box's front face; the wave runs along the floor, so it
    # hits P1 first and P4 last. The record covers the first impact only, at about 1 ms.
    from rtsph.validate.dam_breaks import SPHERIC_SENSORS, _impact_figures, _spheric_pressures
    d = _spheric_pressures()
    assert 0.38 < d["t"][0] < 0.39 and 0.54 < d["t"][-1] < 0.55
    assert np.all(np.diff(d["t"]) > 0.0009) and np.all(np.diff(d["t"]) < 0.0012)
    hits = [_impact_figures(d["t"], d[k])["t_hit"] for k in SPHERIC_SENSORS]
    assert hits == sorted(hits) and hits[0] == pytest.approx(0.394)
    assert max(_impact_figures(d["t"], d[k])["peak"] for k in SPHERIC_SENSORS) == pytest.approx(11239)


def test_the_probes_read_still_water_at_its_depth():
    # A probe's depth is Σ w(r) s³ over the particles: over a lattice of still water it must read
    # the water's depth wherever the probe sits on the lattice (the case's quick and full
    # spacings, probes moved across a whole lattice cell). The cone the probes used before
    # session 35 read 0.980-1.036 of the depth (0.578 m over 0.56 m at H4, quick).
    from rtsph.validate.dam_breaks import SPHERIC_LEVELS, probe_radius, probe_weight
    for s in SPHERIC_LEVELS.values():
        x = (np.arange(round(1.0 / s)) + 0.5) * s
        X, Z = np.meshgrid(x, x)
        reads = []
        for dx in np.linspace(0.0, s, 7):
            for dz in np.linspace(0.0, s, 7):
                w = probe_weight(np.hypot(X - 0.5 - dx, Z - 0.5 - dz), probe_radius(s))
                reads.append(float(np.sum(w)) * s ** 2)  # depth read / depth, whatever the layers
        assert min(reads) > 0.997 and max(reads) < 1.004, (s, min(reads), max(reads))
    # and the weight is normalised over the plane
    r = np.linspace(0.0, 0.2, 20001)
    f = probe_weight(r, 0.1) * 2 * np.pi * r
    assert float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(r))) == pytest.approx(1.0, rel=1e-6)


def test_the_spheric_column_holds_marins_water():
    # The lattice fills whole spacings: each level's spacing must divide the tank's width (1 m)
    # and the water's depth (0.55 m), so the column stands as deep and as wide as MARIN's, and
    # the whole-spacing length (1.228 m rounded) may add or take at most 2% of the water. At
    # 0.04 / 0.02 m (sessions 19-35) it stood 0.56 m deep: 2.8% / 1.2% more water, a faster slosh.
    from rtsph.validate.dam_breaks import SPHERIC_LEVELS
    for s in SPHERIC_LEVELS.values():
        for extent in (1.0, 0.55):
            assert abs(round(extent / s) * s - extent) < 1e-9, (s, extent)
        assert abs(round(1.228 / s) * s / 1.228 - 1.0) <= 0.02, s


def test_the_standing_wave_reads_its_mode():
    # The mode's amplitude from the water's first moment, each particle carrying its area s²: water
    # standing h + A cos(kx) deep in columns of whole spacings reads A (to the columns' rounding),
    # flat water 0; and the theory's period is the dispersion relation's (1.517 s for 1 m by 0.2 m).
    from rtsph.validate.waves import WAVE_H, WAVE_L, mode_amplitude, standing_wave_theory
    k, w, period = standing_wave_theory()
    assert period == pytest.approx(2 * math.pi / math.sqrt(9.81 * math.pi * math.tanh(math.pi * 0.2)))
    assert period == pytest.approx(1.5166, abs=1e-4)
    s = 0.001

    def water(A):
        cols = (np.arange(round(WAVE_L / s)) + 0.5) * s
        return np.array([(x, (j + 0.5) * s) for x in cols
                         for j in range(round((WAVE_H + A * math.cos(k * x)) / s))])
    assert abs(mode_amplitude(water(0.0), k, s)) < 1e-9
    for A in (0.01, -0.005):
        assert mode_amplitude(water(A), k, s) == pytest.approx(A, rel=0.02)


def test_the_standing_waves_velocity_carries_linear_theorys_energy():
    # The case's energy budget is over the imposed field's kinetic energy: at the mode's zero
    # crossing that is all of the wave's energy, (1/4) rho g A^2 L per unit width (0.245 J for
    # 1 cm on 1 m), on a lattice of equal masses rho s^2; and the field has no divergence.
    from rtsph.validate.waves import WAVE_A, WAVE_H, WAVE_L, mode_velocity, standing_wave_theory
    k, w, _ = standing_wave_theory()
    s = 0.0025
    g = (np.arange(round(WAVE_L / s)) + 0.5) * s, (np.arange(round(WAVE_H / s)) + 0.5) * s
    x = np.array([(a, b) for a in g[0] for b in g[1]])
    v = mode_velocity(x, k, w).astype(np.float64)
    kinetic = 0.5 * 1000 * s * s * np.sum(v * v)
    assert kinetic == pytest.approx(0.25 * 1000 * 9.81 * WAVE_A ** 2 * WAVE_L, rel=0.01)
    e = 1e-3  # float32 rows: a step well above their round-off
    div = ((mode_velocity(x + [e, 0], k, w)[:, 0] - mode_velocity(x - [e, 0], k, w)[:, 0]).astype(np.float64)
           + (mode_velocity(x + [0, e], k, w)[:, 1] - mode_velocity(x - [0, e], k, w)[:, 1])) / (2 * e)
    assert np.max(np.abs(div)) < 1e-3 * WAVE_A * w * k


def test_impact_figures_read_a_known_pulse():
    from rtsph.validate.dam_breaks import _impact_figures
    t = np.arange(0.38, 0.544, 0.001)
    p = np.where(t < 0.40, 0.0, np.where(t < 0.42, 8000.0, 3000.0))
    f = _impact_figures(t, p)
    assert f["t_hit"] == pytest.approx(0.40, abs=1e-9) and f["peak"] == 8000.0
    assert f["t_peak"] == pytest.approx(0.40, abs=1e-9) and f["plateau"] == pytest.approx(3000.0)
