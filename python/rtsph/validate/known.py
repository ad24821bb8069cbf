"""The quick level's known failures: what `rtsph validate --quick --known-failures` (the test
command's run) lets fail, and how far.

Each entry is a case and method that fails its tolerance today, with the error the quick level
measured (CPU, sessions 34-39: each entry's `why` says which runs) and why it fails
(docs/validation.md tells the whole story). With --known-failures the run exits 0 only when:
- every failure is listed here, and its error is at most REGRESSION_MARGIN times the recorded
  one (or the entry's own margin, where the figure is known to move that much between hosts; a
  finite one: "did not finish" is never within);
- every listed entry still fails: one that passes must leave the list, so that it is guarded as
  a pass from then on. The exception is an entry marked noisy, whose figure is within its own
  noise and passes or fails by round-off (WCSPH's SPHERIC Test 2 since session 52; DFSPH's 2D
  static drop was one from session 34 until session 50's surface options settled it).
So the passing cases are held to their tolerances, the failing ones are held where they are,
and the report still says FAIL for each. This is not the issue's "validate --quick passes":
that needs this list empty.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Dict, Iterable, List, Optional, Tuple

# A known failure's error may grow by this factor before the run calls it a regression: the
# quick figures move with round-off where a case amplifies it (docs/validation.md: the 2D static
# drop moved from 2.0% to 8.8% with a change of summation order alone).
REGRESSION_MARGIN = 1.25


@dataclass(frozen=True)
class Known:
    measured: Optional[float]  # the quick error recorded; None where the figure is not a number
    why: str
    # Where the figure moves by more than REGRESSION_MARGIN between hosts (the release build is
    # -march=native, so round-off differs by CPU), the spread measured, with the hosts named in
    # `why`.
    margin: float = REGRESSION_MARGIN
    # A figure within its own noise (the case's ± on the quantity it is made of is as large as
    # the quantity): it passes or fails by the draw of round-off, so a pass does not ask for the
    # entry to leave. The report still says PASS or FAIL as measured; `why` gives the spread.
    noisy: bool = False

    def ceiling(self) -> float:
        return math.inf if self.measured is None else self.margin * self.measured


_SPH = ("H1, behind the box, is the worst probe: rtsph's slosh falls 0.1-0.4 s behind MARIN's once the water "
        "has hit the box and the left wall, at every probe, with every method and at every spacing tried "
        "(docs/validation.md, SPHERIC section, sessions 35-36). The quick spacing, 0.05 m, divides the tank's "
        "width and depth, so the water is MARIN's to 1.8%; eight round-off draws (gravity nudged by 1e-7) read "
        "WCSPH 3.24-3.37 cm, PBF 3.45-3.80, DFSPH 3.38-3.80 (session 36). At the full 0.025 m PBF and DFSPH fail too (since session 44)")

_WAVE = ("the default kernel (the cubic spline at h = s) damps gravity waves: on water settled at rest, the "
         "amplitude after one period is 0.19-0.64 of the first's, at 20 or 40 layers deep, and the mode's energy "
         "turns into particle noise in the whole tank within a quarter period. WCSPH needs its α = 0.02 there "
         "(at h = s its Adami wall term runs away without it), and that α damps the noise; at h = 1.3 s the walls "
         "hold without α and every method keeps 0.76-0.86 a period (docs/validation.md, 'A standing wave'; "
         "sessions 36-39 in docs/validation-history.md). The remedy, the default kernel's width, changes every case and the cost of every step. "
         "The figure is that noise's: the recorded one is the median of seven round-off draws (the AMD EPYC "
         "guest's run, session 38, and six with gravity nudged by 0-5e-7 on the Intel Xeon guest, session 39), "
         "which read WCSPH 0.44-0.89, PBF 0.62-0.97, DFSPH 0.49-0.84")

# The static drops' figures are means over lattice draws (drops.DROPLET_DRAWS), each with its
# standard uncertainty from the draws' spread (the report's notes).
KNOWN_FAILURES: Dict[Tuple[str, str], Known] = {
    ("standing_wave_2d", "wcsph"): Known(0.738, _WAVE, margin=1.5),
    ("standing_wave_2d", "pbf"): Known(0.906, _WAVE, margin=1.5),
    ("standing_wave_2d", "dfsph"): Known(0.664, _WAVE, margin=1.5),
    # WCSPH's figure sits at its line on some hosts: on the Intel Xeon guest (session 52) its eight
    # round-off draws read 3.00-3.33 cm, three of them within 0.012 cm of the 3 cm (3.002, 3.006,
    # 3.011). A pass there would be round-off's, not a fix: noisy, so it does not turn CI red.
    ("spheric_test2_3d", "wcsph"): Known(0.0329, _SPH + "; on the Intel Xeon guest (session 52) WCSPH's "
                                         "eight draws read 3.00-3.33 cm, three within 0.012 cm of the line",
                                         noisy=True),
    ("spheric_test2_3d", "pbf"): Known(0.0360, _SPH),
    ("spheric_test2_3d", "dfsph"): Known(0.0357, _SPH),
}


def judge(results: Iterable, known: Dict[Tuple[str, str], Known] = KNOWN_FAILURES) -> List[str]:
    """The problems --known-failures exits 1 for, one line each (empty: the run is as known).
    results: Result-like objects with case, method, applicable, passed and error."""
    problems = []
    for r in results:
        if not r.applicable:
            continue
        k = known.get((r.case, r.method))
        if r.passed:
            if k is not None and not k.noisy:
                problems.append(f"{r.case} ({r.method}) now passes: remove it from "
                                "python/rtsph/validate/known.py, so it is held to its tolerance")
            continue
        if k is None:
            problems.append(f"{r.case} ({r.method}) fails ({r.error:.4g} against {r.tolerance:.4g}) "
                            "and is not a known failure")
        elif not (math.isfinite(r.error) or (k.measured is None and math.isnan(r.error))):
            problems.append(f"{r.case} ({r.method}) did not give a figure ({r.error}): a known failure "
                            "must still finish")
        elif r.error > k.ceiling():
            problems.append(f"{r.case} ({r.method}) got worse: {r.error:.4g} against the recorded "
                            f"{k.measured:.4g} (at most {k.margin}× that)")
    return problems
