"""The quick level's known failures: what `rtsph validate --quick --known-failures` (the test
command's run) lets fail, and how far.

Each entry is a case and method that fails its tolerance today, with the error the quick level
measured (CPU, 2026-11-25) and why it fails (docs/validation.md tells the whole story). With
--known-failures the run exits 0 only when:
- every failure is listed here, and its error is at most REGRESSION_MARGIN times the recorded
  one (or the entry's own margin, where the figure is known to move that much between hosts; a
  finite one: "did not finish" is never within);
- every listed entry still fails: one that passes must leave the list, so that it is guarded as
  a pass from then on. The exception is an entry marked noisy, whose figure is within its own
  noise and passes or fails by round-off (PBF's static drops).
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


_ST2 = ("a liquid drop (Wendland C2 at h = 2 spacings) only 2.5 kernel supports across R1 at the quick spacing: "
        "R2's jump over R1's reads {ratio} against Laplace's 0.5; at the full level (5 supports) {full}")
_SPH = ("H1's bore from the left wall comes late and spread out at 0.04 m (quick); 0.03 and 0.0275 m are no "
        "better (session 28, before the closing sweep: PBF 3.47 and 3.43 cm, DFSPH 3.46 and 3.29 cm); 0.02 m "
        "(full) passes")

# The static drops' figures are means over lattice draws (drops.DROPLET_DRAWS), each with its
# standard uncertainty from the draws' spread (the report's notes); their margins reach three of
# those above the recorded figure.
KNOWN_FAILURES: Dict[Tuple[str, str], Known] = {
    ("static_droplet_2d", "wcsph"): Known(0.1299, _ST2.format(ratio="0.435", full="0.462: a pass, 7.5 ± 2.1%")
                                          + "; 0.130 ± 0.019", margin=1.5),
    ("static_droplet_2d", "dfsph"): Known(0.3145, _ST2.format(ratio="0.343", full="0.63, 26 ± 23%: DFSPH's jump "
                                                                "spreads ±25% draw to draw there")
                                          + "; 0.315 ± 0.030", margin=1.3),
    ("static_droplet_2d", "pbf"): Known(0.09759, "passes at 0.98 of its bound: 9.8 ± 1.0% over the draws (R2/R1 "
                                               "0.451 at R1 = 2.5 kernel supports; the full level reads 2.2 ± 0.8%), "
                                               "so it passes or fails by round-off between hosts",
                                        margin=1.3, noisy=True),
    ("static_droplet_3d", "pbf"): Known(0.01845, "passes within its noise: 0.018 ± 0.059 over the draws (PBF's jump "
                                              "spreads twice as wide per draw as WCSPH's and DFSPH's)",
                                        margin=14.0, noisy=True),
    ("oscillating_droplet_2d", "wcsph"): Known(0.9309, "passes at 0.93 of its bound: the period 14.0% long against 15% "
                                                     "(R = 2.5 kernel supports at the quick spacing; the full level "
                                                     "reads -2.4%), so it passes or fails by round-off between hosts",
                                               noisy=True),
    ("oscillating_droplet_2d", "pbf"): Known(1.147, "the period 17% long at the quick spacing (R = 2.5 kernel "
                                                  "supports), with σ from PBF's own calibration (R2/R1 0.451 there); the "
                                                  "full level reads -1.2% and passes"),
    ("oscillating_droplet_2d", "dfsph"): Known(2.008, "the period 30% long at the quick spacing (R = 2.5 kernel "
                                                    "supports), with σ from DFSPH's own calibration (R2/R1 0.343 "
                                                    "there); the full level reads -3.6% and passes"),
    ("spheric_test2_3d", "pbf"): Known(0.0344, _SPH),
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
