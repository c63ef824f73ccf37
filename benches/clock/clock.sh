#!/usr/bin/env bash
# The newcomer's clock: for each git revision given, a fresh clone of this repository, timed
# from clone to report, into benches/results/clock.csv (benches/REPORT.md, "The newcomer's
# clock"; benches/src/telemetry/clock.rs defines the columns; docs/guide/clock.md).
#
# Per revision: `git clone --no-local` of this repository into a temporary directory, the
# revision checked out (committed code only: uncommitted changes are not in the clone), with a
# CARGO_TARGET_DIR of its own inside the temporary directory, and timed by the wall clock:
#   build      cargo build --release -p reproduce   (cold: an empty target directory)
#   reproduce  cargo run --release -p reproduce     (the whole reproduction, after the build;
#                                                    its results/ and report/ go into the clone)
#   test       cargo test --workspace --release     (the test build included)
#   wheel      pip install ./python                  (in a fresh virtual environment, with a
#                                                    target directory of its own: the Python
#                                                    package built from nothing, maturin
#                                                    fetched from PyPI by pip)
# The reproduce step always follows a build: when `build` is not selected it is built first,
# untimed. A failing step keeps its time and its exit code, and the next steps still run.
#
# Cargo's registry (CARGO_HOME) is shared with the user's by default, so crates already
# downloaded are not downloaded again and downloads are not timed; --fresh-cargo-home gives
# each clone a CARGO_HOME of its own in the temporary directory (every dependency downloaded,
# and timed, within the build step).
#
# Needs an otherwise idle machine: every step uses every core, and the script cannot check
# that nothing else runs. About half an hour of the whole machine per revision on 2 cores.
#
# Writes nothing outside its temporary directory (removed on exit) and the --out file, which
# is replaced atomically at the end (a temporary file beside it, renamed). After it, render
# the benches' page: `cargo run --release -p driftbench-benches --bin telemetry`.
#
# Usage (from anywhere inside the repository):
#   benches/clock/clock.sh [--only build,reproduce,test,wheel] [--out FILE] [--fresh-cargo-home]
#                          [--dry-run] [REVISION...]          (default revisions: cc915b9 HEAD)
set -euo pipefail

usage() {
    sed -n '/^# Usage/,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
    exit "${1:-2}"
}

repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
# shellcheck source=lib.sh
. "$(dirname "$0")/lib.sh"
only="build,reproduce,test,wheel"
out="$repo/benches/results/clock.csv"
fresh_home=0
dry_run=0
revisions=()
while [ $# -gt 0 ]; do
    case "$1" in
        --only) only="${2:?--only needs a list}"; shift 2 ;;
        --only=*) only="${1#--only=}"; shift ;;
        --out) out="${2:?--out needs a file}"; shift 2 ;;
        --out=*) out="${1#--out=}"; shift ;;
        --fresh-cargo-home) fresh_home=1; shift ;;
        --dry-run) dry_run=1; shift ;;
        -h|--help) usage 0 ;;
        -*) echo "clock.sh: unknown option $1" >&2; usage ;;
        *) revisions+=("$1"); shift ;;
    esac
done
[ ${#revisions[@]} -gt 0 ] || revisions=(cc915b9 HEAD)

IFS=',' read -r -a wanted <<< "$only"
for step in "${wanted[@]}"; do
    case "$step" in
        build|reproduce|test|wheel) ;;
        *) echo "clock.sh: --only: unknown step \"$step\" (known: build, reproduce, test, wheel)" >&2; exit 2 ;;
    esac
done
selected() { case ",$only," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }
# The selected steps, always in this order.
steps=()
for step in build reproduce test wheel; do
    if selected "$step"; then steps+=("$step"); fi
