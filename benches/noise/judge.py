#!/usr/bin/env python3
"""Judge a change that reorders floating-point operations: is every result it moves within the
rounding noise of that result?

A change such as solving a linear system by another factorisation gives the same answers to
rounding, and the runs integrate and accumulate those last bits. How far a reported number can
move that way is measured, not assumed: the baseline revision runs again with its inputs moved
by one unit in the last place (perturb.py: every initial configuration and every path's
duration, four patterns; run.sh), and for each cell of each results table the noise floor is
the largest change such a run makes. The rule, cell by cell (rows matched by position; the
tables' row counts and each row's first four cells, its key, must agree, or the judgement stops):

- a number may move by at most 10 times its noise floor, or by 1e-12 relative (1e-12 absolute
  for a value below 1 in magnitude), whichever is larger: the factor 10 because a few samples
  of noise estimate its size only to within an order of magnitude, the 1e-12 for quantities
  that are zero to rounding in one order and not in another (the distance between two exact
  solvers);
- the components of a drift vector (`drift_1` ... `drift_7`) share one floor, the largest
  change a perturbed run makes to any of them (the vector is one quantity, as the tolerance
  ladder judges it);
- a count (both values integers) may move by one, its smallest change;
- a number whose noise floor is half its magnitude or more has no reproducible digit: any value
  is within;
- a row whose headline number (`drift_norm`, else `drift`) has no reproducible digit is noise
  as a whole (the run's, rung's or cycle's trajectory is not reproducible under rounding):
  every cell of it is within, its status and failure message included; so are all the rows of
  one loop (the rows that differ only from their `cycle` column on) once one of them is;
- any other cell (a status, a class, a failure message, a number appearing or vanishing) may
  change only where a perturbed run changes it too.

Timing columns and the timing tables are not judged (TIMING, TIMING_TABLES). The output is one
CSV row per changed cell (table, row, key, column, baseline, candidate, noise floor, verdict)
and a summary per table on stderr; the exit status is 1 when any cell is beyond its floor.

Usage: judge.py BASELINE_RESULTS CANDIDATE_RESULTS PERTURBED_RESULTS... > cells.csv"""
import csv
import math
import re
import sys
from pathlib import Path

TIMING = re.compile(
    r"(_us$|^wall_s|^sim_s|^observe_s|^time_|^machine$|^cores$|^git_rev$|^crate_version$"
    r"|^python$|^numpy$)"
)
# Tables that are measurements of time, or written by something else than `reproduce run`
# (the cost and infer subcommands, the Python package's leaderboard).
TIMING_TABLES = {
    "leaderboard-python.csv",
    "leaderboard-timing.csv",
    "python-call-cost.csv",
    "qp-replay.csv",
    "dof-cost.csv",
    "inference.csv",
    "inference-entries.csv",
}
FACTOR = 10.0
RELATIVE = 1e-12
# A number with a noise floor of at least this fraction of its magnitude has no stable digit.
NO_DIGIT = 0.5
HEADLINE = ("drift_norm", "drift")
COMPONENT = re.compile(r"^drift_[0-9]+$")
LOOP_INDEX = "cycle"
COUNT = re.compile(r"^-?[0-9]+$")


def number(text: str):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if text.strip() else None


def no_digit(base: str, perturbed: list[str]) -> bool:
    """Whether a perturbed run moves the number `base` by half its magnitude or more, or turns
    it into something else (a failed run's empty cell)."""
    b = number(base)
    if b is None:
        return any(p != base for p in perturbed)
    for p in perturbed:
        v = number(p)
        if v is None or abs(v - b) >= NO_DIGIT * abs(b):
            return True
    return False


