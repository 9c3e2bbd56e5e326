"""A sweep mapped over a Dask cluster of two worker processes (docs/python.md) gives the
rows of the local sweep."""

import pytest

import voussoir
from voussoir import _dask
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


def test_sweep_with_a_client_gives_the_local_rows_in_chunks():
    # `client=` splits the product into chunks on any case boundary (here across both keys:
    # chunks of 5 cases over 3 x 7 thicknesses), after a local pilot; the rows come back in
    # the local order. A string in the CLI's syntax is expanded as the local sweep does.
    from voussoir import _dask

    scene = voussoir.Scene.from_toml(str(REPO / "data" / "pointed.toml"))
    vary = {"arch.eccentricity": [0.0, 0.1, 0.2], "arch.thickness": "0.08:0.14:0.01"}
    local = voussoir.sweep(scene, vary)
    assert len(local) == 21
    strip = lambda rows: [{k: v for k, v in r.items() if k != "solve_time_s"} for r in rows]
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        chunked = voussoir.sweep(scene, vary, client=client, chunk=5, progress=False)
        sized = voussoir.sweep(scene, vary, client=client)
        rows, plan = _dask.sweep(
            client, scene, vary, (False, False, "certified", 200), chunk=5, progress=False
        )
    assert strip(chunked) == strip(local)
    assert strip(sized) == strip(local)
    assert strip(rows) == strip(local)
    # With a given chunk the pilot is one case, then ceil(20 / 5) chunks run remotely.
    assert plan.pilot_cases == 1 and plan.chunk_cases == 5 and plan.chunks == 4
    assert plan.overhead_s > 0.0 and plan.case_s > 0.0


def test_chunks_cover_the_product_in_order():
    from voussoir._dask import _pieces, chunk_cases

    sizes = [3, 4, 5]
    flat = [(i, j, k) for i in range(3) for j in range(4) for k in range(5)]
    for lo in range(0, 61, 7):
        for hi in range(lo, 61, 11):
            cases = [
                (i, j, k)
                for (a, b), (c, d), (e, f) in _pieces(sizes, lo, hi)
                for i in range(a, b) for j in range(c, d) for k in range(e, f)
            ]
            assert cases == flat[lo:hi]
    # The rule: the overhead within 10 % of a chunk's work.
    h, c = 0.002, 3e-5
    m = chunk_cases(h, c)
    assert h <= 0.10 * m * c + 1e-15 and h > 0.10 * (m - 1) * c


def test_the_text_progress_bar_counts_to_the_total(capsys):
    from voussoir._dask import _TextBar

    bar = _TextBar(10, "sweep")
    bar.update(4)
    bar.update(6)
    bar.close()
    err = capsys.readouterr().err
    assert "sweep: 4/10 (40 %)" in err and "sweep: 10/10 (100 %)" in err


def test_fragility_with_a_client_gives_the_local_samples_and_curve():
    # `fragility(..., client=)`: the samples in chunks on the cluster (after a local pilot),
    # the fit made from all of them here: the local document, sample for sample.
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "fragility_portal.toml"))
    local = voussoir.fragility(scene, samples=18, seed=5)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        chunked = voussoir.fragility(scene, samples=18, seed=5, client=client, chunk=4, progress=False)
        sized = voussoir.fragility(scene, samples=18, seed=5, client=client, progress=False)
    assert chunked.to_dict() == local.to_dict()
    assert sized.to_dict() == local.to_dict()
    assert chunked.svg == local.svg


