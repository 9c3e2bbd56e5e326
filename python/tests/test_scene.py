"""Scenes from files, dicts and TOML text are the same scene; `with_values` and pickling keep
them; errors carry their key and value and the CLI's messages."""

import pickle

import pytest

import voussoir
from conftest import REPO

SEMI = REPO / "data" / "semicircular.toml"


def test_from_dict_is_the_file_scene():
    scene = voussoir.Scene.from_toml(str(SEMI))
    again = voussoir.Scene.from_dict(scene.to_dict())
    assert again.to_dict() == scene.to_dict()
    a = voussoir.analyze(scene).to_dict()
    b = voussoir.analyze(again).to_dict()
    assert a["scene"].pop("origin") == str(SEMI) and b["scene"].pop("origin") == "<dict>"
    for r in (a, b):
        r.pop("solve_time_s"), r.pop("kinematic_time_s")
    assert a == b


def test_from_dict_by_hand():
    scene = voussoir.Scene.from_dict(
        {"arch": {"shape": "circular", "radius": 2.0, "embrace_deg": 180, "thickness": 0.3,
                  "voussoirs": 16}}
    )
    assert scene.thickness == 0.3 and scene.voussoirs == 16
    assert scene.span == pytest.approx(4.0) and scene.ratios()["t/R"] == pytest.approx(0.15)


def test_with_values_sets_keys_and_ratios():
    scene = voussoir.Scene.from_toml(str(SEMI))
    assert scene.with_values({"arch.thickness": 0.2}).thickness == 0.2
    assert scene.with_values({"t/R": 0.12}).thickness == pytest.approx(0.12)
    assert scene.thickness == 0.15  # scenes are values: the original is unchanged


def test_pickle_round_trip():
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "filled_arch.toml")).with_values(
        {"arch.thickness": 0.25}
    )
    back = pickle.loads(pickle.dumps(scene))
    assert back.to_dict() == scene.to_dict() and back.origin == scene.origin


def test_out_of_range_carries_key_and_value():
    scene = voussoir.Scene.from_toml(str(SEMI))
    with pytest.raises(voussoir.SceneError) as e:
        scene.with_values({"arch.thickness": -0.5})
    assert (e.value.kind, e.value.key, e.value.value) == ("out_of_range", "arch.thickness", "-0.5")
    assert isinstance(e.value, voussoir.VoussoirError)


def test_unknown_key_suggests_the_closest():
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_toml(str(SEMI)).with_values({"arch.thicknes": 0.2})
    assert (e.value.kind, e.value.key) == ("unknown_key", "arch.thicknes")
    assert "did you mean `thickness`?" in str(e.value)


def test_wrong_type_and_missing_key():
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_toml(str(SEMI)).with_values({"arch.voussoirs": "many"})
    assert (e.value.kind, e.value.key, e.value.value) == ("wrong_type", "arch.voussoirs", '"many"')
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_dict({"arch": {"shape": "circular", "radius": 1.0}})
    assert (e.value.kind, e.value.key, e.value.origin) == ("missing_key", "arch.thickness", "<dict>")
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_dict({"arch": {"thickness": None}})
    assert (e.value.kind, e.value.key, e.value.value) == ("wrong_type", "arch.thickness", "None")


@pytest.mark.parametrize(
    "text",
    [
        "[arch]\nshape = 'circular'\nradius = 1.0\nembrace_deg = 180.0\nthickness = -1\nvoussoirs = 8\n",
        "[arch]\nshape = 'circular'\nradius = 1.0\nembrace_deg = 180.0\nthicknes = 0.1\nvoussoirs = 8\n",
        "[arch]\nshape = 'circular'\nradius = 1.0\nembrace_deg = 180.0\nthickness = 0.1\nvoussoirs = 'x'\n",
        "[arch\n",
    ],
    ids=["out_of_range", "unknown_key", "wrong_type", "syntax"],
)
def test_messages_are_the_clis(cli, tmp_path, text):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    p = cli("analyze", path, check=False)
    assert p.returncode != 0 and p.stdout == ""
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_toml(str(path))
    assert p.stderr.strip() == f"error: {e.value}"
    assert e.value.origin == str(path)


def test_unreadable_file():
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.Scene.from_toml("/no/such/scene.toml")
    assert e.value.kind == "io" and e.value.origin == "/no/such/scene.toml"


def test_bad_options_are_value_errors():
    scene = voussoir.Scene.from_toml(str(SEMI))
    with pytest.raises(ValueError, match="direction `up`"):
        voussoir.analyze(scene, direction="up")
    with pytest.raises(ValueError, match="kinematic `fast`"):
        voussoir.analyze(scene, kinematic="fast")


def test_deeply_nested_dict_is_a_value_error_not_a_crash():
    # Issue 26: a dict nested 10,000 deep overflowed the native stack (a segfault).
    deep = {}
    inner = deep
    for _ in range(10_000):
        inner["x"] = {}
        inner = inner["x"]
    with pytest.raises(ValueError, match="nested more than 32 levels"):
        voussoir.Scene.from_dict({"arch": deep})
    # A list inside itself, and a deep list in with_values.
    loop = []
    loop.append(loop)
    with pytest.raises(ValueError, match="nested"):
        voussoir.Scene.from_dict({"arch": {"radius": loop}})
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "semicircular.toml"))
    nested = 1.0
    for _ in range(1000):
        nested = [nested]
    with pytest.raises(ValueError, match="arch.thickness"):
        scene.with_values({"arch.thickness": nested})
    # Ordinary nesting (a blocks scene: a list of polygons of points) is untouched.
    square = [[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]]
    voussoir.Scene.from_dict({"blocks": {"polygons": square}})


def test_scenes_and_results_draw_inline():
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "loaded_portal.toml"))
    svg = scene._repr_svg_()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg and "10 kN" in svg
    r = voussoir.analyze(scene)
    svg = r._repr_svg_()
    assert "λ (static lower bound) = " in svg and "thrust line" in svg
    assert "lambda_lower" not in svg
    # The same drawing as `analyze --svg`: the library draws both.
    assert svg == voussoir._voussoir.analysis_svg(scene)
    # A report without a scene (min-thickness) has no picture; one from a pickle neither.
    import pickle
    assert pickle.loads(pickle.dumps(r))._repr_svg_() is None