done
[ ${#steps[@]} -gt 0 ] || { echo "clock.sh: --only selects no step" >&2; exit 2; }

case "$out" in /*) ;; *) out="$PWD/$out" ;; esac
out_dir=$(dirname "$out")
[ -d "$out_dir" ] || { echo "clock.sh: --out: no directory $out_dir" >&2; exit 2; }

# Every revision resolved before anything runs.
commits=()
for rev in "${revisions[@]}"; do
    commit=$(git -C "$repo" rev-parse --verify --quiet "$rev^{commit}") || {
        echo "clock.sh: $rev: not a commit of $repo" >&2
        exit 2
    }
    commits+=("$commit")
done

machine=$(machine_name)
cores=$(nproc)

# The commands a step runs, in the clone ($1); printed by --dry-run.
command_of() {
    case "$1" in
        build) echo "cargo build --release -p reproduce" ;;
        reproduce) echo "cargo run --release -p reproduce" ;;
        test) echo "cargo test --workspace --release" ;;
        wheel) echo "pip install ./python" ;;
    esac
}

# The program a step runs, as words: the wheel's pip is the fresh virtual environment's ($2).
argv_of() {
    case "$1" in
        wheel) echo "$2/bin/pip install --disable-pip-version-check ./python" ;;
        *) command_of "$1" ;;
    esac
}

if [ "$dry_run" = 1 ]; then
    echo "# dry run: nothing is cloned, built, run or written"
    echo "# machine: $machine ($cores logical cores); output: $out"
    tmp="\$TMP"
    for i in "${!revisions[@]}"; do
        clone="$tmp/clone-$i"
        echo "git clone --no-local --quiet $repo $clone"
        echo "git -C $clone checkout --quiet --detach ${commits[$i]}   # ${revisions[$i]}"
        if [ "$fresh_home" = 1 ]; then
            echo "export CARGO_HOME=$tmp/cargo-home-$i"
        fi
        echo "export CARGO_TARGET_DIR=$clone/target"
        if selected reproduce && ! selected build; then
            echo "(cd $clone && $(command_of build))   # untimed: the reproduction follows a build"
        fi
        for step in "${steps[@]}"; do
            if [ "$step" = wheel ]; then
                echo "python3 -m venv $tmp/venv-$i   # untimed"
                echo "(cd $clone && CARGO_TARGET_DIR=$tmp/wheel-target-$i $(argv_of wheel "$tmp/venv-$i"))   # timed: ${revisions[$i]} wheel"
            else
                echo "(cd $clone && $(command_of "$step"))   # timed: ${revisions[$i]} $step"
            fi
        done
    done
    echo "# rows: revision,commit,step,seconds,exit_code,machine,cores,date -> $out (temporary file + mv)"
    exit 0
fi

make_tmp clock "$out"

rows="$tmp/clock.csv"
echo "revision,commit,step,seconds,exit_code,machine,cores,date" > "$rows"

# Runs the rest of the arguments in the clone $1 and times them: sets `seconds` and `code`.
timed() {
    local dir="$1"; shift
    local start end
    start=$(date +%s.%N)
    code=0
    (cd "$dir" && "$@") > "$log" 2>&1 || code=$?
    end=$(date +%s.%N)
    seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')
}

csv_field() { printf '"%s"' "${1//\"/\"\"}"; }

echo "clock: ${#revisions[@]} revision(s), steps ${steps[*]}, on $machine ($cores cores); temporary directory $tmp" >&2
for i in "${!revisions[@]}"; do
    rev="${revisions[$i]}"
    commit="${commits[$i]}"
    short="${commit:0:12}"
    clone="$tmp/clone-$i"
    echo "[$rev] cloning $short" >&2
    git clone --no-local --quiet "$repo" "$clone"
    git -C "$clone" checkout --quiet --detach "$commit"
    export CARGO_TARGET_DIR="$clone/target"
    if [ "$fresh_home" = 1 ]; then
        export CARGO_HOME="$tmp/cargo-home-$i"
    fi
    if selected reproduce && ! selected build; then
        echo "[$rev] building first (untimed: the reproduction follows a build)" >&2
        log="$tmp/$i-prebuild.log"
        timed "$clone" cargo build --release -p reproduce
        if [ "$code" != 0 ]; then
            echo "[$rev]   the build failed (exit $code); its last lines:" >&2
            tail -n 5 "$log" | sed 's/^/    /' >&2
        fi
    fi
    for step in "${steps[@]}"; do
        log="$tmp/$i-$step.log"
        date=$(date -u +%Y-%m-%dT%H:%M:%SZ)
        echo "[$rev] $step: $(command_of "$step") ..." >&2
        if [ "$step" = wheel ]; then
            # A fresh virtual environment (untimed) and a target directory of its own: the
            # package is built from nothing, as `pip install ./python` on a fresh machine.
            python3 -m venv "$tmp/venv-$i"
            # shellcheck disable=SC2046 # the command's words are split on purpose
            CARGO_TARGET_DIR="$tmp/wheel-target-$i" timed "$clone" $(argv_of wheel "$tmp/venv-$i")
        else
            # shellcheck disable=SC2046 # the command's words are split on purpose
            timed "$clone" $(command_of "$step")
        fi
        echo "[$rev] $step: ${seconds} s, exit code $code" >&2
        if [ "$code" != 0 ]; then
            echo "[$rev]   its last lines:" >&2
            tail -n 5 "$log" | sed 's/^/    /' >&2
        fi
        printf '%s,%s,%s,%s,%s,%s,%s,%s\n' "$(csv_field "$rev")" "$short" "$step" "$seconds" \
            "$code" "$(csv_field "$machine")" "$cores" "$date" >> "$rows"
    done
    # The clone (and its target directory) goes before the next revision's build.
    rm -rf "$clone"
done

cp "$rows" "$partial"
mv -f "$partial" "$out"
echo "wrote $out" >&2
