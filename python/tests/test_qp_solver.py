"""A QP solver written in Python through the suite's one solver seam: it passes the
conformance kit (called from Python) and, registered, is a run's solver as any built-in one."""

import pathlib

import numpy as np
import pytest

import driftbench

ROOT = pathlib.Path(__file__).resolve().parents[2]
CIRCLE = "kong2019-circle / znn-eq22"


class EqualityKkt:
    """Equality-constrained QPs by one KKT solve: [P A'; A 0] [x; lambda] = [-q; b]. It claims
    no inequalities: a QP with inequality rows or finite bounds is refused by status."""

    def __init__(self, dims):
        self.dims = dims
        self.calls = 0

    def solve(self, P, q, A, b, G, h, lower, upper):
        self.calls += 1
        if np.isfinite(h).any() or np.isfinite(lower).any() or np.isfinite(upper).any():
            return {"status": "invalid-input", "message": "inequalities are not handled"}
        nx, ne = len(q), len(b)
        kkt = np.block([[P, A.T], [A, np.zeros((ne, ne))]])
        # A repeated or dependent equality row makes the KKT matrix singular, which
        # np.linalg.solve does not always notice in floating point.
        if np.linalg.matrix_rank(kkt) < nx + ne:
            return {"status": "singular", "message": "the KKT matrix is rank deficient"}
        try:
            y = np.linalg.solve(kkt, np.concatenate([-q, b]))
        except np.linalg.LinAlgError as e:
            return {"status": "singular", "message": str(e)}
        return {"x": y[:nx], "lambda": y[nx:], "iterations": 1}


def test_a_python_solver_passes_the_conformance_kit():
    violations = driftbench.check_qp_solver(EqualityKkt, equality_only=True, seeds=5)
    assert violations == []


def test_the_conformance_kit_catches_a_wrong_python_solver():
    class Wrong(EqualityKkt):
        def solve(self, *qp):
            answer = super().solve(*qp)
            if "x" in answer:
                answer["x"] = answer["x"] + 1e-3
            return answer

    violations = driftbench.check_qp_solver(Wrong, equality_only=True, seeds=2)
    assert violations and any("[cold]" in v for v in violations), violations

    class Raises(EqualityKkt):
        def solve(self, *qp):
            raise RuntimeError("boom")

    violations = driftbench.check_qp_solver(Raises, equality_only=True, seeds=1)
    assert any("boom" in v for v in violations), violations


def test_a_registered_python_solver_is_a_runs_solver():
    built = []

    def factory(dims):
        solver = EqualityKkt(dims)
        built.append(solver)
        return solver

    driftbench.register_qp_solver("numpy-kkt", factory, name="numpy KKT")
    with pytest.raises(driftbench.DriftbenchError, match="numpy-kkt"):
        driftbench.register_qp_solver("numpy-kkt", factory)
    with pytest.raises(driftbench.DriftbenchError, match="not a slug"):
        driftbench.register_qp_solver("Not A Slug", factory)
    circle = driftbench.task(CIRCLE, root=ROOT)
    ours = driftbench.simulate(circle, "numpy-kkt")
    assert len(built) == 1 and built[0].calls > 1000
    assert ours["status"] == "ok", ours["failure"]
    assert ours["solver_kind"] == "numpy-kkt"
    # Clarabel on the same fixed-step loop: the same QPs solved exactly, the same run.
    clarabel = driftbench.simulate(circle, "clarabel")
    assert np.max(np.abs(ours["drift"] - clarabel["drift"])) < 1e-7
    assert ours["score_max_dx"] < 1e-7
