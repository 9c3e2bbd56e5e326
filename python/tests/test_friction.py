"""Issue 25: with finite friction a result says whether its multiplier is exact, and when
joints slip at collapse that it is the associative multiplier, an upper bound of the real one
(docs/friction.md)."""

import pytest

import voussoir


def _semicircle(thickness: float, friction: float) -> voussoir.Scene:
    return voussoir.Scene.from_dict(
        {"arch": {"shape": "circular", "radius": 1.0, "thickness": thickness, "voussoirs": 16},
         "material": {"friction": friction}}
    )


def test_a_rocking_arch_is_exact():
    r = voussoir.analyze(_semicircle(0.15, 0.6))
    assert r.status == "collapse" and r.friction_exact is True
    assert r.lambda_associative == pytest.approx(r.lambda_lower, abs=1e-12)
    assert r.slipping_joints == [] and r.friction_note is None
    assert "friction_exact=True" in repr(r) and "friction_note" not in repr(r)


def test_a_sliding_arch_is_an_upper_bound_in_words():
    r = voussoir.analyze(_semicircle(0.25, 0.4))
    assert r.status == "collapse" and r.friction_exact is False
    assert r.lambda_associative == r.lambda_lower
    assert r.slipping_joints and set(r.slipping_joints) <= set(r.sliding)
    assert "upper bound of the real (non-associative) collapse multiplier" in r.friction_note
    text = repr(r)
    assert "friction_exact=False" in text and "not a safe lower bound" in text


def test_the_non_associative_multiplier_and_the_friction_keyword():
    # The sliding arch: the non-associative multiplier is computed by default, at most the
    # associative one, and it governs; "associative" leaves it out; an unknown word is refused.
    scene = _semicircle(0.25, 0.4)
    r = voussoir.analyze(scene)
    assert r.non_associative_converged is True
    assert r.lambda_non_associative <= r.lambda_associative + 1e-9
    assert r.lambda_governing == r.lambda_non_associative
    assert [s["start"] for s in r.non_associative_starts] == [
        "associative", "least_friction", "at_rest"]
    off = voussoir.analyze(scene, friction="associative")
    assert off.lambda_non_associative is None and off.lambda_governing == off.lambda_lower
    with pytest.raises(voussoir.AnalysisError):
        voussoir.analyze(scene, friction="dilatant")
    # The same numbers as the command line's (the library answers both).
    cli = voussoir.analyze(scene, friction="non-associative")
    assert cli.lambda_non_associative == pytest.approx(r.lambda_non_associative, rel=1e-6)
