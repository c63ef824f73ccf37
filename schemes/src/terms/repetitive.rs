//! The repetitive (drift-free) term: q[..n] += w g(theta), e = theta - theta_ref, in one of two
//! forms:
//!
//! - `linear`: g = lambda e (robio2018 (4) C = lambda (theta - theta(0)); kong2019 (22) with
//!   lambda = mu; jia2019 (2.17) and zhong2021 (2.16) with lambda their coefficient k of
//!   [`spec::RmpReading`]). lambda = 0 drops the term: robio2018's baseline of Fig. 2(a);
//! - `sign-power`: g_i = lambda c(e_i), c(e) ~ |e|^alpha sgn(e) (kong2019 (14), lambda =
//!   beta_theta, 0 < alpha < 1), smoothed as below.
//!
//! The `squared` form is w ||thetadot + g||^2 / 2, which also adds w I to P (jia2019 (2.17)'s
//! tau ||thetadot + C||^2 / 2, zhong2021 (2.16)'s delta; the constant w |g|^2 / 2 is dropped);
//! the plain form is g'thetadot alone (robio2018, kong2019, beside a [`super::joint_norm`]).
//! theta_ref is the scheme's joint reference: theta0, or kong2019's theta*0.
//!
//! Time derivative: qdot = w lambda thetadot (linear), qdot_i = w lambda c'(e_i) thetadot_i
//! (sign-power); Pdot = 0.
//!
//! Regularisation (a deviation, documented in the report): c is Hölder, not Lipschitz, at
//! e = 0 for alpha < 1, so after the finite-time convergence the closed loop
//! thetadot_i = -beta_theta |e_i|^alpha sgn(e_i) chatters around e_i = 0 and no integrator can
//! step there (explicit steps shrink to ~1e-8 s, Newton iterations of implicit ones diverge).
//! We use the smoothed sign-power of the finite-time network, c(e) = e (e^2 +
//! delta^2)^((alpha - 1)/2) (`settings::sign_power`, delta = [`SMOOTHING`]): odd,
//! increasing, smooth, equal to |e|^alpha sgn(e) to 0.5 % for |e| >= 10 delta, and with slope
//! delta^(alpha - 1) at 0 (so e decays exponentially with time constant
//! delta^(1 - alpha) / beta_theta ~ 4e-6 s once inside the band).

use qp::Qp;
use settings::{sign_power, sign_power_slope};

use super::{DotOut, Slot, State, Term};

/// Smoothing width delta (rad) of the sign-power c (module docs).
pub const SMOOTHING: f64 = 1e-6;

/// The form of g (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Form {
    /// g = lambda e.
    Linear,
    /// g_i = lambda c(e_i) with exponent alpha, smoothed over |e| ~ [`SMOOTHING`].
    SignPower {
        /// Exponent alpha (in (0, 1]).
        alpha: f64,
    },
}

/// The repetitive term (module docs).
pub struct Repetitive {
    /// The joint reference theta_ref (theta0 or theta*0), one entry per joint.
    pub theta_ref: Vec<f64>,
    /// Weight w.
    pub weight: f64,
    /// Gain lambda.
    pub lambda: f64,
    /// The form of g.
    pub form: Form,
    /// Whether the term is w ||thetadot + g||^2 / 2 (adds w I to P) or w g'thetadot.
    pub squared: bool,
}

impl Repetitive {
    /// The factor w lambda of g in q.
    fn coefficient(&self) -> f64 {
        self.weight * self.lambda
    }
}

impl Term for Repetitive {
    fn describe(&self) -> String {
        let g = match self.form {
            Form::Linear => "lambda e".to_string(),
            Form::SignPower { alpha } => format!("lambda |e|^{alpha} sgn(e)"),
        };
        let quadratic = if self.squared {
            "P[..n, ..n] += w I, "
        } else {
            ""
        };
        format!(
            "repetitive (w={}, lambda={}): {quadratic}q[..n] += w g, g = {g}, e = theta - theta_ref",
            self.weight, self.lambda
        )
    }

    fn write(&self, state: &State<'_>, _slot: Slot, qp: &mut Qp) {
        // One loop per part, the form chosen once (the entries' sums are those of a loop over
        // the joints writing both).
        let c = self.coefficient();
        let n = state.theta.len().min(self.theta_ref.len());
        if self.squared {
            let rows = qp.p.nrows();
            let p = qp.p.as_mut_slice();
            for i in 0..n {
                p[i + i * rows] += self.weight;
            }
        }
        let q = &mut qp.q.as_mut_slice()[..n];
        let pairs = state.theta.iter().zip(&self.theta_ref);
        match self.form {
            Form::Linear => {
                for (qi, (th, r)) in q.iter_mut().zip(pairs) {
                    *qi += c * (th - r);
                }
            }
            Form::SignPower { alpha } => {
                for (qi, (th, r)) in q.iter_mut().zip(pairs) {
                    *qi += sign_power(th - r, alpha, SMOOTHING) * c;
                }
            }
        }
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, state: &State<'_>, _slot: Slot, out: &mut DotOut<'_>) {
        let c = self.coefficient();
        let q = &mut out.qp.q.as_mut_slice()[..state.thetadot.len()];
        match self.form {
            Form::Linear => {
                for (qi, v) in q.iter_mut().zip(state.thetadot) {
                    *qi += c * v;
                }
            }
            Form::SignPower { alpha } => {
                for (i, (qi, v)) in q.iter_mut().zip(state.thetadot).enumerate() {
                    let e = state.theta[i] - self.theta_ref[i];
                    *qi += c * sign_power_slope(e, alpha, SMOOTHING) * v;
                }
            }
        }
    }
}
