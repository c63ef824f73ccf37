#!/usr/bin/env bash
# Side by side: the cold release build of `reproduce` and the papers' runs' simulation time
# (`sim_s` of results/runs.csv) at two revisions, on the same machine, one after the other
# (issue "any arm, at run time": build at most 0.7 of the baseline's; `sim_s` median ratio at
# most 1.05, worst run at most 1.2).
#
# Per revision: `git clone --no-local` of this repository into a temporary directory at the
# revision, an empty CARGO_TARGET_DIR of its own, then
#   build      cargo build --release -p reproduce      (timed: wall, user and system CPU seconds)
#   reproduce  cargo run --release -p reproduce         (its results/runs.csv is kept)
# Cargo's registry is shared with the user's, so downloads are not timed.
# Needs an otherwise idle machine; the script cannot check that nothing else runs, so it
# records the load average before each step beside the times.
#
# Writes only into its temporary directory (removed on exit) and OUT_DIR (default
# benches/results/side-by-side): build.csv (revision, wall_s, user_s, sys_s, load1) and
# runs-<revision>.csv; then benches/side_by_side/compare.py prints the ratios.
#
# Usage: benches/side_by_side/build_and_runs.sh [--out DIR] BASELINE CANDIDATE
set -euo pipefail
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
out="$repo/benches/results/side-by-side"
if [ "${1:-}" = "--out" ]; then out="${2:?--out needs a directory}"; shift 2; fi
[ $# -eq 2 ] || { sed -n '/^# Usage/p' "$0" | sed 's/^# //' >&2; exit 2; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/driftbench-sbs.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
echo "revision,commit,wall_s,user_s,sys_s,load1" > "$tmp/build.csv"
for rev in "$@"; do
    commit=$(git -C "$repo" rev-parse --verify "$rev^{commit}")
    clone="$tmp/$commit"
    git clone --quiet --no-local "$repo" "$clone"
    git -C "$clone" checkout --quiet "$commit"
    load=$(cut -d' ' -f1 /proc/loadavg)
    echo "[$rev] cold build" >&2
    ( cd "$clone" && CARGO_TARGET_DIR="$clone/target" /usr/bin/time -f "%e %U %S" -o "$tmp/time" \
        cargo build --release -p reproduce --quiet )
    read -r wall user sys < "$tmp/time"
    echo "$rev,$commit,$wall,$user,$sys,$load" >> "$tmp/build.csv"
    echo "[$rev] reproduction" >&2
    ( cd "$clone" && CARGO_TARGET_DIR="$clone/target" cargo run --release --quiet -p reproduce >/dev/null 2>&1 ) || \
        echo "[$rev] the reproduction exited non-zero; its runs.csv is kept as written" >&2
    cp "$clone/results/runs.csv" "$out/runs-$rev.csv"
done
mv "$tmp/build.csv" "$out/build.csv"
python3 "$repo/benches/side_by_side/compare.py" "$out" "$1" "$2"
