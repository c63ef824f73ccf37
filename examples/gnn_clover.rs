//! A network written outside the library, scored against the exact optimum.
//!
//! A gradient neural network (GNN) for the QP  min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,
//! l <= x <= u  (the form of `qp::Qp`) descends the penalised energy
//!
//! ```text
//! E(x) = x'Px/2 + q'x + (rho/2) ( |A x - b|^2 + |max(G x - h, 0)|^2
//!                                 + |max(x - u, 0)|^2 + |max(l - x, 0)|^2 ),
//! xdot = -gamma grad E(x)
//!      = -gamma ( P x + q + rho A'(A x - b) + rho G' max(G x - h, 0)
//!                 + rho max(x - u, 0) - rho max(l - x, 0) ).
//! ```
//!
//! Its equilibrium is the penalised optimum, within O(1/rho) of x*. It implements
//! `solvers::neural::NeuralSolver`, and `simulation::simulate` runs it on jia2019's
//! VLTCO scheme along the four-leaf clover on the Jaco2 exactly as it runs the papers'
//! networks: coupled with the arm, integrated by BDF (RelTol 1e-6, AbsTol 1e-8, as ode15s), and
//! scored against the exact optimum at every accepted step. The exact column and jia2019's own
//! LVI-PDNN run beside it for comparison.
//!
//! `cargo run --release --example gnn_clover`

use catalog::default_exact_integrator;
use nalgebra::{DMatrix, DVector};
use qp::{Qp, QpDims};
use robots::{Jaco2, Robot};
use schemes::build_scheme;
use schemes::paths::build_path;
use settings::IntegratorSettings;
use settings::SolverSpec;
use simulation::build_network;
use simulation::{simulate, Outcome, Settings, Solver};
use solvers::neural::NeuralSolver;
use spec::NetworkInit;
use spec::PathSpec;
use spec::RmpReading;
use spec::SchemeSpec;
use spec::Scoring;
use std::sync::Arc;

/// The gradient neural network (module docs). Scratch buffers live in the struct, so `rhs`
/// does not allocate.
struct Gnn {
    gamma: f64,
    rho: f64,
    eq: DVector<f64>,
    ineq: DVector<f64>,
}

impl Gnn {
    fn new(gamma: f64, rho: f64, dims: QpDims) -> Self {
        Gnn {
            gamma,
            rho,
            eq: DVector::zeros(dims.n_eq),
            ineq: DVector::zeros(dims.n_in),
        }
    }
}

impl NeuralSolver for Gnn {
    fn name(&self) -> String {
        "GNN (user)".to_string()
    }

    fn state_dim(&self, dims: QpDims) -> usize {
        dims.nx
    }

    fn rhs(&mut self, _t: f64, y: &[f64], qp: &Qp, _qp_dot: Option<&Qp>, ydot: &mut [f64]) {
        let x = nalgebra::DVectorView::from_slice(y, y.len());
        // Residuals: A x - b, and the positive part of G x - h.
        self.eq.copy_from(&qp.b);
        self.eq.gemv(1.0, &qp.a, &x, -1.0);
        self.ineq.copy_from(&qp.h);
        self.ineq.gemv(1.0, &qp.g, &x, -1.0);
        self.ineq.apply(|v| *v = v.max(0.0));
        let mut grad = nalgebra::DVectorViewMut::from_slice(ydot, y.len());
        grad.copy_from(&qp.q);
        grad.gemv(1.0, &qp.p, &x, 1.0);
        grad.gemv_tr(self.rho, &qp.a, &self.eq, 1.0);
        grad.gemv_tr(self.rho, &qp.g, &self.ineq, 1.0);
        for i in 0..y.len() {
            let over = (y[i] - qp.upper[i]).max(0.0) - (qp.lower[i] - y[i]).max(0.0);
            grad[i] = -self.gamma * (grad[i] + self.rho * over);
        }
    }

