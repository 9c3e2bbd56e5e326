"""The dynamic DEM from Python: a pulse, a record, an incremental dynamic analysis and a pulse
curve, each equal to `voussoir dem ... --json`, with the time history as arrays."""

import json

import numpy as np
import pytest

import voussoir
from conftest import REPO, assert_same

B, H = 0.2, 1.0
BLOCK = (
    "[blocks]\n"
    f"polygons = [[[{-B / 2}, 0.0], [{B / 2}, 0.0], [{B / 2}, {H}], [{-B / 2}, {H}]]]\n"
    "[material]\nfriction = \"inf\"\n"
)


@pytest.fixture()
def block(tmp_path):
    path = tmp_path / "block.toml"
    path.write_text(BLOCK)
    return path


def test_pulse_run_equals_the_cli(cli, block):
    scene = voussoir.Scene.from_toml(str(block))
    r = voussoir.dem_dynamic(scene, pulse="sine", amplitude=0.05, period=0.5, tail=1.0)
    ref = json.loads(
        cli("dem", block, "--json", "--pulse", "sine", "--amplitude", "0.05", "--period", "0.5",
            "--tail", "1").stdout
    )
    assert_same(r.to_dict(), ref)
    # 0.05 g is below the block's static threshold b/h = 0.2: it stays.
    assert r.status == "survives"
    h = r.history
    assert set(h) == {"time", "ground_acceleration", "displacement", "rotation",
                      "ground_acceleration_vertical"}
    assert np.all(np.diff(h["time"]) > 0) and h["time"][-1] == pytest.approx(1.5, abs=0.02)
    # The pulse as sampled: A sin(2 pi t / T) in m/s^2 over its period, then nothing.
    t, a = h["time"], h["ground_acceleration"]
    on = t < 0.5
    assert np.allclose(a[on], 0.05 * 9.80665 * np.sin(2 * np.pi * t[on] / 0.5), atol=1e-9)
    assert np.all(a[t > 0.51] == 0)


def test_record_run_and_ida_equal_the_cli(cli, block):
    scene = voussoir.Scene.from_toml(str(block))
    record = REPO / "data" / "records" / "synthetic_10s.AT2"
    r = voussoir.dem_dynamic(scene, record=record, scale=0.5, tail=0.5)
    ref = json.loads(
        cli("dem", block, "--json", "--record", record, "--scale", "0.5", "--tail", "0.5").stdout
    )
    assert_same(r.to_dict(), ref)
    ida = voussoir.dem_ida(scene, pulse="rect", amplitude=0.1, period=0.3, tolerance=0.05,
                           tail=1.0)
    ref = json.loads(
        cli("dem", block, "--json", "--pulse", "rect", "--amplitude", "0.1", "--period", "0.3",
            "--ida", "--tolerance", "0.05", "--tail", "1").stdout
    )
    assert_same(ida.to_dict(), ref)
    assert ida.scale_survives < ida.scale_collapses


def test_pulse_curve_equals_the_cli(cli, block, tmp_path):
    scene = voussoir.Scene.from_toml(str(block))
    r = voussoir.dem_pulse_curve(scene, periods=[0.5], shapes=["rect"], tolerance=0.05, tail=1.0)
    ref = json.loads(
        cli("dem", block, "--json", "--pulse-curve", tmp_path / "curve.svg", "--periods", "0.5",
            "--shapes", "rect", "--tolerance", "0.05", "--tail", "1").stdout
    )
    assert_same(r.to_dict(), ref)
    (p,) = r.points
    assert p["amplitude_survives"] < p["amplitude_collapses"]


def test_bad_ground_motion_arguments_name_the_argument(block):
    scene = voussoir.Scene.from_toml(str(block))
    with pytest.raises(voussoir.AnalysisError, match="scale"):
        voussoir.dem_dynamic(scene, pulse="sine", amplitude=0.1, period=0.5, scale=float("nan"))
    with pytest.raises(voussoir.AnalysisError, match="sine"):
        voussoir.dem_dynamic(scene, pulse="square", amplitude=0.1, period=0.5)
    with pytest.raises(voussoir.AnalysisError, match="pulse"):
        voussoir.dem_dynamic(scene)
    with pytest.raises(voussoir.AnalysisError, match="tail"):
        voussoir.dem_dynamic(scene, pulse="sine", amplitude=0.1, period=0.5, tail=-1)
