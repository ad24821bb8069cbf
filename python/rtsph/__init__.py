"""rtsph: real-time SPH fluid simulation from Python.

The engine is the same C++ code as the ``rtsph`` command line; this package only converts
arguments and arrays. See docs/python.md.

    >>> import rtsph
    >>> sim = rtsph.Simulation(rtsph.scene("dam_break_2d"))
    >>> sim.run(until=0.1)
    >>> sim.positions.shape          # (N, 2), float32, rows in particle-id order
"""
from __future__ import annotations

import json
import math
import os
import sys
import time as _time
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np  # noqa: E402

from . import _rtsph  # noqa: E402
from ._rtsph import (  # noqa: E402
    CheckpointError,
    InstabilityError,
    IoError,
    SceneError,
    solver_methods,
)

__all__ = [
    "Scene",
    "Simulation",
    "SceneError",
    "CheckpointError",
    "InstabilityError",
    "IoError",
    "scene",
    "builtin_scenes",
    "solver_methods",
    "render",
]
__version__ = "0.1.0"

PathLike = Union[str, "os.PathLike[str]"]


def _format_value(value: Any) -> str:
    """A Python value as the text of a ``--set key=value`` assignment."""
    if isinstance(value, bool) or isinstance(value, np.bool_):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))  # shortest text that reads back to the same double
    if isinstance(value, (list, tuple, np.ndarray)):
        return ",".join(_format_value(v) for v in value)
    raise TypeError(f"cannot use a {type(value).__name__} as a scene value: {value!r}")


class Scene:
    """A validated scene: what a scene file or ``rtsph scenes`` describes.

    Build one with :func:`rtsph.scene`. Scenes are immutable; :meth:`with_overrides` returns a
    changed copy.
    """

    __slots__ = ("_impl",)

    def __init__(self, impl: "_rtsph._Scene") -> None:
        self._impl = impl

    @property
    def name(self) -> str:
        return self._impl.name

    @property
    def dimension(self) -> int:
        return self._impl.dimension

    @property
    def method(self) -> str:
        return self._impl.method

    @property
    def end_time(self) -> float:
        return self._impl.end_time

    def to_dict(self) -> Dict[str, Any]:
        """Every key of the scene (defaults included) as a JSON-compatible dict."""
        return json.loads(self._impl.to_json())

    def to_json(self) -> str:
        return self._impl.to_json()

    def with_overrides(self, overrides: Optional[Mapping[str, Any]] = None, **kwargs: Any) -> "Scene":
        """A copy with parameters changed by dotted key, as ``--set`` does.

        ``scene.with_overrides({"fluid.spacing": 0.01})`` or
        ``scene.with_overrides(**{"solver.method": "pbf"})``. Raises SceneError naming the key.
        """
        impl = self._impl
        for key, value in {**(overrides or {}), **kwargs}.items():
            impl = impl._override(f"{key}={_format_value(value)}")
        return Scene(impl)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and other.to_json() == self.to_json()

    def __hash__(self) -> int:
        return hash(self.to_json())

    def __repr__(self) -> str:
        return f"<rtsph.Scene {self.name!r} {self.dimension}D {self.method}>"


def scene(source: Union[str, "os.PathLike[str]", Mapping[str, Any], Scene],
          overrides: Optional[Mapping[str, Any]] = None, **kwargs: Any) -> Scene:
    """A scene from a built-in name, a JSON file path, a dict, or another Scene.

    Overrides use the dotted keys of ``rtsph run --set``: ``rtsph.scene("dam_break_2d",
    {"fluid.spacing": 0.01})`` or ``rtsph.scene("dam_break_2d", **{"solver.method": "pbf"})``.
    A bad scene raises :class:`SceneError` (a ValueError) with the CLI's one-line message.
    """
    if isinstance(source, Scene):
        base = source
    elif isinstance(source, Mapping):
        base = Scene(_rtsph._parse_scene(json.dumps(source), "<dict>"))
    elif isinstance(source, (str, os.PathLike)):
        base = Scene(_rtsph._load_scene(os.fspath(source)))
    else:
        raise TypeError(f"scene: expected a name, a path, a dict or a Scene, got {type(source).__name__}")
    if overrides or kwargs:
        return base.with_overrides(overrides, **kwargs)
    return base


def builtin_scenes() -> Dict[str, str]:
    """The built-in scenes: name -> one-line description."""
    return dict(_rtsph._builtin_scenes())


