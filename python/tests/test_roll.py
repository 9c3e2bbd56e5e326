"""`roll` is `voussoir analyze --roll ... --json`: the same positions and multipliers, the same
critical position and analysis there, and the same refusals."""

import json

import pytest

import voussoir
from conftest import REPO, assert_same

BRIDGE = REPO / "data" / "rolling_bridge.toml"


def test_roll_equals_cli_json(cli):
    args = ["--roll", "vehicles[0]", "--from", "-3.2", "--to", "2.0", "--step", "0.2"]
    ref = json.loads(cli("analyze", BRIDGE, "--json", *args).stdout)
    r = voussoir.roll(voussoir.Scene.from_toml(str(BRIDGE)), "vehicles[0]", -3.2, 2.0, 0.2)
    assert_same(r.to_dict(), ref)
    roll = r.roll
    assert len(roll["positions"]) == 27
    assert r.lambda_lower <= min(roll["lambda_lower"]) + 1e-12
    assert "<svg" in r.chart_svg and "critical position" in r.chart_svg
    assert "<svg" in r._repr_svg_()


def test_roll_refuses_what_the_cli_refuses(cli):
    scene = voussoir.Scene.from_toml(str(BRIDGE))
    p = cli("analyze", BRIDGE, "--roll", "vehicles[0]", "--from", "-3.2", "--to", "2.3",
            "--step", "0.5", check=False)
    assert p.returncode != 0
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.roll(scene, "vehicles[0]", -3.2, 2.3, 0.5)
    assert e.value.key == "vehicles[0].at"
    assert str(e.value) in p.stderr
    with pytest.raises(voussoir.AnalysisError):
        voussoir.roll(scene, "vehicles[0]", 0.0, 1.0, 0.0)
    with pytest.raises(voussoir.AnalysisError):
        voussoir.roll(scene, "wagons[0]", 0.0, 1.0, 0.1)
