//! A network as a controller steps it: its continuous dynamics ydot = F(t, y; QP(t)) (see
//! [`solvers::neural::NeuralSolver`]) discretised at the control period, with the QP of the tick
//! held over it (a controller only has the QP of its last sample).
//!
//! # Forms
//!
//! With step s = h / m (m = substeps per tick, 1 for a network run at the control rate):
//!
//! - **Euler**: y_{j+1} = y_j + s F(t, y_j; QP_k). For the zeroing networks (ZNN, FTNN, the
//!   CDNNs), whose F is Q^{-1}(-Qdot y + udot - gamma Phi(Q y - u)), this is the Euler-type
//!   discrete-time ZNN of the literature (Zhang, Xiao, Xiao and Mao, "Discrete-time Zhang
//!   neural network for online time-varying quadratic minimization", 2009 and after:
//!   y_{k+1} = y_k - s Q^{-1}(Qdot y_k - udot) - s gamma Q^{-1} Phi(Q y_k - u)); with a linear
//!   Phi it is stable for 0 < s gamma < 2 and its steady error is O(s).
//! - **Taylor** (zeroing networks only): the Taylor-type discrete-time ZNN of Zhang, Jin, Guo,
//!   Yin and Chou ("Taylor-type 1-step-ahead numerical differentiation rule for first-order
//!   derivative approximation and ZNN discretization", J. Comput. Appl. Math. 273, 2015), from
//!   the rule ydot_j ~ (2 y_{j+1} - 3 y_j + 2 y_{j-1} - y_{j-2}) / (2 s):
//!   y_{j+1} = s F(t, y_j) + (3/2) y_j - y_{j-1} + (1/2) y_{j-2}, steady error O(s^2), stable
//!   for 0 < s gamma < 1 with a linear Phi. Its first two steps are Euler steps (no history).
//!
//! The network's state starts at zero (as in every continuous run) and is kept across ticks.

use crate::error::ControlError;
use crate::tick::TickSolver;
use qp::{Qp, QpDims, QpSolve};
use settings::projection::{ProjectionErrorForm, Scaling};
use settings::SolverSpec;
use solvers::neural::{build_solver, NeuralSolver};
use std::mem;

/// How a network's dynamics are discretised (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Discretisation {
    Euler,
    Taylor,
}

impl Discretisation {
    pub fn name(self) -> &'static str {
        match self {
            Discretisation::Euler => "Euler",
            Discretisation::Taylor => "Taylor DTZNN",
        }
    }
}

/// Products with the LVI matrix M per evaluation of F for the projection family's LVI form
/// (`settings::projection`): two with the scaling I + M' (LVI-PDNN: M y for the residual,
/// then (I + M') Phi(e)), one with the identity (S-LVI-PDNN); `None` for the networks not built
/// on the LVI.
pub fn products_per_evaluation(spec: &SolverSpec) -> Option<u64> {
    match spec.projection()?.error {
        ProjectionErrorForm::Lvi {
            scaling: Scaling::IPlusMt,
        } => Some(2),
        ProjectionErrorForm::Lvi {
            scaling: Scaling::Identity,
        } => Some(1),
        ProjectionErrorForm::Penalty { .. } => None,
    }
}

/// A network stepped in discrete time (module docs).
pub struct NetworkTick {
    net: Box<dyn NeuralSolver>,
    form: Discretisation,
    substeps: u32,
    nx: usize,
    products: Option<u64>,
    y: Vec<f64>,
    f: Vec<f64>,
    /// y_{j-1}, y_{j-2} (Taylor form) and the next state.
    back1: Vec<f64>,
    back2: Vec<f64>,
    next: Vec<f64>,
    steps: u64,
}

impl NetworkTick {
    pub fn new(
        spec: &SolverSpec,
        form: Discretisation,
        substeps: u32,
        dims: QpDims,
    ) -> Result<Self, ControlError> {
        let net = build_solver(spec, dims).map_err(|error| ControlError::Network {
            task: spec.display_name(),
            error,
        })?;
        let n = net.state_dim(dims);
        let mut y = vec![0.0; n];
        net.initial_state(dims, &mut y);
        Ok(NetworkTick {
            net,
            form,
            substeps: substeps.max(1),
            nx: dims.nx,
            products: products_per_evaluation(spec),
            back1: y.clone(),
            back2: y.clone(),
            next: y.clone(),
            y,
            f: vec![0.0; n],
            steps: 0,
        })
    }
}

impl TickSolver for NetworkTick {
    fn needs_qp_dot(&self) -> bool {
        self.net.needs_qp_dot()
    }

    /// `substeps` steps of the discrete form; the products of a projection network's
    /// evaluations ([`products_per_evaluation`] each).
    fn tick(
        &mut self,
        t: f64,
        qp: &Qp,
        qp_dot: Option<&Qp>,
        h: f64,
    ) -> Result<QpSolve, ControlError> {
        let s = h / self.substeps as f64;
        for j in 0..self.substeps {
            let tj = t + j as f64 * s;
            self.net.rhs(tj, &self.y, qp, qp_dot, &mut self.f);
            let taylor = self.form == Discretisation::Taylor && self.steps >= 2;
            for i in 0..self.y.len() {
                self.next[i] = if taylor {
                    s * self.f[i] + 1.5 * self.y[i] - self.back1[i] + 0.5 * self.back2[i]
                } else {
                    self.y[i] + s * self.f[i]
                };
            }
            // back2 <- back1 <- y <- next, rotating the buffers without allocating.
            mem::swap(&mut self.back2, &mut self.back1);
            mem::swap(&mut self.back1, &mut self.y);
            mem::swap(&mut self.y, &mut self.next);
            self.steps += 1;
        }
        Ok(QpSolve {
            iterations: self.substeps,
            products: self.products.map(|p| p * u64::from(self.substeps)),
            ..QpSolve::default()
        })
    }

    fn x(&self) -> &[f64] {
        &self.y[..self.nx]
    }
}
