"""rtsph's validation suite: each case runs a scene through the engine, compares it with an
analytic solution or an experiment, and returns a Result with the measured error, its
tolerance and the series to plot. `python -m rtsph.validate` (or `rtsph validate`) runs them
and writes the report (report.py). docs/validation.md tells what each case shows.
"""
from __future__ import annotations

from .cases import CASES, Result, run_case  # noqa: F401

METHODS = ("wcsph", "pbf", "dfsph")
