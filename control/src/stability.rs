//! Each network's stability limit under forward Euler: the largest step s for which the
//! discretised network does not blow up, from the spectrum of its Jacobian.
//!
//! Near a state y the network ydot = F(t, y; QP) behaves as the linear system
//! d(dy)/dt = J dy with J = dF/dy (the QP frozen over the step; the projection networks are
//! piecewise linear, so J is exact inside each region of the projection). Forward Euler with
//! step s maps dy to (I + s J) dy, which contracts along an eigenvector of eigenvalue lambda iff
//! |1 + s lambda| <= 1, i.e.
//!
//! ```text
//! s <= s_max(lambda) = -2 Re(lambda) / |lambda|^2     (Re lambda < 0).
//! ```
//!
//! The network's limit at a state is the smallest s_max over its eigenvalues with
//! Re lambda < 0 (eigenvalues with Re lambda >= 0 do not contract in continuous time either,
//! so they are no limit of the discretisation). It is evaluated at y = 0 (every network's
//! start) and at y = [x*; 0] (the command at the exact optimum, multipliers zero) at every
//! [`SAMPLE_EVERY`]-th tick of a run of the task at the control period with the exact
//! optimum in the loop ([`solvers::HotActiveSet`]), and the smallest value is
//! the network's stability limit on the task. The Jacobians are the networks' analytic ones
//! ([`solvers::neural::NeuralSolver::jacobian`]).
//!
//! With a linear zeroing network (ZNN), J = -gamma I - Q^{-1} Qdot, so s_max ~ 2 / gamma; for
//! LVI-PDNN J = gamma (I + M')(D (I - M) - I) and s_max ~ 1 / (gamma |M|^2): the gain sets the
//! limit, and the product gain x s_max is the figure of merit beside the papers' gains.

use crate::control_loop::Observer;
use nalgebra::{DMatrix, Schur};
use qp::Qp;
use settings::SolverSpec;
use solvers::neural::NeuralSolver;

/// Ticks between two states the Jacobian is evaluated at.
pub const SAMPLE_EVERY: usize = 250;

/// The gain that sets a network's time scale, with its name as the papers write it
/// (VP-RNN-PF's is gamma exp(t), growing: its limit shrinks along the run).
pub fn gain(spec: &SolverSpec) -> (&'static str, f64) {
    match spec {
        SolverSpec::LviPdnn { gamma } => ("gamma", *gamma),
        SolverSpec::SLviPdnn { beta } => ("beta", *beta),
        SolverSpec::VpRnnPf { gamma, .. } => ("gamma (x exp t)", *gamma),
        SolverSpec::FpCdnn { gamma, .. } | SolverSpec::VpCdnn { gamma, .. } => ("gamma", *gamma),
        SolverSpec::FiniteTime { beta, .. } => ("beta", *beta),
        SolverSpec::Znn { gamma } | SolverSpec::GroupZnn { gamma, .. } => ("gamma", *gamma),
        SolverSpec::Zeroing { gain, .. } | SolverSpec::Projection { gain, .. } => {
            ("g(0)", gain.at(0.0))
        }
    }
}

/// Iteration limit of the Schur decomposition the eigenvalues come from.
const SCHUR_ITERATIONS: usize = 100_000;

/// s_max of one Jacobian (module docs); `None` when no eigenvalue has a negative real part or
/// the eigenvalues cannot be computed. The matrix is first scaled to unit largest entry c
/// (eigenvalues lambda = c mu, so s_max = (1/c) min -2 Re(mu) / |mu|^2), which keeps the Schur
/// iteration well scaled for gains of 1e7.
pub fn euler_limit(jac: &DMatrix<f64>) -> Option<f64> {
    let c = jac.amax();
    if !(c > 0.0 && c.is_finite()) {
        return None;
    }
    let schur = Schur::try_new(jac / c, 1e-14, SCHUR_ITERATIONS)?;
    schur
        .complex_eigenvalues()
        .iter()
        .filter(|mu| mu.re < -1e-12 * mu.norm())
        .map(|mu| -2.0 * mu.re / mu.norm_sqr() / c)
        .reduce(f64::min)
}

/// Collects the smallest Euler limit of a network over the observed ticks (an [`Observer`]).
pub struct LimitProbe {
    net: Box<dyn NeuralSolver>,
    y: Vec<f64>,
    jac: DMatrix<f64>,
    /// The smallest limit seen, and at which instant.
    pub limit: Option<(f64, f64)>,
    /// Whether the network gave its Jacobian.
    pub analytic: bool,
}

impl LimitProbe {
    pub fn new(net: Box<dyn NeuralSolver>, state_dim: usize) -> Self {
        LimitProbe {
            net,
            y: vec![0.0; state_dim],
            jac: DMatrix::zeros(state_dim, state_dim),
            limit: None,
            analytic: true,
        }
    }

    fn probe(&mut self, t: f64, qp: &Qp, qp_dot: Option<&Qp>) {
        if !self.net.jacobian(t, &self.y, qp, qp_dot, &mut self.jac) {
            self.analytic = false;
            return;
        }
        if let Some(s) = euler_limit(&self.jac) {
            if self.limit.is_none_or(|(best, _)| s < best) {
                self.limit = Some((s, t));
            }
        }
    }
}

impl Observer for LimitProbe {
    fn needs_qp_dot(&self) -> bool {
        self.net.needs_qp_dot()
    }

    fn observe(&mut self, k: usize, t: f64, qp: &Qp, qp_dot: Option<&Qp>, x_star: &[f64]) {
        if !k.is_multiple_of(SAMPLE_EVERY) || !self.analytic {
            return;
        }
        let qp_dot = qp_dot.filter(|_| self.net.needs_qp_dot());
        self.y.fill(0.0);
        self.probe(t, qp, qp_dot);
        self.y[..x_star.len()].copy_from_slice(x_star);
        self.probe(t, qp, qp_dot);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_euler_limit_of_known_spectra() {
        // A linear ZNN: J = -gamma I, limit 2 / gamma.
        let j = DMatrix::from_diagonal_element(3, 3, -200.0);
        assert!((euler_limit(&j).unwrap() - 0.01).abs() < 1e-15);
        // A damped rotation: lambda = -a +- i w, limit 2a / (a^2 + w^2).
        let (a, w) = (1e6, 3e6);
        let j = DMatrix::from_row_slice(2, 2, &[-a, w, -w, -a]);
        let expected = 2.0 * a / (a * a + w * w);
        assert!((euler_limit(&j).unwrap() / expected - 1.0).abs() < 1e-12);
        // Nothing contracts: no limit.
        assert!(euler_limit(&DMatrix::from_diagonal_element(2, 2, 1.0)).is_none());
    }
}
