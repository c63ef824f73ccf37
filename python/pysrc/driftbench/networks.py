"""Two networks written in numpy, as a user would write them: examples of the network interface
(see the package docs), run by ``driftbench.simulate`` like the suite's own.

``Gnn``: the gradient neural network of ``examples/gnn_clover.rs`` (its Rust twin). For the QP
``min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  l <= x <= u`` it descends the penalised energy

    E(x) = x'Px/2 + q'x + (rho/2)(|Ax - b|^2 + |max(Gx - h, 0)|^2
                                   + |max(x - u, 0)|^2 + |max(l - x, 0)|^2),
    xdot = -gamma grad E(x),

whose equilibrium is within O(1/rho) of x*; its Jacobian is
-gamma (P + rho A'A + rho G_act'G_act + rho D_act) (active rows and violated bounds).

``Znn``: the zeroing neural network of kong2019's comparison (its twin is the suite's ``ZNN``),
for equality-only QPs (``handles(dims)``: no inequality rows). With y = [x; lambda], Q = [[P, A'], [A, 0]] and u = [-q; b] the
Lagrange conditions are Q y = u; the error E = Q y - u is made to obey Edot = -gamma E, so

    Q ydot = -Qdot y + udot - gamma (Q y - u),

with Qdot and udot from dQP/dt (``needs_qp_dot``). Jacobian with the QP frozen:
dF/dy = -Q^-1 Qdot - gamma I.
"""

import numpy as np


class Gnn:
    """The gradient network (module docs), gain ``gamma`` and penalty ``rho``."""

    def __init__(self, gamma=1e4, rho=1e3, name="GNN (numpy)"):
        self.gamma, self.rho, self.name = gamma, rho, name

    def state_dim(self, dims):
        return dims.nx

    def rhs(self, t, y, qp):
        rho = self.rho
        eq = qp["A"] @ y - qp["b"]
        ineq = np.maximum(qp["G"] @ y - qp["h"], 0.0)
        over = np.maximum(y - qp["upper"], 0.0) - np.maximum(qp["lower"] - y, 0.0)
        grad = (
            qp["P"] @ y
            + qp["q"]
            + rho * (qp["A"].T @ eq)
            + rho * (qp["G"].T @ ineq)
            + rho * over
        )
        return -self.gamma * grad

    def jacobian(self, t, y, qp):
        rho = self.rho
        active = qp["G"][qp["G"] @ y > qp["h"]]
        jac = qp["P"] + rho * (qp["A"].T @ qp["A"]) + rho * (active.T @ active)
        jac[np.diag_indices_from(jac)] += rho * ((y > qp["upper"]) | (y < qp["lower"]))
        return -self.gamma * jac


class Znn:
    """The zeroing network (module docs), gain ``gamma``."""

    needs_qp_dot = True

    def __init__(self, gamma=1.0, name="ZNN (numpy)"):
        self.gamma, self.name = gamma, name

    @staticmethod
    def handles(dims):
        """Equality-only QPs (no G x <= h): the other tasks are N/A for it."""
        return dims.n_in == 0

    def state_dim(self, dims):
        return dims.nx + dims.n_eq

    @staticmethod
    def _system(qp):
        """Q and u of the Lagrange conditions Q y = u."""
        a = qp["A"]
        q_mat = np.block([[qp["P"], a.T], [a, np.zeros((a.shape[0], a.shape[0]))]])
        return q_mat, np.concatenate([-qp["q"], qp["b"]])

    def rhs(self, t, y, qp, qp_dot):
        q_mat, u = self._system(qp)
        q_dot, u_dot = self._system(qp_dot)
        return np.linalg.solve(q_mat, -q_dot @ y + u_dot - self.gamma * (q_mat @ y - u))

    def jacobian(self, t, y, qp, qp_dot):
        q_mat, _ = self._system(qp)
        q_dot, _ = self._system(qp_dot)
        return -np.linalg.solve(q_mat, q_dot) - self.gamma * np.eye(len(y))

    def error_norm(self, qp, y):
        q_mat, u = self._system(qp)
        return float(np.linalg.norm(q_mat @ y - u))