def test_the_dynamic_route_with_a_client_maps_its_runs_and_gives_the_local_document():
    # `fragility(..., records=, stripes=, client=)`: one DEM run per case (a sample under one
    # record at one stripe), the samples made from all runs here: the local document.
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "fragility_portal.toml"))
    records = REPO / "data" / "records"
    kwargs = dict(samples=3, seed=2, records=records, stripes=[0.1, 0.6])
    local = voussoir.fragility(scene, **kwargs)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        one = voussoir.fragility(scene, client=client, chunk=1, progress=False, **kwargs)
        # Chunks of 3 runs: each spans two samples (2 runs a sample).
        sized = voussoir.fragility(scene, client=client, chunk=3, progress=False, **kwargs)
    assert one.to_dict() == local.to_dict()
    assert sized.to_dict() == local.to_dict()
    assert one.svg == local.svg
    # No run on the client: no pilot, one run a chunk.
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        samples, plan = _dask.fragility(
            client, scene, 3, 2, str(records), [0.1, 0.6], progress=False
        )
    assert (plan.cases, plan.pilot_cases, plan.chunk_cases, plan.chunks) == (6, 0, 1, 6)
    table = local.to_dict()["samples"]
    assert [s["values"] for s in samples] == [s["values"] for s in table]
    # The document counts each sample's collapses at each stripe over the records.
    assert [[sum(c) for c in s["collapsed"]] for s in samples] == [s["collapses"] for s in table]
    # 3 samples x 2 stripes x 1 record: the runs numbered sample, stripe, record.
    assert voussoir._voussoir.fragility_run_count(scene, 3, 2, str(records), [0.1, 0.6]) == 6
    with pytest.raises(voussoir.AnalysisError, match="run range"):
        voussoir._voussoir.fragility_runs_json(scene, 3, 2, str(records), [0.1, 0.6], 5, 7)


def test_a_refused_sample_is_said_on_the_client_before_any_run_goes_out():
    # Samples are refused, never truncated: with a coefficient of variation of 2 some
    # thicknesses are negative, and the dynamic route on a cluster says so before it maps
    # its runs (the local route checks every sample before its runs too).
    text = (REPO / "data" / "fragility_portal.toml").read_text()
    head = text.split("[uncertain]")[0]
    wide = head + '[uncertain]\n"arch.thickness" = { dist = "normal", mean = 0.2, cov = 2.0 }\n'
    scene = voussoir.Scene.from_toml_str(wide, "wide")
    records = str(REPO / "data" / "records")
    with pytest.raises(voussoir.AnalysisError, match="refused, not truncated"):
        voussoir._voussoir.fragility_run_count(scene, 20, 1, records, [0.1, 0.6])
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        with pytest.raises(voussoir.AnalysisError, match="arch.thickness = -"):
            voussoir.fragility(
                scene, samples=20, records=records, stripes=[0.1, 0.6], client=client,
                progress=False,
            )


def failing_run(lo, hi, *, bad):
    # Runs on a worker process: the numbers lo..hi-1, or an error in the chunk holding `bad`.
    if lo <= bad < hi:
        raise ValueError(f"case {bad} refused")
    return list(range(lo, hi))


def test_an_error_on_a_worker_reaches_the_client_and_cancels_the_other_chunks():
    # Each chunk comes back as one pickle (_packed); an exception raised in a worker process
    # still reaches the caller as itself, and the chunks still out are cancelled. The tasks
    # keep the run's name.
    import time

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        out, plan = _dask.map_chunked(
            client, 30, failing_run, {"bad": -1}, chunk=3, pilot=False, progress=False
        )
        assert out == list(range(30))
        assert (plan.chunk_cases, plan.chunks, plan.pilot_cases) == (3, 10, 0)
        with distributed.get_task_stream(client) as ts:
            with pytest.raises(ValueError, match="case 17 refused"):
                _dask.map_chunked(
                    client, 300, failing_run, {"bad": 17}, chunk=3, pilot=False, progress=False
                )
        deadline = time.monotonic() + 10.0
        left = None
        while time.monotonic() < deadline:
            left = client.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks))
            if left == 0:
                break
            time.sleep(0.05)
        assert left == 0, f"{left} tasks left on the scheduler"
        # The overhead probe's empty tasks aside, every task is named after the run.
        keys = {str(t["key"]) for t in ts.data if not str(t["key"]).startswith("_noop")}
        assert keys and all(k.startswith("failing_run-") for k in keys), keys
