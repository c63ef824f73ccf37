//! Eliminating an unweighted auxiliary variable: MVN's QP (jia2019 (2.17)–(2.20) with
//! phi = 1, tau = 0; zhong2021 (2.16)–(2.18) with eta + delta = 1) gives its max-norm variable
//! p zero weight, so P is singular and the active-set solver ([`crate::active_set`]) cannot
//! factorise its KKT matrices. p is eliminated instead, the reduced QP (positive definite in
//! the rest) solved by the active set, and the answer lifted back and certified on the
//! original QP.
//!
//! # Which variable (structural)
//!
//! Variable j is eliminable when it does not enter the objective or the equalities
//! (row and column j of P zero, q_j = 0, column j of A zero) and every row of G that involves
//! it is either
//!
//! - a *bound row* (x_j its only nonzero): `g x_j <= h`, an upper bound h / g when g > 0, a
//!   lower bound h / g when g < 0; or
//! - a *coupled row* with a negative coefficient on x_j: `c'y - alpha x_j <= h`, alpha > 0,
//!   y the other variables.
//!
//! The first such j (smallest index) is eliminated; nothing looks at the scheme. MVN's
//! |thetadot_i| <= p rows (jia2019 (2.19), zhong2021's s block) are coupled rows with
//! alpha = 1, and zhong2021's rows p <= varpi and -p <= 0 are bound rows.
//!
//! # The reduced QP
//!
//! Let [l, u] be x_j's bounds intersected with its bound rows. For fixed y, a feasible x_j
//! exists if and only if
//!
//! ```text
//! max(l, max_i (c_i'y - h_i) / alpha_i) <= u,   i.e.   c_i'y <= h_i + alpha_i u  for every
//! coupled row i, and l <= u.
//! ```
//!
//! Since x_j does not enter the objective, the original QP's optimal y are exactly the optima
//! of the reduced QP in y: P, q, A, the other rows of G and y's bounds unchanged, each coupled
//! row replaced by `c_i'y <= h_i + alpha_i u` (absent, h = +inf, when u = +inf, as with the
//! papers' varpi = +inf), the bound rows dropped. For MVN with varpi = +inf this is minimise
//! |thetadot|^2 / 2 subject to J thetadot = rdot* and the joint bounds; with a finite varpi it
//! adds the box |thetadot_i| <= varpi.
//!
//! # The lifted answer and why x_j is the smallest feasible value
//!
//! Every x_j in [max(l, max_i (c_i'y* - h_i) / alpha_i), u] is optimal (the objective does not
//! see it). We return the smallest, x_j* = max(l, max_i (c_i'y* - h_i) / alpha_i): for MVN
//! (l = 0, c_i'y - h_i = +-thetadot_i) that is p* = |thetadot*|_inf, the quantity the auxiliary
//! variable stands for (jia2019's "p = |thetadot|_inf"), and it is defined without any
//! arbitrary choice (an interior-point method such as Clarabel returns some interior point of
//! that interval instead, typically near its centre when u is finite, or large when u = +inf).
//!
//! # Multipliers and certification
//!
//! The reduced multipliers carry over (lambda, the kept rows' mu, y's bound multipliers; a
//! coupled row keeps its reduced multiplier), and stationarity in x_j,
//! `-sum_i alpha_i mu_i + (upper-bound multiplier) - (lower-bound multiplier) = 0`, puts
//! S = sum_i alpha_i mu_i >= 0 on the bound that makes u (x_j's own upper bound or the bound
//! row, divided by its coefficient). S > 0 only if some coupled row is active in the reduced
//! QP, c_i'y* = h_i + alpha_i u, and then x_j* = u: complementarity holds. The lifted
//! (x, multipliers) is certified by [`qp::Qp::kkt_residuals`] on the original QP with
//! the active-set solver's tolerance, so the answer is the original QP's optimum (KKT
//! sufficiency, [`crate::active_set`]), whatever the reduction's arithmetic did.
//!
//! # Allocation
//!
//! [`AuxiliaryElimination::recognise`] allocates the reduced QP; [`AuxiliaryElimination::reduce`]
//! and [`AuxiliaryElimination::lift`] refill it and a caller's buffers in place.

use crate::active_set::ActiveSetSolution;
use nalgebra::DVector;
use qp::{Qp, QpDims, QpDuals};

