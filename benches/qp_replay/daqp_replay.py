"""Replays the recorded QPs to DAQP and writes results/qp-replay.csv beside the suite's numbers
(records/src/qp_replay.rs states the file).

DAQP states min x'Hx/2 + f'x s.t. blower <= [x; C x] <= bupper, the first nx bounds simple
bounds; the QP's equalities A x = b are rows with sense 5 (active and immutable), its
inequalities G x <= h rows without a lower bound, and an infinite bound is DAQP's infinity
(1e30). DAQP's tolerances are tightened (primal 1e-12) so that its answers are comparable with
the suite's certified ones. Times are DAQP's own C timers, setup_time + solve_time of one
daqp.solve call (the setup factors H, as the suite factors its KKT matrix at every solve):
cold from nothing; warm with the constraints active at the previous QP's answer (nonzero
multiplier) marked active in `sense`, DAQP's way of starting from a working set.

Usage: python daqp_replay.py QPS_DIR REPEATS GIT_REV > results/qp-replay.csv"""

import csv
import importlib.metadata
import pathlib
import statistics
import sys

import daqp
import numpy as np

INF = 1e30
FIELDS = ["P", "q", "A", "b", "G", "h", "lower", "upper"]
SETTINGS = {"primal_tol": 1e-12}


def parse(path):
    qps, lines = [], pathlib.Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        nx, ne, ni = map(int, lines[i].split()[1:])
        qp = {}
        for k, line in zip(FIELDS, lines[i + 1 : i + 9]):
            name, *values = line.split()
            assert name == k, (path, i, name, k)
            qp[k] = np.array([float(v) for v in values])
        qp["P"] = qp["P"].reshape(nx, nx)
        qp["A"] = qp["A"].reshape(ne, nx)
        qp["G"] = qp["G"].reshape(ni, nx)
        qps.append(qp)
        i += 9
    return qps


def daqp_form(qp):
    nx, ne, ni = len(qp["q"]), len(qp["b"]), len(qp["h"])
    C = np.vstack([qp["A"], qp["G"]]) if ne + ni else np.zeros((0, nx))
    finite = lambda v, s: np.where(np.isfinite(v), v, s * INF)
    bupper = np.concatenate([finite(qp["upper"], 1), qp["b"], qp["h"]])
    blower = np.concatenate([finite(qp["lower"], -1), qp["b"], np.full(ni, -INF)])
    sense = np.concatenate([np.zeros(nx), np.full(ne, 5), np.zeros(ni)]).astype(np.int32)
    return (np.ascontiguousarray(qp["P"]), qp["q"].copy(), np.ascontiguousarray(C), bupper, blower, sense)


def replay(qps, repeats):
    forms = [daqp_form(qp) for qp in qps]
    cold = [[0.0] * repeats for _ in qps]
    warm = [[0.0] * repeats for _ in qps]
    answers = []
    for rep in range(repeats):
        for k, (H, f, C, bu, bl, sense) in enumerate(forms):
            x, _, flag, info = daqp.solve(H, f, C, bu, bl, sense, **SETTINGS)
            if flag < 1:
                sys.exit(f"daqp_replay: DAQP exit flag {flag} on QP {k} (cold)")
            cold[k][rep] = (info["setup_time"] + info["solve_time"]) * 1e6
            if rep == 0:
                answers.append(np.array(x))
        active = None
        for k, (H, f, C, bu, bl, sense) in enumerate(forms):
            start = sense.copy()
            if active is not None:
                # Bit 1: start active (equalities are 5 already).
                start[active & (start == 0)] = 1
            x, _, flag, info = daqp.solve(H, f, C, bu, bl, start, **SETTINGS)
            if flag < 1:
                sys.exit(f"daqp_replay: DAQP exit flag {flag} on QP {k} (warm)")
            warm[k][rep] = (info["setup_time"] + info["solve_time"]) * 1e6
            active = np.asarray(info["lam"]) != 0.0
    return warm, cold, answers


def summary(times):
    medians = sorted(statistics.median(t) for t in times)
    return statistics.fmean(medians), medians[round((len(medians) - 1) * 0.95)]


def main():
    folder, repeats, rev = pathlib.Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    version = importlib.metadata.version("daqp")
    w = csv.writer(sys.stdout, lineterminator="\n")
    w.writerow(["task", "nx", "n_eq", "n_in", "n_bounds", "qps", "repeats", "solver", "start",
                "mean_us", "p95_us", "max_dx_vs_other", "git_rev"])
    for t in csv.DictReader(open(folder / "tasks.csv")):
        qps = parse(folder / t["file"])
        warm, cold, daqp_x = replay(qps, repeats)
        out = folder / ("out" + t["file"].split(".")[0])
        suite_x = [np.array([float(v) for v in l.split()]) for l in (out / "suite-x.txt").read_text().splitlines()]
        dx = max(float(np.max(np.abs(a - b))) for a, b in zip(daqp_x, suite_x))
        sizes = [t["task"], t["nx"], t["n_eq"], t["n_in"], t["n_bounds"], len(qps), repeats]
        for s in csv.DictReader(open(out / "suite-times.csv")):
            w.writerow(sizes + ["active-set", s["start"], s["mean_us"], s["p95_us"], dx, rev])
        for start, times in [("warm", warm), ("cold", cold)]:
            mean, p95 = summary(times)
            w.writerow(sizes + [f"daqp {version}", start, mean, p95, dx, rev])
        print(f"replayed {len(qps)} QPs of {t['task']} to DAQP; max |dx| = {dx:.1e}", file=sys.stderr)


if __name__ == "__main__":
    main()
