"""Arcades and spandrel walls (`[arcade]`, `[spandrel]`) from Python: the scene keys pass
through as any other, and the numbers are the CLI's."""

import csv
import io
import json

import voussoir
from conftest import REPO

ARCADE = REPO / "data" / "arcade.toml"


def test_the_arcade_analyses_as_the_cli(cli):
    result = voussoir.analyze(voussoir.Scene.from_toml(str(ARCADE))).to_dict()
    ref = json.loads(cli("analyze", ARCADE, "--json").stdout)
    assert result["lambda_lower"] == ref["lambda_lower"]
    assert result["scene"]["arcade"] == ref["scene"]["arcade"] == {"bays": 3, "column_width": 0.5}
    assert result["scene"]["spandrel"] == ref["scene"]["spandrel"]
    assert result["scene"]["spandrel"]["pieces"] > 0


def test_one_bay_without_a_wall_is_the_portal():
    d = voussoir.Scene.from_toml(str(ARCADE)).to_dict()
    d.pop("spandrel")
    d["arcade"]["bays"] = 1
    portal = {k: v for k, v in d.items() if k != "arcade"}
    one = voussoir.analyze(voussoir.Scene.from_dict(d)).to_dict()["lambda_lower"]
    bare = voussoir.analyze(voussoir.Scene.from_dict(portal)).to_dict()["lambda_lower"]
    assert one == bare


def test_a_sweep_over_the_bays_gives_the_cli_rows(cli):
    rows = voussoir.sweep(voussoir.Scene.from_toml(str(ARCADE)), {"arcade.bays": [1, 2]})
    ref = list(csv.DictReader(io.StringIO(cli("sweep", ARCADE, "--vary", "arcade.bays=1,2").stdout)))
    assert len(rows) == len(ref) == 2
    for row, r in zip(rows, ref):
        assert float(row["arcade.bays"]) == float(r["arcade.bays"])
        assert abs(row["lambda_lower"] - float(r["lambda_lower"])) <= 1e-12
