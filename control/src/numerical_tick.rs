//! The numerical QP methods as a controller calls them at every tick: any
//! [`solvers::QpSolver`] behind one adapter, [`QpTick`], each method started from what the
//! previous tick left where it can:
//!
//! - robio2018's six PLPE methods, 94LVI, E47 and M3 to M6 ([`solvers::lvi_numerical`]):
//!   iterated from the previous tick's primal-dual point to |e(U)|_2 <= tolerance;
//! - the dense active-set solver ([`solvers::HotActiveSet`]) hot-started from the previous
//!   tick's optimal working set, without its KKT certification (the control loop scores every
//!   tick against the certified reference instead), cold-started again and then handed to
//!   Clarabel when that fails;
//! - Clarabel ([`solvers::ExactSolver`]): an interior-point method, started afresh every tick;
//! - OSQP (`solvers::osqp_qp`, with the `osqp` feature): data updated in place, warm-started.

use crate::error::ControlError;
use crate::tick::TickSolver;
use qp::Qp;
use solvers::{QpSolve, QpSolver};

/// A [`QpSolver`] at every tick; its work and iterations are those of the last tick.
pub struct QpTick<S> {
    solver: S,
    last: QpSolve,
}

impl<S: QpSolver> QpTick<S> {
    pub fn new(solver: S) -> Self {
        QpTick {
            solver,
            last: QpSolve::default(),
        }
    }
}

impl<S: QpSolver> TickSolver for QpTick<S> {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<(), ControlError> {
        self.last = self.solver.solve(qp)?;
        Ok(())
    }

    fn x(&self) -> &[f64] {
        self.solver.x()
    }

    /// The PLPE methods' products ([`solvers::lvi_numerical::LviMethod::products`]: its
    /// iterations, the residual that confirms convergence, and its LU factorisation if any).
    fn products(&self) -> Option<u64> {
        self.last.products
    }

    fn iterations(&self) -> u32 {
        self.last.iterations
    }
}
