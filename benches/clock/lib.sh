# Shared by clock.sh and build_profile.sh (sourced, not run).

# The CPU model (/proc/cpuinfo), without quotes or repeated spaces.
machine_name() {
    local m
    m=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
    echo "${m:-unknown CPU}" | tr -s ' ' | tr -d '"'
}

# make_tmp NAME OUT: sets `tmp`, a new temporary directory driftbench-NAME.XXXXXX, and
# `partial`, the temporary name of the file OUT. It has the program's own pattern
# <name>.<pid>.<n>.tmp, so a reproduce run cleans it up if the script is killed before its
# rename. Both are removed on exit, also when interrupted.
make_tmp() {
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/driftbench-$1.XXXXXX")
    partial="$2.$$.0.tmp"
    trap 'rm -rf "$tmp"; rm -f "$partial"' EXIT
    trap 'exit 130' INT TERM
}
