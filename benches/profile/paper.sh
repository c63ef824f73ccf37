#!/bin/sh
# Profiles each named paper's runs and writes benches/results/profile.csv (the tables of
# benches/REPORT.md, "Where the time goes", one per paper): perf samples the optimised binary
# with debug info (Cargo.toml's `profiling` profile: release plus `debug = 1`) over PASSES
# passes of
#   reproduce --paper PAPER --skip-explain --threads 1 --dry-run
# pinned to one CPU, and classify.py sorts every sample by what it was doing (classify.py's
# module doc lists the categories). Run from the repository root after
#   cargo build --profile profiling -p reproduce
# and re-render the benches' page with `cargo run --release -p driftbench-benches --bin telemetry`. Needs `perf` (Debian: linux-perf) and python3.
# Usage: [PASSES=5] benches/profile/paper.sh PAPER [PAPER ...]
set -eu
passes="${PASSES:-5}"
freq=1999
target="${CARGO_TARGET_DIR:-target}"
bin="$target/profiling/reproduce"
out="$target/profile"
mkdir -p "$out"
cpu=$(( $(nproc) - 1 ))
rev=$(git rev-parse --short=12 HEAD)
csv="$out/profile.csv"
rm -f "$csv"
for paper in "$@"; do
    echo "profiling $paper ($passes passes)" >&2
    perf record -q -F "$freq" -g --call-graph dwarf,16384 -o "$out/$paper.data" -- \
        taskset -c "$cpu" sh -c "i=0; while [ \$i -lt $passes ]; do \"$bin\" --paper $paper --skip-explain --threads 1 --dry-run >/dev/null 2>&1; i=\$((i+1)); done"
    perf script -i "$out/$paper.data" -F comm,ip,sym 2>/dev/null > "$out/$paper.stacks"
    # One header: the first paper's.
    if [ -e "$csv" ]; then from=2; else from=1; fi
    python3 benches/profile/classify.py "$out/$paper.stacks" "$paper" "$passes" "$freq" "$rev" \
        | tail -n +"$from" >> "$csv"
done
mv "$csv" benches/results/profile.csv
echo "wrote benches/results/profile.csv"