def table(path: Path):
    with path.open(newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def judge(name: str, base: Path, cand: Path, perturbed: list[Path], out) -> tuple[int, int]:
    header, rows = table(base / name)
    cheader, crows = table(cand / name)
    pert = [table(p / name) for p in perturbed]
    for h, r in [(cheader, crows)] + pert:
        if len(r) != len(rows):
            raise SystemExit(f"{name}: {len(r)} rows against the baseline's {len(rows)}")
    cols = [c for c in header if c in cheader and not TIMING.search(c)]
    index = lambda h: {c: i for i, c in enumerate(h)}
    bi, ci = index(header), index(cheader)
    pis = [index(h) for h, _ in pert]
    changed = beyond = 0
    headline = next((c for c in HEADLINE if c in bi), None)
    noisy = [
        headline is not None
        and no_digit(row[bi[headline]], [p[1][k][pi[headline]] for p, pi in zip(pert, pis)])
        for k, row in enumerate(rows)
    ]
    if LOOP_INDEX in bi:
        loop = lambda row: tuple(row[: bi[LOOP_INDEX]])
        noisy_loops = {loop(row) for row, n in zip(rows, noisy) if n}
        noisy = [loop(row) in noisy_loops for row in rows]
    components = [c for c in header if COMPONENT.match(c) and c in ci]
    for k, row in enumerate(rows):
        key = " | ".join(row[:4])
        crow = crows[k]
        for other in [crow] + [p[1][k] for p in pert]:
            if other[:4] != row[:4]:
                raise SystemExit(f"{name}, line {k + 2}: the rows differ in their key ({key})")
        noise_row = noisy[k]
        vector_floor = 0.0
        for col in components:
            b = number(row[bi[col]])
            for p, pi in zip(pert, pis):
                v = number(p[1][k][pi[col]]) if col in pi else None
                if b is not None and v is not None:
                    vector_floor = max(vector_floor, abs(v - b))
        for col in cols:
            b, c = row[bi[col]], crow[ci[col]]
            if b == c:
                continue
            changed += 1
            ps = [p[1][k][pi[col]] if col in pi else b for p, pi in zip(pert, pis)]
            bn, cn, pn = number(b), number(c), [number(p) for p in ps]
            if noise_row:
                ok, shown = True, f"{headline} has no stable digit"
            elif bn is not None and cn is not None and all(p is not None for p in pn):
                floor = max(abs(p - bn) for p in pn) if pn else 0.0
                if col in components:
                    floor = max(floor, vector_floor)
                allowed = max(FACTOR * floor, RELATIVE * max(1.0, abs(bn)))
                if COUNT.match(b) and COUNT.match(c):
                    allowed = max(allowed, 1.0)
                ok = (
                    abs(cn - bn) <= allowed
                    or floor >= NO_DIGIT * abs(bn)
                    or (math.isnan(bn) and math.isnan(cn))
                )
                shown = f"{floor:.3g}"
            else:
                ok = any(p != b for p in ps)
                shown = "changes" if ok else "unchanged"
            beyond += not ok
            out.writerow([name, k + 2, key, col, b, c, shown, "within" if ok else "BEYOND"])
    return changed, beyond


def main() -> None:
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    base, cand = Path(sys.argv[1]), Path(sys.argv[2])
    perturbed = [Path(p) for p in sys.argv[3:]]
    out = csv.writer(sys.stdout)
    out.writerow(["table", "line", "key", "column", "baseline", "candidate", "noise_floor",
                  "verdict"])
    total = 0
    for path in sorted(base.glob("*.csv")):
        name = path.name
        if name in TIMING_TABLES:
            continue
        if not (cand / name).exists() or not all((p / name).exists() for p in perturbed):
            print(f"{name}: missing in the candidate or a perturbed run", file=sys.stderr)
            total += 1
            continue
        changed, beyond = judge(name, base, cand, perturbed, out)
        total += beyond
        print(f"{name}: {changed} cells changed, {beyond} beyond the noise floor",
              file=sys.stderr)
    sys.exit(1 if total else 0)


if __name__ == "__main__":
    main()
