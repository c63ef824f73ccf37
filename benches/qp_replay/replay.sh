#!/bin/sh
# The exact reference per tick against DAQP, on the same QPs (records/src/qp_replay.rs states
# the table): builds the Python package into a private virtual environment with DAQP from PyPI
# (pinned; DAQP is not a dependency of the suite), records 2,000 consecutive QPs of each task
# along a run (record.py), replays them to the suite's active set (benches/src/bin/qp_replay.rs)
# and to DAQP (daqp_replay.py), each pinned to one CPU, and writes results/qp-replay.csv.
# Run from the repository root on an otherwise idle machine; then re-render the report with
# `cargo run --release -p reproduce -- report --accept-edited`.
# Usage: [REPEATS=20] benches/qp_replay/replay.sh
set -eu
repeats="${REPEATS:-20}"
target="${CARGO_TARGET_DIR:-target}"
work="$target/qp-replay"
venv="$work/venv"
cpu=$(( $(nproc) - 1 ))
rm -rf "$work/qps" "$work/wheels"
mkdir -p "$work"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --disable-pip-version-check \
    maturin==1.16.0 numpy==2.4.6 daqp==0.11.0
"$venv/bin/maturin" build --release --manifest-path python/Cargo.toml \
    --interpreter "$venv/bin/python" --out "$work/wheels"
"$venv/bin/pip" install --quiet --disable-pip-version-check --force-reinstall --no-deps \
    --no-index --find-links "$work/wheels" driftbench
"$venv/bin/python" benches/qp_replay/record.py "$work/qps" 2000
cargo build --release --quiet -p driftbench-benches --bin qp_replay
for f in "$work"/qps/*.qps; do
    n=$(basename "$f" .qps)
    taskset -c "$cpu" "$target/release/qp_replay" "$f" "$work/qps/out$n" "$repeats"
done
rev=$(git rev-parse --short=12 HEAD)
taskset -c "$cpu" "$venv/bin/python" benches/qp_replay/daqp_replay.py "$work/qps" "$repeats" "$rev" \
    > "$work/qp-replay.csv"
mv "$work/qp-replay.csv" results/qp-replay.csv
echo "wrote results/qp-replay.csv"
