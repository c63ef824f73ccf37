#!/bin/sh
# Times every paper's runs under an earlier revision of driftbench and under this one, each run
# alone, and writes benches/results/speedup.csv (the table of benches/REPORT.md, "Against an
# earlier revision"). Each pass runs
#   reproduce shard 1/1 --paper PAPER --threads 1 --results-dir DIR
# (the shard mode: no explanation runs, no timing pass, no report; runs.csv and traces written
# to a scratch directory under the target directory) pinned to the last CPU, alternating the two
# revisions pass by pass so that both see the same machine. compare.py matches the two
# revisions' rows by experiment, variant and solver label (the exact column by its kind) and
# keeps, per run, the median over the passes of sim_s (the simulation: the network's or the
# exact column's integration) and wall_s (the run, its observation and scoring included).
# Usage (from the repository root, after `cargo build --release -p reproduce`):
#   benches/speedup/papers.sh OLD_CHECKOUT OLD_BINARY [PASSES]
# The earlier revision's binary is given the mode as the flag `--shard`, which every revision
# before the old flags' removal takes; OLD_MODE=shard runs one that takes only the subcommand.
# OLD_CHECKOUT is a checkout of the earlier revision (its experiments/ are the ones its binary
# runs), OLD_BINARY that checkout's release build of reproduce. Then re-render the benches' page
# with `cargo run --release -p driftbench-benches --bin telemetry`.
# Needs python3.
set -eu
old_root="$1"
old_bin="$2"
passes="${3:-3}"
papers="jia2019 zhang2018 zhong2021 kong2019 cross"
target="${CARGO_TARGET_DIR:-target}"
case "$target" in /*) ;; *) target="$(pwd)/$target" ;; esac
new_bin="$target/release/reproduce"
out="$target/speedup"
rm -rf "$out"
mkdir -p "$out"
cpu=$(( $(nproc) - 1 ))
old_rev=$(git -C "$old_root" rev-parse --short=12 HEAD)
new_rev=$(git rev-parse --short=12 HEAD)
pass=1
while [ "$pass" -le "$passes" ]; do
    for paper in $papers; do
        for side in old new; do
            dir="$out/$side-$paper-$pass"
            if [ "$side" = old ]; then
                root="$old_root"; bin="$old_bin"; mode="${OLD_MODE:---shard}"
            else
                root=.; bin="$new_bin"; mode=shard
            fi
            echo "pass $pass/$passes: $paper at the $side revision" >&2
            (cd "$root" && taskset -c "$cpu" "$bin" "$mode" 1/1 --paper "$paper" --threads 1 \
                --results-dir "$dir" >/dev/null 2>"$dir.err") || echo "  failed: see $dir.err" >&2
        done
    done
    pass=$((pass + 1))
done
python3 benches/speedup/compare.py "$out" "$passes" "$old_rev" "$new_rev" > benches/results/speedup.csv
echo "wrote benches/results/speedup.csv"
