#!/usr/bin/env python3
"""Ratios of the side-by-side measurement (build_and_runs.sh): the candidate's cold build over
the baseline's (wall and CPU seconds), and per run present in both, the candidate's sim_s over
the baseline's (median and worst), runs matched by paper, experiment, variant and solver."""
import csv, statistics, sys
from pathlib import Path

out, base, cand = Path(sys.argv[1]), sys.argv[2], sys.argv[3]
builds = {r["revision"]: r for r in csv.DictReader(open(out / "build.csv"))}
b, c = builds[base], builds[cand]
cpu = lambda r: float(r["user_s"]) + float(r["sys_s"])
print(f"cold build: {base} {float(b['wall_s']):.0f} s wall, {cpu(b):.0f} CPU s (load {b['load1']}); "
      f"{cand} {float(c['wall_s']):.0f} s wall, {cpu(c):.0f} CPU s (load {c['load1']})")
print(f"build ratio: wall {float(c['wall_s']) / float(b['wall_s']):.3f}, CPU {cpu(c) / cpu(b):.3f}")

def runs(rev):
    key = lambda r: (r["paper"], r["experiment"], r.get("variant_id", ""), r.get("solver_id", ""))
    return {key(r): float(r["sim_s"]) for r in csv.DictReader(open(out / f"runs-{rev}.csv"))
            if r.get("sim_s") not in (None, "") and float(r["sim_s"]) > 0}

rb, rc = runs(base), runs(cand)
common = sorted(set(rb) & set(rc))
ratios = [rc[k] / rb[k] for k in common]
if not ratios:
    sys.exit("no run with a sim_s in both revisions")
worst = max(zip(ratios, common))
print(f"sim_s over {len(common)} runs in both: median ratio {statistics.median(ratios):.3f}, "
      f"worst {worst[0]:.3f} ({'/'.join(worst[1])}); total {sum(rc[k] for k in common):.1f} s "
      f"against {sum(rb[k] for k in common):.1f} s")
