//! The one scheme: a level and a list of terms ([`crate::terms`]), x = [command; extra
//! variables], the command x[..n] being thetadot (velocity level) or thetaddot (acceleration
//! level). At every instant the QP is zeroed (bounds -inf, +inf), then each term writes its
//! block in list order; the papers' schemes are presets, term lists ([`spec::SchemeSpec`], built by [`crate::build`]).
//!
//! Where the bounds go ([`BoundPlacement`]): as the QP's variable bounds l <= x <= u, or as
//! rows of G appended after every term's rows,
//!
//! ```text
//! [ I_m; -I_m ] x <= [ u; -l ]        (m = the number of variables; l, u then -inf, +inf)
//! ```
//!
//! which is zhong2021 (2.18)'s B = [s; E; -E], h = [0; x+; -x-] when the terms are an infinity
//! norm and a bound conversion (the paper prints h's last block x-; the rows encode x >= x- only
//! with -x-, which is used), so that VP-RNN-PF's penalty zhong2021 (2.19) sees every bound.

use spec::BoundPlacement;

use crate::scheme::{central_difference, default_step, Scheme};
use crate::terms::{DotOut, Footprint, Slot, State, Term};
use qp::QpDotScratch;
use qp::{Qp, QpDims};
use spec::Level;

/// A scheme composed of terms (module docs).
pub struct Composed {
    name: String,
    level: Level,
    joints: usize,
    dims: QpDims,
    placement: BoundPlacement,
    /// The terms with their slots, in list order.
    terms: Vec<(Box<dyn Term>, Slot)>,
    /// Whether every term writes its exact derivative.
    exact_dot: bool,
}

impl Composed {
    /// The scheme `name` (display only) of `terms` on an arm of `joints` joints at `level`,
    /// with its bounds placed by `placement`.
    pub fn new(
        name: String,
        level: Level,
        joints: usize,
        placement: BoundPlacement,
        terms: Vec<Box<dyn Term>>,
    ) -> Self {
        let mut dims = QpDims {
            nx: joints,
            n_eq: 0,
            n_in: 0,
        };
        let mut slotted = Vec::with_capacity(terms.len());
        for term in terms {
            let Footprint {
                variables,
                equalities,
                inequalities,
                ..
            } = term.footprint();
            let slot = Slot {
                variable: dims.nx,
                equality: dims.n_eq,
                inequality: dims.n_in,
            };
            dims.nx += variables;
            dims.n_eq += equalities;
            dims.n_in += inequalities;
            slotted.push((term, slot));
        }
        if placement == BoundPlacement::Rows {
            dims.n_in += 2 * dims.nx;
        }
        let exact_dot = slotted.iter().all(|(term, _)| term.has_dot());
        Self {
            name,
            level,
            joints,
            dims,
            placement,
            terms: slotted,
            exact_dot,
        }
    }

    /// The composed QP term by term, one line each, followed by the bounds' placement.
    fn describe(&self) -> Vec<String> {
        let mut lines: Vec<String> = self
            .terms
            .iter()
            .map(|(term, slot)| {
                let fp = term.footprint();
                let mut at = Vec::new();
                if fp.variables > 0 {
                    at.push(format!("variable x[{}]", slot.variable));
                }
                if fp.equalities > 0 {
                    at.push(format!(
                        "A rows {}..{}",
                        slot.equality,
                        slot.equality + fp.equalities
                    ));
                }
                if fp.inequalities > 0 {
                    at.push(format!(
                        "G rows {}..{}",
                        slot.inequality,
                        slot.inequality + fp.inequalities
                    ));
                }
                if fp.bounds {
                    at.push("bounds".to_string());
                }
                if at.is_empty() {
                    term.describe()
                } else {
                    format!("{} [{}]", term.describe(), at.join(", "))
                }
            })
            .collect();
        if self.placement == BoundPlacement::Rows {
            let r0 = self.dims.n_in - 2 * self.dims.nx;
            lines.push(format!(
                "bounds as rows: G rows {r0}..{} = [I; -I], h = [u; -l]; l, u = -inf, +inf",
                self.dims.n_in
            ));
        }
        lines
    }

