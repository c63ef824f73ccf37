#!/bin/sh
# A sweep end to end on this machine, against the number of runs (docs/cluster.md, "What a
# shard and a merge hold" and "A sweep of 10^7 runs: the plan"). For each size n: a sweep of
# about n short runs of equal cost (kong2019's exact column, mu swept over [1, 2] in steps of
# 1/n, T = DURATION s; a sweep of mu over 1..n would make the late runs stiff and slow) run as
# SHARDS shards (`reproduce shard K/SHARDS --threads 1`, PARALLEL of them at a time), merged
# (`reproduce merge --no-report`) and its page rendered (`reproduce report`). Each process is
# measured by /usr/bin/time -v (maximum resident set size, CPU and wall time); disk is `du` of
# what the step left. Prints one Markdown row per process and step, and appends the same rows
# to CSV (default benches/results/sweep-e2e.csv; columns below).
#
#   cargo build --release -p reproduce
#   benches/sweep_e2e/run.sh [n ...]          # default: 1000 10000 100000
#
# Environment: BIN (default target/release/reproduce), DURATION (default 0.05), SHARDS
# (default 8), PARALLEL (default 2: this machine's cores), CSV (default
# benches/results/sweep-e2e.csv; empty: none), WORK (default a fresh directory under
# ${TMPDIR:-/tmp}, removed at the end unless KEEP=1).
#
# CSV columns: revision (`reproduce --version`), runs (of the sweep), step (`shard K/N`; `shards`:
# the N shards as one stage, PARALLEL at a time: its peak is the largest shard's, its CPU their
# sum, its wall the stage's; `merge`; `report`), peak_mb (maximum resident set size), cpu_s
# (user + system), wall_s, disk_mb (what the step left: its shard directory, every shard
# directory, the merged results, the report), machine (CPU model), cores, load (1-minute load
# average when the step began: the machine is shared), date (UTC).
set -eu
cd "$(dirname "$0")/../.."
BIN=${BIN:-target/release/reproduce}
DURATION=${DURATION:-0.05}
SHARDS=${SHARDS:-8}
PARALLEL=${PARALLEL:-2}
CSV=${CSV-benches/results/sweep-e2e.csv}
WORK=${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/driftbench-sweep-e2e.XXXXXX")}
[ $# -gt 0 ] || set -- 1000 10000 100000
[ -x "$BIN" ] || { echo "no $BIN: cargo build --release -p reproduce" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (GNU time, for -v)" >&2; exit 2; }

REVISION=$("$BIN" --version | sed -n "s/.*(revision \(.*\))/\1/p")
MACHINE=$(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo | awk '{ print $1, $2 }')
CORES=$(nproc)
if [ -n "$CSV" ] && [ ! -s "$CSV" ]; then
    echo "revision,runs,step,peak_mb,cpu_s,wall_s,disk_mb,machine,cores,load,date" > "$CSV"
fi

# "<max RSS MB> <CPU s> <wall s>" of the /usr/bin/time -v log $1.
measured() {
    awk -F': ' '/Maximum resident set size/ { kb = $2 }
        /(User|System) time/ { cpu += $2 }
        /Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i] }
        END { printf "%.0f %.1f %.1f", kb / 1024, cpu, s }' "$1"
}
load() { cut -d' ' -f1 /proc/loadavg; }
now() { date +%s.%N; }
# One row: runs step peak cpu wall disk load.
row() {
    echo "| $2 | $1 | $3 | $4 | $5 | $6 | $7 |"
    [ -z "$CSV" ] || echo "\"$REVISION\",$1,$2,$3,$4,$5,$6,\"$MACHINE\",$CORES,$7,$(date -u +%Y-%m-%dT%H:%M:%SZ)" >> "$CSV"
}

echo "| step | runs | peak memory (MB) | CPU (s) | wall (s) | disk (MB) | load |"
echo "|---|---|---|---|---|---|---|"
for n in "$@"; do
    dir="$WORK/n$n"
    mkdir -p "$dir/experiments"
    cat > "$dir/experiments/kong2019.toml" <<TOML
paper = "kong2019"
title = "sweep end to end"
[[experiment]]
id = "kong2019-e2e"
paper_output = "none"
robot = "katana6m180"
path = { name = "circle", duration = $DURATION }
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
[[experiment.variant]]
label = "ZNN"
scheme = { kind = "znn-rmp", mu = 1.0, k_p = 1.0 }
sweep = { "scheme.mu" = { from = 1.0, to = 2.0, step = $(awk "BEGIN { print 1 / $n }") } }
TOML
    runs=$((n + 1))
    # The shards, PARALLEL at a time; each measured alone.
    stage_load=$(load)
    start=$(now)
    seq 1 "$SHARDS" | xargs -P "$PARALLEL" -I K /usr/bin/time -v -o "$dir/shard-K.time" \
        "$BIN" shard "K/$SHARDS" --threads 1 --experiments-dir "$dir/experiments" \
        --results-dir "$dir/results-shard-K-of-$SHARDS" \
        > "$dir/shards.out" 2> "$dir/shards.err" || { tail -5 "$dir/shards.err" >&2; exit 1; }
    stage_wall=$(awk "BEGIN { printf \"%.1f\", $(now) - $start }")
    peak=0 cpu=0
    for k in $(seq 1 "$SHARDS"); do
        set -- $(measured "$dir/shard-$k.time")
        row "$runs" "shard $k/$SHARDS" "$1" "$2" "$3" \
            "$(du -sm "$dir/results-shard-$k-of-$SHARDS" | cut -f1)" "$stage_load"
        peak=$(awk "BEGIN { print ($1 > $peak) ? $1 : $peak }")
        cpu=$(awk "BEGIN { print $cpu + $2 }")
    done
    row "$runs" shards "$peak" "$cpu" "$stage_wall" \
        "$(du -smc "$dir"/results-shard-*-of-"$SHARDS" | tail -1 | cut -f1)" "$stage_load"
    step_load=$(load)
    /usr/bin/time -v -o "$dir/merge.time" "$BIN" merge "$dir"/results-shard-*-of-"$SHARDS" \
        --no-report --experiments-dir "$dir/experiments" --results-dir "$dir/results" \
        > "$dir/merge.out" 2> "$dir/merge.err" || { tail -5 "$dir/merge.err" >&2; exit 1; }
    merged=$(($(wc -l < "$dir/results/runs.csv") - 1))
    [ "$merged" = "$runs" ] || { echo "merged $merged runs, expected $runs" >&2; exit 1; }
    set -- $(measured "$dir/merge.time")
    row "$runs" merge "$1" "$2" "$3" "$(du -sm "$dir/results" | cut -f1)" "$step_load"
    step_load=$(load)
    /usr/bin/time -v -o "$dir/report.time" "$BIN" report \
        --experiments-dir "$dir/experiments" --results-dir "$dir/results" \
        > "$dir/report.out" 2> "$dir/report.err" || { tail -5 "$dir/report.err" >&2; exit 1; }
    set -- $(measured "$dir/report.time")
    row "$runs" report "$1" "$2" "$3" "$(du -sm "$dir/report" | cut -f1)" "$step_load"
    # The shards' directories are not needed past the merge: free their disk for the next size.
    [ "${KEEP:-0}" = 1 ] || rm -rf "$dir"/results-shard-*
done
[ "${KEEP:-0}" = 1 ] || rm -rf "$WORK"
