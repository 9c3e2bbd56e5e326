#!/usr/bin/env bash
# Issue 28, "sweeps on every core": the wall time of one large `voussoir sweep` (96,641 cases,
# the whole process: start, cases, CSV file) on 1, 2, 4, 8 and 16 threads, and the speed-up
# against one thread, as a Markdown table for docs/performance.md.
#
# Run from the repository root after `cargo build --release`:
#
#     bash benches/sweep_scaling.sh
#
# Settings (environment): THREADS (default "1 2 4 8 16"), REPS (runs per count, the median
# is reported; default 3), VOUSSOIR (the binary; default target/release/voussoir).
# It also checks that every thread count wrote the same rows in the same order (the CSV less
# its wall-time column solve_time_s), and states the machine's cores and load.
set -euo pipefail

VOUSSOIR=${VOUSSOIR:-target/release/voussoir}
THREADS=${THREADS:-1 2 4 8 16}
REPS=${REPS:-3}
SCENE=data/semicircular.toml
VARY=(--vary t/R=0.1:0.5:0.001 --vary arch.embrace_deg=120:240:0.5)

if [[ ! -x $VOUSSOIR ]]; then
    echo "error: $VOUSSOIR not found: run 'cargo build --release' from the repository root first" >&2
    exit 1
fi
if [[ ! -f $SCENE ]]; then
    echo "error: $SCENE not found: run this script from the repository root" >&2
    exit 1
fi
if ! [[ $REPS =~ ^[1-9][0-9]*$ ]]; then
    echo "error: REPS must be a whole number >= 1, not '$REPS'" >&2
    exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The CSV without its solve_time_s column (the only field that changes from run to run); the
# fields before it hold no commas (values, status, numbers, hinges), so cutting is exact.
without_times() {
    local col
    col=$(head -n 1 "$1" | tr ',' '\n' | grep -n -x solve_time_s | cut -d: -f1)
    cut -d, -f"$col" --complement "$1"
}

# Seconds since the epoch, to the nanosecond.
now() { date +%s.%N; }

cores=$(nproc)
echo "Sweep scaling: $VOUSSOIR sweep $SCENE ${VARY[*]} --csv FILE"
echo "Machine: $cores cores ($(uname -m)); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "Median of $REPS runs per thread count; wall time of the whole process."
echo
echo "| threads | wall s (median) | runs (s) | cases/s | speed-up |"
echo "|---:|---:|---|---:|---:|"

one=""
reference=""
cases=""
for t in $THREADS; do
    times=()
    for ((r = 0; r < REPS; r++)); do
        out="$work/t$t.csv"
        start=$(now)
        message=$(RAYON_NUM_THREADS=$t "$VOUSSOIR" sweep "$SCENE" "${VARY[@]}" --csv "$out")
        end=$(now)
        times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')")
    done
    cases=${message%% *}
    median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
    one=${one:-$median}
    rate=$(awk -v n="$cases" -v s="$median" 'BEGIN { printf "%.0f", n / s }')
    speedup=$(awk -v a="$one" -v b="$median" 'BEGIN { printf "%.2f", a / b }')
    echo "| $t | $median | ${times[*]} | $rate | ${speedup}x |"
    # Same rows, same order, whatever the thread count.
    without_times "$out" >"$work/t$t.rows"
    if [[ -z $reference ]]; then
        reference="$work/t$t.rows"
    elif ! cmp -s "$reference" "$work/t$t.rows"; then
        echo "error: the CSV on $t threads differs from the first count's (beyond solve_time_s)" >&2
        exit 1
    fi
done
echo
echo "$cases cases; every thread count wrote the same rows in the same order."
echo "Load average after: $(cut -d' ' -f1-3 /proc/loadavg). Targets (issue 28): >= 1.8x on 2 threads, >= 10x on 16."
