//! The exact reference at the speed of the networks: the KKT-certified, hot-started active-set
//! solver ([`crate::active_set`]) first, Clarabel ([`crate::exact`]) whenever it fails, and
//! Clarabel again on a sample of instants to record how far the two are apart.
//!
//! # Why the answer is the exact optimum
//!
//! For the convex QPs of [`qp`] the KKT conditions (stationarity, primal and dual
//! feasibility, complementarity) are necessary and sufficient for optimality. The active-set
//! solver returns an answer only if its own residuals meet them to 1e-10 (relative to
//! 1 + max(|q|, |b|)); otherwise (a singular KKT matrix, an iteration limit, a failed
//! certification) the QP goes to Clarabel, which stays the reference of record.
//!
//! # MVN's unweighted p
//!
//! A QP with a variable that has no weight and appears only in max-norm rows and bounds (MVN's
//! p, jia2019 (2.17) with phi = 1, tau = 0; recognised from the data's structure, not the
//! scheme) has a singular P. It is solved in reduced form without that variable
//! ([`crate::auxiliary`]), and the lifted answer, with p* the smallest feasible value
//! (|thetadot*|_inf for MVN), is certified on the original QP to the same tolerance. Any p in
//! [p*, its upper bound] is as optimal, so the Clarabel check below leaves that variable out.
//!
//! # The sample
//!
//! The first solve and every [`CHECK_EVERY`]-th one are also solved by Clarabel, and the largest
//! |x_fast - x_clarabel|_inf / max(1, |x_clarabel|_inf) is kept in [`ExactPathStats`] (each run
//! records it; over every variable but an eliminated one, whose optimum is not unique). Clarabel's own x is accurate to ~1e-8 (near degenerate bounds ~1e-7, see the
//! active-set tests), so that is the size of difference to expect.
//!
//! # Hot start
//!
//! Along a trajectory the active set rarely changes between two evaluations, so the previous
//! answer's working set is tried first: usually one dense KKT solve. After a fallback the next
//! solve starts cold.
//!
//! # Equality-only QPs
//!
//! A QP without inequality rows and with every bound infinite (kong2019's schemes, the group's)
//! has an empty active set: its optimum is the solution of the KKT system
//! [P A'; A 0] [x; lambda] = [-q; b], solved directly (`solvers/src/equality_kkt.rs`: through
//! the Schur complement of a diagonal P, by LU otherwise) and certified by the same KKT
//! residuals and tolerance as the active-set solver's answers; a QP it cannot factorise or
//! certify goes to the active-set solver, then Clarabel, as any other.

