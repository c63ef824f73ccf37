#!/bin/sh
# Profiles the hot-started active-set solve of the 7-variable QP (criterion bench
# `jia2019/exact-active-set/hot` of benches/benches/solvers.rs) and writes
# benches/results/profile-active-set.csv (benches/REPORT.md, "Where the exact solve's time
# goes"): perf samples the bench binary (the `profiling` profile: release with debug info) for
# PROFILE_SECONDS seconds of criterion's --profile-time loop, pinned to one CPU, and active_set.py sorts
# the samples by the function they were in (self time; the module doc of active_set.py lists
# the categories). Run from the repository root; re-render the benches' page with
# `cargo run --release -p driftbench-benches --bin telemetry`. Needs `perf` (Debian: linux-perf) and python3.
# Usage: [PROFILE_SECONDS=10] benches/profile/active_set.sh
set -eu
seconds="${PROFILE_SECONDS:-10}"
freq=4999
target="${CARGO_TARGET_DIR:-target}"
out="$target/profile"
mkdir -p "$out"
bench=$(cargo bench --profile profiling -p driftbench-benches --bench solvers --no-run --message-format=json 2>/dev/null \
    | python3 -c 'import json,sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("target", {}).get("name") == "solvers" and m.get("executable"):
        print(m["executable"])')
bench_id='jia2019/exact-active-set/hot'
cpu=$(( $(nproc) - 1 ))
perf record -q -F "$freq" -o "$out/active-set.data" -- taskset -c "$cpu" "$bench" --bench \
    --profile-time "$seconds" "$bench_id" >/dev/null 2>&1
perf report -i "$out/active-set.data" --no-children --sort sym --stdio 2>/dev/null \
    > "$out/active-set.report"
rev=$(git rev-parse --short=12 HEAD)
python3 benches/profile/active_set.py "$out/active-set.report" "$bench_id" "$seconds" "$freq" "$rev" \
    > benches/results/profile-active-set.csv
echo "wrote benches/results/profile-active-set.csv"
