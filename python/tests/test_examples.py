"""The examples in examples/ run (at tiny sizes) and write their plots."""
import subprocess
import sys

import pytest

from conftest import REPO


@pytest.mark.parametrize("script, args", [
    ("dam_break_front.py", ["--spacing", "0.1", "--until", "1.0", "--threads", "1"]),
    ("viscosity_sweep.py", ["--spacing", "0.1", "--until", "0.1", "--viscosities", "1e-6,1e-1", "--threads", "1"]),
])
def test_example_runs(script, args, tmp_path):
    out = tmp_path / "plot.png"
    r = subprocess.run([sys.executable, str(REPO / "examples" / script), *args, "--out", str(out)],
                       capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "wrote" in r.stdout