/// What a row of the original G is to the eliminated variable.
#[derive(Clone, Copy, Debug, PartialEq)]
enum RowRole {
    /// Does not involve x_j: row `reduced` of the reduced G, unchanged.
    Kept { reduced: usize },
    /// c'y - alpha x_j <= h (alpha = -G_ij > 0): row `reduced`, right-hand side h + alpha u.
    Coupled { reduced: usize },
    /// g x_j <= h, x_j its only nonzero: part of [l, u], dropped.
    Bound,
}

/// Which bound makes x_j's effective upper bound u (it takes the multiplier S).
#[derive(Clone, Copy, Debug, PartialEq)]
enum UpperSource {
    /// x_j's own upper bound (or u = +inf).
    Own,
    /// Bound row i (coefficient > 0).
    Row(usize),
}

/// The elimination of one unweighted auxiliary variable (module docs).
#[derive(Clone, Debug)]
pub struct AuxiliaryElimination {
    /// The eliminated variable.
    var: usize,
    /// One role per row of the original G.
    roles: Vec<RowRole>,
    reduced: Qp,
    lower: f64,
    upper: f64,
    upper_source: UpperSource,
}

impl AuxiliaryElimination {
    /// The elimination of the first eliminable variable of `qp` (module docs), `None` if no
    /// variable qualifies or its bounds are inconsistent (l > u, or no lower limit at all:
    /// l = -inf and no coupled row). Allocates the reduced QP.
    pub fn recognise(qp: &Qp) -> Option<Self> {
        let dims = qp.dims();
        if dims.nx < 2 {
            return None;
        }
        let var = (0..dims.nx).find(|&j| eliminable(qp, j))?;
        let mut roles = Vec::with_capacity(dims.n_in);
        let mut kept = 0;
        for i in 0..dims.n_in {
            let role = match row_kind(qp, i, var) {
                RowKind::Free => RowRole::Kept { reduced: kept },
                RowKind::Coupled => RowRole::Coupled { reduced: kept },
                RowKind::Bound => RowRole::Bound,
                RowKind::Blocking => return None,
            };
            if role != RowRole::Bound {
                kept += 1;
            }
            roles.push(role);
        }
        let mut elimination = Self {
            var,
            roles,
            reduced: Qp::zeros(QpDims {
                nx: dims.nx - 1,
                n_eq: dims.n_eq,
                n_in: kept,
            }),
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            upper_source: UpperSource::Own,
        };
        elimination.reduce(qp).then_some(elimination)
    }

    /// The eliminated variable's index.
    pub fn variable(&self) -> usize {
        self.var
    }

    /// The reduced QP of the last [`Self::reduce`].
    pub fn reduced(&self) -> &Qp {
        &self.reduced
    }

    /// Refills the reduced QP from `qp`; false (and the reduced QP unspecified) if `qp` no
    /// longer has the recognised structure (other sizes, x_j weighted or in an equality, a row
    /// whose role changed) or x_j's bounds are inconsistent. Allocates nothing.
    pub fn reduce(&mut self, qp: &Qp) -> bool {
        let dims = qp.dims();
        let j = self.var;
        if dims.nx != self.reduced.q.len() + 1
            || dims.n_eq != self.reduced.b.len()
            || dims.n_in != self.roles.len()
            || !eliminable(qp, j)
        {
            return false;
        }
        // x_j's effective bounds [l, u].
        let (mut lower, mut upper) = (qp.lower[j], qp.upper[j]);
        let mut upper_source = UpperSource::Own;
        let mut coupled = false;
        for (i, &role) in self.roles.iter().enumerate() {
            let kind = row_kind(qp, i, j);
            let consistent = matches!(
                (role, kind),
                (RowRole::Kept { .. }, RowKind::Free)
                    | (RowRole::Coupled { .. }, RowKind::Coupled)
                    | (RowRole::Bound, RowKind::Bound)
            );
            if !consistent {
                return false;
            }
            match role {
                RowRole::Bound => {
                    let g = qp.g[(i, j)];
                    let limit = qp.h[i] / g;
                    if g > 0.0 {
                        if limit < upper {
                            upper = limit;
                            upper_source = UpperSource::Row(i);
                        }
                    } else {
                        lower = lower.max(limit);
                    }
                }
                RowRole::Coupled { .. } => coupled = true,
                RowRole::Kept { .. } => {}
            }
        }
        if lower.is_nan() || upper.is_nan() || lower > upper || (!coupled && lower.is_infinite()) {
            return false;
        }
        self.lower = lower;
        self.upper = upper;
        self.upper_source = upper_source;
        // The reduced data: every matrix and vector without entry (row, column) j.
        let skip = |k: usize| if k < j { k } else { k + 1 };
        let n = dims.nx - 1;
        let r = &mut self.reduced;
        for c in 0..n {
            for rr in 0..n {
                r.p[(rr, c)] = qp.p[(skip(rr), skip(c))];
            }
            for e in 0..dims.n_eq {
                r.a[(e, c)] = qp.a[(e, skip(c))];
            }
            r.q[c] = qp.q[skip(c)];
            r.lower[c] = qp.lower[skip(c)];
            r.upper[c] = qp.upper[skip(c)];
        }
        r.b.copy_from(&qp.b);
        for (i, &role) in self.roles.iter().enumerate() {
            let (row, h) = match role {
                RowRole::Kept { reduced } => (reduced, qp.h[i]),
                // h + alpha u, alpha = -G_ij (+inf when u = +inf: the row is absent).
                RowRole::Coupled { reduced } => (reduced, qp.h[i] - qp.g[(i, j)] * upper),
                RowRole::Bound => continue,
            };
            for c in 0..n {
                r.g[(row, c)] = qp.g[(i, skip(c))];
            }
            r.h[row] = h;
        }
        true
    }

