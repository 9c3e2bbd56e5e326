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


_SITE = {"ag": 0.25, "soil": "B", "F0": 2.4, "Tc_star": 0.3}


def test_site_design_passes_assess_at_the_site():
    r = voussoir.retrofit(_portal("design"), site=_SITE)
    assert r.site["passes"] is True and r.site["assessment"]["passes"] is True
    tie = r.ties[0]
    assert tie["needed"] is True and tie["capacity_required"] > 0.0
    assert r.site["lambda_needed"] == pytest.approx(r.target_lambda)
    # The designed capacity written into the scene passes `assess` at the same site.
    assert voussoir.assess(_portal(tie["capacity_required"]), site=_SITE).passes is True
    # The scene's own [site] table, without the keyword: the same design.
    sited = _portal("design").with_values({f"site.{k}": v for k, v in _SITE.items()})
    again = voussoir.retrofit(sited)
    assert again.ties[0]["capacity_required"] == pytest.approx(tie["capacity_required"])


def test_site_or_target_but_not_both_nor_neither():
    with pytest.raises(ValueError, match="not both"):
        voussoir.retrofit(_portal("design"), 0.2, site=_SITE)
    with pytest.raises(ValueError, match="target_lambda"):
        voussoir.retrofit(_portal("design"))


def _portal_with_strip(capacity) -> voussoir.Scene:
    return voussoir.Scene.from_dict(
        {
            "arch": {"shape": "circular", "radius": 1.0, "thickness": 0.2, "voussoirs": 32},
            "piers": {"height": 1.0, "width": 0.4, "courses": 4},
            "reinforcements": [
                {
                    "face": "extrados",
                    "from_joint": 0,
                    "to_joint": 32,
                    "tensile_capacity": capacity,
                }
            ],
        }
    )


def test_strips_are_designed_and_the_analysis_agrees():
    r = voussoir.retrofit(_portal_with_strip("design"), 0.2)
    assert r.feasible is True and r.ties == []
    strip = r.reinforcements[0]
    assert strip["needed"] is True and "bar" not in strip
    assert r.lambda_lower == pytest.approx(0.2, rel=1e-6)
    again = voussoir.analyze(_portal_with_strip(strip["capacity_required"]))
    assert again.lambda_lower == pytest.approx(0.2, rel=1e-6)
    with pytest.raises(voussoir.AnalysisError, match="strips"):
        voussoir.retrofit(_portal_with_strip("design"), site=_SITE)
