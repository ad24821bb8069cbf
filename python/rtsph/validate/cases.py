"""The validation cases. Each takes (method, level, threads) and returns a Result; the cases
live in one module per family (tanks, dam_breaks, channels, drops, oscillating, elliptical, waves), what they share in _common.

Levels: "quick" (coarse, for CI: the whole suite in a few minutes on two cores) and "full"
(the report's resolution, with a convergence study where the issue asks for one).
"""
from __future__ import annotations

import time
from typing import Callable, Dict, List, Optional

import rtsph

from . import _common, drops
from ._common import NotOnBackend, Result, _order  # noqa: F401
from .channels import couette, couette_exact, poiseuille, taylor_green  # noqa: F401
from .dam_breaks import MARTIN_MOYCE_HEIGHT, _height_error, _spheric_data, dam_break, spheric_test2  # noqa: F401
from .drops import _ball_blocks, _virial_pressures, static_droplet  # noqa: F401
from .elliptical import elliptical_drop, elliptical_drop_exact  # noqa: F401
from .oscillating import oscillating_droplet
from .tanks import hydrostatic, still_water
from .waves import standing_wave

CASES: Dict[str, Callable[[str, str, int], Result]] = {
    "hydrostatic_2d": hydrostatic(2),
    "hydrostatic_3d": hydrostatic(3),
    "dam_break_2d": dam_break,
    "poiseuille_2d": poiseuille,
    "taylor_green_2d": taylor_green,
    "still_water_3d": still_water,
    "static_droplet_2d": static_droplet(2),
    "static_droplet_3d": static_droplet(3),
    "oscillating_droplet_2d": oscillating_droplet,
    "elliptical_drop_2d": elliptical_drop,
    "couette_2d": couette,
    "spheric_test2_3d": spheric_test2,
    "standing_wave_2d": standing_wave,
}


def set_context(backend: str = "cpu", overrides: Optional[Dict[str, str]] = None) -> None:
    """Where the cases this process runs next run: the backend and `--set`'s parameters."""
    _common._BACKEND = backend
    _common._OVERRIDES = dict(overrides or {})


# Parts: independent runs inside a case that `--jobs` runs as tasks of their own, the case then
# seeded with their results (drops.py: a static drop's lattice draws). By key, so that cases that
# share parts (the oscillating drop reuses the static drop's calibration) run each once.
def part_keys(name: str, method: str, level: str) -> List[tuple]:
    return drops.draw_keys(name, method, level)


def part_cost(key: tuple) -> float:
    """A part's cost relative to the others', to start the longest first."""
    return drops.draw_cost(key)


def run_part(key: tuple, threads: int, backend: str = "cpu", overrides: Optional[Dict[str, str]] = None):
    set_context(backend, overrides)
    return drops.run_draw(key, threads)


def seed_parts(results: Dict[tuple, object]) -> None:
    """Installs parts run elsewhere for the cases this process runs next (after set_context)."""
    drops.seed_draws(results)


def run_case(name: str, method: str, level: str, threads: int, backend: str = "cpu",
             overrides: Optional[Dict[str, str]] = None, parts: Optional[Dict[tuple, object]] = None) -> Result:
    """Runs one case with one method; `parts` are its parts' results from other processes."""
    set_context(backend, overrides)
    if parts:
        seed_parts(parts)
    t0 = time.perf_counter()
    try:
        r = CASES[name](method, level, threads)
    except NotOnBackend as e:
        return Result(case=name, method=method, metric="(not on this backend)", applicable=False,
                      notes=str(e), wall_s=time.perf_counter() - t0)
    except (rtsph.InstabilityError, RuntimeError, ValueError) as e:
        # A case the method cannot run (the instability guard tripped, a solve gave up) fails
        # with the engine's diagnostic; the rest of the suite goes on.
        notes = f"{type(e).__name__}: {e}"
        if isinstance(e, rtsph.SceneError) and "unknown key" in str(e):
            # The cases come with the package; an engine built from an older checkout does not
            # know the keys newer cases set.
            notes += (" (the installed rtsph package may be older than these cases: "
                      "run scripts/setup-python.sh)")
        return Result(case=name, method=method, metric="(did not finish)", error=float("inf"), tolerance=0.0,
                      notes=notes, wall_s=time.perf_counter() - t0)
    if r.convergence:
        r.extra["observed_order"] = _order(r.convergence)
    return r
