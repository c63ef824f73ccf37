//! The interface of a per-tick solver, [`TickSolver`]: what a controller calls once per tick
//! with the tick's QP, whatever computes the answer (a network stepped in discrete time,
//! [`crate::network_tick`], or a numerical QP method, [`crate::numerical_tick`]; which one a run
//! uses is its [`crate::method::Method`]).

use crate::error::ControlError;
use qp::Qp;

/// One solver as a controller calls it: once per tick, with the tick's QP.
pub trait TickSolver {
    /// Whether [`TickSolver::tick`] needs dQP/dt (the zeroing networks).
    fn needs_qp_dot(&self) -> bool {
        false
    }
    /// Computes this tick's answer from the tick's QP (and its time derivative where needed),
    /// h being the control period.
    fn tick(&mut self, t: f64, qp: &Qp, qp_dot: Option<&Qp>, h: f64) -> Result<(), ControlError>;
    /// The answer x of the last tick (its first N entries are the joint command).
    fn x(&self) -> &[f64];
    /// Work of the last tick in products with the LVI matrix M (or M', or LU solves with M or
    /// I + M: [`solvers::lvi_numerical`]'s unit), for the methods built on jia2019's LVI (the six
    /// PLPE methods, LVI-PDNN, S-LVI-PDNN); `None` for the others.
    fn products(&self) -> Option<u64> {
        None
    }
    /// Iterations (or network steps) of the last tick.
    fn iterations(&self) -> u32;
}
