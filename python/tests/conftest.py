"""Shared fixtures: the repository, its bundled scenes, and the command-line binary the
Python results are compared with (built by cargo when needed, or given by $VOUSSOIR_CLI)."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENES = sorted((REPO / "data").glob("*.toml"))


def _build_cli() -> Path:
    given = os.environ.get("VOUSSOIR_CLI")
    if given:
        return Path(given)
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.skip("cargo not found: set VOUSSOIR_CLI to the voussoir binary")
    subprocess.run(
        [cargo, "build", "--release", "--quiet", "--bin", "voussoir"],
        cwd=REPO,
        check=True,
    )
    meta = subprocess.run(
        [cargo, "metadata", "--no-deps", "--format-version", "1"],
        cwd=REPO,
        check=True,
        capture_output=True,
        text=True,
    )
    return Path(json.loads(meta.stdout)["target_directory"]) / "release" / "voussoir"


@pytest.fixture(scope="session")
def cli():
    """Run the CLI: cli(*args) -> CompletedProcess (text, not checked)."""
    binary = _build_cli()
    assert binary.exists(), binary

    def run(*args, check=True):
        p = subprocess.run(
            [str(binary), *map(str, args)], cwd=REPO, capture_output=True, text=True
        )
        if check and p.returncode != 0:
            raise AssertionError(f"voussoir {' '.join(map(str, args))}: {p.stderr}")
        return p

    run.binary = binary
    return run


def is_timing(key: str) -> bool:
    """Wall times, which differ from run to run."""
    return key.endswith("_time_s")


def assert_same(py, ref, path="$", tol=1e-12):
    """`py` equals the JSON value `ref`: numbers to `tol` relative to max(1, |ref|), every
    other value exactly, the same keys; wall times (`*_time_s`) left out."""
    if isinstance(ref, dict):
        assert isinstance(py, dict), f"{path}: {py!r} is not an object"
        keys = {k for k in ref if not is_timing(k)}
        assert keys == {k for k in py if not is_timing(k)}, f"{path}: keys differ"
        for k in keys:
            assert_same(py[k], ref[k], f"{path}.{k}", tol)
    elif isinstance(ref, list):
        assert isinstance(py, list) and len(py) == len(ref), f"{path}: lengths differ"
        for i, (a, b) in enumerate(zip(py, ref)):
            assert_same(a, b, f"{path}[{i}]", tol)
    elif isinstance(ref, float) or (isinstance(ref, int) and not isinstance(ref, bool)
                                    and isinstance(py, float)):
        assert isinstance(py, (int, float)) and not isinstance(py, bool), f"{path}: {py!r}"
        assert abs(py - ref) <= tol * max(1.0, abs(ref)), f"{path}: {py!r} != {ref!r}"
    else:
        assert py == ref, f"{path}: {py!r} != {ref!r}"
