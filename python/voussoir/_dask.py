"""Independent cases mapped over a ``dask.distributed`` client in chunks sized from measured
costs, streamed back with a progress bar, returned in order (private: ``voussoir.sweep``'s
``client=``, and whatever maps many cases).

The chunk rule (docs/python.md, "Scaling a study out with Dask"): a task costs the scheduler
and the network a fixed overhead ``h`` (submit, schedule, send the arguments, return the
result), and a chunk of ``m`` cases computes for ``m c``. The overhead stays under the share
``s`` (10 %) of the work when ``h <= s m c``, so a chunk holds

    m = ceil(h / (s c))

cases. ``h`` is measured on the client: the median round trip of a few empty tasks (the
latency a chunk pays, an upper bound of its share of a pipelined stream of tasks). ``c`` is
measured here: the first cases run locally, in chunks of 1, 4, 16, ... cases until
``pilot_s`` seconds have passed (one case at least), and are kept as the first rows (no case runs twice). The
rest is cut into chunks of ``m`` cases (the last one shorter), and each chunk's rows come
back as soon as it is done, as one pickle (``_packed``: a list returned as it is would be
serialised and decoded element by element); the rows are
returned in case order, so the answer is the local one row for row.

dask is imported only when a client is given: it is no dependency of the package (the
``dask`` extra installs it); the progress bar is tqdm's when tqdm is installed, a line of
text on stderr otherwise.
"""

from __future__ import annotations

import math
import pickle
import statistics
import sys
import time
import uuid
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

#: The largest share of a chunk's time the per-task overhead may take.
OVERHEAD_SHARE = 0.10
#: Seconds of local pilot work that measure the cost of a case.
PILOT_S = 0.05
#: Empty tasks timed to measure the per-task overhead.
PROBES = 7


@dataclass(frozen=True)
class Plan:
    """What a chunked map measured and decided (``plan`` of :func:`map_chunked`)."""

    #: Cases mapped (samples, sweep cases, or a fragility's DEM runs on its dynamic route).
    cases: int
    #: Median round trip of an empty task on the client (s).
    overhead_s: float
    #: Cost of one case measured on the pilot (s); 0 when no pilot ran.
    case_s: float
    #: Cases run locally as the pilot.
    pilot_cases: int
    #: Cases per remote chunk, and the number of chunks.
    chunk_cases: int
    chunks: int

    @property
    def overhead_share(self) -> float:
        """The overhead as a share of a full chunk's time, by the measured costs (NaN when
        no pilot measured a case's cost)."""
        if self.case_s <= 0.0:
            # No pilot ran (the case's cost was not measured).
            return float("nan")
        work = self.chunk_cases * self.case_s
        return self.overhead_s / (self.overhead_s + work)


def _noop() -> None:
    return None


def measure_overhead(client: Any, probes: int = PROBES) -> float:
    """The median wall time (s) of submitting an empty task and getting its result back."""
    times = []
    for _ in range(probes):
        t0 = time.perf_counter()
        client.submit(_noop, pure=False).result()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def chunk_cases(overhead_s: float, case_s: float, share: float = OVERHEAD_SHARE) -> int:
    """Cases per chunk so the overhead stays within ``share`` of the work: ``ceil(h/(s c))``."""
    if case_s <= 0.0:
        return 1 << 30
    return max(1, math.ceil(overhead_s / (share * case_s)))


class _TextBar:
    """A progress line on stderr: ``label: done/total (percent)``."""

    def __init__(self, total: int, desc: str):
        self.total, self.desc, self.n = total, desc, 0
        self._draw()

    def _draw(self) -> None:
        pct = 100.0 * self.n / self.total if self.total else 100.0
        sys.stderr.write(f"\r{self.desc}: {self.n}/{self.total} ({pct:.0f} %)")
        sys.stderr.flush()

    def update(self, n: int) -> None:
        self.n += n
        self._draw()

    def close(self) -> None:
        sys.stderr.write("\n")
        sys.stderr.flush()


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass


def _bar(total: int, desc: str, progress: bool):
    if not progress:
        return _NoBar()
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _TextBar(total, desc)
    return tqdm(total=total, desc=desc, unit="case")


def _packed(lo: int, hi: int, *, _run: Callable[..., List[Any]], **kwargs: Any) -> bytes:
    """``_run(lo, hi, **kwargs)`` on a worker, its list of results returned as one pickle.

    Why: a list returned as it is travels element by element through Dask's serialisation
    (a frame for each row, dumped on the worker and loaded on the client in its one
    communication thread): about 30 us a row in all for a sweep's rows (dicts of a dozen
    fields), which bounded every cluster (a 97,971-case sweep took 5.0 s on 1 worker and
    5.8 s on 16; docs/performance.md, "Sweeps on Dask"). One pickle is one frame, a fraction
    of that."""
    return pickle.dumps(_run(lo, hi, **kwargs), protocol=pickle.HIGHEST_PROTOCOL)


