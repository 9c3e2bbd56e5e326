"""Scaling of ``voussoir.sweep(..., client=...)`` on a ``LocalCluster`` of 1, 2, ... worker
processes (one thread each, one core each: ``RAYON_NUM_THREADS=1``), against the local sweep
on one core; the figures of docs/performance.md ("Sweeps on Dask").

    python python/benchmarks/dask_scaling.py [MAX_WORKERS | COUNT,COUNT,...] [THICKNESS_STEP]

(``8``: every count from 1 to 8; ``1,2,4,8,16``: those counts. ``THICKNESS_STEP``, default
0.0002, the step of the thickness: 0.0000625 gives 97,971 cases, enough chunks for 16
workers. ``REPS`` in the environment, default 3, the runs of which the best is kept.)

Prints, per worker count, the best of ``REPS`` (default three) wall times, the chunk plan (measured per-task
overhead, per-case cost, cases per chunk) and the speed-up over the local sweep, with the
load average of the machine (other jobs share it).
"""

import os
import sys
import time
from contextlib import contextmanager
from pathlib import Path

# One core per worker process and for the local sweep: the speed-up is then the workers'.
os.environ["RAYON_NUM_THREADS"] = "1"

import voussoir  # noqa: E402
from voussoir import _dask  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


def best_of(n, f):
    times, out = [], None
    for _ in range(n):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def study(step):
    """The benchmark's sweep: the scene, the varied keys (thickness step `step`, a string)
    and the options of ``_dask.sweep``."""
    scene = voussoir.Scene.from_toml(str(REPO / "data" / "pointed.toml"))
    vary = {"arch.eccentricity": "0:0.2:0.004", "arch.thickness": f"0.08:0.2:{step}"}
    options = (False, False, "certified", voussoir.KINEMATIC_DEFAULT_MAX_JOINTS)
    return scene, vary, options


def strip(rows):
    """The rows without their wall times, to compare two sweeps."""
    return [{k: v for k, v in r.items() if k != "solve_time_s"} for r in rows]


@contextmanager
def warm_cluster(workers):
    """A client of a ``LocalCluster`` of `workers` one-thread worker processes that have
    imported voussoir (outside any timing)."""
    from distributed import Client, LocalCluster

    with LocalCluster(
        n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, Client(cluster) as client:
        client.run(lambda: __import__("voussoir") and None)
        yield client


def main():
    arg = sys.argv[1] if len(sys.argv) > 1 else str(os.cpu_count() or 1)
    if "," in arg:
        worker_counts = [int(x) for x in arg.split(",") if x]
    else:
        worker_counts = list(range(1, int(arg) + 1))
    scene, vary, options = study(sys.argv[2] if len(sys.argv) > 2 else "0.0002")
    reps = int(os.environ.get("REPS", "3"))
    local_s, local = best_of(reps, lambda: voussoir.sweep(scene, vary))
    print(f"cores: {os.cpu_count()}, load average: {os.getloadavg()}")
    print(f"local sweep, one core: {len(local)} cases in {local_s:.2f} s (best of {reps})")
    for workers in worker_counts:
        with warm_cluster(workers) as client:
            run = lambda: _dask.sweep(client, scene, vary, options, progress=False)
            t, (rows, plan) = best_of(reps, run)
        assert strip(rows) == strip(local)
        print(
            f"{workers} worker(s): {t:.2f} s, speed-up {local_s / t:.2f}; "
            f"overhead {plan.overhead_s * 1e3:.2f} ms/task, case {plan.case_s * 1e6:.1f} us, "
            f"chunk {plan.chunk_cases} cases x {plan.chunks} (pilot {plan.pilot_cases}), "
            f"overhead share {100 * plan.overhead_share:.1f} %; load {os.getloadavg()}"
        )


if __name__ == "__main__":
    main()