    /// The original QP's answer from the reduced one's (`reduced`, solved for
    /// [`Self::reduced`] after [`Self::reduce`] of the same `qp`): x_j* the smallest feasible
    /// value and the multipliers of the module docs, written into `x` and `duals` (of `qp`'s
    /// sizes). Allocates nothing.
    pub fn lift(
        &self,
        qp: &Qp,
        reduced: &ActiveSetSolution,
        x: &mut DVector<f64>,
        duals: &mut QpDuals,
    ) {
        let j = self.var;
        let skip = |k: usize| if k < j { k } else { k + 1 };
        let y = &reduced.x;
        let rd = &reduced.duals;
        for c in 0..y.len() {
            x[skip(c)] = y[c];
            duals.z_lower[skip(c)] = rd.z_lower[c];
            duals.z_upper[skip(c)] = rd.z_upper[c];
        }
        duals.lambda.copy_from(&rd.lambda);
        let mut xj = self.lower;
        let mut s = 0.0;
        for (i, &role) in self.roles.iter().enumerate() {
            match role {
                RowRole::Kept { reduced } => duals.mu[i] = rd.mu[reduced],
                RowRole::Coupled { reduced } => {
                    let alpha = -qp.g[(i, j)];
                    let mut cy = 0.0;
                    for c in 0..y.len() {
                        cy += qp.g[(i, skip(c))] * y[c];
                    }
                    xj = xj.max((cy - qp.h[i]) / alpha);
                    duals.mu[i] = rd.mu[reduced];
                    s += alpha * rd.mu[reduced];
                }
                RowRole::Bound => duals.mu[i] = 0.0,
            }
        }
        // A coupled row active in the reduced QP puts x_j at u, up to rounding.
        x[j] = xj.min(self.upper);
        duals.z_lower[j] = 0.0;
        duals.z_upper[j] = 0.0;
        match self.upper_source {
            UpperSource::Own => duals.z_upper[j] = s,
            UpperSource::Row(i) => duals.mu[i] = s / qp.g[(i, j)],
        }
    }
}

/// What row i of G is to variable j.
enum RowKind {
    /// G_ij = 0.
    Free,
    /// G_ij < 0 and another nonzero.
    Coupled,
    /// G_ij the only nonzero.
    Bound,
    /// G_ij > 0 and another nonzero: an upper limit on x_j that depends on the others; j is
    /// not eliminable this way.
    Blocking,
}

fn row_kind(qp: &Qp, i: usize, j: usize) -> RowKind {
    let g = qp.g[(i, j)];
    if g == 0.0 {
        return RowKind::Free;
    }
    let others = (0..qp.g.ncols()).any(|c| c != j && qp.g[(i, c)] != 0.0);
    match (others, g < 0.0) {
        (false, _) => RowKind::Bound,
        (true, true) => RowKind::Coupled,
        (true, false) => RowKind::Blocking,
    }
}

/// Whether x_j is absent from the objective and the equalities and every row of G involving
/// it is a bound row or a coupled row (module docs).
fn eliminable(qp: &Qp, j: usize) -> bool {
    let nx = qp.q.len();
    qp.q[j] == 0.0
        && (0..nx).all(|k| qp.p[(j, k)] == 0.0 && qp.p[(k, j)] == 0.0)
        && (0..qp.b.len()).all(|e| qp.a[(e, j)] == 0.0)
        && (0..qp.h.len()).all(|i| !matches!(row_kind(qp, i, j), RowKind::Blocking))
}
