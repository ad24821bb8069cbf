"""rtsph validate: cases run, the report is written, exit codes say pass (0), fail (1), bad input (2)."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

from rtsph import validate
from rtsph.validate import __main__ as vmain
from rtsph.validate.cases import Result

pytestmark = pytest.mark.usefixtures("validate_context")


def test_passing_cases_write_the_report(tmp_path):
    out = tmp_path / "v"
    r = subprocess.run([sys.executable, "-m", "rtsph.validate", "poiseuille_2d", "couette_2d", "--quick",
                        "--out", str(out), "--threads", "2"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["passed"] is True and summary["meta"]["level"] == "quick"
    rows = {(c["case"], c["method"]): c for c in summary["cases"]}
    assert set(rows) == {(c, m) for c in ("poiseuille_2d", "couette_2d") for m in validate.METHODS}
    assert rows[("poiseuille_2d", "pbf")]["applicable"] is False  # PBF has no laminar viscosity
    pw = rows[("poiseuille_2d", "wcsph")]
    assert pw["passed"] and pw["error"] <= pw["tolerance"] == 0.02
    page = (out / "report.html").read_text()
    assert "data:image/png;base64," in page and "poiseuille_2d" in page and "n/a" in page
    assert (out / "poiseuille_2d.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    header = (out / "couette_2d_dfsph.csv").read_text().splitlines()[0]
    assert header.split(",")[0] == "t_s"
    assert "pass" in r.stderr  # a progress line per case


def test_jobs_give_the_same_figures_and_plots(tmp_path):
    """--jobs runs cases in worker processes; every method's bits are independent of the thread
    count, so a serial two-thread run and two one-thread workers write the same figures, CSVs
    and plots (the dam break's plot reuses a line's colour: the recorded plot must replay it)."""
    runs = {}
    for jobs, threads in ((1, 2), (2, 1)):
        out = tmp_path / f"j{jobs}"
        r = subprocess.run([sys.executable, "-m", "rtsph.validate", "dam_break_2d", "poiseuille_2d", "--quick",
                            "--out", str(out), "--threads", str(threads), "--jobs", str(jobs)],
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr  # every method passes both (PBF's dam break since session 27)
        assert r.stderr.count("dam_break_2d (") == 3
        runs[jobs] = out
    rows = [{(c["case"], c["method"]): c["error"] for c in json.loads((o / "summary.json").read_text())["cases"]}
            for o in runs.values()]
    assert list(rows[0]) == list(rows[1])  # the serial order, whatever finished first
    assert all(rows[0][k] == rows[1][k] or (rows[0][k] != rows[0][k] and rows[1][k] != rows[1][k]) for k in rows[0])
    for name in ("dam_break_2d.png", "poiseuille_2d.png", "dam_break_2d_wcsph.csv", "poiseuille_2d_dfsph.csv"):
        assert (runs[1] / name).read_bytes() == (runs[2] / name).read_bytes(), name


def _always_fails(method, level, threads):
    """A case that fails its tolerance, with a series to plot."""
    r = Result(case="always_fails", method=method, metric="m", error=1.0, tolerance=0.5)
    r.series = {"x": [0.0, 1.0]}
    r.plot = lambda ax, res: ax.plot(res.series["x"], res.series["x"])
    return r


def test_a_failing_case_exits_1(tmp_path, monkeypatch):
    monkeypatch.setitem(validate.CASES, "always_fails", _always_fails)
    assert vmain.main(["always_fails", "--method", "wcsph", "--jobs", "1", "--out", str(tmp_path)]) == 1
    assert json.loads((tmp_path / "summary.json").read_text())["passed"] is False


def test_known_failures_hold_the_failing_cases_where_they_are(tmp_path, monkeypatch):
    from rtsph.validate.known import Known, judge
    known = {("c", "wcsph"): Known(0.2, "why"), ("c", "pbf"): Known(None, "no figure")}

    def res(method, error, passed=False, case="c"):
        return Result(case=case, method=method, metric="m", error=error, tolerance=0.1, passed=passed)
    assert judge([res("wcsph", 0.24), res("pbf", float("nan")), res("dfsph", 0.05, True)], known) == []
    worse = judge([res("wcsph", 0.26)], known)  # above 1.25 × 0.2
    assert len(worse) == 1 and "got worse" in worse[0]
    assert "not a known failure" in judge([res("dfsph", 0.2)], known)[0]
    assert "now passes" in judge([res("wcsph", 0.05, True)], known)[0]
    assert "did not give a figure" in judge([res("wcsph", float("inf"))], known)[0]
    assert "did not give a figure" in judge([res("wcsph", float("nan"))], known)[0]
    # An entry with a margin of its own (a figure known to swing between hosts) is held to that.
    wide = {("c", "wcsph"): Known(0.2, "swings", margin=2.5)}
    assert judge([res("wcsph", 0.45)], wide) == []
    assert "at most 2.5× that" in judge([res("wcsph", 0.55)], wide)[0]
    # A noisy entry (a figure within its own noise) may pass without leaving the list, and is
    # still held to its ceiling when it fails.
    noisy = {("c", "wcsph"): Known(0.2, "within its noise", margin=2.0, noisy=True)}
    assert judge([res("wcsph", 0.05, True)], noisy) == []
    assert judge([res("wcsph", 0.35)], noisy) == []
    assert "got worse" in judge([res("wcsph", 0.45)], noisy)[0]

    # Through the command: a failure listed in known.py exits 0 with the flag, 1 without.
    monkeypatch.setitem(validate.CASES, "always_fails", _always_fails)
    from rtsph.validate import known as known_mod
    monkeypatch.setitem(known_mod.KNOWN_FAILURES, ("always_fails", "wcsph"), Known(1.0, "a test's failure"))
    args = ["always_fails", "--method", "wcsph", "--jobs", "1", "--out", str(tmp_path)]
    assert vmain.main(args) == 1
    assert vmain.main(args + ["--known-failures"]) == 0
    row = json.loads((tmp_path / "summary.json").read_text())["cases"][0]
    assert row["passed"] is False and row["known_failure"] == "a test's failure"
    assert "(known)" in (tmp_path / "report.html").read_text()
    assert vmain.main(args + ["--known-failures", "--full"]) == 2
    monkeypatch.setitem(known_mod.KNOWN_FAILURES, ("always_fails", "wcsph"), Known(0.7, "recorded lower"))
    assert vmain.main(args + ["--known-failures"]) == 1


@pytest.mark.parametrize("args", [["no_such_case"], ["--method", "sph2014"], ["--backend", "cuda"], ["--threads", "-1"],
                                  ["--jobs", "-1"], ["--no-such-flag"], ["--set", "solver.smoothing_ratio"],
                                  ["--set", "fluid.spacing=0.01"], ["--set", "solver.method=pbf"],
                                  ["--set", "gravity=0,0"], ["--set", "solver.smoothing_ratio=9"],
                                  ["--set", "solver.smoothing_rati=1.3"],
                                  ["--set", "solver.smoothing_ratio=1.3", "--known-failures"]])
def test_bad_arguments_exit_2(args, tmp_path):
    assert vmain.main(args + ["--out", str(tmp_path)]) == 2


def test_set_reaches_every_scene_in_every_worker(tmp_path, monkeypatch):
    """--set changes a parameter in every scene a case builds, over the case's own, and the
    report says so; a run without it is back at the case's parameters."""
    import rtsph
    from rtsph.validate import _common

    def h_over_s(method, level, threads):
        sim = _common._simulation(rtsph.scene({"dimension": 2, "domain": {"min": [0, 0], "max": [1, 1]},
                                               "fluid": {"spacing": 0.1}, "solver": {"smoothing_ratio": 1.1},
                                               "fluid_blocks": [{"min": [0, 0], "max": [0.5, 0.5]}]}), threads)
        return _common._finish(Result(case="h_over_s", method=method, metric="h/s", error=sim.stats["h"] / 0.1,
                                      tolerance=10.0))
    monkeypatch.setitem(validate.CASES, "h_over_s", h_over_s)
    args = ["h_over_s", "--method", "wcsph", "--threads", "1", "--jobs", "1"]
    assert vmain.main(args + ["--out", str(tmp_path / "a"), "--set", "solver.smoothing_ratio=1.3"]) == 0
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert summary["cases"][0]["error"] == pytest.approx(1.3)
    assert summary["meta"]["overrides"] == {"solver.smoothing_ratio": "1.3"}
    assert "--set solver.smoothing_ratio=1.3" in (tmp_path / "a" / "report.html").read_text()
    assert vmain.main(args + ["--out", str(tmp_path / "b")]) == 0
    assert json.loads((tmp_path / "b" / "summary.json").read_text())["cases"][0]["error"] == pytest.approx(1.1)
    # Worker processes (--jobs) get the same parameters: a real case, the same bits as a serial run,
    # and not those of the defaults.
    errors = {}
    for name, extra in (("default", []), ("serial", ["--jobs", "1"]), ("jobs", ["--jobs", "2"])):
        out = tmp_path / name
        over = [] if name == "default" else ["--set", "solver.smoothing_ratio=1.3"]
        r = subprocess.run([sys.executable, "-m", "rtsph.validate", "poiseuille_2d", "--method", "wcsph", "--quick",
                            "--threads", "1", "--out", str(out)] + extra + over,
                           capture_output=True, text=True, timeout=600)
        assert r.returncode in (0, 1), r.stderr
        errors[name] = json.loads((out / "summary.json").read_text())["cases"][0]["error"]
    assert errors["jobs"] == errors["serial"] != errors["default"]


