#!/usr/bin/env python3
"""The side-by-side measurement (build_and_runs.sh): each cold build as measured (wall and CPU
seconds, the load before it), and per run present in both, the candidate's sim_s over the
baseline's (median and worst), runs matched by paper, experiment, variant and solver (skipped,
and said so, when the measurement was --build-only). The build ratio and its verdict are not
computed here: benches/REPORT.md has them ("The cold build against f5570fd", from build.csv;
`cargo run --release -p driftbench-benches --bin telemetry`)."""
import csv, statistics, sys
from pathlib import Path

out, base, cand = Path(sys.argv[1]), sys.argv[2], sys.argv[3]
rows = list(csv.DictReader(open(out / "build.csv")))
cpu = lambda r: float(r["user_s"]) + float(r["sys_s"])
wall = lambda r: float(r["wall_s"])
of = lambda rev: [r for r in rows if r["revision"] == rev]
b, c = of(base), of(cand)
if not b or not c:
    sys.exit(f"build.csv has no build of {base if not b else cand}")
for rev, builds in ((base, b), (cand, c)):
    each = "; ".join(f"round {r.get('round', '1')}: {wall(r):.0f} s wall, {cpu(r):.0f} CPU s "
                     f"(load {r['load1']})" for r in builds)
    print(f"cold build {rev}: {each}")
print("build ratio: benches/REPORT.md, \"The cold build against f5570fd\" "
      "(cargo run --release -p driftbench-benches --bin telemetry)")

def passes(rev):
    """runs-REV.csv (one pass) or runs-REV-p1.csv, runs-REV-p2.csv, ... (several)."""
    one = out / f"runs-{rev}.csv"
    return [one] if one.exists() else sorted(out.glob(f"runs-{rev}-p*.csv"))

def runs(rev):
    """Each run's sim_s, the median over the passes that timed it."""
    key = lambda r: (r["paper"], r["experiment"], r.get("variant_id", ""), r.get("solver_id", ""))
    times = {}
    for path in passes(rev):
        for r in csv.DictReader(open(path)):
            if r.get("sim_s") not in (None, "") and float(r["sim_s"]) > 0:
                times.setdefault(key(r), []).append(float(r["sim_s"]))
    return {k: statistics.median(v) for k, v in times.items()}

if not all(passes(rev) for rev in (base, cand)):
    print("sim_s: not measured (no runs-<revision>.csv for both: a --build-only measurement)")
    sys.exit(0)
rb, rc = runs(base), runs(cand)
common = sorted(set(rb) & set(rc))
ratios = [rc[k] / rb[k] for k in common]
if not ratios:
    sys.exit("no run with a sim_s in both revisions")
worst = max(zip(ratios, common))
print(f"sim_s over {len(common)} runs in both ({len(passes(base))} and {len(passes(cand))} passes, "
      f"a run's sim_s the median over them): median ratio {statistics.median(ratios):.3f}, "
      f"worst {worst[0]:.3f} ({'/'.join(worst[1])}); total {sum(rc[k] for k in common):.1f} s "
      f"against {sum(rb[k] for k in common):.1f} s")
