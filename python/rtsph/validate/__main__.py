"""`python -m rtsph.validate` (what `rtsph validate` runs): the validation cases, a progress line
per case, and the report. Exit code 0 when every applicable case passes, 1 when one fails,
2 for bad arguments."""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

from . import CASES, METHODS, run_case
from .known import judge
from .parallel import run_parallel, schedule
from .report import write_report


def _unwritable(out: str) -> str:
    """Why the report cannot be written to directory `out` (created if missing), or ''."""
    if os.path.exists(out) and not os.path.isdir(out):
        return "it is a file, not a directory"
    try:
        os.makedirs(out, exist_ok=True)
        with tempfile.TemporaryFile(dir=out):
            pass
    except OSError as e:
        return f"cannot write the report there ({e.strerror or e})"
    return ""


# --set keys the cases own: each level's spacing is the case's geometry and its reference's
# resolution, and --method/--backend choose the rest.
_NOT_SETTABLE = ("fluid.spacing", "solver.method", "solver.backend")


def _overrides(assignments) -> tuple:
    """({key: value}, '') from --set's KEY=VALUE texts, or ({}, the problem's one line)."""
    out = {}
    for a in assignments:
        key, eq, value = a.partition("=")
        key = key.strip()
        if not eq or not key:
            return {}, f"{a!r}: expected KEY=VALUE, e.g. solver.smoothing_ratio=1.3"
        if not key.startswith(("solver.", "fluid.")) or key in _NOT_SETTABLE:
            return {}, (f"{a!r}: {key} is not one --set may change here (a solver.* or fluid.* parameter "
                        f"other than {', '.join(_NOT_SETTABLE)})")
        out[key] = value.strip()
    if out:
        # The engine's own check, on a small scene, before any case runs: the key and value's
        # one-line message (unknown key, out of range).
        import rtsph
        probe = {"dimension": 2, "domain": {"min": [0, 0], "max": [1, 1]},
                 "fluid_blocks": [{"min": [0, 0], "max": [0.5, 0.5]}]}
        try:
            rtsph.scene(probe).with_overrides(out)
        except ValueError as e:
            return {}, f"{e}"
    return out, ""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="rtsph validate", description="Run rtsph's validation cases and write a report.")
    ap.add_argument("cases", nargs="*", metavar="CASE", help=f"cases to run (default: all): {', '.join(CASES)}")
    ap.add_argument("--method", default="all", help="wcsph, pbf, dfsph or all (default)")
    ap.add_argument("--backend", default="cpu",
                    help="cpu (default) or gpu (OpenGL compute; cases the GPU cannot run yet are n/a)")
    lvl = ap.add_mutually_exclusive_group()
    lvl.add_argument("--quick", action="store_const", const="quick", dest="level", help="coarse sizes (CI; default)")
    lvl.add_argument("--full", action="store_const", const="full", dest="level", help="report resolution and convergence")
    ap.add_argument("--out", default="validation", help="output directory (default: ./validation)")
    ap.add_argument("--threads", type=int, default=0,
                    help="solver threads per case (0 = all cores, or all cores over --jobs)")
    ap.add_argument("--jobs", type=int, default=0,
                    help="cases run at once, each in its own process (0, the default: one per core on the "
                         "cpu backend, 1 on the gpu); the figures are the same bits whatever --jobs and "
                         "--threads")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", dest="overrides",
                    help="a solver or fluid parameter for every scene of the run, over the case's own "
                         "(as `rtsph run --set`; repeatable): e.g. solver.smoothing_ratio=1.3. Not "
                         "fluid.spacing (the cases' levels choose it) nor the method or backend")
    ap.add_argument("--known-failures", action="store_true",
                    help="exit 0 when what fails is the quick level's known failures (rtsph/validate/known.py), "
                         "none worse than recorded, and none of them passes (the test command's run; quick, cpu)")
    try:
        args = ap.parse_args(argv)
    except SystemExit as e:
        return 0 if e.code == 0 else 2
    level = args.level or "quick"
    bad = [c for c in args.cases if c not in CASES]
    if bad:
        print(f"rtsph validate: unknown case {bad[0]!r}; expected one of {', '.join(CASES)}", file=sys.stderr)
        return 2
    methods = METHODS if args.method == "all" else (args.method,)
    if any(m not in METHODS for m in methods):
        print(f"rtsph validate: --method {args.method!r}: expected wcsph, pbf, dfsph or all", file=sys.stderr)
        return 2
    if args.backend not in ("cpu", "gpu"):
        print(f"rtsph validate: --backend {args.backend!r}: expected cpu or gpu", file=sys.stderr)
        return 2
    if args.threads < 0:
        print("rtsph validate: --threads must be 0 (all cores) or more", file=sys.stderr)
        return 2
    if args.jobs < 0:
        print(f"rtsph validate: --jobs {args.jobs}: must be 0 (one per core) or more", file=sys.stderr)
        return 2
    # Most cases are too small to keep two solver threads busy (the drops: 500-4,000 particles),
    # so by default the CPU backend runs one case per core, one thread each; the GPU backend's
    # cases share one device.
    if args.jobs == 0:
        args.jobs = max(1, os.cpu_count() or 1) if args.backend == "cpu" else 1
    if args.known_failures and (level != "quick" or args.backend != "cpu"):
        print("rtsph validate: --known-failures records the quick level on the cpu backend only", file=sys.stderr)
        return 2
    overrides, problem = _overrides(args.overrides)
    if problem:
        print(f"rtsph validate: --set {problem}", file=sys.stderr)
        return 2
    if args.known_failures and overrides:
        print("rtsph validate: --known-failures records the default parameters; drop --set", file=sys.stderr)
        return 2
    # The report is written at the end: an --out that cannot take it must stop the run before a
    # case runs, not after the full level's quarter of an hour.
    problem = _unwritable(args.out)
    if problem:
        print(f"rtsph validate: --out {args.out!r}: {problem}", file=sys.stderr)
        return 2
    where = ("" if args.backend == "cpu" else f", {args.backend}") + \
        "".join(f", {k}={v}" for k, v in overrides.items())

    def line(r, wall_s: float) -> str:
        status = "n/a" if not r.applicable else ("pass" if r.passed else "FAIL")
        err = "" if not r.applicable else f" {r.error:.4g} (tolerance {r.tolerance:.4g})"
        if r.metric == "(did not finish)":  # the engine's diagnostic, not a figure
            err = f": did not finish: {r.notes}"
        return f" {status}{err}, {r.particles} particles, {wall_s:.1f} s"

    cases = args.cases or list(CASES)
    threads = args.threads
    if args.jobs > 1 and threads == 0:
        threads = max(1, (os.cpu_count() or 1) // args.jobs)
    t0 = time.perf_counter()
    if args.jobs > 1:
        parts = len(schedule(cases, methods, level)[2])
        first = f"; {parts} drops' lattice draws run first" if parts else ""
        print(f"rtsph validate: {args.jobs} jobs of {threads} solver thread(s){first}; a line as each case ends",
              file=sys.stderr)
        results = run_parallel(cases, methods, level, threads, args.backend, args.jobs,
                               lambda r, w: print(f"rtsph validate: {r.case} ({r.method}{where}, {level})"
                                                  f"{line(r, w)}", file=sys.stderr), overrides)
    else:
        results = []
        for case in cases:
            for m in methods:
                t = time.perf_counter()
                print(f"rtsph validate: {case} ({m}{where}, {level}) ...", end="", file=sys.stderr, flush=True)
                r = run_case(case, m, level, threads, args.backend, overrides)
                results.append(r)
                print(line(r, time.perf_counter() - t), file=sys.stderr)
    wall = time.perf_counter() - t0
    try:
        write_report(args.out, results, level, threads, wall, args.backend, args.jobs, overrides)
    except OSError as e:  # the disk filled, or the directory went away, during the run
        print(f"rtsph validate: --out {args.out!r}: could not write the report ({e.strerror or e}); "
              "each case's figure is in the lines above", file=sys.stderr)
        return 2
    failed = [r for r in results if r.applicable and not r.passed]
    print(f"rtsph validate: {len(results) - len(failed)}/{len(results)} passed or n/a in {wall:.0f} s; "
          f"report: {args.out}/report.html", file=sys.stderr)
    if args.known_failures:
        problems = judge(results)
        for p in problems:
            print(f"rtsph validate: {p}", file=sys.stderr)
        if not problems and failed:
            print(f"rtsph validate: the {len(failed)} failures are the known ones, none worse than recorded "
                  "(python/rtsph/validate/known.py)", file=sys.stderr)
        return 1 if problems else 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