def map_chunked(
    client: Any,
    cases: int,
    run: Callable[..., List[Any]],
    kwargs: Optional[Dict[str, Any]] = None,
    *,
    progress: bool = True,
    desc: str = "voussoir",
    share: float = OVERHEAD_SHARE,
    pilot_s: float = PILOT_S,
    chunk: Optional[int] = None,
    pilot: bool = True,
) -> Tuple[List[Any], Plan]:
    """Run ``run(lo, hi, **kwargs)`` (the results of cases ``lo`` to ``hi - 1``, a list of
    ``hi - lo`` items; a module-level function, so that it pickles) over ``range(cases)`` on
    ``client`` in chunks sized by the module's rule (or of ``chunk`` cases when given, after
    a pilot of one case), after a local pilot. ``pilot=False`` (with ``chunk`` given) runs
    no case locally: for cases of seconds each, whose size needs no measuring and whose
    pilot would keep every worker waiting on the client. Returns the results in case order
    and the :class:`Plan`. An error in a chunk cancels the others and is raised here; so
    does Ctrl-C."""
    kwargs = dict(kwargs or {})
    from distributed import as_completed

    if not pilot and chunk is None:
        raise ValueError("map_chunked: pilot=False needs a chunk size")
    if chunk is not None:
        # The chunk is given: the pilot is one case (it still checks the input locally).
        pilot_s = 0.0

    overhead = measure_overhead(client)
    bar = _bar(cases, desc, progress)
    results: List[Any] = []
    futures: List[Any] = []
    try:
        # The pilot: one case, then chunks growing fourfold until pilot_s has passed.
        t0 = time.perf_counter()
        size = 1
        while (
            pilot
            and len(results) < cases
            and (not results or time.perf_counter() - t0 < pilot_s)
        ):
            lo = len(results)
            hi = min(cases, lo + size)
            results.extend(run(lo, hi, **kwargs))
            bar.update(hi - lo)
            size *= 4
        piloted = len(results)
        # 0 when no pilot ran: not measured.
        case_s = (time.perf_counter() - t0) / piloted if piloted else 0.0
        m = chunk if chunk is not None else chunk_cases(overhead, case_s, share)
        m = max(1, int(m))
        bounds = [(lo, min(cases, lo + m)) for lo in range(piloted, cases, m)]
        plan = Plan(cases, overhead, case_s, piloted, m, len(bounds))
        parts: Dict[int, List[Any]] = {}
        if bounds:
            # Each task keeps the run's name (the dashboard's and the task stream's key).
            name = getattr(run, "__name__", "chunk")
            futures = client.map(
                _packed,
                [b[0] for b in bounds],
                [b[1] for b in bounds],
                key=[f"{name}-{uuid.uuid4().hex}" for _ in bounds],
                pure=False,
                _run=run,
                **kwargs,
            )
            index = {f.key: k for k, f in enumerate(futures)}
            for future in as_completed(futures):
                k = index[future.key]
                part = pickle.loads(future.result())
                lo, hi = bounds[k]
                if len(part) != hi - lo:
                    raise RuntimeError(
                        f"a chunk of cases {lo}-{hi - 1} gave {len(part)} results, not {hi - lo}"
                    )
                parts[k] = part
                bar.update(hi - lo)
        for k in range(len(bounds)):
            results.extend(parts[k])
    except BaseException:
        if futures:
            client.cancel(futures)
        raise
    finally:
        bar.close()
    return results, plan


# --- sweeps -------------------------------------------------------------------------------


def _pieces(sizes: Sequence[int], lo: int, hi: int) -> List[List[Tuple[int, int]]]:
    """The cases ``lo`` to ``hi - 1`` of a cartesian product (``sizes`` per key, the last key
    fastest) as a few sub-products, in order: each a list of per-key index ranges."""
    if lo >= hi:
        return []
    if len(sizes) == 1:
        return [[(lo, hi)]]
    inner = math.prod(sizes[1:])
    a, ra = divmod(lo, inner)
    b, rb = divmod(hi, inner)
    if a == b:
        return [[(a, a + 1)] + p for p in _pieces(sizes[1:], ra, rb)]
    out = []
    if ra:
        out += [[(a, a + 1)] + p for p in _pieces(sizes[1:], ra, inner)]
        a += 1
    if b > a:
        out.append([(a, b)] + [(0, n) for n in sizes[1:]])
    if rb:
        out += [[(b, b + 1)] + p for p in _pieces(sizes[1:], 0, rb)]
    return out


