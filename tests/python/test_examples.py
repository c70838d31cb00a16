"""The examples a user runs first keep working: each at a small size, its PNG written."""
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_render_sunset_elevations(tmp_path):
    pytest.importorskip("matplotlib")
    plot = tmp_path / "sky.png"
    run = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "render_sunset_elevations.py"), "--res", "32x18",
         "--elevations", "2,10", "-o", str(plot)],
        capture_output=True, text=True, env=os.environ, check=True)
    lines = [l for l in run.stdout.splitlines() if l.startswith("sun at")]
    assert len(lines) == 2, run.stdout
    low, high = (float(l.split("luminance")[1].split()[0]) for l in lines)
    assert 0.0 < low < high  # the sky brightens as the sun rises
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
