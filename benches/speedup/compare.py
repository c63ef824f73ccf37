"""Matches the runs of two revisions of driftbench, each timed alone over several passes
(benches/speedup/papers.sh), and prints one CSV row per run both revisions have.

A run is matched by (experiment, variant label, solver label); where the labels differ between
the revisions (the exact column was renamed), by (experiment, variant label, solver kind) when
that kind is unique in the variant on both sides. Per run and revision the row keeps the median
over the passes of sim_s (the integration) and wall_s (the whole run, observation and scoring
included), their ratios old / new, and both revisions' status and drift norm, so that a reader
can check the speed-up did not change what was computed.

Usage: compare.py DIR PASSES OLD_REV NEW_REV   (DIR holds old-PAPER-PASS/ and new-PAPER-PASS/)
"""
import csv
import os
import statistics
import sys


def read(dir_, side):
    """{run identity: [row of each pass]} of one revision."""
    runs = {}
    for name in sorted(os.listdir(dir_)):
        if not name.startswith(side + "-") or not os.path.isdir(os.path.join(dir_, name)):
            continue
        path = os.path.join(dir_, name, "runs.csv")
        if not os.path.exists(path):
            continue
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                runs.setdefault((row["experiment"], row["variant"], row["solver"]), []).append(row)
    return runs


def by_kind(runs):
    """{(experiment, variant, solver kind): identity} for kinds unique in their variant."""
    seen = {}
    for key, rows in runs.items():
        k = (key[0], key[1], rows[0]["solver_kind"])
        seen[k] = None if k in seen else key
    return {k: v for k, v in seen.items() if v is not None}


def median(rows, column):
    values = [float(r[column]) for r in rows if r[column] != ""]
    return statistics.median(values) if values else None


def main():
    dir_, passes, old_rev, new_rev = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
    old, new = read(dir_, "old"), read(dir_, "new")
    old_kind, new_kind = by_kind(old), by_kind(new)
    pairs = []
    for key in sorted(new):
        if key in old:
            pairs.append((old[key], new[key]))
            continue
        k = (key[0], key[1], new[key][0]["solver_kind"])
        if new_kind.get(k) == key and k in old_kind and old_kind[k] not in new:
            pairs.append((old[old_kind[k]], new[key]))
    unmatched = len(new) - len(pairs)
    print(f"{len(pairs)} runs matched, {unmatched} of the new revision's runs have no "
          f"counterpart", file=sys.stderr)
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["paper", "experiment", "variant", "solver", "old_rev", "new_rev", "passes",
                "old_sim_s", "new_sim_s", "sim_speedup", "old_wall_s", "new_wall_s",
                "wall_speedup", "old_status", "new_status", "old_drift_norm", "new_drift_norm"])
    for o, n in pairs:
        first = n[0]
        o_sim, n_sim = median(o, "sim_s"), median(n, "sim_s")
        o_wall, n_wall = median(o, "wall_s"), median(n, "wall_s")
        ratio = lambda a, b: f"{a / b:.4g}" if a is not None and b else ""
        fmt = lambda v: f"{v:.6g}" if v is not None else ""
        w.writerow([first["paper"], first["experiment"], first["variant"], first["solver"],
                    old_rev, new_rev, passes, fmt(o_sim), fmt(n_sim), ratio(o_sim, n_sim),
                    fmt(o_wall), fmt(n_wall), ratio(o_wall, n_wall), o[0]["status"],
                    first["status"], o[0]["drift_norm"], first["drift_norm"]])


main()
