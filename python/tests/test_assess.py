"""`voussoir.assess`: the seismic assessment from Python equals `voussoir assess --json` (both
directions, the governing one, the code's rule), and its charts show inline."""

import json

import numpy as np
import pytest

import voussoir
from conftest import REPO, assert_same

SITE = {"ag": 0.25, "soil": "B", "F0": 2.4, "Tc_star": 0.3}
SITE_ARGS = [a for k, v in SITE.items() for a in ("--site", f"{k}={v}")]


@pytest.fixture(scope="module")
def portal():
    return voussoir.Scene.from_toml(str(REPO / "data" / "loaded_portal.toml"))


@pytest.mark.parametrize("direction", [None, "right", "left"])
def test_assess_equals_the_cli(cli, portal, direction):
    r = voussoir.assess(portal, site=SITE, direction=direction)
    args = ["assess", "data/loaded_portal.toml", "--json", *SITE_ARGS]
    if direction:
        args += ["--direction", direction]
    ref = json.loads(cli(*args).stdout)
    py = r.to_dict()
    # The scene report names its source (the CLI adds its --site overrides): all else equal.
    assert py["scene"].pop("origin").endswith("loaded_portal.toml")
    assert ref["scene"].pop("origin").startswith("data/loaded_portal.toml (with --set site.ag")
    assert_same(py, ref)


def test_both_directions_and_the_worse_governs(portal):
    r = voussoir.assess(portal, site=SITE)
    assert set(r.directions) == {"right", "left"}
    assert r.directions_assessed == ["right", "left"] and not r.restricted
    right, left = r.directions["right"], r.directions["left"]
    worse = "left" if (left["passes"], left["ag_max"]) < (right["passes"], right["ag_max"]) else "right"
    assert r.governing == worse == r.direction
    assert r.alpha0 == r.directions[worse]["alpha0"]
    assert r.passes == (right["passes"] and left["passes"])
    # The governing capacity curve as an array: rest at alpha0, alpha = 0 at d_k0.
    c = r.curve
    assert c.shape == (200, 5)
    assert c[0, 2] == pytest.approx(r.alpha0, rel=1e-12)
    assert c[-1, 1] == pytest.approx(r.d_k0, rel=1e-12)
    assert abs(c[-1, 2]) < 1e-9
    assert np.array_equal(r.curve_of(worse), c)
    with pytest.raises(KeyError, match="not assessed"):
        voussoir.assess(portal, site=SITE, direction="right").curve_of("left")


def test_the_rule_either_check_passes(portal):
    r = voussoir.assess(portal, site=SITE, direction="right")
    assert r.linear_check["passes"] and not r.nonlinear_check["passes"]
    assert r.passes and r.satisfied == "linear" and not r.both_checks_pass
    assert "C8.7.1" in r.rule


def test_assessment_charts_show_inline(portal):
    r = voussoir.assess(portal, site=SITE)
    svg = r._repr_svg_()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg
    assert "spectral acceleration a* (m/s²)" in svg and "governing" in svg
    cap = r.svg("capacity")
    assert "capacity curves" in cap and "α₀" in cap


def test_no_site_is_an_analysis_error(portal):
    with pytest.raises(voussoir.AnalysisError, match="--site ag="):
        voussoir.assess(portal)


def test_a_bad_site_value_is_a_scene_error(portal):
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.assess(portal, site={**SITE, "soil": "Q"})
    assert e.value.key == "site.soil"
