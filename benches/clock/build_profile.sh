#!/usr/bin/env bash
# Where a cold build's time goes: a fresh clone of one revision (default HEAD) built with
# `cargo build --release -p reproduce --timings` into an empty target directory of its own, and
# cargo's unit table turned into benches/results/build-profile.csv (build_units.py; the columns
# are benches/src/telemetry/build_profile.rs's). benches/REPORT.md ("Where the build's time
# goes") shows the build's critical path, its CPU time against the wall time and the costliest
# units, beside the newcomer's clock (clock.sh, whose `build` step is the same command).
#
# Needs an otherwise idle machine, as clock.sh does: every unit's duration stretches when
# something else runs. About 3 minutes of the whole machine on 2 cores. Cargo's registry is
# shared with the user's (downloads are not timed). Writes nothing outside its temporary
# directory (removed on exit) and the --out file, replaced atomically at the end. After it,
# render the benches' page: `cargo run --release -p driftbench-benches --bin telemetry`.
#
# Usage (from anywhere inside the repository):
#   benches/clock/build_profile.sh [--out FILE] [REVISION]      (default revision: HEAD)
set -euo pipefail

usage() {
    sed -n '/^# Usage/,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
    exit "${1:-2}"
}

repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=lib.sh
. "$here/lib.sh"
out="$repo/benches/results/build-profile.csv"
rev=HEAD
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out="${2:?--out needs a file}"; shift 2 ;;
        --out=*) out="${1#--out=}"; shift ;;
        -h|--help) usage 0 ;;
        -*) echo "build_profile.sh: unknown option $1" >&2; usage ;;
        *) rev="$1"; shift ;;
    esac
done
case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
[ -d "$(dirname "$out")" ] || { echo "build_profile.sh: --out: no directory $(dirname "$out")" >&2; exit 2; }
commit=$(git -C "$repo" rev-parse --verify --quiet "$rev^{commit}") || {
    echo "build_profile.sh: $rev: not a commit of $repo" >&2
    exit 2
}
machine=$(machine_name)

make_tmp build-profile "$out"

clone="$tmp/clone"
echo "build_profile: cloning ${commit:0:12} into $tmp" >&2
git clone --no-local --quiet "$repo" "$clone"
git -C "$clone" checkout --quiet --detach "$commit"
export CARGO_TARGET_DIR="$clone/target"
date=$(date -u +%Y-%m-%dT%H:%M:%SZ)
echo "build_profile: cargo build --release -p reproduce --timings (cold) ..." >&2
start=$(date +%s.%N)
(cd "$clone" && cargo build --release -p reproduce --timings)
end=$(date +%s.%N)
wall=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
echo "build_profile: built in $wall s" >&2
python3 "$here/build_units.py" "$clone/target/cargo-timings/cargo-timing.html" "$clone" \
    "${commit:0:12}" "$machine" "$(nproc)" "$date" "$wall" > "$partial"
mv -f "$partial" "$out"
echo "wrote $out" >&2
