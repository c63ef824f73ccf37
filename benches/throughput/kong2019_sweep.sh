#!/bin/sh
# Single-thread throughput of a kong2019 ZNN sweep at two revisions of driftbench, side by side
# (issue 43 item 8: at least twice f5570fd's runs per core). Writes
# benches/results/throughput.csv, one row per revision and pass.
#
# The sweep (written by this script into a scratch directory): kong2019's ZNN scheme (eq. 22) on
# the Katana 6M180 (5 joints), the circle of 9 s started 0.5 rad off theta*0, solved by the
# linear ZNN, no exact column, integrated by Tsitouras 5(4) at RelTol 1e-10, AbsTol 1e-12 (an
# explicit method at tight tolerances: the right-hand side dominates), swept over
# mu (SIDE values, geometric from 0.25 to 8) x gamma (SIDE values, geometric from 1 to 1000):
# SIDE^2 runs, 1024 at the default SIDE = 32. The sweep keeps every run's trace (it sets no
# `traces`: the default, and the only form an older revision such as f5570fd reads, so both
# revisions run the same file), so a pass also formats, seals and folds SIDE^2 traces. Each pass
# runs the whole sweep as one shard
#   reproduce shard 1/1 --threads 1 --experiments-dir SWEEP --results-dir DIR
# (no explanation runs, no report) pinned to the last CPU, the two revisions alternating pass by
# pass so that both see the same machine.
#
# Per pass it records the process's user CPU seconds (what one core spent) and its wall time
# (GNU time), and the user-space instruction and cycle counts of `perf stat` where the machine
# exposes hardware counters (empty otherwise: a virtual machine often does not); instruction
# counts do not depend on the load of the machine, CPU seconds much less than wall time does.
# From the pass's runs.csv: runs, RHS evaluations, accepted steps, and the sums of sim_s and
# wall_s. runs per CPU second = runs / user_s.
#
# Then one more pass of the new revision, on the sweep at PROFILE_SIDE (default 8: 64 runs),
# sampled by `perf record` (call graphs) and sorted by classify.py: where a right-hand side's
# time goes (kinematics, path, QP assembly, the network's KKT solve, integrator, observer),
# written to benches/results/throughput-profile.csv.
#
# Usage (from the repository root):
#   benches/throughput/kong2019_sweep.sh [--passes P] [--side SIDE] [--profile-side S] \
#       OLD_CHECKOUT OLD_BINARY NEW_CHECKOUT NEW_BINARY
# A CHECKOUT is a checkout of the revision (its papers/ are the ones its binary reads), BINARY its
# release build of reproduce (`cargo build --release -p reproduce`). Needs python3, GNU time
# (/usr/bin/time) and, for the counters, perf.
set -eu
passes=3
side=32
profile_side=8
while [ $# -gt 4 ]; do
    case "$1" in
        --passes) passes="$2"; shift 2 ;;
        --side) side="$2"; shift 2 ;;
        --profile-side) profile_side="$2"; shift 2 ;;
        *) echo "unknown option $1" >&2; exit 2 ;;
    esac
