"""Writes a validation run: DIR/report.html (self-contained, plots inlined as PNG),
DIR/summary.json, DIR/<case>_<method>.csv and DIR/<case>.png."""
from __future__ import annotations

import base64
import csv
import datetime
import html
import io
import itertools
import json
import os
import platform
from typing import Dict, List, Optional

from .cases import Result
from .known import KNOWN_FAILURES


def _plot_case(case: str, results: List[Result]):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ran = [r for r in results if r.applicable and r.plot is not None and r.series]
    conv = [r for r in ran if r.convergence]
    side = [r for r in ran if r.side_plot is not None]
    ncols = 1 + (1 if conv else 0) + (1 if side else 0)
    fig, axes = plt.subplots(1, ncols, figsize=(5.2 * ncols, 3.8), squeeze=False)

    def legend(ax):
        handles, labels = ax.get_legend_handles_labels()
        seen = {}
        for h, lab in zip(handles, labels):
            seen.setdefault(lab, h)
        if seen:
            ax.legend(seen.values(), seen.keys(), fontsize=8)
    ax = axes[0][0]
    for r in ran:
        r.plot(ax, r)
    legend(ax)
    ax.set_title(case)
    if side:
        axs = axes[0][1]
        for r in side:
            r.side_plot(axs, r)
        legend(axs)
    if conv:
        ax2 = axes[0][-1]
        for r in conv:
            h = [c[0] for c in r.convergence]
            e = [c[1] for c in r.convergence]
            ax2.loglog(h, e, "o-", label=f"{r.method} (order {r.extra.get('observed_order', float('nan')):.2f})")
        ax2.set_xlabel("spacing (m)")
        ax2.set_ylabel("error")
        ax2.set_title("convergence")
        ax2.legend(fontsize=8)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    return buf.getvalue()


def _fmt(x: float) -> str:
    return "n/a" if x != x else f"{100 * x:.2f}%" if abs(x) < 10 else f"{x:.3g}"


def write_report(out: str, results: List[Result], level: str, threads: int, wall_s: float,
                 backend: str = "cpu", jobs: int = 1, overrides: Optional[Dict[str, str]] = None) -> None:
    os.makedirs(out, exist_ok=True)
    overrides = dict(overrides or {})

    def known(r: Result) -> str:
        """Why a quick CPU failure at the defaults is a known one (known.py), else ''."""
        k = KNOWN_FAILURES.get((r.case, r.method)) if level == "quick" and backend == "cpu" and not overrides \
            else None
        return k.why if k is not None and r.applicable and not r.passed else ""

    by_case: Dict[str, List[Result]] = {}
    for r in results:
        by_case.setdefault(r.case, []).append(r)
        if r.applicable:
            cols = list(r.series)
            with open(os.path.join(out, f"{r.case}_{r.method}.csv"), "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(cols)
                # Series may differ in length (a case sampled more finely over part of its run):
                # the shorter columns end in blanks.
                for row in itertools.zip_longest(*(r.series[c] for c in cols)):
                    w.writerow(["" if v is None else repr(float(v)) for v in row])
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "level": level, "backend": backend, "threads": threads, "jobs": jobs, "wall_s": wall_s,
            "machine": f"{platform.machine()} {platform.processor() or ''}".strip(),
            "cpus": os.cpu_count(), "python": platform.python_version(), "overrides": overrides}
    summary = {"meta": meta, "passed": all(r.passed or not r.applicable for r in results), "cases": [
        {"case": r.case, "method": r.method, "applicable": r.applicable, "passed": r.passed,
         "metric": r.metric, "error": r.error, "tolerance": r.tolerance, "particles": r.particles,
         "wall_s": r.wall_s, "setup": r.setup, "reference": r.reference, "notes": r.notes,
         "convergence": r.convergence, "extra": r.extra, "known_failure": known(r) or None} for r in results]}
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2, default=float)

    methods = sorted({r.method for r in results})
    rows = []
    for case, rs in by_case.items():
        cells = []
        for m in methods:
            r = next((x for x in rs if x.method == m), None)
            if r is None:
                cells.append("<td></td>")
            elif not r.applicable:
                cells.append("<td class=na>n/a</td>")
            else:
                cells.append(f"<td class={'pass' if r.passed else 'fail'}>{'pass' if r.passed else 'FAIL'} "
                             f"{_fmt(r.error)}{' (known)' if known(r) else ''}</td>")
        rows.append(f"<tr><td><a href='#{case}'>{case}</a></td>{''.join(cells)}</tr>")
    sections = []
    for case, rs in by_case.items():
        png = _plot_case(case, rs)
        with open(os.path.join(out, f"{case}.png"), "wb") as f:
            f.write(png)
        first = rs[0]
        lines = []
        for r in rs:
            if not r.applicable:
                lines.append(f"<tr><td>{r.method}</td><td colspan=5 class=na>{html.escape(r.notes)}</td></tr>")
                continue
            conv = ", ".join(f"{c[0]:.3g} m: {_fmt(c[1])}" for c in r.convergence)
            if conv:
                conv += f" (order {r.extra.get('observed_order', float('nan')):.2f})"
            lines.append(f"<tr><td>{r.method}</td><td class={'pass' if r.passed else 'fail'}>"
                         f"{'pass' if r.passed else 'FAIL'}</td><td>{_fmt(r.error)} (tolerance {_fmt(r.tolerance)})</td>"
                         f"<td>{r.particles:,}</td><td>{r.wall_s:.1f} s</td><td>{html.escape(r.notes)} {conv}"
                         f"{'<br>Known failure: ' + html.escape(known(r)) if known(r) else ''}</td></tr>")
        sections.append(
            f"<h2 id='{case}'>{case}</h2><p><b>Set-up:</b> {html.escape(first.setup)}<br>"
            f"<b>Reference:</b> {html.escape(first.reference)}<br><b>Measured:</b> {html.escape(first.metric)}</p>"
            f"<img src='data:image/png;base64,{base64.b64encode(png).decode()}'>"
            "<table><tr><th>method</th><th>result</th><th>error</th><th>particles</th><th>run time</th><th>notes</th></tr>"
            + "".join(lines) + "</table>")
    set_args = "".join(f" --set {k}={v}" for k, v in overrides.items())
    changed = ("<br><b>Parameters changed from every case's own (--set):</b> " +
               html.escape(", ".join(f"{k} = {v}" for k, v in overrides.items()))) if overrides else ""
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>rtsph validation</title><style>
body{{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}} table{{border-collapse:collapse;margin:.5em 0}}
td,th{{border:1px solid #ccc;padding:3px 8px;font-size:90%}} .pass{{background:#dfd}} .fail{{background:#fdd}}
.na{{color:#888}} img{{max-width:100%}}</style></head><body>
<h1>rtsph validation ({level}, {backend} backend)</h1>
<p>{html.escape(meta['date'])}, {meta['cpus']} CPUs, {threads or 'all'} solver threads{f" in each of {jobs} jobs" if jobs > 1 else ""}, {wall_s:.0f} s in all.
Every case: <code>rtsph validate --{level} --backend {backend}{html.escape(set_args)}</code>; the narrative is docs/validation.md.{changed}</p>
<table><tr><th>case</th>{''.join(f'<th>{m}</th>' for m in methods)}</tr>{''.join(rows)}</table>
{''.join(sections)}</body></html>"""
    with open(os.path.join(out, "report.html"), "w") as f:
        f.write(page)
