"""`sweep` gives the rows of `voussoir sweep` (same columns, same numbers), refuses what the
CLI refuses with the same message, runs at the CLI's speed, and releases the GIL."""

import csv
import io
import threading
import time

import pytest

import voussoir
from conftest import REPO

SEMI = REPO / "data" / "semicircular.toml"


def cli_rows(cli, *args):
    text = cli("sweep", *args).stdout
    return list(csv.DictReader(io.StringIO(text)))


def same_cell(py, text):
    """A CSV cell (text; empty for a missing number) and the Python value."""
    if py is None:
        return text == ""
    if isinstance(py, bool):
        return text == str(py).lower()
    if isinstance(py, (int, float)):
        ref = float(text)
        return abs(py - ref) <= 1e-12 * max(1.0, abs(ref))
    return py == text


@pytest.mark.parametrize(
    "scene, vary, args",
    [
        (
            "semicircular.toml",
            {"arch.thickness": "0.08:0.2:0.02", "arch.voussoirs": [8, 16, 31]},
            ["--vary", "arch.thickness=0.08:0.2:0.02", "--vary", "arch.voussoirs=8,16,31",
             "--continuous"],
        ),
        (
            "pointed.toml",
            {"e/R": [0.0, 0.1, 0.2], "t/R": [0.1, 0.15]},
            ["--vary", "e/R=0,0.1,0.2", "--vary", "t/R=0.1,0.15", "--continuous"],
        ),
        (
            "portal.toml",
            {"piers.height": [0.5, 1.0], "material.friction": ["inf", 0.4]},
            ["--vary", "piers.height=0.5,1.0", "--vary", "material.friction=inf,0.4",
             "--continuous"],
        ),
    ],
    ids=["thickness-voussoirs", "pointed-ratios", "portal-friction"],
)
def test_rows_equal_cli_csv(cli, scene, vary, args):
    path = REPO / "data" / scene
    ref = cli_rows(cli, path, *args)
    rows = voussoir.sweep(voussoir.Scene.from_toml(str(path)), vary, continuous=True)
    assert len(rows) == len(ref) > 0
    for row, r in zip(rows, ref):
        assert list(row) == list(r)  # the same columns in the same order
        for k in r:
            if k != "solve_time_s":
                assert same_cell(row[k], r[k]), (k, row[k], r[k])


def test_invalid_cases_stay_as_rows():
    rows = voussoir.sweep(voussoir.Scene.from_toml(str(SEMI)), {"arch.thickness": [0.1, -1.0]})
    assert [r["status"] for r in rows] == ["cannot_stand", "error"]
    assert "arch.thickness" in rows[1]["error"] and rows[1]["lambda_lower"] is None


@pytest.mark.parametrize(
    "vary, arg, key, value",
    [
        ({"arch.thickness": [0.1, "abc"]}, "arch.thickness=0.1,abc", "arch.thickness", "abc"),
        ({"arch.thicknes": [0.1]}, "arch.thicknes=0.1", "arch.thicknes", "0.1"),
        ({"t/Q": [0.1]}, "t/Q=0.1", "t/Q", None),
    ],
    ids=["wrong-type", "unknown-key", "unknown-ratio"],
)
def test_refused_like_the_cli(cli, vary, arg, key, value):
    p = cli("sweep", SEMI, "--vary", arg, check=False)
    assert p.returncode != 0
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.sweep(voussoir.Scene.from_toml(str(SEMI)), vary)
    assert p.stderr.strip() == f"error: {e.value}"
    assert (e.value.kind, e.value.key, e.value.value) == ("bad_variation", key, value)


def test_values_as_numpy_range_and_scalar():
    np = pytest.importorskip("numpy")
    scene = voussoir.Scene.from_toml(str(SEMI))
    a = voussoir.sweep(scene, {"arch.thickness": np.array([0.12, 0.16]), "arch.voussoirs": 16})
    b = voussoir.sweep(scene, {"arch.thickness": "0.12,0.16", "arch.voussoirs": range(16, 17)})
    strip = lambda rows: [{k: v for k, v in r.items() if k != "solve_time_s"} for r in rows]
    assert strip(a) == strip(b) and len(a) == 2
    assert type(a[0]["arch.voussoirs"]) is int


