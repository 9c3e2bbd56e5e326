"""The notebook-style example runs and draws its PNG."""

import os
import subprocess
import sys

import pytest

from conftest import REPO

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("scene", ["semicircular.toml", "loaded_portal.toml"])
def test_thrust_line_example_draws_a_png(tmp_path, scene):
    out = tmp_path / "thrust_line.png"
    p = subprocess.run(
        [sys.executable, str(REPO / "examples" / "thrust_line.py"), str(REPO / "data" / scene),
         str(out)],
        capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert p.returncode == 0, p.stderr
    assert "collapse, lambda = " in p.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000
