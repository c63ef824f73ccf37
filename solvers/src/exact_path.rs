//! The exact reference at the speed of the networks: the KKT-certified, hot-started active-set
//! solver ([`crate::active_set`]) first, Clarabel ([`crate::exact`]) whenever it fails, and
//! Clarabel again on a sample of instants to record how far the two are apart.
//!
//! # Why the answer is the exact optimum
//!
//! For the convex QPs of [`schemes::qp`] the KKT conditions (stationarity, primal and dual
//! feasibility, complementarity) are necessary and sufficient for optimality. The active-set
//! solver returns an answer only if its own residuals meet them to 1e-10 (relative to
//! 1 + max(|q|, |b|)); otherwise (a singular KKT matrix, as MVN's QP whose p has no weight, an
//! iteration limit, a failed certification) the QP goes to Clarabel, which stays the reference
//! of record.
//!
//! # The sample
//!
//! The first solve and every [`CHECK_EVERY`]-th one are also solved by Clarabel, and the largest
//! |x_fast - x_clarabel|_inf / max(1, |x_clarabel|_inf) is kept in [`ExactPathStats`] (each run
//! records it). Clarabel's own x is accurate to ~1e-8 (near degenerate bounds ~1e-7, see the
//! active-set tests), so that is the size of difference to expect.
//!
//! # Hot start
//!
//! Along a trajectory the active set rarely changes between two evaluations, so the previous
//! answer's working set is tried first: usually one dense KKT solve. After a fallback the next
//! solve starts cold.

use crate::active_set::{ActiveSetSolution, ActiveSetSolver, WorkingSet};
use crate::exact::{ExactError, ExactSolver};
use nalgebra::DVector;
use schemes::qp::Qp;

/// Every this many solves (and on the first), Clarabel solves the same QP as a check.
pub const CHECK_EVERY: usize = 100;

/// What an [`ExactPath`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExactPathStats {
    /// QPs solved.
    pub solves: usize,
    /// QPs the active-set solver could not answer with a certificate (Clarabel answered).
    pub fallbacks: usize,
    /// Certified answers also solved by Clarabel.
    pub checks: usize,
    /// Largest relative difference |x_fast - x_clarabel|_inf / max(1, |x_clarabel|_inf) over
    /// the checks (0 without checks).
    pub check_max_dx: f64,
}

impl ExactPathStats {
    /// Adds the counts of `other` (the largest difference of both).
    pub fn add(&mut self, other: &ExactPathStats) {
        self.solves += other.solves;
        self.fallbacks += other.fallbacks;
        self.checks += other.checks;
        self.check_max_dx = self.check_max_dx.max(other.check_max_dx);
    }
}

/// The exact optimum of a sequence of QPs (see the module docs).
pub struct ExactPath {
    fast: ActiveSetSolver,
    out: ActiveSetSolution,
    warm: WorkingSet,
    has_warm: bool,
    clarabel: ExactSolver,
    x: DVector<f64>,
    pub stats: ExactPathStats,
}

impl ExactPath {
    /// A path for QPs of `qp`'s sizes.
    pub fn new(qp: &Qp) -> Self {
        let dims = qp.dims();
        Self {
            fast: ActiveSetSolver::new(dims),
            out: ActiveSetSolution::zeros(dims),
            warm: WorkingSet::with_capacity(dims.n_in + 2 * dims.nx),
            has_warm: false,
            clarabel: ExactSolver::new(),
            x: DVector::zeros(dims.nx),
            stats: ExactPathStats::default(),
        }
    }

    /// The optimum of `qp`, or Clarabel's error when neither solver answers.
    pub fn solve(&mut self, qp: &Qp) -> Result<&DVector<f64>, ExactError> {
        self.stats.solves += 1;
        let warm = self.has_warm.then_some(&self.warm);
        match self.fast.solve_into(qp, warm, &mut self.out) {
            Ok(()) => {
                self.warm.clone_from(&self.out.working_set);
                self.has_warm = true;
                self.x.copy_from(&self.out.x);
                if self.stats.solves % CHECK_EVERY == 1 {
                    if let Ok(reference) = self.clarabel.solve(qp) {
                        let dx = (&self.x - &reference.x).amax() / reference.x.amax().max(1.0);
                        self.stats.checks += 1;
                        self.stats.check_max_dx = self.stats.check_max_dx.max(dx);
                    }
                }
                Ok(&self.x)
            }
            Err(_) => {
                self.stats.fallbacks += 1;
                self.has_warm = false;
                let s = self.clarabel.solve(qp)?;
                self.x.copy_from(&s.x);
                Ok(&self.x)
            }
        }
    }
}
