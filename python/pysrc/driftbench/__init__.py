"""driftbench from Python.

The tasks of the suite (every experiment and variant, and the leaderboard's standard task set),
a run of a network written in Python on any of them, and the leaderboard, as bindings to the
Rust library: the arm, the scheme, the integrator and the score against the exact optimum are
the library's; only the network's methods are Python.

The project data (the experiment files, ``papers/`` and the committed results the leaderboard
ranks against) comes with the package: without ``root=`` every function uses that copy
(``data_root()`` says where it is unpacked), from any working directory. ``root=`` names a
driftbench checkout (or any directory with ``experiments/*.toml``) to use instead.

A network is any object with

- ``state_dim``: an int, or a method ``state_dim(dims)`` of the QP's sizes (``dims.nx``,
  ``dims.n_eq``, ``dims.n_in``); its state starts with the QP's unknowns x (``nx`` entries:
  the joint command x[:dof], thetadot or thetaddot, then the scheme's auxiliary variables,
  e.g. p = |thetadot|_inf on the jia2019 and zhong2021 tasks, where nx = dof + 1; see
  ``Task``);
- ``rhs(t, y, qp)`` returning dy/dt (a 1-D array), ``qp`` a dict of numpy arrays for
  ``min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  lower <= x <= upper`` (keys ``P q A b G h
  lower upper``);
- optionally ``needs_qp_dot = True`` (then ``rhs`` and ``jacobian`` get dQP/dt as a fourth
  argument, a dict of the same form), ``jacobian(t, y, qp)`` (dF/dy with the QP frozen; without
  it the library takes finite differences), ``error_norm(qp, y)`` and ``name``;
- optionally ``handles(dims)``: False for the QPs the network cannot solve (e.g. ``dims.n_in >
  0`` for an equality-only network). ``simulate`` then raises ``NotApplicable``, and
  ``leaderboard`` counts the task as N/A for the network and ranks it on the others, as it
  ranks the suite's zeroing networks. Raising ``NotApplicable`` from ``handles`` or
  ``state_dim`` means the same.

``simulate`` returns the run's ``results/runs.csv`` columns as a dict (``drift`` and ``trace``
as numpy arrays, ``python_calls`` and ``python_seconds`` the cost of the Python calls);
``score(task, trajectory)`` scores a trajectory made elsewhere (a CSV file with columns ``t,
theta_1..n[, thetadot_1..n]``, or a dict of arrays) with the same metrics and the same score
against the exact optimum at the trajectory's own states.

A QP solver written in Python (an object with ``solve(P, q, A, b, G, h, lower, upper)``
returning a dict with ``x`` and the multipliers ``lambda``, ``mu``, ``z_lower``, ``z_upper``,
or a failure ``status``) goes through the suite's one solver seam:
``register_qp_solver(id, factory)`` makes ``id`` a run's solver (``simulate(task, id)``), and
``check_qp_solver(factory)`` holds it to the conformance kit. ``frame`` turns a list of such rows into a pandas DataFrame when pandas is installed.
"""

from ._driftbench import (
    DriftbenchError,
    NotApplicable,
    QpDims,
    Task,
    add_robots,
    check_qp_solver,
    data_root,
    into_results,
    leaderboard,
    register_qp_solver,
    score,
    simulate,
    standard_tasks,
    task,
    tasks,
)

__all__ = [
    "DriftbenchError",
    "NotApplicable",
    "QpDims",
    "Task",
    "add_robots",
    "check_qp_solver",
    "data_root",
    "frame",
    "into_results",
    "leaderboard",
    "register_qp_solver",
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
