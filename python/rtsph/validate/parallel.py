"""`rtsph validate --jobs N`: the cases in N worker processes.

Every method gives the same bits for any thread count (docs/architecture.md), so a case run in
a worker with one solver thread measures exactly what a serial run with two measures; only the
wall times differ. Most quick cases are too small to keep two solver threads busy (a pair loop
wakes a thread only for 512 pairs of work), so two one-thread workers finish the quick suite
sooner than one two-thread run.

A Result's plot is a closure of its case, which pickle cannot carry back from a worker. The
worker draws it on a recording axes instead (_Recorder), and the parent replays the calls on the
report's real axes (_Replay): the same figure, from the same matplotlib calls.

A case's independent runs (its parts: a static drop's 4-32 lattice draws) run as tasks of their
own, and the case's task, seeded with their results, only assembles them. As one task, DFSPH's 2D
static drop (757 s of the quick level's 2,582 s in session 40) was a floor whatever the jobs.
"""
from __future__ import annotations

import multiprocessing
import sys
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from .cases import Result, part_cost, part_keys, run_case, run_part

# Cases that reuse another's work in the same process (drops.calibrate_sigma caches σ(γ) per
# method): they run in one task, after it.
_AFTER = {"oscillating_droplet_2d": "static_droplet_2d"}
# Tasks start longest first, so that the last one to finish is a short one: a (case, method) or a
# whole case, by the quick level's times on two cores (CI, session 34, one thread each: the 2D
# static drop 571 s with DFSPH, 258 s WCSPH, 124 s PBF since they run 8 s; the 3D drops 202, 175
# and 65 s; SPHERIC Test 2 61 s with WCSPH). With DFSPH's 2D drop started sixth, the suite took
# 984 s where the rest of its 1,590 s of cases fit beside it. The drops' draws (parts) start in
# this order too, each task's longest first (schedule). Since session 53 the 3D drops are the
# longest (liquid drops of 33,500 particles at R2: 343 s with DFSPH, 223 s WCSPH, 193 s PBF, each
# R2 draw about half of it), so they start first.
_LONG_FIRST = (("static_droplet_3d", "dfsph"), "static_droplet_3d", ("static_droplet_2d", "dfsph"),
               ("static_droplet_2d", "wcsph"), "static_droplet_2d", "spheric_test2_3d", "taylor_green_2d")


class _ColorOf:
    """Stands for the colour of the line a recorded call returned (dam_breaks' plots reuse it)."""
    def __init__(self, call: int):
        self.call = call


class _LineRef:
    def __init__(self, call: int):
        self.call = call

    def get_color(self):
        return _ColorOf(self.call)


class _Recorder:
    """Axes that record each call (name, args, kwargs). Calls that draw lines return one line
    reference, so `line, = ax.plot(...)` and `line.get_color()` work."""
    def __init__(self):
        self.calls: List[Tuple[str, tuple, dict]] = []

    def __getattr__(self, name: str):
        def call(*args, **kwargs):
            self.calls.append((name, args, kwargs))
            return [_LineRef(len(self.calls) - 1)]
        return call


class _Replay:
    """A picklable plot(ax, result) that replays recorded calls on real axes."""
    def __init__(self, calls):
        self.calls = calls

    def __call__(self, ax, _result=None):
        returned = {}

        def real(v):
            return returned[v.call][0].get_color() if isinstance(v, _ColorOf) else v
        for i, (name, args, kwargs) in enumerate(self.calls):
            returned[i] = getattr(ax, name)(*[real(a) for a in args], **{k: real(v) for k, v in kwargs.items()})


def _picklable_plots(r: Result) -> Result:
    """Turns r's plot panels into recorded calls a parent process can replay."""
    for attr in ("plot", "side_plot"):
        if getattr(r, attr) is not None:
            rec = _Recorder()
            getattr(r, attr)(rec, r)
            setattr(r, attr, _Replay(rec.calls))
    return r


def _run_task(task: Sequence[Tuple[str, str]], level: str, threads: int, backend: str,
              overrides: Optional[Dict[str, str]] = None, parts: Optional[Dict[tuple, object]] = None) -> List[Result]:
    out = []
    for case, method in task:
        r = run_case(case, method, level, threads, backend, overrides, parts)
        out.append(_picklable_plots(r))
    return out


def tasks_for(cases: Sequence[str], methods: Sequence[str]) -> List[List[Tuple[str, str]]]:
    """The (case, method) runs grouped into tasks, longest first."""
    tasks: Dict[Tuple[str, str], List[Tuple[str, str]]] = {}
    for case in cases:
        for m in methods:
            key = (_AFTER.get(case, case), m)
            if key[0] not in cases:
                key = (case, m)
            tasks.setdefault(key, []).append((case, m))
    rank = {c: i for i, c in enumerate(_LONG_FIRST)}
    return [tasks[k] for k in sorted(tasks, key=lambda k: rank.get(k, rank.get(k[0], len(rank))))]


def schedule(cases: Sequence[str], methods: Sequence[str], level: str):
    """The tasks (tasks_for), each task's parts (cases.part_keys), and the order to start the parts
    in: task by task in the tasks' order, each task's longest first. A task with parts starts as
    soon as its last part is back, before any task not yet started: so a case's line comes when
    its parts are done, not at the end of the suite."""
    tasks = tasks_for(cases, methods)
    needs = [sorted({k for case, m in t for k in part_keys(case, m, level)}) for t in tasks]
    order, seen = [], set()
    for need in needs:
        for k in sorted(need, key=part_cost, reverse=True):
            if k not in seen:
                seen.add(k)
                order.append(k)
    return tasks, needs, order


def run_parallel(cases: Sequence[str], methods: Sequence[str], level: str, threads: int, backend: str,
                 jobs: int, report: Callable[[Result, float], None],
                 overrides: Optional[Dict[str, str]] = None) -> List[Result]:
    """Runs every (case, method) in `jobs` processes and returns the results in the serial order;
    report(result, wall_s) is called as each finishes. Parts (a static drop's draws) run as tasks
    of their own first; the cases without parts follow, longest first."""
    results: Dict[Tuple[str, str], Result] = {}
    tasks, needs, part_order = schedule(cases, methods, level)
    waiting = {i: set(n) for i, n in enumerate(needs) if n}
    queue = deque([("part", k) for k in part_order] + [("task", i) for i in range(len(tasks)) if not needs[i]])
    ready = deque()  # tasks whose parts are all back: they go before the queue
    done_parts: Dict[tuple, object] = {}
    # spawn, not fork: the parent may hold OpenMP or GL state that a forked child must not inherit.
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
        running = {}

        def start():
            # Only `jobs` in flight, so that a task whose parts are back starts next.
            while len(running) < jobs and (ready or queue):
                kind, x = (ready or queue).popleft()
                if kind == "part":
                    f = pool.submit(run_part, x, threads, backend, overrides)
                else:
                    f = pool.submit(_run_task, tasks[x], level, threads, backend, overrides,
                                    {k: done_parts[k] for k in needs[x]})
                running[f] = (kind, x)
        start()
        while running:
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for f in done:
                kind, x = running.pop(f)
                if kind == "part":
                    done_parts[x] = f.result()
                    for i in [i for i, w in waiting.items() if x in w]:
                        waiting[i].discard(x)
                        if not waiting[i]:
                            del waiting[i]
                            ready.append(("task", i))
                    continue
                for r in f.result():
                    results[(r.case, r.method)] = r
                    report(r, r.wall_s)
                sys.stderr.flush()
            start()
    return [results[(c, m)] for c in cases for m in methods]
