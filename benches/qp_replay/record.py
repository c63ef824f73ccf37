"""Records the QPs a network is handed along a run, through the Python package: one QP per
distinct instant (the integrator's repeated calls at one t, for its Jacobian, are one), the
first QPS of each task, in the text format benches/src/bin/qp_replay.rs reads.

Usage: python record.py OUT_DIR [QPS]   (writes OUT_DIR/<n>.qps and OUT_DIR/tasks.csv)"""

import pathlib
import sys

import numpy as np

import driftbench
from driftbench.networks import Gnn, Znn

# The tasks of the per-tick table, the numpy network that drives each run (the QPs are the
# scheme's along the trajectory that network follows), and simulate's keyword arguments: the
# ZNN's run takes ~200 steps at the task's tolerances, so its step is capped at 4 ms to give
# 2,000 instants.
TASKS = [
    ("jia2019-clover / vltco", Gnn, {}),
    ("zhong2021-clover-a / cmco-eta-0.2-delta-0.4", Gnn, {}),
    ("kong2019-circle / znn-eq22", Znn, {"max_step": 0.004}),
]
FIELDS = ["P", "q", "A", "b", "G", "h", "lower", "upper"]


class Enough(Exception):
    """Raised inside rhs once QPS instants are recorded: it ends the run."""


def recorder(base, limit):
    class Recorder(base):
        def __init__(self):
            super().__init__(name="recorder")
            self.qps, self.last_t = [], None

        def keep(self, t, qp):
            if t != self.last_t:
                self.last_t = t
                self.qps.append({k: np.array(qp[k], dtype=float, copy=True) for k in FIELDS})
                if len(self.qps) >= limit:
                    raise Enough()

        def rhs(self, t, y, qp, *rest):
            self.keep(t, qp)
            return super().rhs(t, y, qp, *rest)

    return Recorder()


def write(path, qps):
    with open(path, "w") as f:
        for qp in qps:
            nx, ne, ni = len(qp["q"]), len(qp["b"]), len(qp["h"])
            f.write(f"qp {nx} {ne} {ni}\n")
            for k in FIELDS:
                f.write(k + "".join(" " + repr(float(v)) for v in np.ravel(qp[k], order="C")) + "\n")


def main():
    out = pathlib.Path(sys.argv[1])
    limit = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
    out.mkdir(parents=True, exist_ok=True)
    lines = ["file,task,nx,n_eq,n_in,n_bounds,qps"]
    for i, (task_id, base, options) in enumerate(TASKS):
        net = recorder(base, limit)
        try:
            driftbench.simulate(driftbench.task(task_id), net, **options)
        except RuntimeError as e:
            if not isinstance(e.__cause__, Enough):
                raise
        qps = net.qps
        write(out / f"{i}.qps", qps)
        first = qps[0]
        bounds = int(np.isfinite(first["lower"]).sum() + np.isfinite(first["upper"]).sum())
        lines.append(
            f"{i}.qps,{task_id},{len(first['q'])},{len(first['b'])},{len(first['h'])},{bounds},{len(qps)}"
        )
        print(f"recorded {len(qps)} QPs of {task_id}", file=sys.stderr)
    (out / "tasks.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
