"""Summary of benches/results/throughput.csv (benches/throughput/kong2019_sweep.sh): per
revision, the medians over its passes of the user CPU seconds, the runs per CPU second, the CPU
time per right-hand-side evaluation (the whole process's, observation and scoring included) and,
where measured, the instructions; then new / old ratios of the throughput.

Usage: python3 benches/throughput/summary.py benches/results/throughput.csv
"""

import csv
import statistics
import sys


def main(path):
    rows = list(csv.DictReader(open(path)))
    sides = {}
    for r in rows:
        sides.setdefault(r["revision"], []).append(r)
    summary = {}
    for side in ("old", "new"):
        rs = sides.get(side, [])
        if not rs:
            sys.exit(f"{path}: no rows of the {side} revision")
        med = lambda f: statistics.median(f(r) for r in rs)
        instr = [float(r["instructions"]) for r in rs if r["instructions"]]
        summary[side] = {
            "commit": rs[0]["commit"],
            "passes": len(rs),
            "runs": int(rs[0]["runs"]),
            "user_s": med(lambda r: float(r["user_s"])),
            "runs_per_cpu_s": med(lambda r: int(r["runs"]) / float(r["user_s"])),
            "cpu_us_per_rhs": med(lambda r: 1e6 * float(r["user_s"]) / float(r["rhs_evals"])),
            "rhs_per_run": med(lambda r: float(r["rhs_evals"]) / int(r["runs"])),
            "instructions": statistics.median(instr) if instr else None,
        }
    print("revision  commit        passes  runs  user_s (median)  runs/CPU-s  CPU us/RHS  RHS/run  instructions")
    for side, s in summary.items():
        instr = f"{s['instructions']:.4g}" if s["instructions"] else "not measured"
        print(f"{side:9} {s['commit']:13} {s['passes']:6}  {s['runs']:4}  {s['user_s']:15.3f}  "
              f"{s['runs_per_cpu_s']:10.1f}  {s['cpu_us_per_rhs']:10.3f}  {s['rhs_per_run']:7.0f}  {instr}")
    old, new = summary["old"], summary["new"]
    print(f"throughput new / old (runs per CPU second): {new['runs_per_cpu_s'] / old['runs_per_cpu_s']:.2f}"
          " (target: at least 2)")
    if old["instructions"] and new["instructions"]:
        print(f"instructions old / new: {old['instructions'] / new['instructions']:.2f}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
