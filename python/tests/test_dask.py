"""A sweep mapped over a Dask cluster of two worker processes (docs/python.md) gives the
rows of the local sweep."""

import pytest

import voussoir
from conftest import REPO

distributed = pytest.importorskip("distributed")


def chunk_rows(scene, vary):
    # Runs on a worker: the scene arrives pickled (as its TOML).
    return voussoir.sweep(scene, vary)


def test_dask_local_cluster_equals_local_sweep():
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "pointed.toml"))
    thicknesses = [round(0.08 + 0.01 * i, 10) for i in range(12)]
    eccentricities = [0.0, 0.1, 0.2]
    local = voussoir.sweep(
        scene, {"arch.eccentricity": eccentricities, "arch.thickness": thicknesses}
    )
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        futures = client.map(
            chunk_rows,
            [scene] * len(eccentricities),
            [{"arch.eccentricity": [e], "arch.thickness": thicknesses} for e in eccentricities],
        )
        remote = [row for rows in client.gather(futures) for row in rows]
        workers = len(client.scheduler_info()["workers"])
    assert workers == 2
    strip = lambda rows: [{k: v for k, v in r.items() if k != "solve_time_s"} for r in rows]
    assert strip(remote) == strip(local)
    assert {r["status"] for r in local} >= {"collapse"}
