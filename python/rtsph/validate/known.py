"""The quick level's known failures: what `rtsph validate --quick --known-failures` (the test
command's run) lets fail, and how far.

Each entry is a case and method that fails its tolerance today, with the error the quick level
measured (CPU, 2026-11-25) and why it fails (docs/validation.md tells the whole story). With
--known-failures the run exits 0 only when:
- every failure is listed here, and its error is at most REGRESSION_MARGIN times the recorded
  one (or the entry's own margin, where the figure is known to move that much between hosts; a
  finite one: "did not finish" is never within);
- every listed entry still fails: one that passes must leave the list, so that it is guarded as
  a pass from then on.
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

    def ceiling(self) -> float:
        return math.inf if self.measured is None else self.margin * self.measured


_ST3 = "the 3D calibration drop is 5 spacings in radius at the quick level; the prediction at 2·R is off"
_OSC = "the drop locks into an ellipse (Akinci's cohesion at h = spacing): no liquid oscillation to time"
_SPH = ("0.04 m (quick) is too coarse for 3 cm at H1 (0.03 m was no better, PBF 3.7 cm and DFSPH 3.4 cm, measured "
        "before session 26's wall change and session 27's s_corr change); 0.02 m (full) passes")

KNOWN_FAILURES: Dict[Tuple[str, str], Known] = {
    ("static_droplet_2d", "pbf"): Known(0.5767, "σ calibrates to 0.36 N/m from a jump of 7.2 ± 5.3 Pa at R1; the "
                                             "jump at R2 (5.7 Pa) is larger than Laplace's 3.6. The figure swings "
                                             "with round-off (0.29 to 2.31 across builds before session 27's "
                                             "s_corr change, 1.30 after session 14's), so its margin keeps the "
                                             "ceiling near where it was (1.6)", margin=2.8),
    ("static_droplet_3d", "wcsph"): Known(0.4432, _ST3),
    ("static_droplet_3d", "pbf"): Known(0.2883, _ST3 + " (its R1 jump 115 ± 96 Pa: margin 2)", margin=2.0),
    ("static_droplet_3d", "dfsph"): Known(0.3914, _ST3),
    ("oscillating_droplet_2d", "wcsph"): Known(4.193, _OSC),
    ("oscillating_droplet_2d", "pbf"): Known(5.328, _OSC),
    ("oscillating_droplet_2d", "dfsph"): Known(9.449, _OSC),
    ("spheric_test2_3d", "pbf"): Known(0.03327, _SPH),
    ("spheric_test2_3d", "dfsph"): Known(0.03358, _SPH),
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
            if k is not None:
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
