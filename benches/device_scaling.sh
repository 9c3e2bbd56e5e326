#!/usr/bin/env bash
# The scaling figures of issue 28 on a many-core machine, as one run: the sweep of
# benches/sweep_scaling.sh with the binary before and after the parallel case pipeline, and
# the DEM's throughput over a sweep's cases (each case one DEM bracket) on 1, 4 and 16
# threads. Binaries in BIN_DIR (default target/device): voussoir-before, voussoir (stripped
# release builds). Output: Markdown in OUT (default the current directory).
set -uo pipefail
BIN_DIR=${BIN_DIR:-target/device}
OUT=${OUT:-.}
echo "machine: $(nproc) cores, $(uname -m), load $(cut -d' ' -f1-3 /proc/loadavg)" > "$OUT/machine.txt"
grep -m1 "model name" /proc/cpuinfo >> "$OUT/machine.txt" || true
for b in voussoir-before voussoir; do
    VOUSSOIR="$BIN_DIR/$b" REPS=${REPS:-3} bash benches/sweep_scaling.sh > "$OUT/sweep-$b.md" 2>&1
done
TIMEFORMAT=%R
{
    echo "DEM throughput: voussoir sweep data/semicircular.toml --vary arch.thickness=0.10:0.25:0.01 --dem (16 cases, each a DEM bracket to 1 %)"
    echo
    echo "| threads | wall s | cases/s |"
    echo "|---:|---:|---:|"
    for t in 1 4 16; do
        s=$( { time RAYON_NUM_THREADS=$t "$BIN_DIR/voussoir" sweep data/semicircular.toml \
            --vary arch.thickness=0.10:0.25:0.01 --dem --csv "/tmp/dem$t.csv" > /dev/null 2>&1; } 2>&1 )
        echo "| $t | $s | $(awk -v s="$s" 'BEGIN { printf "%.2f", 16 / s }') |"
    done
} > "$OUT/dem.md" 2>&1
cat "$OUT"/machine.txt "$OUT"/sweep-*.md "$OUT"/dem.md
