"""The Python results are the CLI's: for every bundled scene, `analyze` (both directions,
with the continuous model), `min_thickness` and `dem` give the JSON of `voussoir analyze /
min-thickness / dem --json` to 1e-12, field for field (wall times aside)."""

import json

import numpy as np
import pytest

import voussoir
from conftest import SCENES, assert_same


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
@pytest.mark.parametrize("direction", ["right", "left"])
def test_analyze_equals_cli_json(cli, path, direction):
    p = cli("analyze", path, "--json", "--continuous", "--direction", direction, check=False)
    if p.returncode != 0:
        # A live action has no direction: the CLI refuses --direction left, so must Python.
        assert "[action] kind = \"live\"" in p.stderr
        with pytest.raises(voussoir.AnalysisError) as e:
            voussoir.analyze(voussoir.Scene.from_toml(str(path)), direction=direction)
        assert "live" in str(e.value) and e.value.kind == "not_for_action"
        return
    ref = json.loads(p.stdout)
    r = voussoir.analyze(voussoir.Scene.from_toml(str(path)), direction=direction, continuous=True)
    assert_same(r.to_dict(), ref)
    assert r.status == ref["status"] and r.direction == direction


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_min_thickness_equals_cli_json(cli, path):
    scene = voussoir.Scene.from_toml(str(path))
    if (
        scene.thickness is None
        or scene.to_dict().get("action", {}).get("kind") == "live"
        or scene.to_dict().get("ties")
    ):
        # A scene of the user's own blocks has no ring to thin, a live action's loads vanish at
        # lambda = 0, and tie anchors are fixed points a thickness search would leave behind:
        # all refuse, in the same words.
        p = cli("min-thickness", path, "--json", "--continuous", check=False)
        assert p.returncode != 0
        with pytest.raises(voussoir.VoussoirError) as e:
            voussoir.min_thickness(scene, continuous=True)
        assert str(e.value) in p.stderr
        return
    ref = json.loads(cli("min-thickness", path, "--json", "--continuous").stdout)
    m = voussoir.min_thickness(scene, continuous=True)
    assert_same(m.to_dict(), ref)


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_dem_equals_cli_json(cli, path):
    scene = voussoir.Scene.from_toml(str(path))
    p = cli("dem", path, "--json", check=False)
    if p.returncode != 0:
        # The walled arcade: its wall's smallest pieces set a time step so short that a run
        # would pass the default step limit; both refuse it, in the same words (--max-steps).
        assert "time steps" in p.stderr, p.stderr
        with pytest.raises(voussoir.VoussoirError) as e:
            voussoir.dem(scene)
        assert str(e.value) in p.stderr
        return
    ref = json.loads(p.stdout)
    d = voussoir.dem(scene)
    assert_same(d.to_dict(), ref)


def test_overrides_equal_cli_set(cli):
    """`with_values` is `--set`: the same scene, the same numbers (the origin aside, which
    the CLI writes with its `--set` options)."""
    path = SCENES[0].parent / "pointed.toml"
    ref = json.loads(
        cli("analyze", path, "--json", "--set", "arch.thickness=0.2", "--set", "arch.voussoirs=24").stdout
    )
    scene = voussoir.Scene.from_toml(str(path)).with_values(
        {"arch.thickness": 0.2, "arch.voussoirs": 24}
    )
    got = voussoir.analyze(scene).to_dict()
    ref["scene"].pop("origin")
    got["scene"].pop("origin")
    assert_same(got, ref)


def test_numpy_views_are_the_joints_of_the_json():
    """The numpy arrays carry the JSON's numbers, and the thrust-line point of each joint is
    p_mid + e u (README: sign conventions), so they line up with the joints."""
    r = voussoir.analyze(voussoir.Scene.from_toml(str(SCENES[0].parent / "semicircular.toml")))
    joints = r.joints
    n = len(joints)
    assert r.p1.shape == r.p2.shape == r.thrust.shape == (n, 2)
    assert r.forces.shape == (n, 3) and r.eccentricity.shape == (n,)
    assert r.mechanism_array.shape == (r.blocks, 3)
    np.testing.assert_array_equal(r.forces[:, 0], [j["N"] for j in joints])
    u = (r.p2 - r.p1) / np.linalg.norm(r.p2 - r.p1, axis=1)[:, None]
    expected = 0.5 * (r.p1 + r.p2) + r.eccentricity[:, None] * u
    np.testing.assert_allclose(r.thrust, expected, rtol=0, atol=1e-12)
    # Every resultant stays inside its joint (no tension) and every hinge sits at an end.
    half = 0.5 * np.linalg.norm(r.p2 - r.p1, axis=1)
    assert np.all(np.abs(r.eccentricity) <= half * (1 + 1e-9))
    for h in r.hinges:
        assert abs(abs(r.eccentricity[h["joint"]]) - half[h["joint"]]) <= 1e-9 * half[h["joint"]]


def test_a_scene_without_collapse_state_gives_nan_arrays():
    scene = voussoir.Scene.from_toml(str(SCENES[0].parent / "semicircular.toml"))
    r = voussoir.analyze(scene.with_values({"arch.thickness": 0.05}))
    assert r.status == "cannot_stand" and r.lambda_lower is None
    assert np.isnan(r.thrust).all() and np.isnan(r.forces).all()
    assert not np.isnan(r.p1).any()