    /// dF/dy = -gamma (P + rho A'A + rho G_act'G_act + rho D_act), D_act the bounds that are
    /// violated (the active rows of the penalty).
    fn jacobian(
        &mut self,
        _t: f64,
        y: &[f64],
        qp: &Qp,
        _qp_dot: Option<&Qp>,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        let x = nalgebra::DVectorView::from_slice(y, y.len());
        jac.copy_from(&qp.p);
        jac.gemm_tr(self.rho, &qp.a, &qp.a, 1.0);
        for r in 0..qp.g.nrows() {
            if (qp.g.row(r) * x)[0] > qp.h[r] {
                let row = qp.g.row(r);
                for i in 0..y.len() {
                    for j in 0..y.len() {
                        jac[(i, j)] += self.rho * row[i] * row[j];
                    }
                }
            }
        }
        for i in 0..y.len() {
            if y[i] > qp.upper[i] || y[i] < qp.lower[i] {
                jac[(i, i)] += self.rho;
            }
        }
        *jac *= -self.gamma;
        true
    }
}

/// One line of the comparison: drift, tracking error, distance to the optimum, cost.
struct Line {
    solver: String,
    drift_norm: f64,
    max_pos_err: f64,
    max_dx: Option<f64>,
    steps: usize,
    wall_s: f64,
}

fn run() -> Vec<Line> {
    let robot = Arc::new(Jaco2::pen());
    let theta0 = robots::JACO2_PAPERS_THETA0;
    let path: Arc<dyn schemes::paths::Path> = Arc::from(
        build_path(
            &PathSpec::new("four-leaf-clover", 5.0),
            robot.position(&theta0),
        )
        .expect("the clover is a known path"),
    );
    // jia2019's VLTCO (phi = 0.2, tau = 0.4, kappa = lambda = 20).
    let spec = SchemeSpec::Vltco {
        phi: 0.2,
        tau: 0.4,
        kappa: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        mu: 5.0,
    };
    let scheme = build_scheme(&spec, robot.clone(), None, path.clone(), &theta0)
        .expect("jia2019's VLTCO with the paper's parameters");
    let dims = scheme.dims();
    // The networks as the papers integrate them (BDF, RelTol 1e-6, AbsTol 1e-8, as ode15s);
    // the exact column as the suite does (Dormand-Prince, RelTol 1e-11: converged).
    let networks = Settings {
        integrator: IntegratorSettings::default(),
        scoring: Scoring::EveryStep,
        network_init: NetworkInit::Zero,
    };
    let exact = Settings {
        integrator: default_exact_integrator(),
        ..networks.clone()
    };
    let gnn = move || Ok(Box::new(Gnn::new(1e4, 1e3, dims)) as Box<dyn NeuralSolver>);
    let scheme_name = scheme.name();
    let lvi = move || build_network(&SolverSpec::LviPdnn { gamma: 1e7 }, dims, &scheme_name);
    let solvers: [(&str, Solver); 3] = [
        ("exact (certified active set / Clarabel)", Solver::Exact),
        ("LVI-PDNN (jia2019, gamma = 1e7)", Solver::Network(&lvi)),
        (
            "GNN (this example, gamma = 1e4, rho = 1e3)",
            Solver::Network(&gnn),
        ),
    ];
    solvers
        .into_iter()
        .map(|(name, solver)| {
            let settings = if matches!(solver, Solver::Exact) {
                &exact
            } else {
                &networks
            };
            let run = simulate(
                robot.as_ref(),
                path.as_ref(),
                scheme.as_ref(),
                solver,
                &theta0,
                &theta0,
                settings,
            )
            .expect("the run starts");
            let Outcome::Completed(m) = &run.outcome else {
                panic!("{name}: {:?}", run.outcome);
            };
            Line {
                solver: name.to_string(),
                drift_norm: m.drift_norm,
                max_pos_err: m.max_position_error,
                max_dx: m.score.map(|s| s.max_dx),
                steps: run.stats.steps,
                wall_s: run.stats.wall_seconds,
            }
        })
        .collect()
}

fn main() {
    println!("jia2019 VLTCO on the four-leaf clover (jaco2-pen, T = 5 s)");
    println!(
        "{:<46} {:>10} {:>10} {:>10} {:>8} {:>8}",
        "solver", "|drift|", "max err", "|x-x*|max", "steps", "wall s"
    );
    for l in run() {
        println!(
            "{:<46} {:>10.3e} {:>10.3e} {:>10} {:>8} {:>8.3}",
            l.solver,
            l.drift_norm,
            l.max_pos_err,
            l.max_dx.map_or("-".to_string(), |d| format!("{d:.3e}")),
            l.steps,
            l.wall_s
        );
    }
}