def test_as_frame():
    pd = pytest.importorskip("pandas")
    scene = voussoir.Scene.from_toml(str(SEMI))
    vary = {"arch.thickness": [0.12, 0.16, 0.2]}
    df = voussoir.sweep(scene, vary, as_frame=True)
    assert isinstance(df, pd.DataFrame) and len(df) == 3
    rows = voussoir.sweep(scene, vary)
    assert list(df.columns) == list(rows[0])
    assert df["lambda_lower"].tolist() == [r["lambda_lower"] for r in rows]
    assert voussoir.sweep_frame(scene, vary)["status"].tolist() == ["collapse"] * 3


# A sweep of 1,000 cases (256 voussoirs; the static bound, the certified kinematic bound).
SPEED_ARGS = ("arch.thickness", "0.1:0.2998:0.0002")


def test_a_thousand_cases_at_the_speed_of_the_cli(cli, tmp_path):
    """The same 1,000 cases from Python and from the CLI (which also starts a process, reads
    the scene and writes a CSV): best of three runs each, interleaved; Python within 20 %."""
    scene = voussoir.Scene.from_toml(str(SEMI)).with_values({"arch.voussoirs": 256})
    out = tmp_path / "sweep.csv"
    key, spec = SPEED_ARGS
    cli_args = ["sweep", SEMI, "--set", "arch.voussoirs=256", "--vary", f"{key}={spec}",
                "--csv", out]
    py_times, cli_times = [], []
    for _ in range(3):
        t = time.perf_counter()
        cli(*cli_args)
        cli_times.append(time.perf_counter() - t)
        t = time.perf_counter()
        rows = voussoir.sweep(scene, {key: spec})
        py_times.append(time.perf_counter() - t)
    assert len(rows) == 1000 == len(out.read_text().splitlines()) - 1
    ratio = min(py_times) / min(cli_times)
    print(f"1000 cases: Python {min(py_times):.3f} s, CLI {min(cli_times):.3f} s, ratio {ratio:.2f}")
    assert ratio <= 1.2, (py_times, cli_times)


def test_the_gil_is_released_while_solving():
    """Python code runs on while a sweep solves in another thread."""
    # Long enough to measure (the chain program solves a 1000-voussoir case in under 1 ms).
    scene = voussoir.Scene.from_toml(str(SEMI)).with_values({"arch.voussoirs": 1000})
    done = threading.Event()
    ticks = 0

    def solve():
        voussoir.sweep(scene, {"arch.thickness": "0.1:0.2999:0.0001"})
        done.set()

    worker = threading.Thread(target=solve)
    start = time.perf_counter()
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    elapsed = time.perf_counter() - start
    # With the GIL held the loop would not run at all until the sweep returned.
    assert elapsed > 0.05 and ticks >= 10, (elapsed, ticks)


def test_too_many_cases_are_refused_before_any_is_built(cli):
    """Three ranges of 2,000 values: 8e9 cases, refused at once like the CLI (not allocated,
    which would end the interpreter)."""
    vary = {
        "arch.thickness": "0.1:0.2999:0.0001",
        "arch.radius": "1:2.999:0.001",
        "material.unit_weight": "1:2000:1",
    }
    with pytest.raises(voussoir.SceneError) as e:
        voussoir.sweep(voussoir.Scene.from_toml(str(SEMI)), vary)
    assert e.value.kind == "bad_variation"
    assert "2000 x 2000 x 2000 values make 8000000000 cases" in str(e.value)
    args = [a for k, v in vary.items() for a in ("--vary", f"{k}={v}")]
    p = cli("sweep", SEMI, *args, check=False)
    assert p.returncode != 0
    assert p.stderr.strip() == f"error: {e.value}"
