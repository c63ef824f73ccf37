"""Type stubs of the extension module (``driftbench._driftbench``, Rust: ``python/src``); the
docs are the functions' own (``help(driftbench.simulate)``) and ``python/README.md``."""

import os
import pathlib
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
_Array = npt.NDArray[np.float64]
_QpDict = Mapping[str, _Array]

class DriftbenchError(Exception):
    """An error of the driftbench library (the message is the library's own)."""

class NotApplicable(DriftbenchError):
    """A network does not handle a task's QP (``handles(dims)`` False, or raised by the
    network while it is built): ``simulate`` raises it, ``leaderboard`` counts the task N/A."""

class QpDims:
    """The sizes of a task's QP: ``nx`` unknowns (x[:dof] the joint command, then auxiliary
    variables), ``n_eq`` rows of A x = b, ``n_in`` rows of G x <= h."""

    @property
    def nx(self) -> int: ...
    @property
    def n_eq(self) -> int: ...
    @property
    def n_in(self) -> int: ...

class Task:
    """One task of the suite (an experiment file's variant); see ``help(driftbench.Task)``."""

    @property
    def id(self) -> str: ...
    @property
    def paper(self) -> str: ...
    @property
    def experiment(self) -> str: ...
    @property
    def variant(self) -> str: ...
    @property
    def robot(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def nx(self) -> int: ...
    @property
    def n_eq(self) -> int: ...
    @property
    def n_in(self) -> int: ...
    @property
    def n_aux(self) -> int: ...
    @property
    def dims(self) -> QpDims: ...
    @property
    def level(self) -> str: ...
    @property
    def path(self) -> dict[str, Any]: ...
    @property
    def duration(self) -> float: ...
    @property
    def theta0(self) -> list[float]: ...
    @property
    def theta_ref(self) -> list[float]: ...
    @property
    def scheme(self) -> dict[str, Any]: ...
    @property
    def scheme_name(self) -> str: ...
    @property
    def integrator(self) -> dict[str, Any]: ...
    @property
    def scoring(self) -> Any: ...
    @property
    def network_init(self) -> str: ...
    @property
    def solvers(self) -> list[str]: ...

# A network: any object with state_dim and rhs(t, y, qp[, qp_dot]), optionally needs_qp_dot,
# jacobian, error_norm, handles and name (python/README.md); not a class of the module.
_Network = Any

def data_root() -> pathlib.Path: ...
def add_robots(path: _Path) -> list[str]: ...
def tasks(root: Optional[_Path] = None) -> list[Task]: ...
def task(id: str, root: Optional[_Path] = None) -> Task: ...
def standard_tasks(root: Optional[_Path] = None) -> list[Task]: ...
def simulate(
    task: Task,
    network: Union[_Network, str],
    *,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    max_step: Optional[float] = None,
    scoring: Union[str, int, None] = None,
    network_init: Optional[str] = None,
    wall_budget: Optional[float] = None,
) -> dict[str, Any]: ...
def leaderboard(
    entries: Union[Mapping[str, _Network], Sequence[_Network]],
    *,
    tasks: Optional[Sequence[Union[Task, str]]] = None,
    root: Optional[_Path] = None,
    out_dir: Optional[_Path] = None,
    wall_budget: float = 120.0,
) -> dict[str, list[dict[str, Any]]]: ...
def score(
    task: Task,
    trajectory: Union[_Path, Mapping[str, npt.ArrayLike]],
    *,
    out_dir: Optional[_Path] = None,
) -> dict[str, Any]: ...
def into_results(file: _Path, *, root: _Path) -> pathlib.Path: ...

# A QP solver: an object with solve(P, q, A, b, G, h, lower, upper) -> dict (x and the
# multipliers lambda, mu, z_lower, z_upper, iterations; or status and message), built by a
# factory of the QP's sizes (python/README.md).
_QpSolverFactory = Callable[[QpDims], Any]

def register_qp_solver(id: str, factory: _QpSolverFactory, *, name: Optional[str] = None) -> None: ...
def check_qp_solver(
    factory: _QpSolverFactory, *, equality_only: bool = False, seeds: int = 10
) -> list[str]: ...
