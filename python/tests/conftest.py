"""Shared fixtures: small scenes (the suite runs in CI on 2 cores) and the CLI binary."""
import os
import pathlib
import shutil

import pytest

import rtsph

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def tank():
    """hydrostatic_2d at a coarse spacing: 200 fluid particles."""
    return rtsph.scene("hydrostatic_2d", {"fluid.spacing": 0.05})


@pytest.fixture
def dam3d():
    """dam_break_3d at a coarse spacing (a few hundred particles)."""
    return rtsph.scene("dam_break_3d", {"fluid.spacing": 0.08})


@pytest.fixture
def validate_context(monkeypatch):
    """rtsph.validate keeps the backend and `--set` parameters of the case it runs in module state
    (run_case and main set them, a case run directly reads them): each test that uses this starts
    from and leaves the state it found, so no test's overrides reach the next one's scenes."""
    from rtsph.validate import _common
    monkeypatch.setattr(_common, "_BACKEND", _common._BACKEND)
    monkeypatch.setattr(_common, "_OVERRIDES", dict(_common._OVERRIDES))


@pytest.fixture
def cli():
    """The rtsph executable: $RTSPH_BINARY (set by scripts/test-python.sh), else the release build."""
    path = os.environ.get("RTSPH_BINARY") or str(REPO / "build" / "release" / "rtsph")
    if not os.path.exists(path):
        if os.environ.get("RTSPH_BINARY"):
            pytest.fail(f"RTSPH_BINARY={path} does not exist")
        pytest.skip("no rtsph executable (build the release preset or set RTSPH_BINARY)")
    return path


_REPORTS = []


@pytest.fixture
def report():
    """report(line): a measured figure to print in the summary (speed is reported, not asserted)."""
    return _REPORTS.append


def pytest_terminal_summary(terminalreporter):
    if _REPORTS:
        terminalreporter.section("rtsph figures")
        for line in _REPORTS:
            terminalreporter.write_line(line)