    /// The state passed to the terms.
    fn state<'a>(t: f64, theta: &'a [f64], thetadot: &'a [f64], thetaddot: &'a [f64]) -> State<'a> {
        State {
            t,
            theta,
            thetadot,
            thetaddot,
        }
    }

    /// The first row of the bounds' rows (placement [`BoundPlacement::Rows`]).
    fn bound_rows(&self) -> usize {
        self.dims.n_in - 2 * self.dims.nx
    }
}

/// Zeroes every field of `qp` and sets its bounds to `lower`, `upper`.
fn clear(qp: &mut Qp, lower: f64, upper: f64) {
    qp.p.as_mut_slice().fill(0.0);
    qp.q.as_mut_slice().fill(0.0);
    qp.a.as_mut_slice().fill(0.0);
    qp.b.as_mut_slice().fill(0.0);
    qp.g.as_mut_slice().fill(0.0);
    qp.h.as_mut_slice().fill(0.0);
    qp.lower.as_mut_slice().fill(lower);
    qp.upper.as_mut_slice().fill(upper);
}

impl Scheme for Composed {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn level(&self) -> Level {
        self.level
    }

    fn dims(&self) -> QpDims {
        self.dims
    }

    fn joints(&self) -> usize {
        self.joints
    }

    fn build(&self, t: f64, theta: &[f64], thetadot: &[f64], qp: &mut Qp) {
        debug_assert_eq!(qp.dims(), self.dims);
        clear(qp, f64::NEG_INFINITY, f64::INFINITY);
        let state = Self::state(t, theta, thetadot, &[]);
        for (term, slot) in &self.terms {
            term.write(&state, *slot, qp);
        }
        if self.placement == BoundPlacement::Rows {
            let (r0, m) = (self.bound_rows(), self.dims.nx);
            for i in 0..m {
                qp.g[(r0 + i, i)] = 1.0;
                qp.g[(r0 + m + i, i)] = -1.0;
                qp.h[r0 + i] = qp.upper[i];
                // 0 - l: +0 (not -0) where l = 0, as zhong2021's h prints it.
                qp.h[r0 + m + i] = 0.0 - qp.lower[i];
            }
            qp.lower.as_mut_slice().fill(f64::NEG_INFINITY);
            qp.upper.as_mut_slice().fill(f64::INFINITY);
        }
    }

    /// The sum of the terms' exact derivatives, or the central difference of the whole QP
    /// when a term has none (module docs of `terms`).
    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        thetaddot: &[f64],
        qp_dot: &mut Qp,
        scratch: &mut QpDotScratch,
    ) {
        debug_assert_eq!(qp_dot.dims(), self.dims);
        if !self.exact_dot {
            let h = default_step(self.level, thetadot, thetaddot);
            central_difference(self, t, theta, thetadot, thetaddot, h, qp_dot, scratch);
            return;
        }
        clear(qp_dot, 0.0, 0.0);
        // The running bounds of the merge live in the scratch QP's bounds.
        let bounds = &mut scratch.plus;
        bounds.lower.as_mut_slice().fill(f64::NEG_INFINITY);
        bounds.upper.as_mut_slice().fill(f64::INFINITY);
        let mut out = DotOut {
            qp: qp_dot,
            lower: bounds.lower.as_mut_slice(),
            upper: bounds.upper.as_mut_slice(),
        };
        let state = Self::state(t, theta, thetadot, thetaddot);
        for (term, slot) in &self.terms {
            term.write_dot(&state, *slot, &mut out);
        }
        if self.placement == BoundPlacement::Rows {
            let (r0, m) = (self.bound_rows(), self.dims.nx);
            for i in 0..m {
                qp_dot.h[r0 + i] = qp_dot.upper[i];
                qp_dot.h[r0 + m + i] = 0.0 - qp_dot.lower[i];
            }
            qp_dot.lower.as_mut_slice().fill(0.0);
            qp_dot.upper.as_mut_slice().fill(0.0);
        }
    }

    fn terms(&self) -> Vec<String> {
        self.describe()
    }

    fn torque(&self, theta: &[f64], thetadot: &[f64], thetaddot: &[f64], tau: &mut [f64]) -> bool {
        self.terms
            .iter()
            .any(|(term, _)| term.torque(theta, thetadot, thetaddot, tau))
    }
}
