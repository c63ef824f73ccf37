#!/bin/sh
# Peak memory of one shard and of the merge against the number of runs (docs/cluster.md,
# "What a shard and a merge hold"). For each size n: a sweep of about n short runs of equal
# cost (kong2019's exact column, mu swept over [1, 2] in steps of 1/n, T = DURATION s; a
# sweep of mu over 1..n would make the late runs stiff and slow) run as one shard
# (`--shard 1/1`, every run in one process, the worst case), then merged with `--no-report`;
# each process is measured by /usr/bin/time -v (maximum resident set size, CPU and wall
# time). Prints one Markdown row per step.
#
#   cargo build --release -p reproduce
#   benches/sweep_e2e/run.sh [n ...]          # default: 1000 10000
#
# Environment: BIN (default target/release/reproduce), DURATION (default 0.05), THREADS
# (default 2), WORK (default a fresh directory under ${TMPDIR:-/tmp}, removed at the end
# unless KEEP=1).
set -eu
cd "$(dirname "$0")/../.."
BIN=${BIN:-target/release/reproduce}
DURATION=${DURATION:-0.05}
THREADS=${THREADS:-2}
WORK=${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/driftbench-sweep-e2e.XXXXXX")}
[ $# -gt 0 ] || set -- 1000 10000
[ -x "$BIN" ] || { echo "no $BIN: cargo build --release -p reproduce" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (GNU time, for -v)" >&2; exit 2; }

# "<max RSS MB> <CPU s> <wall s>" of the /usr/bin/time -v log $1.
measured() {
    awk -F': ' '/Maximum resident set size/ { kb = $2 }
        /(User|System) time/ { cpu += $2 }
        /Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i] }
        END { printf "%.0f %.1f %.1f", kb / 1024, cpu, s }' "$1"
}

echo "| step | runs | peak memory (MB) | CPU (s) | wall (s) | disk (MB) |"
echo "|---|---|---|---|---|---|"
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
    /usr/bin/time -v -o "$dir/shard.time" "$BIN" --shard 1/1 --threads "$THREADS" \
        --experiments-dir "$dir/experiments" --results-dir "$dir/shard" \
        > "$dir/shard.out" 2> "$dir/shard.err" || { tail -5 "$dir/shard.err" >&2; exit 1; }
    runs=$(($(wc -l < "$dir/shard/runs.csv") - 1))
    set -- $(measured "$dir/shard.time")
    echo "| shard (--shard 1/1) | $runs | $1 | $2 | $3 | $(du -sm "$dir/shard" | cut -f1) |"
    /usr/bin/time -v -o "$dir/merge.time" "$BIN" merge "$dir/shard" --no-report \
        --experiments-dir "$dir/experiments" --results-dir "$dir/merged" \
        > "$dir/merge.out" 2> "$dir/merge.err" || { tail -5 "$dir/merge.err" >&2; exit 1; }
    set -- $(measured "$dir/merge.time")
    echo "| merge --no-report | $runs | $1 | $2 | $3 | $(du -sm "$dir/merged" | cut -f1) |"
done
[ "${KEEP:-0}" = 1 ] || rm -rf "$WORK"
