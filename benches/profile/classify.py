"""Sorts the samples of `perf script -F comm,ip,sym` (call graphs, leaf first) of a
`reproduce` process by what the program was doing, and prints one CSV row per category.

Parts (by the frames on the stack):
- observer: the closure that observes accepted steps (`simulate::simulate::{{closure}}`):
  the exact QP that scores a network run (or gives the exact column's command), metrics,
  trace and the network's own error;
- exact column: the exact optimum as the right-hand side of the exact column's ODE;
- simulation: everything else under `solvers::ode::integrate` (the neural runs' integration);
- other: start-up, experiment files, output.
Categories of the simulation, by the innermost frame that names one: the RHS (network and QP
assembly), the network's analytic Jacobian, the Jacobian assembled from J e_j products,
the LU factorisation and the LU solves of the Newton matrix, allocation, and the BDF method's
own work (Newton loop, predictor, error estimate, order and step-size control, the
difference array). RHS, Jacobian and LU are the floor: the work the run's counts require.

Usage: classify.py STACKS PASSES FREQ_HZ GIT_REV
"""
import collections
import csv
import re
import sys

SIMULATION = [  # (category, in the floor, pattern), matched leaf first
    ("allocation", False, re.compile(r"\b(malloc|_int_free|_int_malloc|free|realloc|cfree|_int_realloc)\b")),
    ("LU factorisation", True, re.compile(r"BatchLu<T>::factor|gauss_step")),
    ("LU solve", True, re.compile(r"ReusableLU<T> as diffsol_la::linear_solver::LinearSolver.*solve|BatchLu<T>::solve")),
    ("Jacobian from J e_j products", False, re.compile(r"Counted<S>::jac_mul")),
    ("network Jacobian", True, re.compile(r"OdeSystem>::jacobian|refresh_jacobian")),
    ("RHS (network and QP assembly)", True, re.compile(r"NeuralLoop<_>::eval|OdeSystem>::rhs|Counted<S>::rhs")),
]
BDF = ("BDF method (Newton loop, predictor, error and step control)", False, re.compile(r"diffsol"))


def classify(frames):
    """(part, category, in the floor) of one sample."""
    if any("ExactLoop<_> as solvers::ode::OdeSystem>::rhs" in f for f in frames):
        return "exact column", "exact QP as the RHS", False
    if any("simulate::simulate::{{closure}}" in f for f in frames):
        if any("ExactPath::solve" in f or "ExactLoop<_>::optimum" in f for f in frames):
            return "observer", "exact QP (score, exact column's command)", False
        return "observer", "metrics, trace, network error", False
    if not any("solvers::ode::integrate" in f for f in frames):
        return "other", "start-up, files, output", False
    for f in frames:
        for name, floor, pattern in SIMULATION:
            if pattern.search(f):
                return "simulation", name, floor
    for f in frames:
        if BDF[2].search(f):
            return "simulation", BDF[0], BDF[1]
    return "simulation", "other", False


def samples(path):
    """The frames (leaf first) of each sample of the `reproduce` process."""
    block = []
    for line in open(path):
        if line.strip():
            block.append(line.rstrip("\n"))
            continue
        if block and block[0].strip().startswith("reproduce"):
            yield [l.strip().split(None, 1)[1] if len(l.strip().split(None, 1)) > 1 else "" for l in block[1:]]
        block = []
    if block and block[0].strip().startswith("reproduce"):
        yield [l.strip().split(None, 1)[1] for l in block[1:] if len(l.strip().split(None, 1)) > 1]


def main():
    path, paper, passes, freq, rev = (sys.argv[1], sys.argv[2], int(sys.argv[3]),
                                     float(sys.argv[4]), sys.argv[5])
    counts = collections.Counter()
    floor = {}
    for frames in samples(path):
        part, name, in_floor = classify(frames)
        counts[(part, name)] += 1
        floor[(part, name)] = in_floor
    total = sum(counts.values())
    simulation = sum(c for (part, _), c in counts.items() if part == "simulation")
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["part", "category", "floor", "samples", "share_of_process",
                  "share_of_simulation", "ms_per_pass", "paper", "passes", "frequency_hz", "git_rev"])
    order = ["simulation", "exact column", "observer", "other"]
    for key, c in sorted(counts.items(), key=lambda kc: (order.index(kc[0][0]), -kc[1])):
        part, name = key
        sim_share = f"{c / simulation:.4f}" if part == "simulation" and simulation else ""
        out.writerow([part, name, "yes" if floor[key] else "no", c, f"{c / total:.4f}",
                      sim_share, f"{1e3 * c / freq / passes:.3f}", paper, passes, f"{freq:g}", rev])

main()
