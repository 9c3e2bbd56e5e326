"""Issue 30: voussoir.fragility, the capacity route from Python, checked against the CLI's
JSON and against the assessment of a sample's own scene (docs/fragility.md)."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import voussoir

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "data" / "fragility_portal.toml"


def test_fragility_matches_the_cli_and_repeats_with_its_seed():
    scene = voussoir.Scene.from_toml(SCENE)
    r = voussoir.fragility(scene, samples=20, seed=3)
    again = voussoir.fragility(scene, samples=20, seed=3)
    assert r.to_dict() == again.to_dict()
    assert r.route == "capacity" and r.sample_count == 20
    assert r.median_bounds[0] < r.median < r.median_bounds[1]
    assert r.capacities.shape == (20,) and np.all(np.isfinite(r.capacities))
    assert r.svg.startswith("<svg") or "<svg" in r.svg[:200]
    binary = ROOT / "target" / "release" / "voussoir"
    if binary.exists():
        out = subprocess.run(
            [str(binary), "fragility", str(SCENE), "--samples", "20", "--seed", "3", "--json"],
            check=True,
            capture_output=True,
            text=True,
        )
        cli = json.loads(out.stdout)
        assert cli["samples"] == r.samples
        assert cli["median"] == r.median and cli["beta"] == r.beta


def test_a_sample_is_the_assessment_of_its_own_scene():
    scene = voussoir.Scene.from_toml(SCENE)
    r = voussoir.fragility(scene, samples=8, seed=5)
    row = r.samples[2]
    keys = [i["key"] for i in r.inputs]
    one = scene.with_values(dict(zip(keys, row["values"])))
    a = voussoir.assess(one)
    least = min(d["nonlinear_check"]["ag_max"] for d in a.directions.values())
    assert row["ag_capacity"] == least


def test_certain_inputs_give_a_step_and_the_site_can_be_set():
    scene = voussoir.Scene.from_toml(ROOT / "data" / "portal.toml")
    with pytest.raises(voussoir.AnalysisError, match=r"\[site\]"):
        voussoir.fragility(scene, samples=2)
    site = {"ag": 0.25, "soil": "B", "F0": 2.4, "Tc_star": 0.3}
    r = voussoir.fragility(scene, samples=4, site=site)
    assert r.beta == 0.0
    assert len(set(r.capacities.tolist())) == 1 and r.median == r.capacities[0]
