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
