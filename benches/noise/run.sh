#!/bin/sh
# Judge a candidate revision's results against the rounding noise of the baseline's (judge.py):
# runs the baseline's binary on its own experiment files four times, each time with every
# initial configuration moved by one unit in the last place (perturb.py: up, down, alternating
# both ways), into scratch roots, then compares the candidate's results/ with the baseline's
# committed results/ cell by cell against the largest change those four runs make.
#
# Usage (from the repository root):
#   benches/noise/run.sh BASE_CHECKOUT BASE_BINARY CANDIDATE_RESULTS [CELLS_CSV]
# BASE_CHECKOUT is a checkout of the baseline revision with its results/ as committed,
# BASE_BINARY its release build of reproduce, CANDIDATE_RESULTS the candidate's reproduced
# results/ directory. Writes the changed cells with their verdicts to CELLS_CSV (default
# benches/results/noise-judgement.csv); exit 1 when a cell is beyond its noise floor. Each
# perturbed run is a whole reproduction (several minutes on 2 cores). Needs python3.
set -eu
[ $# -ge 3 ] || { sed -n '/^# Usage/,/^# perturbed/p' "$0" | sed 's/^# //' >&2; exit 2; }
base="$1"; bin="$2"; cand="$3"
here=$(cd "$(dirname "$0")" && pwd)
out="${4:-$here/../results/noise-judgement.csv}"
[ -x "$bin" ] || { echo "$bin: not an executable" >&2; exit 2; }
for d in "$base/experiments" "$base/papers" "$base/results" "$cand"; do
    [ -d "$d" ] || { echo "$d: not a directory" >&2; exit 2; }
done
tmp=$(mktemp -d "${TMPDIR:-/tmp}/driftbench-noise.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
roots=""
for pattern in up down alternate alternate-down; do
    root="$tmp/$pattern"
    mkdir -p "$root"
    python3 "$here/perturb.py" "$base/experiments" "$root/experiments" "$pattern"
    cp -r "$base/papers" "$root/papers"
    echo "baseline, theta0 moved $pattern: reproducing (log in $root/log)" >&2
    "$bin" run --root "$root" > "$root/log" 2>&1 || {
        echo "the perturbed run ($pattern) failed: tail of its log" >&2
        tail -20 "$root/log" >&2
        exit 2
    }
    roots="$roots $root/results"
done
# shellcheck disable=SC2086
python3 "$here/judge.py" "$base/results" "$cand" $roots > "$out.tmp" && status=0 || status=$?
mv "$out.tmp" "$out"
echo "wrote $out" >&2
exit "$status"
