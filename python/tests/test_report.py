"""voussoir.report (issue 27): the hand-in report from Python is the CLI's for the scene as
``Scene.to_toml()`` writes it: the same JSON (wall times and where the scene came from
aside), the same hash, a page that fetches nothing."""

import hashlib
import json

import voussoir

from conftest import REPO, assert_same


def test_report_is_the_clis_for_the_same_toml(cli, tmp_path):
    scene = voussoir.Scene.from_toml(REPO / "data" / "assess_portal.toml")
    r = voussoir.report(scene, site={"ag": 0.2})
    text = scene.with_values({"site.ag": 0.2}).to_toml()
    assert r.scene_sha256 == hashlib.sha256(text.encode()).hexdigest()
    assert r.html.startswith("<!DOCTYPE html>")
    assert "http://" not in r.html and "https://" not in r.html and "<script" not in r.html
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    ref = json.loads(cli("report", path, "--json").stdout)
    py = r.to_dict()
    for d in (py, ref):
        d.pop("wall_time_s")
        for part in ("analysis", "min_thickness", "assessment"):
            d[part]["scene"].pop("origin")
    assert_same(py, ref)
    assert r.assessment["passes"] == ref["assessment"]["passes"]
    r.save(tmp_path / "r.html")
    assert (tmp_path / "r.html").read_text(encoding="utf-8") == r.html