def _as_rows(array: Any, what: str) -> np.ndarray:
    a = np.asarray(array)
    if a.dtype.kind != "f":
        raise TypeError(f"{what}: expected a float array, got dtype {a.dtype}")
    if a.ndim != 2:
        raise ValueError(f"{what}: expected an array of shape (N, D), got shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)


class _Progress:
    """A one-line progress bar on stderr, redrawn at most 10 times a second."""

    def __init__(self, start: float, end: float) -> None:
        self.start, self.end, self.last, self.t0 = start, end, 0.0, _time.monotonic()

    def update(self, t: float, force: bool = False) -> None:
        now = _time.monotonic()
        if not force and now - self.last < 0.1:
            return
        self.last = now
        span = self.end - self.start
        frac = min(1.0, max(0.0, (t - self.start) / span)) if span > 0 else 1.0
        bar = "#" * int(30 * frac)
        wall = now - self.t0
        rate = (t - self.start) / wall if wall > 0 else 0.0
        sys.stderr.write(f"\rrtsph [{bar:<30}] t = {t:.4f} / {self.end:.4f} s, {rate:.3g}x real time")
        sys.stderr.flush()

    def close(self, t: float) -> None:
        self.update(t, force=True)
        sys.stderr.write("\n")


class Simulation(_rtsph._Simulation):
    """A running simulation of a scene on the CPU engine.

    ``threads=0`` uses every core; results are bitwise identical for any thread count.
    Particle arrays (``positions``, ``velocities``, ``density``, ``pressure``) are fresh numpy
    copies in ascending particle-id order, so a particle keeps its row between steps and an
    array stays valid however long it is kept.
    """

    def __init__(self, scene: Union[Scene, str, Mapping[str, Any]], threads: int = 0, backend: str = "cpu") -> None:
        if not isinstance(scene, Scene):
            scene = globals()["scene"](scene)
        super().__init__(scene._impl, threads, backend)

    # -- stepping --------------------------------------------------------------------------
    def step(self, n: int = 1) -> "Simulation":
        """Advances n time steps (the GIL is released meanwhile); returns the simulation."""
        if n < 0:
            raise ValueError(f"step: n must be >= 0, got {n}")
        self._advance(float("inf"), int(n))
        return self

    def run(self, until: Optional[float] = None, every: Optional[float] = None,
            callback: Optional[Callable[["Simulation"], Any]] = None, progress: bool = False) -> "Simulation":
        """Steps until simulated time ``until`` (default: the scene's end time).

        With ``every``, ``callback(sim)`` is called at the start and after the first step that
        reaches each multiple of ``every`` seconds (the last one at ``until``); without it, once
        at the end. Steps are the method's own, so a call comes at most one dt late. Ctrl-C raises
        KeyboardInterrupt between two steps, leaving the simulation usable.
        """
        end = self.scene.end_time if until is None else float(until)
        if math.isnan(end):  # every comparison with NaN is false: it would return at once
            raise ValueError(f"run: until must be a time in s, got {until}")
        if every is not None and not every > 0:
            raise ValueError(f"run: every must be positive, got {every}")
        bar = _Progress(self.time, end) if progress else None
        periodic = callback is not None and every is not None
        try:
            if periodic:
                callback(self)
            while self.time < end:
                target = end
                if every is not None:
                    k = int(np.floor(self.time / every + 1e-9)) + 1
                    target = min(end, k * every)
                while self.time < target:
                    self._advance(target, 1 << 30 if bar is None else 64)
                    if bar:
                        bar.update(self.time)
                if periodic:
                    callback(self)
            if callback is not None and not periodic:
                callback(self)
        finally:
            if bar:
                bar.close(self.time)
        return self

    @property
    def scene(self) -> Scene:
        """The scene being run, with live changes (parameters, gravity) applied."""
        return Scene(self._scene)

    # -- particle data ---------------------------------------------------------------------
    def set_positions(self, positions: Any) -> None:
        """Overwrites fluid positions: shape (N, D), floats, finite, rows in id order."""
        self._set_positions(_as_rows(positions, "set_positions"))

    def set_velocities(self, velocities: Any) -> None:
        """Overwrites fluid velocities (m/s): shape (N, D), floats, finite, rows in id order."""
        self._set_velocities(_as_rows(velocities, "set_velocities"))

    def set_parameter(self, key: str, value: Any) -> None:
        """Changes a live parameter (e.g. "fluid.viscosity") from the next step on."""
        self._set_parameter(key, _format_value(value))

    # -- files -----------------------------------------------------------------------------
    @classmethod
    def from_checkpoint(cls, path: PathLike, threads: int = 0, backend: str = "cpu") -> "Simulation":
        """Resumes a checkpoint written by save_checkpoint or ``rtsph run`` (bit-for-bit), on
        either backend: the format is the same on the CPU and the GPU."""
        impl = _rtsph._checkpoint_scene(os.fspath(path))
        sim = cls(Scene(impl), threads=threads, backend=backend)
        sim._read_checkpoint(os.fspath(path))
        return sim

    def export(self, directory: PathLike, format: str = "vtk", attributes: str = "all") -> str:
        """Writes the current state as the next frame of ``directory`` (frame_NNNNNN.EXT plus
        index.csv, as ``rtsph run --export``); returns the file written."""
        return self._export(os.fspath(directory), format, attributes)

    def __repr__(self) -> str:
        s = self.scene
        where = "" if self.backend == "cpu" else f" on the {self.backend}"
        return (f"<rtsph.Simulation {s.name!r} {s.dimension}D {s.method}{where}, {self.particle_count} fluid particles, "
                f"t = {self.time:.6g} s, step {self.step_count}>")

    def __enter__(self) -> "Simulation":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()


def render(sim: Simulation, path: Optional[PathLike] = None, size: Tuple[int, int] = (1280, 720),
           color: str = "speed", display: str = "obstacles", colormap: str = "viridis",
           style: str = "surface") -> np.ndarray:
    """Draws the simulation as ``rtsph render`` does (headless EGL) and returns the image as an
    (H, W, 4) uint8 array; with ``path``, also writes it as PNG. ``style``: "surface" (the water
    surface, as the CLI's default) or "particles" (which ``color`` applies to)."""
    width, height = size
    if path is not None and not os.fspath(path).lower().endswith(".png"):
        raise ValueError(f"render: path {os.fspath(path)!r}: the picture is written as PNG; name it FILE.png")
    return _rtsph._render(sim, int(width), int(height), color, display, colormap, style,
                          "" if path is None else os.fspath(path))
