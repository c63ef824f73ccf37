//! The infinity norm of thetadot through an auxiliary variable s (velocity level): one extra
//! variable s (the column after the earlier variables), 2n rows of G and a bound,
//!
//! ```text
//! P_ss += w   (squared: w s^2 / 2)    or    q_s += w   (linear: w s)
//! [I -1; -I -1] [thetadot; s] <= 0            (|thetadot_i| <= s)
//! 0 <= s <= varpi
//! ```
//!
//! The squared form is jia2019 (2.17)-(2.20) and zhong2021 (2.16)-(2.18) (their p, with weight
//! 1 - phi - tau, 1 - eta - delta on p^2 / 2 in D, and varpi "a large constant standing for
//! +inf", here +inf by default); the linear form penalises |thetadot|_inf itself. At the optimum
//! s = |thetadot|_inf whenever w > 0. Constant rows: derivative 0.

use qp::Qp;

use super::{DotOut, Footprint, Slot, State, Term};

/// The infinity-norm term (module docs).
pub struct InfinityNorm {
    /// Whether the penalty is w s^2 / 2 (true) or w s.
    pub squared: bool,
    /// Joint count n.
    pub joints: usize,
    /// Weight w >= 0 of s^2 / 2.
    pub weight: f64,
    /// Upper bound varpi of s (> 0; +inf: none).
    pub varpi: f64,
}

impl Term for InfinityNorm {
    fn describe(&self) -> String {
        let penalty = if self.squared {
            "P_ss += w"
        } else {
            "q_s += w"
        };
        format!(
            "infinity-norm (w={}, varpi={}): variable s, {penalty}, [I -1; -I -1] [thetadot; s] \
             <= 0, 0 <= s <= varpi",
            self.weight, self.varpi
        )
    }

    fn footprint(&self) -> Footprint {
        Footprint {
            variables: 1,
            inequalities: 2 * self.joints,
            bounds: true,
            ..Default::default()
        }
    }

    fn write(&self, _state: &State<'_>, slot: Slot, qp: &mut Qp) {
        let (n, s, r) = (self.joints, slot.variable, slot.inequality);
        if self.squared {
            qp.p[(s, s)] += self.weight;
        } else {
            qp.q[s] += self.weight;
        }
        for i in 0..n {
            qp.g[(r + i, i)] = 1.0;
            qp.g[(r + i, s)] = -1.0;
            qp.g[(r + n + i, i)] = -1.0;
            qp.g[(r + n + i, s)] = -1.0;
        }
        qp.lower[s] = qp.lower[s].max(0.0);
        qp.upper[s] = qp.upper[s].min(self.varpi);
    }

    fn has_dot(&self) -> bool {
        true
    }

    fn write_dot(&self, _state: &State<'_>, slot: Slot, out: &mut DotOut<'_>) {
        out.merge_lower(slot.variable, 0.0, 0.0);
        out.merge_upper(slot.variable, self.varpi, 0.0);
    }
}
