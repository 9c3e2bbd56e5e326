#!/usr/bin/env bash
# The Dask figures of docs/performance.md ("Sweeps on Dask", "Fragility") on a many-core
# machine, as one run: `voussoir.sweep(..., client=...)` on LocalClusters of 1 to 16 workers
# with map_chunked as it was (each chunk's rows returned as a list) and as it is (one pickle
# per chunk), the task stream of the 16-worker sweep, and the dynamic route's weak scaling at
# 16 workers. Needs, in CARRY (default .devcarry): wheels/ (the voussoir wheel and dask,
# distributed and their pure-Python dependencies, for a machine with no registry: `maturin
# build --release` in python/, and `pip download --no-deps --only-binary=:all:
# --python-version 3.12 dask distributed tornado tblib zict locket partd` for a Python 3.12
# machine), _dask_before.py (`git show 499d10a:python/voussoir/_dask.py`, map_chunked before
# the change) and records5/ (`voussoir
# records --site ag=0.25 --site soil=B --site F0=2.4 --site Tc_star=0.3 --count 7 --duration
# 5 --seed 3`). Output: text files in OUT (default the current directory).
set -uo pipefail
CARRY=${CARRY:-.devcarry}
OUT=${OUT:-.}
PY=${PY:-python3}
{
    echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)"
    grep -m1 "model name" /proc/cpuinfo
    $PY --version
} > "$OUT/machine.txt" 2>&1
$PY -m pip install -q --no-index --no-deps "$CARRY"/wheels/*.whl >> "$OUT/machine.txt" 2>&1
site=$($PY -c "import os, voussoir; print(os.path.dirname(voussoir.__file__))")
cp "$site/_dask.py" /tmp/_dask_after.py
cp "$CARRY/_dask_before.py" "$site/_dask.py"
REPS=${REPS:-2} timeout 240 $PY python/benchmarks/dask_scaling.py 1,2,4,8,16 0.0000625 > "$OUT/sweep-before.txt" 2>&1
cp /tmp/_dask_after.py "$site/_dask.py"
REPS=${REPS:-2} timeout 180 $PY python/benchmarks/dask_scaling.py 1,2,4,8,16 0.0000625 > "$OUT/sweep-after.txt" 2>&1
timeout 90 $PY python/benchmarks/dask_sweep_probe.py 16 0.0000625 > "$OUT/sweep-probe.txt" 2>&1
timeout 120 $PY python/benchmarks/dask_fragility.py "$CARRY/records5" --workers 16 --stripes 0.3 \
    --samples-per-worker 1 > "$OUT/fragility-16.txt" 2>&1
echo "end: load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)" >> "$OUT/machine.txt"
tail -n 30 "$OUT"/*.txt
