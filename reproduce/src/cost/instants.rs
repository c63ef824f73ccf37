//! The per-instant quantities of a case on a list of QPs (one per sampled state), as the
//! harness ([`super::harness`]) times them:
//!
//! - `network-rhs`, `network-jacobian`: one right-hand side and one analytic Jacobian of the
//!   network at a state near the optimum (x* + 1e-3 sin(i + 1), multipliers 0, as the criterion
//!   benches use);
//! - `network-lu`: the LU factorisation ([`solvers::DenseLu::factor`], buffers preallocated)
//!   of that state's network Jacobian, the matrix an implicit integrator's Newton matrix
//!   I - h gamma J has the size and structure of, on each backend;
//! - `exact-active-set`: the certified active-set solver ([`ActiveSetSolver`]) hot-started from
//!   the previous sampled instant's optimal working set, what the exact column and the scorer
//!   call at every instant ([`solvers::ExactPath`] adds a Clarabel check on every 100th solve,
//!   not timed here);
//! - `exact-clarabel`: one Clarabel solve ([`ExactSolver::solve`]), the reference of record;
//! - `kkt-floor`: one dense LU solve of the equality-constrained KKT system of the same QP
//!   (`[[P, A'], [A, 0]]`, size nx + n_eq, assembled, factorised and solved by
//!   [`solve_equality_kkt_with`], allocation included) on each backend: what no exact method
//!   that factorises the KKT matrix can beat, the active-set method's cost when its working set
//!   is empty.

use super::error::CostError;
use nalgebra::{DMatrix, DVector};
use qp::{Qp, QpDims};
use records::dof_cost::Quantity;
use settings::SolverSpec;
use solvers::neural::{build_solver, NeuralSolver};
use solvers::{
    solve_equality_kkt_with, ActiveSetSolution, ActiveSetSolver, Backend, DenseLu, ExactSolver,
    WorkingSet,
};

/// The QPs of the sampled states, with everything the per-instant quantities need.
pub struct Instants {
    ts: Vec<f64>,
    qps: Vec<Qp>,
    /// dQP/dt at each state, for networks that need it (empty otherwise).
    qp_dots: Vec<Qp>,
    network: Box<dyn NeuralSolver>,
    needs_dot: bool,
    has_jacobian: bool,
    has_kkt: bool,
    /// Network states near the optimum.
    ys: Vec<Vec<f64>>,
    /// The network Jacobian at each state (what `network-lu` factorises).
    jacs: Vec<DMatrix<f64>>,
    /// The previous sampled instant's optimal working set (the hot start).
    warm: Vec<WorkingSet>,
    /// The equality-constrained QPs of the same P, q, A, b (the KKT floor).
    equality: Vec<Qp>,
    fast: ActiveSetSolver,
    sol: ActiveSetSolution,
    clarabel: ExactSolver,
    ydot: Vec<f64>,
    jac: DMatrix<f64>,
    /// One preallocated LU per backend, in [`Backend::ALL`]'s order.
    lus: Vec<DenseLu>,
}

/// The exact optima of `qps` and their optimal working sets, in order: each by the active-set
/// solver `fast` (into `sol`) hot-started from the previous optimal working set, by `clarabel`
/// where the active set does not certify an answer (said on standard error, with the case's
/// `label`; its working set is then the previous one).
fn exact_optima(
    label: &str,
    qps: &[Qp],
    fast: &mut ActiveSetSolver,
    sol: &mut ActiveSetSolution,
    clarabel: &mut ExactSolver,
) -> (Vec<DVector<f64>>, Vec<WorkingSet>) {
    let mut x_star: Vec<DVector<f64>> = Vec::with_capacity(qps.len());
    let mut optimal: Vec<WorkingSet> = Vec::with_capacity(qps.len());
    let mut uncertified = 0usize;
    for qp in qps {
        match fast.solve_into(qp, optimal.last(), sol) {
            Ok(()) => {
                x_star.push(sol.x.clone());
                optimal.push(sol.working_set.clone());
            }
            Err(_) => {
                uncertified += 1;
                let x = clarabel
                    .solve(qp)
                    .map(|s| s.x)
                    .unwrap_or_else(|_| DVector::zeros(qp.dims().nx));
                x_star.push(x);
                optimal.push(optimal.last().cloned().unwrap_or_default());
            }
        }
    }
    if uncertified > 0 {
        eprintln!(
            "{label}: {uncertified} of {} sampled QPs not certified by the active-set solver",
            qps.len()
        );
    }
    (x_star, optimal)
}

/// Network states of dimension `dim` near each optimum of `x_star`: x* + 1e-3 sin(i + 1) in
/// entry i, multipliers 0 (as the criterion benches use).
fn states_near(x_star: &[DVector<f64>], dim: usize) -> Vec<Vec<f64>> {
    x_star
        .iter()
        .map(|x| {
            let mut y = vec![0.0; dim];
            for (i, xi) in x.iter().enumerate() {
                y[i] = xi + 1e-3 * ((i + 1) as f64).sin();
            }
            y
        })
        .collect()
}