def test_an_out_it_cannot_write_exits_2_before_any_case_runs(tmp_path, monkeypatch, capsys):
    ran = []
    monkeypatch.setitem(validate.CASES, "always_fails", lambda *a: ran.append(a) or _always_fails(*a))
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    for out in (blocker, blocker / "below"):  # a file where the directory should be, and below one
        assert vmain.main(["always_fails", "--method", "wcsph", "--jobs", "1", "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--out" in err and str(out) in err
    assert ran == []
    assert blocker.read_text() == ""  # nothing lost

    # A report that cannot be written at the end (the disk filled): one line, and the figures were
    # already printed, a line per case.
    def full_disk(*a, **k):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(vmain, "write_report", full_disk)
    assert vmain.main(["always_fails", "--method", "wcsph", "--jobs", "1", "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert "No space left on device" in err and "always_fails (wcsph, quick) ... FAIL 1" in err
    assert "Traceback" not in err


def test_the_cli_hands_over_to_python(cli, tmp_path):
    env = dict(os.environ, RTSPH_PYTHON=sys.executable)
    r = subprocess.run([cli, "validate", "poiseuille_2d", "--method", "dfsph", "--out", str(tmp_path / "v")],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "v" / "report.html").exists()
    env["RTSPH_PYTHON"] = str(tmp_path / "no_python")
    r = subprocess.run([cli, "validate"], capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 2 and "setup-python.sh" in r.stderr and r.stderr.count("\n") == 1


def test_csv_columns_of_different_lengths_end_in_blanks(tmp_path):
    from rtsph.validate import report
    r = Result(case="x", method="wcsph", metric="m", error=0.0, tolerance=1.0, particles=1, wall_s=0.0,
               setup="", reference="", series={"t_s": [0.0, 1.0, 2.0], "fine_t_s": [0.5]})
    report.write_report(str(tmp_path), [r], level="quick", threads=1, wall_s=0.0)
    lines = (tmp_path / "x_wcsph.csv").read_text().splitlines()
    assert lines == ["t_s,fine_t_s", "0.0,0.5", "1.0,", "2.0,"]


def test_both_plot_panels_survive_a_worker_process():
    # --jobs carries a result's panels back from a worker as recorded calls; the side panel
    # (SPHERIC's pressures) must come back too, and reuse a line's colour as the first does.
    import pickle
    from rtsph.validate import parallel, report

    def main(ax, res):
        line, = ax.plot([0, 1], [0, 1], "-", label=f"rtsph {res.method}")
        ax.plot([0, 1], [1, 0], "--", color=line.get_color())

    def side(ax, res):
        ax.plot([0, 1], [2, 3], label="side")
    r = Result(case="x", method="wcsph", metric="m", series={"t_s": [0.0, 1.0]}, plot=main, side_plot=side)
    back = pickle.loads(pickle.dumps(parallel._picklable_plots(r)))
    assert [c[0] for c in back.side_plot.calls] == ["plot"]
    png = report._plot_case("x", [back])
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_jobs_start_the_longest_task_first():
    # --jobs 2 finishes when its last task does: the 3D static drops (DFSPH's the longest) are
    # the quick suite's longest since session 53 and must start first, then DFSPH's and WCSPH's
    # 2D static drops (each with its oscillating drop, which reuses its σ), the cheap cases last,
    # each case's methods together in the serial order otherwise.
    from rtsph.validate.parallel import tasks_for
    methods = ["wcsph", "pbf", "dfsph"]
    tasks = tasks_for(["hydrostatic_2d", "static_droplet_2d", "static_droplet_3d", "oscillating_droplet_2d"], methods)
    assert [t[0] for t in tasks[0:3]] == [("static_droplet_3d", m) for m in ["dfsph", "wcsph", "pbf"]]
    assert tasks[3] == [("static_droplet_2d", "dfsph"), ("oscillating_droplet_2d", "dfsph")]
    assert tasks[4] == [("static_droplet_2d", "wcsph"), ("oscillating_droplet_2d", "wcsph")]
    assert tasks[5] == [("static_droplet_2d", "pbf"), ("oscillating_droplet_2d", "pbf")]
    assert [t[0] for t in tasks[6:]] == [("hydrostatic_2d", m) for m in methods]
    assert sorted(x for t in tasks for x in t) == sorted(
        (c, m) for c in ["hydrostatic_2d", "static_droplet_2d", "static_droplet_3d", "oscillating_droplet_2d"] for m in methods)


def test_jobs_run_a_drops_draws_as_tasks_of_their_own():
    # The parts (a static drop's lattice draws) start first, task by task in the tasks' order and
    # each task's largest drop first; the oscillating drop shares its static drop's draws.
    from rtsph.validate.parallel import schedule
    methods = ["wcsph", "pbf", "dfsph"]
    tasks, needs, order = schedule(["hydrostatic_2d", "static_droplet_2d", "oscillating_droplet_2d"], methods, "quick")
    assert tasks[0] == [("static_droplet_2d", "dfsph"), ("oscillating_droplet_2d", "dfsph")]
    assert needs[0] == sorted(validate.cases.part_keys("static_droplet_2d", "dfsph", "quick"))
    assert set(validate.cases.part_keys("oscillating_droplet_2d", "dfsph", "quick")) < set(needs[0])
    assert order[0][:3] == ("dfsph", 2, 0.1) and order[len(needs[0])][:3] == ("wcsph", 2, 0.1)
    assert len(order) == len(set(order)) == sum(len(n) for n in needs)
    assert [n for t, n in zip(tasks, needs) if t[0][0] == "hydrostatic_2d"] == [[], [], []]
    # A case alone keeps its parts (the oscillating drop calibrates on the static drop's R1 draws).
    _, needs, _ = schedule(["oscillating_droplet_2d"], ["pbf"], "quick")
    assert needs == [sorted(validate.cases.part_keys("oscillating_droplet_2d", "pbf", "quick"))] and needs[0]


def test_a_drop_seeded_with_its_draws_reads_as_the_drop_run_whole(monkeypatch):
    # What a worker process receives: each draw run by run_part, then the case seeded with them.
    # It must give the figures of the case run in one piece, without running a draw again, and
    # count the draws' time in its own. A small drop, briefly: the mechanism, not the physics.
    from rtsph.validate import cases, drops
    monkeypatch.setitem(drops.DROPLET_LEVELS, 2, {"quick": (0.01, 0.3), "full": (0.01, 0.3)})
    monkeypatch.setitem(drops.DROPLET_DRAWS, "quick", {2: (3, 2), 3: (1, 1)})
    monkeypatch.setattr(drops, "QUICK_HALVED", {})
    monkeypatch.setattr(drops, "_SIGMA_CACHE", {})
    monkeypatch.setattr(drops, "_DRAWS", {})
    whole = cases.run_case("static_droplet_2d", "wcsph", "quick", 1)
    keys = cases.part_keys("static_droplet_2d", "wcsph", "quick")
    assert len(keys) == 5
    parts = {k: cases.run_part(k, 1) for k in keys}
    drops._SIGMA_CACHE.clear()

    def no_run(*args, **kwargs):
        raise AssertionError("a seeded draw ran again")
    monkeypatch.setattr(drops, "_simulation", no_run)
    seeded = cases.run_case("static_droplet_2d", "wcsph", "quick", 1, parts=parts)
    assert np.isfinite(whole.error)
    def figures(r):  # NaN-aware: the early samples' virials are NaN by design
        return json.dumps([r.error, r.extra, r.series, r.notes, r.particles], sort_keys=True)
    assert figures(seeded) == figures(whole)
    assert seeded.wall_s >= sum(v[4] for v in parts.values()) > 0
    # Seeds belong to the context they were given in: under other --set parameters, in the same
    # process, the draws run again.
    drops._SIGMA_CACHE.clear()
    with pytest.raises(AssertionError, match="ran again"):
        cases.run_case("static_droplet_2d", "wcsph", "quick", 1, "cpu", {"solver.smoothing_ratio": "2.1"})
