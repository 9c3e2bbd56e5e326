"""Where the time of ``voussoir.sweep(..., client=...)`` goes on a ``LocalCluster``: the
phases seen from the client (overhead probe, pilot, submission, each chunk's arrival), and
from the workers (Dask's task stream: which worker computed each chunk, when, and how long
the result took to serialise and transfer). Diagnoses docs/performance.md, "Sweeps on Dask".

    python python/benchmarks/dask_sweep_probe.py [COUNT,COUNT,...] [THICKNESS_STEP]

Every process on one core (``RAYON_NUM_THREADS=1``), one thread per worker process.
"""

import os
import statistics
import sys
import time

os.environ["RAYON_NUM_THREADS"] = "1"

import voussoir  # noqa: E402
from voussoir import _dask  # noqa: E402

# The same sweep, comparison and warmed cluster as the scaling benchmark beside this file.
from dask_scaling import strip, study, warm_cluster  # noqa: E402


def summary(name, xs):
    if not xs:
        return f"{name}: none"
    xs = sorted(xs)
    return (
        f"{name}: n {len(xs)} sum {sum(xs):.3f} min {xs[0]:.4f} "
        f"median {statistics.median(xs):.4f} max {xs[-1]:.4f}"
    )


def probe(client, scene, vary, options, workers):
    from distributed import get_task_stream

    clock = {}
    real_map = client.map

    def timed_map(*a, **k):
        clock["submit"] = time.perf_counter()
        out = real_map(*a, **k)
        clock["submitted"] = time.perf_counter()
        return out

    client.map = timed_map
    t0 = time.perf_counter()
    try:
        with get_task_stream(client) as ts:
            rows, plan = _dask.sweep(client, scene, vary, options, progress=False)
        t1 = time.perf_counter()
    finally:
        client.map = real_map
    tasks = [t for t in ts.data if str(t.get("key", "")).startswith("sweep_range")]
    per_worker = {}
    compute, transfer, serial = [], [], []
    first, last = float("inf"), 0.0
    for t in tasks:
        per_worker[t["worker"]] = per_worker.get(t["worker"], 0) + 1
        for s in t["startstops"]:
            d = s["stop"] - s["start"]
            if s["action"] == "compute":
                compute.append(d)
                first = min(first, s["start"])
                last = max(last, s["stop"])
            elif s["action"] == "transfer":
                transfer.append(d)
            else:
                serial.append(d)
    print(
        f"  {workers} workers: {t1 - t0:.2f} s for {len(rows)} rows; plan {plan}; "
        f"submit at {clock.get('submit', t0) - t0:.3f} s, map returned after "
        f"{clock.get('submitted', t0) - clock.get('submit', t0):.3f} s"
    )
    print(f"    tasks {len(tasks)} on {len(per_worker)} workers: {sorted(per_worker.values())}")
    print("    " + summary("compute s", compute))
    print("    " + summary("transfer s", transfer))
    print("    " + summary("other s (serialise, ...)", serial))
    if compute:
        print(
            f"    compute window {last - first:.3f} s; the sweep ended "
            f"{t1 - t0:.3f} s after it began"
        )
    return rows


def main():
    counts = [int(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "1,2").split(",")]
    scene, vary, options = study(sys.argv[2] if len(sys.argv) > 2 else "0.0002")
    t0 = time.perf_counter()
    local = voussoir.sweep(scene, vary)
    print(f"cores {os.cpu_count()}, load {os.getloadavg()}")
    print(f"local sweep, one core: {len(local)} rows in {time.perf_counter() - t0:.2f} s")
    for w in counts:
        with warm_cluster(w) as client:
            for rep in range(2):
                rows = probe(client, scene, vary, options, w)
                assert strip(rows) == strip(local), "the cluster's rows differ from the local ones"
        sys.stdout.flush()


if __name__ == "__main__":
    main()
