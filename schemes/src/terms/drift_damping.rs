//! zhang2018's drift damping at the acceleration level: q[..n] += w sigma with
//!
//! ```text
//! sigma = (alpha + beta) thetadot + alpha beta (theta - theta0)          zhang2018 (2.5)
//! ```
//!
//! alpha, beta > 0: with [`super::joint_norm`]'s acceleration norm of the same weight it is
//! w ||thetaddot + sigma||^2 / 2 up to a constant, whose minimiser thetaddot = -sigma drives
//! theta - theta0 to 0 as a critically or over-damped second-order system. No exact derivative
//! is written (a scheme with it takes the central difference, as zhang2018's did).

use qp::Qp;

use super::{Slot, State, Term};

/// The drift damping (module docs).
pub struct DriftDamping {
    /// The joint reference theta0.
    pub theta0: Vec<f64>,
    /// Weight w.
    pub weight: f64,
    /// Gain alpha.
    pub alpha: f64,
    /// Gain beta.
    pub beta: f64,
}

impl Term for DriftDamping {
    fn describe(&self) -> String {
        format!(
            "drift-damping (w={}, alpha={}, beta={}): q[..n] += w sigma, sigma = (alpha + beta) \
             thetadot + alpha beta (theta - theta0)",
            self.weight, self.alpha, self.beta
        )
    }

    fn write(&self, state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        for (i, t0) in self.theta0.iter().enumerate() {
            let sigma = state.thetadot[i] * (self.alpha + self.beta)
                + (state.theta[i] - t0) * (self.alpha * self.beta);
            qp.q[i] += sigma * self.weight;
        }
    }
}
