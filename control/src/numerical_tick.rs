//! The numerical QP methods as a controller calls them at every tick, each started from what
//! the previous tick left (where the method can be):
//!
//! - E47 / 94LVI ([`solvers::lvi_numerical`]): iterated from the previous tick's primal-dual
//!   point to |e(y)|_inf <= tolerance;
//! - the dense active-set solver ([`solvers::ActiveSetSolver`]) hot-started from the previous
//!   tick's optimal working set, without its KKT certification (which allocates; the control
//!   loop scores every tick against the certified reference instead), cold-started again
//!   and then handed to Clarabel when that fails (MVN's QP, whose p has no weight, has a
//!   singular KKT matrix);
//! - Clarabel ([`solvers::ExactSolver`]): an interior-point method, started afresh every tick;
//! - OSQP ([`solvers::osqp_qp`]): data updated in place, warm-started.

use crate::error::ControlError;
use crate::method::TickSolver;
use schemes::qp::{Qp, QpDims};
use solvers::lvi_numerical::{LviMethod, LviSettings, LviSolver, PRODUCTS_PER_ITERATION};
use solvers::osqp_qp::{OsqpQp, OsqpSettings};
use solvers::{ActiveSetSolution, ActiveSetSolver, ExactSolver, WorkingSet};

/// E47 or 94LVI at every tick, warm-started.
pub struct LviTick {
    solver: LviSolver,
    iterations: u32,
}

impl LviTick {
    pub fn new(method: LviMethod, dims: QpDims, settings: LviSettings) -> Self {
        LviTick {
            solver: LviSolver::new(method, dims, settings),
            iterations: 0,
        }
    }
}

impl TickSolver for LviTick {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<(), ControlError> {
        self.iterations = self.solver.solve(qp)?;
        Ok(())
    }

    fn x(&self) -> &[f64] {
        self.solver.x()
    }

    /// Each iteration's two products, plus the residual that confirms convergence.
    fn products(&self) -> Option<u64> {
        Some(PRODUCTS_PER_ITERATION * self.iterations as u64 + 1)
    }

    fn iterations(&self) -> u32 {
        self.iterations
    }
}

/// The active-set solver, hot-started (module docs).
pub struct ActiveSetTick {
    solver: ActiveSetSolver,
    out: ActiveSetSolution,
    warm: WorkingSet,
    has_warm: bool,
    clarabel: ExactSolver,
    x: Vec<f64>,
    iterations: u32,
}

impl ActiveSetTick {
    pub fn new(dims: QpDims) -> Self {
        ActiveSetTick {
            solver: ActiveSetSolver::new(dims).with_certification(false),
            out: ActiveSetSolution::zeros(dims),
            warm: WorkingSet::with_capacity(dims.n_in + 2 * dims.nx),
            has_warm: false,
            clarabel: ExactSolver::new(),
            x: vec![0.0; dims.nx],
            iterations: 0,
        }
    }
}

impl TickSolver for ActiveSetTick {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<(), ControlError> {
        let warm = self.has_warm.then_some(&self.warm);
        let solved = self.solver.solve_into(qp, warm, &mut self.out).is_ok()
            || (warm.is_some() && self.solver.solve_into(qp, None, &mut self.out).is_ok());
        if solved {
            self.warm.clone_from(&self.out.working_set);
            self.has_warm = true;
            self.iterations = self.out.iterations;
            self.x.copy_from_slice(self.out.x.as_slice());
        } else {
            self.has_warm = false;
            let s = self.clarabel.solve(qp)?;
            self.iterations = s.iterations;
            self.x.copy_from_slice(s.x.as_slice());
        }
        Ok(())
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn iterations(&self) -> u32 {
        self.iterations
    }
}

/// Clarabel at every tick.
pub struct ClarabelTick {
    solver: ExactSolver,
    x: Vec<f64>,
    iterations: u32,
}

impl ClarabelTick {
    pub fn new(dims: QpDims) -> Self {
        ClarabelTick {
            solver: ExactSolver::new(),
            x: vec![0.0; dims.nx],
            iterations: 0,
        }
    }
}

impl TickSolver for ClarabelTick {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<(), ControlError> {
        let s = self.solver.solve(qp)?;
        self.iterations = s.iterations;
        self.x.copy_from_slice(s.x.as_slice());
        Ok(())
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn iterations(&self) -> u32 {
        self.iterations
    }
}

/// OSQP at every tick, warm-started.
pub struct OsqpTick {
    solver: OsqpQp,
    iterations: u32,
}

impl OsqpTick {
    pub fn new(dims: QpDims, settings: OsqpSettings) -> Self {
        OsqpTick {
            solver: OsqpQp::new(dims, settings),
            iterations: 0,
        }
    }
}

impl TickSolver for OsqpTick {
    fn tick(&mut self, _t: f64, qp: &Qp, _: Option<&Qp>, _h: f64) -> Result<(), ControlError> {
        self.iterations = self.solver.solve(qp)?;
        Ok(())
    }

    fn x(&self) -> &[f64] {
        self.solver.x()
    }

    fn iterations(&self) -> u32 {
        self.iterations
    }
}