use crate::active_set::{
    ActiveSetError, ActiveSetSolution, ActiveSetSolver, WorkingSet, DEFAULT_CERT_TOL,
};
use crate::auxiliary::AuxiliaryElimination;
use crate::equality_kkt::Kkt;
use crate::exact::{ExactError, ExactSolver};
use nalgebra::DVector;
use qp::{Qp, QpDuals};

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
    /// The elimination of an unweighted auxiliary variable, while the QPs have one.
    elimination: Option<AuxiliaryElimination>,
    /// Whether `warm` is a working set of the reduced QP.
    warm_reduced: bool,
    /// The lifted multipliers of a reduced solve (certified on the original QP).
    duals: QpDuals,
    clarabel: ExactSolver,
    /// The KKT factors of an equality-only QP, and the solution [x; lambda] (module docs).
    kkt: Kkt,
    z: Vec<f64>,
    x: DVector<f64>,
    /// What the path has done so far, summed over every solve since [`ExactPath::new`].
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
            elimination: None,
            warm_reduced: false,
            duals: QpDuals::zeros(dims),
            clarabel: ExactSolver::new(),
            kkt: Kkt::new(dims),
            z: vec![0.0; dims.nx + dims.n_eq],
            x: DVector::zeros(dims.nx),
            stats: ExactPathStats::default(),
        }
    }

    /// The optimum of `qp`, or Clarabel's error when neither solver answers.
    pub fn solve(&mut self, qp: &Qp) -> Result<&DVector<f64>, ExactError> {
        self.stats.solves += 1;
        match self.solve_fast(qp) {
            Ok(()) => {
                if self.stats.solves % CHECK_EVERY == 1 {
                    if let Ok(reference) = self.clarabel.solve(qp) {
                        // An eliminated variable's optimum is not unique: left out.
                        let free = self
                            .elimination
                            .as_ref()
                            .filter(|_| self.warm_reduced)
                            .map(AuxiliaryElimination::variable);
                        let (mut dx, mut scale) = (0.0f64, 1.0f64);
                        for i in (0..self.x.len()).filter(|&i| Some(i) != free) {
                            dx = dx.max((self.x[i] - reference.x[i]).abs());
                            scale = scale.max(reference.x[i].abs());
                        }
                        self.stats.checks += 1;
                        self.stats.check_max_dx = self.stats.check_max_dx.max(dx / scale);
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

    /// The certified active-set answer into `x`, in reduced form when `qp` has an eliminable
    /// variable (module docs), hot-started from the previous answer of the same form.
    fn solve_fast(&mut self, qp: &Qp) -> Result<(), ActiveSetError> {
        if self.solve_equality(qp) {
            self.warm.clear();
            self.has_warm = true;
            self.warm_reduced = false;
            return Ok(());
        }
        let still = self.elimination.as_mut().is_some_and(|e| e.reduce(qp));
        if !still {
            self.elimination = AuxiliaryElimination::recognise(qp);
        }
        let reduced = self.elimination.is_some();
        let warm = (self.has_warm && self.warm_reduced == reduced).then_some(&self.warm);
        self.has_warm = false;
        match &self.elimination {
            Some(e) => {
                self.fast.solve_into(e.reduced(), warm, &mut self.out)?;
                e.lift(qp, &self.out, &mut self.x, &mut self.duals);
                let kkt = qp.kkt_residuals(&self.x, &self.duals);
                let tolerance = DEFAULT_CERT_TOL * (1.0 + qp.q.amax().max(qp.b.amax()));
                if kkt.max().is_nan() || kkt.max() > tolerance {
                    return Err(ActiveSetError::NotCertified { kkt, tolerance });
                }
            }
            None => {
                self.fast.solve_into(qp, warm, &mut self.out)?;
                self.x.copy_from(&self.out.x);
            }
        }
        self.warm.clone_from(&self.out.working_set);
        self.has_warm = true;
        self.warm_reduced = reduced;
        Ok(())
    }

    /// The optimum of an equality-only QP into `x` from its KKT system, certified (module
    /// docs); false (nothing written but scratch) when `qp` has inequality rows or a finite
    /// bound, or its KKT system is singular or its answer not certified.
    fn solve_equality(&mut self, qp: &Qp) -> bool {
        let equality_only = qp.h.is_empty()
            && qp.lower.iter().all(|l| *l == f64::NEG_INFINITY)
            && qp.upper.iter().all(|u| *u == f64::INFINITY);
        if !equality_only || qp.dims() != self.kkt.dims() || !self.kkt.factor(qp) {
            return false;
        }
        let nx = qp.q.len();
        let (top, bottom) = self.z.split_at_mut(nx);
        for (z, q) in top.iter_mut().zip(qp.q.iter()) {
            *z = -q;
        }
        bottom.copy_from_slice(qp.b.as_slice());
        self.kkt.solve(&mut self.z);
        self.x.as_mut_slice().copy_from_slice(&self.z[..nx]);
        self.duals
            .lambda
            .as_mut_slice()
            .copy_from_slice(&self.z[nx..]);
        self.duals.mu.fill(0.0);
        self.duals.z_lower.fill(0.0);
        self.duals.z_upper.fill(0.0);
        let kkt = qp.kkt_residuals(&self.x, &self.duals);
        let tolerance = DEFAULT_CERT_TOL * (1.0 + qp.q.amax().max(qp.b.amax()));
        kkt.max() <= tolerance
    }
}