/// The equality-constrained QP of the same P, q, A, b as `qp` (no inequalities, no bounds):
/// what the KKT floor solves.
fn equality_qp(qp: &Qp) -> Qp {
    let dims = qp.dims();
    let mut e = Qp::zeros(QpDims {
        nx: dims.nx,
        n_eq: dims.n_eq,
        n_in: 0,
    });
    e.p.copy_from(&qp.p);
    e.q.copy_from(&qp.q);
    e.a.copy_from(&qp.a);
    e.b.copy_from(&qp.b);
    e.lower.fill(f64::NEG_INFINITY);
    e.upper.fill(f64::INFINITY);
    e
}

impl Instants {
    /// The network of `spec` on `qps` at times `ts` (with `qp_dots` when the network needs
    /// them): exact optima (active set, Clarabel where it does not certify), hot starts,
    /// network states and Jacobians, equality QPs.
    pub fn new(
        label: &str,
        spec: &SolverSpec,
        ts: Vec<f64>,
        qps: Vec<Qp>,
        qp_dots: Vec<Qp>,
    ) -> Result<Self, CostError> {
        let dims = qps[0].dims();
        let mut network = build_solver(spec, dims).map_err(|error| CostError::Network {
            label: label.to_string(),
            error,
        })?;
        let needs_dot = network.needs_qp_dot();
        if needs_dot && qp_dots.len() != qps.len() {
            return Err(CostError::NeedsQpDot(label.to_string()));
        }

        let mut fast = ActiveSetSolver::new(dims);
        let mut sol = ActiveSetSolution::zeros(dims);
        let mut clarabel = ExactSolver::new();
        let (x_star, optimal) = exact_optima(label, &qps, &mut fast, &mut sol, &mut clarabel);
        let warm: Vec<WorkingSet> = (0..qps.len())
            .map(|i| optimal[i.saturating_sub(1)].clone())
            .collect();
        let dim = network.state_dim(dims);
        let ys = states_near(&x_star, dim);
        let mut jac = DMatrix::zeros(dim, dim);
        let mut has_jacobian = true;
        let mut jacs = Vec::with_capacity(qps.len());
        for i in 0..qps.len() {
            let dot = needs_dot.then(|| &qp_dots[i]);
            has_jacobian &= network.jacobian(ts[i], &ys[i], &qps[i], dot, &mut jac);
            jacs.push(jac.clone());
        }

        let equality: Vec<Qp> = qps.iter().map(equality_qp).collect();
        let has_kkt = solve_equality_kkt_with(&equality[0], Backend::Nalgebra).is_some();
        Ok(Instants {
            ts,
            qps,
            qp_dots,
            network,
            needs_dot,
            has_jacobian,
            has_kkt,
            ys,
            jacs,
            warm,
            equality,
            fast,
            sol,
            clarabel,
            ydot: vec![0.0; dim],
            jac,
            lus: Backend::ALL.iter().map(|&b| DenseLu::new(dim, b)).collect(),
        })
    }

    /// Whether `quantity` is one of the per-instant quantities and can be timed here.
    pub fn supports(&self, quantity: Quantity) -> bool {
        match quantity {
            Quantity::NetworkRhs | Quantity::ExactActiveSet | Quantity::ExactClarabel => true,
            Quantity::NetworkJacobian | Quantity::NetworkLu => self.has_jacobian,
            Quantity::KktFloor => self.has_kkt,
            Quantity::SchemeBuild | Quantity::RunExact | Quantity::RunNetwork => false,
        }
    }

    /// One call of the per-instant `quantity` on `backend` at state `i` (modulo the states);
    /// nothing for the others.
    pub fn call(&mut self, quantity: Quantity, backend: Backend, i: usize) {
        let i = i % self.qps.len();
        let t = self.ts[i];
        let dot = self.needs_dot.then(|| &self.qp_dots[i]);
        match quantity {
            Quantity::NetworkRhs => {
                self.network
                    .rhs(t, &self.ys[i], &self.qps[i], dot, &mut self.ydot)
            }
            Quantity::NetworkJacobian => {
                self.network
                    .jacobian(t, &self.ys[i], &self.qps[i], dot, &mut self.jac);
            }
            Quantity::NetworkLu => {
                let lu = &mut self.lus[backend as usize];
                std::hint::black_box(lu.factor(&self.jacs[i]));
            }
            Quantity::ExactActiveSet => {
                let _ = self
                    .fast
                    .solve_into(&self.qps[i], Some(&self.warm[i]), &mut self.sol);
            }
            Quantity::ExactClarabel => {
                let _ = self.clarabel.solve(&self.qps[i]);
            }
            Quantity::KktFloor => {
                std::hint::black_box(solve_equality_kkt_with(&self.equality[i], backend));
            }
            Quantity::SchemeBuild | Quantity::RunExact | Quantity::RunNetwork => {}
        }
    }
}
