"""The cost of a Python call per right-hand-side evaluation, for the report's Performance section.

Each case is simulated ``REPEATS`` times through ``driftbench.simulate`` and the median of each
quantity is sealed into ``results/python-call-cost.csv`` (one row per case) by
``driftbench.into_results``, as ``reproduce`` writes there (recorded in
``results/manifest.toml``):

- ``us_per_python_call``: ``python_seconds / python_calls`` of the numpy network's run, i.e. one
  call back into Python (the QP converted into numpy arrays, the method, its result read back);
- ``us_per_rhs_python_run`` and ``us_per_rhs_twin_run``: ``sim_s / rhs_evals`` of the run of the
  numpy network and of its Rust twin (the suite's network of the same equations) on the same
  task: the whole simulation (integrator, arm, scheme, network, Jacobians) per evaluation of the
  coupled right-hand side; ``ratio`` is the first over the second.

Cases: kong2019's ZNN in numpy (``driftbench.networks.Znn``) against the suite's ``ZNN`` on
``kong2019-circle / znn-eq22``; a network whose ``rhs`` returns ``-y`` on the same task (the
binding's own overhead: no numpy work); the numpy GNN (``Gnn``) on ``jia2019-clover / vltco``,
whose twin (``examples/gnn_clover.rs``) is not a suite network, so it has no twin columns.

Run from the repository root, with the package installed (``pip install -v ./python``)::

    python python/bench/call_cost.py
"""

import csv
import pathlib
import platform
import statistics
import sys
import tempfile

import numpy as np

import driftbench
from driftbench.networks import Gnn, Znn

REPEATS = 5
ROOT = pathlib.Path(__file__).resolve().parents[2]


class MinusY:
    """dy/dt = -y: the cheapest network, so its calls cost the binding alone."""

    name = "rhs = -y (numpy)"

    def state_dim(self, dims):
        return dims.nx

    def rhs(self, t, y, qp):
        return -y

    def jacobian(self, t, y, qp):
        return -np.eye(len(y))


def median_of(task, network):
    """The medians over REPEATS runs of (us per Python call, us per RHS, rhs_evals, calls)."""
    per_call, per_rhs, evals, calls = [], [], [], []
    for _ in range(REPEATS):
        run = driftbench.simulate(task, network)
        if run["status"] != "ok":
            sys.exit(f"{task.id}: {run['status']} {run['failure']}")
        if not isinstance(network, str):
            per_call.append(1e6 * run["python_seconds"] / run["python_calls"])
            calls.append(run["python_calls"])
        per_rhs.append(1e6 * run["sim_s"] / run["rhs_evals"])
        evals.append(run["rhs_evals"])
    med = statistics.median
    return (
        med(per_call) if per_call else None,
        med(per_rhs),
        int(med(evals)),
        int(med(calls)) if calls else None,
    )


def main():
    circle = driftbench.task("kong2019-circle / znn-eq22", root=ROOT)
    clover = driftbench.task("jia2019-clover / vltco", root=ROOT)
    cases = [
        (Znn(), circle, "znn"),
        (MinusY(), circle, None),
        (Gnn(), clover, None),
    ]
    fields = [
        "network", "task", "twin", "repeats", "python_calls", "us_per_python_call",
        "us_per_rhs_python_run", "rhs_evals_python_run", "us_per_rhs_twin_run",
        "rhs_evals_twin_run", "ratio", "python", "numpy", "machine",
    ]
    rows = []
    for network, task, twin in cases:
        per_call, per_rhs, evals, calls = median_of(task, network)
        row = {
            "network": network.name, "task": task.id, "twin": twin or "",
            "repeats": REPEATS, "python_calls": calls,
            "us_per_python_call": f"{per_call:.3g}",
            "us_per_rhs_python_run": f"{per_rhs:.3g}", "rhs_evals_python_run": evals,
            "us_per_rhs_twin_run": "", "rhs_evals_twin_run": "", "ratio": "",
            "python": platform.python_version(), "numpy": np.__version__,
            "machine": f"{platform.machine()}, {len(__import__('os').sched_getaffinity(0))} cores",
        }
        if twin:
            _, twin_rhs, twin_evals, _ = median_of(task, twin)
            row.update(us_per_rhs_twin_run=f"{twin_rhs:.3g}", rhs_evals_twin_run=twin_evals,
                       ratio=f"{per_rhs / twin_rhs:.3g}")
        rows.append(row)
        print(row)
    with tempfile.TemporaryDirectory() as scratch:
        table = pathlib.Path(scratch) / "python-call-cost.csv"
        with open(table, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
            w.writeheader()
            w.writerows(rows)
        out = driftbench.into_results(table, root=ROOT)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
