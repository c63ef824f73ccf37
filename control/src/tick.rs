//! The interface of a per-tick solver, [`TickSolver`]: what a controller calls once per tick
//! with the tick's QP, whatever computes the answer (a network stepped in discrete time,
//! [`crate::network_tick`], or any QP solver of the one seam, `qp::QpSolver`; which one a run
//! uses is its [`crate::method::Method`]).
//!
//! Every [`QpSolver`] is a tick solver as it is, with no adapter: a tick is one
//! [`QpSolver::solve`] of the tick's QP, started from what the previous tick left where the
//! method can (robio2018's six PLPE methods from the previous primal-dual point, the active
//! set hot-started from the previous optimal working set, OSQP warm-started; Clarabel afresh),
//! so any solver of the registry (`solvers::registry`, built-in or registered from outside) can
//! be a tick's solver.

use crate::error::ControlError;
use qp::{Qp, QpSolve, QpSolver};

/// One solver as a controller calls it: once per tick, with the tick's QP.
pub trait TickSolver {
    /// Whether [`TickSolver::tick`] needs dQP/dt (the zeroing networks).
    fn needs_qp_dot(&self) -> bool {
        false
    }
    /// Computes this tick's answer from the tick's QP (and its time derivative where needed),
    /// h being the control period, and returns what the tick cost: its iterations (or network
    /// steps) and its work in products with the LVI matrix M (or M', or LU solves with M or
    /// I + M: `solvers::lvi_numerical`'s unit) for the methods built on jia2019's LVI (the six
    /// PLPE methods, LVI-PDNN, S-LVI-PDNN), `None` for the others.
    fn tick(
        &mut self,
        t: f64,
        qp: &Qp,
        qp_dot: Option<&Qp>,
        h: f64,
    ) -> Result<QpSolve, ControlError>;
    /// The answer x of the last tick (its first N entries are the joint command).
    fn x(&self) -> &[f64];
}

/// A QP solver of the seam at every tick (module docs).
impl<S: QpSolver + ?Sized> TickSolver for S {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<QpSolve, ControlError> {
        Ok(self.solve(qp)?)
    }

    fn x(&self) -> &[f64] {
        QpSolver::x(self)
    }
}
