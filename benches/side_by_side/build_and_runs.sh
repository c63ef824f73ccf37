#!/usr/bin/env bash
# Side by side: the cold release build of `reproduce` and the papers' runs' simulation time
# (`sim_s` of results/runs.csv) at two revisions, on the same machine, one after the other
# (issue "any arm, at run time": build at most 0.7 of the baseline's; `sim_s` median ratio at
# most 1.05, worst run at most 1.2).
#
# Per revision: `git clone --no-local` of this repository into a temporary directory at the
# revision; then per round, the revisions taking turns (baseline, candidate, baseline, ...),
#   build      cargo build --release -p reproduce      (timed: wall, user and system CPU seconds
#                                                       of cargo and every process it starts)
# into an empty CARGO_TARGET_DIR of its own, removed after the round unless the reproduction
# needs it; after the last round, unless --build-only, per pass (--passes N, default 1; the
# revisions taking turns, as the builds do)
#   reproduce  cargo run --release -p reproduce         (its results/runs.csv is kept)
# Cargo's registry is shared with the user's, so downloads are not timed.
# f5570fd, the baseline of issue 38, builds OSQP's C code with CMake: the machine needs `cmake`
# (apt-get install cmake) to build it; driftbench's own default build needs none.
# Wall time needs an otherwise idle machine; the script cannot check that nothing else runs, so
# it records the load average before each build beside the times. CPU seconds (user + system)
# are less disturbed by other work than wall time, but not immune (shared caches, frequency).
#
# Writes only into its temporary directory (removed on exit) and OUT_DIR (default
# benches/results/side-by-side): build.csv (revision, commit, round, wall_s, user_s, sys_s,
# load1) and, without --build-only, runs-<revision>.csv; then benches/side_by_side/compare.py
# prints each build and the sim_s ratios (the build ratio is benches/REPORT.md's, from build.csv).
#
# Usage: benches/side_by_side/build_and_runs.sh [--out DIR] [--rounds N] [--passes N] [--build-only] BASELINE CANDIDATE
set -euo pipefail
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
out="$repo/benches/results/side-by-side"
rounds=1
passes=1
build_only=false
usage() { sed -n '/^# Usage/p' "$0" | sed 's/^# //' >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out="${2:?--out needs a directory}"; shift 2 ;;
        --rounds)
            rounds="${2:?--rounds needs a count}"; shift 2
            case "$rounds" in ''|*[!0-9]*|0) echo "--rounds: a whole number from 1, not $rounds" >&2; exit 2 ;; esac ;;
        --passes)
            passes="${2:?--passes needs a count}"; shift 2
            case "$passes" in ''|*[!0-9]*|0) echo "--passes: a whole number from 1, not $passes" >&2; exit 2 ;; esac ;;
        --build-only) build_only=true; shift ;;
        -*) echo "unknown option $1 (choices: --out DIR, --rounds N, --passes N, --build-only)" >&2; usage ;;
        *) break ;;
    esac
done
[ $# -eq 2 ] || usage
tmp=$(mktemp -d "${TMPDIR:-/tmp}/driftbench-sbs.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
echo "revision,commit,round,wall_s,user_s,sys_s,load1" > "$tmp/build.csv"
clone_of() { [ "$1" = "$base" ] && echo "$tmp/baseline" || echo "$tmp/candidate"; }
base=$1
for rev in "$@"; do
    commit=$(git -C "$repo" rev-parse --verify "$rev^{commit}")
    git clone --quiet --no-local "$repo" "$(clone_of "$rev")"
    git -C "$(clone_of "$rev")" checkout --quiet "$commit"
done
for round in $(seq 1 "$rounds"); do
    for rev in "$@"; do
        clone=$(clone_of "$rev")
        commit=$(git -C "$clone" rev-parse HEAD)
        rm -rf "$clone/target"
        load=$(cut -d' ' -f1 /proc/loadavg)
        echo "[$rev] cold build, round $round of $rounds (load $load)" >&2
        ( cd "$clone" && CARGO_TARGET_DIR="$clone/target" /usr/bin/time -f "%e %U %S" -o "$tmp/time" \
            cargo build --release -p reproduce --quiet )
        read -r wall user sys < "$tmp/time"
        echo "$rev,$commit,$round,$wall,$user,$sys,$load" >> "$tmp/build.csv"
        if [ "$round" -lt "$rounds" ] || $build_only; then rm -rf "$clone/target"; fi
    done
done
if ! $build_only; then
    for pass in $(seq 1 "$passes"); do
        for rev in "$@"; do
            clone=$(clone_of "$rev")
            echo "[$rev] reproduction, pass $pass of $passes" >&2
            ( cd "$clone" && CARGO_TARGET_DIR="$clone/target" cargo run --release --quiet -p reproduce >/dev/null 2>&1 ) || \
                echo "[$rev] the reproduction exited non-zero; its runs.csv is kept as written" >&2
            if [ "$passes" -eq 1 ]; then name="runs-$rev.csv"; else name="runs-$rev-p$pass.csv"; fi
            cp "$clone/results/runs.csv" "$out/$name"
            if [ "$pass" -eq "$passes" ]; then rm -rf "$clone/target"; fi
        done
    done
fi
mv "$tmp/build.csv" "$out/build.csv"
python3 "$repo/benches/side_by_side/compare.py" "$out" "$1" "$2"