done
[ $# -eq 4 ] || { sed -n '/^# Usage/,/^# release/p' "$0" | sed 's/^# //' >&2; exit 2; }
old_root="$1"; old_bin="$2"; new_root="$3"; new_bin="$4"
for f in "$old_bin" "$new_bin"; do [ -x "$f" ] || { echo "$f: not an executable" >&2; exit 2; }; done
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/driftbench-throughput.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
# The sweep at SIDE x SIDE runs, written into the directory $2.
sweep() {
mkdir -p "$2"
python3 - "$1" > "$2/kong2019.toml" <<'PY'
import sys
side = int(sys.argv[1])
geo = lambda a, b: [float(f"{a * (b / a) ** (i / (side - 1)):.6g}") for i in range(side)] if side > 1 else [a]
print(f'''paper = "kong2019"
title = "kong2019 ZNN sweep (throughput)"

[[experiment]]
id = "kong2019-znn-throughput"
paper_output = "none: a throughput measurement"
robot = "katana6m180"
path = {{ name = "circle", duration = 9.0 }}
theta_ref = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.5471975511965976]

[[experiment.variant]]
id = "znn-eq22"
label = "ZNN (eq. 22)"
scheme = {{ kind = "znn-rmp", k_p = 1.0 }}
solvers = [{{ kind = "znn", gamma = 1.0 }}]
exact = false
integrator = {{ method = "tsit45", rtol = 1e-10, atol = 1e-12 }}
sweep = {{ "scheme.mu" = {geo(0.25, 8.0)}, "solvers.0.gamma" = {geo(1.0, 1000.0)} }}''')
PY
}
sweep "$side" "$tmp/sweep"
sweep "$profile_side" "$tmp/profile-sweep"
cpu=$(( $(nproc) - 1 ))
counters=instructions:u,cycles:u
echo "revision,commit,pass,runs,user_s,wall_s,instructions,cycles,rhs_evals,steps,sum_sim_s,sum_wall_s,load1" > "$tmp/throughput.csv"
pass=1
while [ "$pass" -le "$passes" ]; do
    for which in old new; do
        if [ "$which" = old ]; then root="$old_root"; bin="$old_bin"; else root="$new_root"; bin="$new_bin"; fi
        commit=$(git -C "$root" rev-parse --short=12 HEAD)
        dir="$tmp/$which-$pass"
        load=$(cut -d' ' -f1 /proc/loadavg)
        echo "pass $pass/$passes: the $which revision ($commit)" >&2
        (cd "$root" && /usr/bin/time -f "%U %e" -o "$dir.time" \
            perf stat -x, -e "$counters" -o "$dir.perf" \
            taskset -c "$cpu" "$bin" shard 1/1 --threads 1 --experiments-dir "$tmp/sweep" \
            --results-dir "$dir" >/dev/null 2>"$dir.err") || { echo "  failed: see $dir.err" >&2; exit 1; }
        python3 - "$dir" "$which" "$commit" "$pass" "$load" >> "$tmp/throughput.csv" <<'PY'
import csv, sys
d, which, commit, p, load = sys.argv[1:]
user, wall = open(d + ".time").read().split()[-2:]
count = {}
for line in open(d + ".perf"):
    f = line.strip().split(",")
    if len(f) > 2 and f[0] and f[0][0].isdigit():
        count[f[2].split(":")[0]] = f[0]
rows = list(csv.DictReader(open(d + "/runs.csv")))
total = lambda k: sum(float(r[k]) for r in rows if r[k])
print(",".join([which, commit, p, str(len(rows)), user, wall, count.get("instructions", ""),
                count.get("cycles", ""), f"{total('rhs_evals'):.0f}", f"{total('steps'):.0f}",
                f"{total('sim_s'):.6g}", f"{total('wall_s'):.6g}", load]))
PY
    done
    pass=$((pass + 1))
done
echo "profile: the new revision on $profile_side x $profile_side runs" >&2
commit=$(git -C "$new_root" rev-parse --short=12 HEAD)
(cd "$new_root" && /usr/bin/time -f "%U" -o "$tmp/profile.time" \
    perf record -q -F 999 --call-graph dwarf,8192 -o "$tmp/profile.data" -- \
    taskset -c "$cpu" "$new_bin" shard 1/1 --threads 1 --experiments-dir "$tmp/profile-sweep" \
    --results-dir "$tmp/profile" >/dev/null 2>"$tmp/profile.err") || { echo "  failed: see $tmp/profile.err" >&2; exit 1; }
perf script -i "$tmp/profile.data" -F comm,ip,sym 2>/dev/null > "$tmp/profile.stacks"
rhs=$(python3 -c "import csv,sys; print(sum(int(r['rhs_evals']) for r in csv.DictReader(open(sys.argv[1]))))" "$tmp/profile/runs.csv")
python3 "$repo/benches/throughput/classify.py" "$tmp/profile.stacks" "$(tail -1 "$tmp/profile.time")" "$rhs" "$commit" > "$tmp/profile.csv"
mkdir -p "$repo/benches/results"
mv "$tmp/throughput.csv" "$repo/benches/results/throughput.csv"
mv "$tmp/profile.csv" "$repo/benches/results/throughput-profile.csv"
echo "wrote benches/results/throughput.csv and throughput-profile.csv" >&2
python3 "$repo/benches/throughput/summary.py" "$repo/benches/results/throughput.csv"
