"""driftbench from Python.

The tasks of the suite (every experiment and variant, and the leaderboard's standard task set),
a run of a network written in Python on any of them, and the leaderboard, as bindings to the
Rust library: the arm, the scheme, the integrator and the score against the exact optimum are
the library's; only the network's methods are Python.

A network is any object with

- ``state_dim``: an int, or a method ``state_dim(dims)`` of the QP's sizes (``dims.nx``,
  ``dims.n_eq``, ``dims.n_in``); its state starts with the joint command x (``nx`` entries);
- ``rhs(t, y, qp)`` returning dy/dt (a 1-D array), ``qp`` a dict of numpy arrays for
  ``min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  lower <= x <= upper`` (keys ``P q A b G h
  lower upper``);
- optionally ``needs_qp_dot = True`` (then ``rhs`` and ``jacobian`` get dQP/dt as a fourth
  argument, a dict of the same form), ``jacobian(t, y, qp)`` (dF/dy with the QP frozen; without
  it the library takes finite differences), ``error_norm(qp, y)`` and ``name``.

``simulate`` returns the run's ``results/runs.csv`` columns as a dict (``drift`` and ``trace``
as numpy arrays, ``python_calls`` and ``python_seconds`` the cost of the Python calls);
``score(task, trajectory)`` scores a trajectory made elsewhere (a CSV file with columns ``t,
theta_1..n[, thetadot_1..n]``, or a dict of arrays) with the same metrics and the same score
against the exact optimum at the trajectory's own states. ``frame`` turns a list of such rows into a pandas DataFrame when pandas is installed.
"""

from ._driftbench import (
    DriftbenchError,
    QpDims,
    Task,
    leaderboard,
    score,
    simulate,
    standard_tasks,
    task,
    tasks,
)

__all__ = [
    "DriftbenchError",
    "QpDims",
    "Task",
    "frame",
    "leaderboard",
    "score",
    "simulate",
    "standard_tasks",
    "task",
    "tasks",
]


def frame(rows):
    """Rows (dicts, e.g. ``leaderboard(...)["leaderboard"]``) as a pandas DataFrame; the array
    entries (``drift``, ``trace``) are left out. Needs pandas."""
    import pandas

    return pandas.DataFrame(
        [{k: v for k, v in r.items() if k not in ("drift", "trace")} for r in rows]
    )
