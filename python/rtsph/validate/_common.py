"""What every validation case shares: the Result, where the cases run (the backend), and
the helpers that turn errors into verdicts and orders of convergence."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

import rtsph

G = 9.81

# Where the cases run: "cpu" or "gpu" (run_case sets it for the case it runs).
_BACKEND = "cpu"
# `rtsph validate --set KEY=VALUE`: parameters applied to every scene the case builds, over the
# case's own (run_case sets them for the case it runs). What a case reads with another kernel or
# viscosity, without a copy of the case.
_OVERRIDES: Dict[str, str] = {}


class NotOnBackend(Exception):
    """The backend has no model for a scene the case needs (the engine's one-line reason)."""


def _simulation(scene, threads: int) -> "rtsph.Simulation":
    if _OVERRIDES:
        scene = rtsph.scene(scene).with_overrides(_OVERRIDES)
    try:
        return rtsph.Simulation(scene, threads=threads, backend=_BACKEND)
    except ValueError as e:
        # The GPU backend refuses what it does not model (the gas method: self-gravity) with
        # one line ending "use --backend cpu": not a failure of the physics, so n/a.
        if _BACKEND != "cpu" and "use --backend cpu" in str(e):
            raise NotOnBackend(str(e)) from None
        raise


def periodic_columns(solver: dict, own: int) -> int:
    """Columns of a periodic channel whose scene has this `solver` block: the case's own count, or
    enough for the kernel when `validate --set` widens it. The scene check asks a periodic extent of
    at least three kernel supports (the neighbour grid tiles each period with whole cells): 6
    spacings at the default cubic spline with h = s, 9 at Wendland C2 with h = 1.5 s, 12 at h = 2 s.
    The flow is uniform along the channel, so its length does not enter the reference."""
    def setting(key, default):
        value = _OVERRIDES.get(f"solver.{key}", solver.get(key, default))
        return str(value).strip('"') if key == "kernel" else float(value)
    support = (3.0 if setting("kernel", "cubic_spline") == "gaussian" else 2.0) * setting("smoothing_ratio", 1.0)
    return max(own, int(3 * support * (1 + 1e-4)) + 1)


@dataclass
class Result:
    case: str
    method: str
    metric: str                 # what the error measures
    error: float = float("nan")
    tolerance: float = float("nan")
    passed: bool = False
    applicable: bool = True     # False: the method has no model for this case (reason in notes)
    setup: str = ""
    reference: str = ""
    notes: str = ""
    particles: int = 0
    wall_s: float = 0.0
    series: Dict[str, List[float]] = field(default_factory=dict)  # columns of the case's CSV
    plot: Optional[Callable] = None                                 # plot(ax, result)
    side_plot: Optional[Callable] = None                            # a second panel, side_plot(ax, result)
    convergence: List[Tuple[float, float]] = field(default_factory=list)  # (spacing, error)
    extra: Dict[str, float] = field(default_factory=dict)           # other figures for the summary


def _finish(r: Result) -> Result:
    r.passed = bool(r.applicable and np.isfinite(r.error) and r.error <= r.tolerance)
    return r


def _order(conv: List[Tuple[float, float]]) -> float:
    """Observed order of convergence: slope of log(error) against log(spacing)."""
    h = np.log([c[0] for c in conv])
    e = np.log([max(c[1], 1e-300) for c in conv])
    return float(np.polyfit(h, e, 1)[0]) if len(conv) >= 2 else float("nan")


NO_LAMINAR_VISCOSITY = ("PBF has no laminar viscosity ν (its XSPH term smooths velocities without one), "
                        "so this viscous case does not apply.")
