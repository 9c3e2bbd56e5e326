"""Scaling of the dynamic route of ``voussoir.fragility(..., client=...)`` (issue 30): the
DEM runs of a multiple-stripe analysis of ``data/fragility_portal.toml`` mapped over a
``LocalCluster`` of 1, 2, 4, ... worker processes (one thread each, one core each:
``RAYON_NUM_THREADS=1``); the figures of docs/performance.md ("Fragility").

    python python/benchmarks/dask_fragility.py RECORDS_DIR --workers 1,2,4,8,16 \\
        --stripes 0.3 --samples-per-worker 1
    python python/benchmarks/dask_fragility.py RECORDS_DIR --workers 16 --samples 4 \\
        --stripes 0.05,0.1,0.2,0.25,0.3,0.4,0.5,0.6

With ``--samples-per-worker K`` each worker count ``w`` runs ``K w`` samples (weak scaling:
a one-worker run of the whole study would take the hours this measures); with ``--samples
N`` every count runs ``N``. For each count it prints the wall time, the runs and runs/s, the
chunk plan, and the parallel efficiency: the compute time of every run (on the workers, from
Dask's task stream, plus the client's pilot, which the dynamic route no longer runs) over
``w`` times the wall time. The records: ``voussoir records --site ag=0.25 --site soil=B
--site F0=2.4 --site Tc_star=0.3 --count 7 --duration 5 --seed 3 --out RECORDS`` (or
``--duration 20`` for the benchmark's own). The runs' own
times (shortest, median, longest) show how unevenly they weigh: a run skipped by the rest
test costs milliseconds, one that rocks through a 20 s record seconds.
"""

import argparse
import os
import statistics
import time
from pathlib import Path

# One core per worker process and for the client's pilot.
os.environ["RAYON_NUM_THREADS"] = "1"

import voussoir  # noqa: E402
from voussoir import _dask  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


def counts(text):
    return [int(x) for x in text.split(",") if x]


def main():
    from distributed import Client, LocalCluster, get_task_stream

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("records", help="directory of .AT2 records")
    ap.add_argument("--workers", type=counts, default=[1, 2])
    ap.add_argument("--stripes", default="0.3")
    ap.add_argument("--samples", type=int, default=None)
    ap.add_argument("--samples-per-worker", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    stripes = [float(x) for x in args.stripes.split(",")]
    records = str(Path(args.records).resolve())
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "fragility_portal.toml"))
    n_records = len(list(Path(records).glob("*.AT2")))
    print(
        f"cores: {os.cpu_count()}, load average: {os.getloadavg()}; "
        f"{n_records} records in {records}, stripes {stripes} g",
        flush=True,
    )
    print(
        "| workers | samples | runs | wall s | runs/s | run s (min / median / max) "
        "| compute s | efficiency | pilot runs | chunk x chunks |"
    )
    print("|---:|---:|---:|---:|---:|---|---:|---:|---:|---|")
    for w in args.workers:
        samples = args.samples if args.samples is not None else args.samples_per_worker * w
        with LocalCluster(
            n_workers=w, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster, Client(cluster) as client:
            # Warm the workers (import voussoir, first task) outside the timing.
            client.run(lambda: __import__("voussoir") and None)
            with get_task_stream(client) as ts:
                t0 = time.perf_counter()
                done, plan = _dask.fragility(
                    client, scene, samples, args.seed, records, stripes, progress=False
                )
                wall = time.perf_counter() - t0
        runs = plan.cases
        assert len(done) == samples
        durations = [
            ss["stop"] - ss["start"]
            for task in ts.data
            if str(task.get("key", "")).startswith("fragility_runs")
            for ss in task["startstops"]
            if ss["action"] == "compute"
        ]
        pilot = plan.case_s * plan.pilot_cases
        compute = sum(durations) + pilot
        per_run = sorted(durations)
        spread = (
            f"{per_run[0]:.2f} / {statistics.median(per_run):.2f} / {per_run[-1]:.2f}"
            if per_run
            else "-"
        )
        print(
            f"| {w} | {samples} | {runs} | {wall:.1f} | {runs / wall:.2f} | {spread} "
            f"| {compute:.1f} | {100 * compute / (w * wall):.0f} % | {plan.pilot_cases} "
            f"| {plan.chunk_cases} x {plan.chunks} |",
            flush=True,
        )
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
