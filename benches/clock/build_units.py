"""Reads the unit table of a `cargo build --timings` report (cargo-timing.html: the UNIT_DATA
array, one entry per compilation unit) and prints `benches/results/build-profile.csv`'s rows
(records/src/build_profile.rs defines the columns) on stdout.

Per unit: its index, crate, version, kind (`lib`, `bin`, `build-script` for compiling a build
script, `build-script-run` for running it), whether the crate is one of the workspace's
(`cargo metadata --no-deps` of the clone), its start and duration (s, from the build's start),
and `unblocked_by`: the unit whose end (or whose metadata, under pipelining) let it start, the
last of its dependencies to finish, from cargo's own `unblocked_units` and
`unblocked_rmeta_units` lists. Following `unblocked_by` back from the unit that ends last gives
the build's critical path (crate `analysis`, `performance::build`).

Usage: build_units.py TIMINGS_HTML CLONE_DIR COMMIT MACHINE CORES DATE WALL_S
"""
import csv
import json
import re
import subprocess
import sys

KINDS = [  # (kind, pattern in cargo's `target` text), first match wins
    ("build-script-run", re.compile(r"\(run\)")),
    ("build-script", re.compile(r"build[- ]script")),
    ("bin", re.compile(r'"bin"')),
    ("test", re.compile(r'"test"|\(test\)')),
]


def kind_of(target):
    target = target.strip()
    for kind, pattern in KINDS:
        if pattern.search(target):
            return kind
    if target in ("", '"lib"', "lib"):
        return "lib"
    sys.exit(f"build_units.py: unknown unit target {target!r}: add it to KINDS")


def units(html):
    """The UNIT_DATA array of a cargo timings report."""
    m = re.search(r"const UNIT_DATA = (\[.*?\n\]);", html, re.S)
    if not m:
        sys.exit("build_units.py: no UNIT_DATA in the timings report (a cargo that writes another format?)")
    return json.loads(m.group(1))


def workspace_crates(clone):
    meta = subprocess.run(
        ["cargo", "metadata", "--no-deps", "--format-version", "1", "--offline"],
        cwd=clone, check=True, capture_output=True, text=True,
    )
    return {p["name"] for p in json.loads(meta.stdout)["packages"]}


def main():
    if len(sys.argv) != 8:
        sys.exit(__doc__.strip().splitlines()[-1])
    path, clone, commit, machine, cores, date, wall = sys.argv[1:]
    with open(path, encoding="utf-8") as f:
        data = units(f.read())
    ours = workspace_crates(clone)
    unblocked_by = {}
    for u in data:
        for v in u.get("unblocked_units", []) + u.get("unblocked_rmeta_units", []):
            unblocked_by[v] = u["i"]
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["unit", "crate_name", "version", "kind", "workspace", "start_s", "duration_s",
                  "unblocked_by", "commit", "machine", "cores", "date", "build_wall_s"])
    for u in sorted(data, key=lambda u: u["i"]):
        out.writerow([
            u["i"], u["name"], u["version"], kind_of(u.get("target", "")),
            "true" if u["name"] in ours else "false",
            f'{u["start"]:.2f}', f'{u["duration"]:.2f}',
            unblocked_by.get(u["i"], ""), commit, machine, cores, date, wall,
        ])


if __name__ == "__main__":
    main()
