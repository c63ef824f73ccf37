"""Where a right-hand side's time goes: sorts the samples of `perf script -F comm,ip,sym`
(call graphs, leaf first) of one `reproduce shard` pass of the throughput sweep and prints one
CSV row per category with its share of the samples and its CPU time per right-hand-side
evaluation (share x the pass's user CPU seconds / its RHS evaluations).

Categories, by the stack (the innermost frame that names one decides within a part):
- rhs (under `NeuralLoop::eval`, the coupled right-hand side): kinematics (`robots::`: f, J,
  Jdot), the path (`schemes::paths`: r*, rdot*, rddot*), the network's KKT solve (`equality_kkt::`, the
  Schur complement of a diagonal P, and `lu::factor`, `lu::solve` otherwise: Q ydot = r), the network's other work (Q, E = Q y - u, Qdot y, the activation),
  QP assembly (the scheme and its terms writing P, q, A, b and their time derivatives), and the
  loop's own glue;
- integrator: the rest of `solvers::ode` (diffsol's Runge-Kutta stages, error control);
- observer: the closure that observes each accepted step (metrics, the exact QP that scores
  the run, the trace);
- other: start-up, experiment files, output.

Usage: classify.py STACKS USER_S RHS_EVALS GIT_REV
"""
import collections
import re
import sys

RHS = [  # (category, pattern), matched leaf first
    ("kinematics (f, J, Jdot)", re.compile(r"\brobots::")),
    ("path (r*, rdot*, rddot*)", re.compile(r"schemes::paths")),
    ("network: KKT solve (factor, solve)", re.compile(r"equality_kkt::|neural::lu::(factor|solve)")),
    ("network: Q, E, Qdot y, activation", re.compile(r"neural::")),
    ("QP assembly (terms, dQP/dt)", re.compile(r"\bschemes::|qp_data_at")),
]


def classify(frames):
    """(part, category) of one sample."""
    if any(re.search(r"simulate::.*\{\{closure\}\}", f) for f in frames):
        return "observer", "observer (metrics, scoring exact QP, trace)"
    if any("NeuralLoop::eval" in f for f in frames):
        for f in frames:
            for name, pattern in RHS:
                if pattern.search(f):
                    return "rhs", name
        return "rhs", "RHS glue (loop, copies)"
    if any("solvers::ode::" in f for f in frames):
        return "integrator", "integrator (Runge-Kutta stages, error control)"
    return "other", "other (start-up, files, output)"


def main(stacks, user_s, rhs_evals, rev):
    counts = collections.Counter()
    frames = []
    for line in list(open(stacks, errors="replace")) + [""]:
        if not line.strip():
            if frames:
                counts[classify(frames)] += 1
            frames = []
        elif line.startswith(("\t", " ")):
            frames.append(line.strip())
    total = sum(counts.values())
    if total == 0:
        sys.exit(f"{stacks}: no samples")
    print("part,category,samples,share,cpu_us_per_rhs,user_s,rhs_evals,git_rev")
    for (part, category), n in sorted(counts.items(), key=lambda kv: (kv[0][0], -kv[1])):
        share = n / total
        per_rhs = share * float(user_s) / float(rhs_evals) * 1e6
        print(f'{part},"{category}",{n},{share:.4f},{per_rhs:.4g},{user_s},{rhs_evals},{rev}')


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
