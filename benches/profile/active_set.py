"""Sorts the self-time lines of `perf report --no-children --sort sym --stdio` over the
active-set bench (benches/profile/active_set.sh) by what the solver was doing, and prints one CSV
row per category that has samples, with its share of the solve's samples (the bench harness
excluded).

Categories, by the function a sample's instruction pointer was in:
- KKT factorisation and solves: the Schur-complement factorisation of the working set's KKT
  matrix (Cholesky of P when it changes, the rows of Y = L^-1 C' and of the Cholesky factor of
  S), its triangular solves and the step of iterative refinement (solvers::kkt_schur, the active
  set's begin, factor, factor_and_solve, solve_z, solve_direction and refine, the LU fallback);
- certification: the KKT residuals every answer is checked by, where a function of its own
  computes them (ActiveSetSolver::certificate; schemes::qp::Qp::kkt_residuals before revision
  9ca1d83); since 46f5891 they are computed in the same pass that writes the answer out, and
  their samples fall in the answer's category below;
- QP validation: the shapes and finiteness of the QP's data (schemes::qp::Qp::validate; with
  certification on, since 9ca1d83, only when the answer's residuals are not finite);
- working-set logic: loading the warm set, the primal feasibility and multiplier checks, the
  rows' right-hand sides and dot products (the rest of solvers::active_set but finish);
- the answer and its certificate: x, the multipliers and the objective written out, with the
  KKT residuals since 46f5891 (ActiveSetSolver::finish);
- other: anything else in the solver's process (copies, allocation).
The bench harness itself (criterion, the closure's loop) is left out of the shares.

Usage: active_set.py REPORT BENCH SECONDS FREQ_HZ GIT_REV
"""
import csv
import re
import sys

CATEGORIES = [  # (category, pattern), first match wins
    ("certification (KKT residuals)", re.compile(r"kkt_residuals|ActiveSetSolver::certificate")),
    ("QP validation", re.compile(r"Qp::validate")),
    ("KKT factorisation and solves (Schur complement, refinement)",
     re.compile(r"kkt_schur|ActiveSetSolver::(begin|factor|refine|solve_z|solve_direction|lu_refined)"
                r"|solve_refined|lu_factor|lu_solve")),
    ("the answer and its certificate (x, multipliers, objective, KKT residuals in one pass)",
     re.compile(r"ActiveSetSolver::finish")),
    ("working-set logic (warm set, feasibility and multiplier checks)",
     re.compile(r"solvers::active_set::")),
]
HARNESS = re.compile(r"criterion|Bencher|iter_batched|black_box")
LINE = re.compile(r"^\s*([0-9.]+)%\s+\[\.\]\s+(.*)$")


def main():
    path, bench, seconds, freq, rev = sys.argv[1:6]
    shares = {name: 0.0 for name, _ in CATEGORIES}
    shares["other"] = 0.0
    with open(path) as f:
        for line in f:
            m = LINE.match(line)
            if not m:
                continue
            pct, sym = float(m.group(1)), m.group(2)
            if HARNESS.search(sym):
                continue
            name = next((n for n, p in CATEGORIES if p.search(sym)), "other")
            shares[name] += pct
    total = sum(shares.values())
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["category", "share", "bench", "seconds", "frequency_hz", "git_rev"])
    # A category without a sample is left out (no row says 0 % of what did not run).
    for name, pct in sorted(shares.items(), key=lambda kv: -kv[1]):
        if pct == 0.0:
            continue
        out.writerow([name, f"{pct / total:.4f}", bench, seconds, freq, rev])


main()
