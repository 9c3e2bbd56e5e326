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


@pytest.mark.parametrize("scene", ["semicircular.toml", "loaded_portal.toml"])
def test_the_legend_does_not_cover_the_structure(tmp_path, monkeypatch, scene):
    # Issue 26: the legend sat inside the axes, over the arch's crown or a pier.
    import runpy

    import matplotlib

    matplotlib.use("Agg")
    out = tmp_path / "thrust_line.png"
    monkeypatch.setattr(
        sys, "argv", ["thrust_line.py", str(REPO / "data" / scene), str(out)]
    )
    ns = runpy.run_path(str(REPO / "examples" / "thrust_line.py"), run_name="__main__")
    fig, ax = ns["fig"], ns["ax"]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legend = ax.get_legend().get_window_extent(renderer)
    blocks = [p.get_window_extent(renderer) for p in ax.patches]
    assert blocks and not any(legend.overlaps(b) for b in blocks)
    assert not legend.overlaps(ax.get_window_extent(renderer))
