"""Issue 24: tie rods in a scene and the retrofit design from Python, checked against the
analysis with the designed capacities (docs/retrofit.md)."""

import pytest

import voussoir


def _portal(capacity) -> voussoir.Scene:
    return voussoir.Scene.from_dict(
        {
            "arch": {"shape": "circular", "radius": 1.0, "thickness": 0.2, "voussoirs": 32},
            "piers": {"height": 1.0, "width": 0.4, "courses": 4},
            "ties": [{"from": [-1.0, -0.05], "to": [1.0, -0.05], "capacity": capacity}],
        }
    )


def test_retrofit_reaches_the_target_and_the_analysis_agrees():
    r = voussoir.retrofit(_portal("design"), 0.2)
    assert r.feasible is True
    assert r.lambda_lower == pytest.approx(0.2, rel=1e-6)
    tie = r.ties[0]
    assert tie["needed"] is True and tie["bar"]["diameter_mm"] == 6.0
    again = voussoir.analyze(_portal(tie["capacity_required"]))
    assert again.lambda_lower == pytest.approx(0.2, rel=1e-6)
    assert again.ties[0]["yielded"] is True


def test_an_unreachable_target_says_so():
    r = voussoir.retrofit(_portal("design"), 0.3)
    assert r.feasible is False and r.best_reachable_lambda < 0.3


def test_a_capacity_to_design_is_refused_by_analyze():
    with pytest.raises(voussoir.VoussoirError, match=r"ties\[0\]\.capacity"):
        voussoir.analyze(_portal("design"))