def sweep_range(
    lo: int,
    hi: int,
    *,
    scene: Any,
    keys: Sequence[str],
    values: Sequence[Sequence[Any]],
    options: Tuple[Any, ...],
) -> List[Dict[str, Any]]:
    """The rows of cases ``lo`` to ``hi - 1`` of the sweep over the product of ``values``
    (runs on a worker)."""
    from . import _voussoir

    rows: List[Dict[str, Any]] = []
    for piece in _pieces([len(v) for v in values], lo, hi):
        vary = {k: list(v[s:e]) for k, v, (s, e) in zip(keys, values, piece)}
        rows.extend(_voussoir.sweep_rows(scene, vary, *options))
    return rows


def sweep(
    client: Any,
    scene: Any,
    vary: Dict[str, Any],
    options: Tuple[Any, ...],
    **map_options: Any,
) -> Tuple[List[Dict[str, Any]], Plan]:
    """A sweep on ``client``: the rows of the local sweep, in its order."""
    from . import _voussoir

    keys = list(vary)
    values = [list(_voussoir.variation_values(k, vary[k])) for k in keys]
    cases = math.prod(len(v) for v in values) if values else 0
    if cases == 0:
        # Nothing to split: the local sweep says why (no key, or no value).
        return _voussoir.sweep_rows(scene, dict(vary), *options), Plan(0, 0.0, 0.0, 0, 0, 0)
    return map_chunked(
        client,
        cases,
        sweep_range,
        {"scene": scene, "keys": keys, "values": values, "options": tuple(options)},
        desc="sweep",
        **map_options,
    )


def fragility_range(
    lo: int,
    hi: int,
    *,
    scene: Any,
    samples: int,
    seed: int,
    records: Optional[str],
    stripes: Optional[List[float]],
) -> List[Any]:
    """Samples ``lo`` to ``hi - 1`` of a fragility, each with its outcome (runs on a
    worker; the records directory must be readable there)."""
    import json

    from . import _voussoir

    text = _voussoir.fragility_samples_json(scene, samples, seed, records, stripes, lo, hi)
    return json.loads(text)


def fragility_runs(
    lo: int,
    hi: int,
    *,
    scene: Any,
    samples: int,
    seed: int,
    records: str,
    stripes: List[float],
) -> List[bool]:
    """Runs ``lo`` to ``hi - 1`` of a dynamic-route fragility (numbered sample, then stripe,
    then record), whether each collapsed (runs on a worker; the records directory must be
    readable there)."""
    import json

    from . import _voussoir

    text = _voussoir.fragility_runs_json(scene, samples, seed, records, stripes, lo, hi)
    return json.loads(text)


def fragility(
    client: Any,
    scene: Any,
    samples: int,
    seed: int,
    records: Optional[str],
    stripes: Optional[List[float]],
    **map_options: Any,
) -> Tuple[List[Any], Plan]:
    """The samples of a fragility on ``client``, in sample order: those of the local run.

    The capacity route maps its samples (a millisecond each). The dynamic route maps its
    DEM runs, one per sample, stripe and record (seconds each): chunks of whole samples
    (tens of runs) would leave workers idle at the end of a study, as 50 samples over 16
    workers take four rounds, the last a third full."""
    if records is None or stripes is None:
        return map_chunked(
            client,
            samples,
            fragility_range,
            {
                "scene": scene,
                "samples": samples,
                "seed": seed,
                "records": records,
                "stripes": stripes,
            },
            desc="fragility",
            **map_options,
        )
    import json

    from . import _voussoir

    # The checks a pilot would make are made here: the settings, records and stripes, and
    # every sample's scene (milliseconds), so a refused sample is said before any run.
    runs = _voussoir.fragility_run_count(scene, samples, seed, records, stripes)
    # No pilot, one run a chunk unless told: a run costs seconds (milliseconds when the rest
    # test skips it), against a per-task overhead of about 10 ms, and a run computed on
    # the client first would keep every worker waiting for it (12 % of a 16-worker study
    # of 55 s, measured).
    map_options.setdefault("chunk", None)
    if map_options["chunk"] is None:
        map_options["chunk"] = 1
    flags, plan = map_chunked(
        client,
        runs,
        fragility_runs,
        {"scene": scene, "samples": samples, "seed": seed, "records": records, "stripes": stripes},
        desc="fragility runs",
        pilot=False,
        **map_options,
    )
    text = _voussoir.fragility_samples_from_runs_json(
        scene, samples, seed, records, stripes, flags
    )
    return json.loads(text), plan
