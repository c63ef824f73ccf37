//! A scheme is a list of terms. Each term owns a block of the QP
//!
//! ```text
//! minimise    x'Px/2 + q'x          objective terms ADD into P and q
//! subject to  A x  = b              equality terms write their own rows
//!             G x <= h              inequality terms write their own rows
//!             l <= x <= u           limit terms INTERSECT the bounds (l = max, u = min)
//! ```
//!
//! and may declare extra variables appended after the joint command x[..n] (the infinity
//! norm's auxiliary s). The composed scheme ([`crate::composed::Composed`]) sizes the QP from
//! the terms' [`Footprint`]s once, gives each term its [`Slot`] (first extra variable, first
//! equality row, first inequality row), zeroes the QP (bounds to -inf/+inf) at every instant
//! and lets each term write in order: objective contributions are summed in list order, as
//! mink's `solve_ik` sums its tasks' (H, c) and stacks its limits' (G, h).
//!
//! The time derivative dQP/dt along the motion (the zeroing networks' Qdot, udot) is summed the
//! same way from each term's exact derivative ([`Term::write_dot`]); if any term of a scheme has
//! none ([`Term::has_dot`] false), the scheme takes the central difference of the whole QP
//! ([`crate::central_difference`]). Where several limit terms bound one variable the
//! derivative is that of the active one, and at a tie the right-hand derivative (the larger
//! slope for a lower bound, the smaller for an upper bound; [`DotOut::merge_lower`]).
//!
//! The terms, one a file (docs/schemes.md lists them with their equations):
//!
//! | term | level | adds |
//! |---|---|---|
//! | [`joint_norm`] (velocity-norm, acceleration-norm) | both | P[..n, ..n] += w I |
//! | [`repetitive`] | velocity | q += w g(theta); squared form also P += w I |
//! | [`drift_damping`] | acceleration | q += w sigma |
//! | [`torque_norm`] | acceleration | P += w H^2, q += w H'(c + g) |
//! | [`infinity_norm`] | velocity | variable s, P_ss += w, 2n rows of G, 0 <= s <= varpi |
//! | [`tracking`] | both | one row of A x = b per task axis (pose: 3 more, orientation) |
//! | [`bound_conversion`] | velocity | l, u from the joint-angle limits |
//! | [`velocity_limits`] | velocity | l, u from the joint-velocity limits |
//! | [`acceleration_limits`] | acceleration | l, u from the acceleration limit and the converted velocity limits |
//!
//! No term allocates when it writes: each keeps its scratch space from its construction.

use qp::Qp;

pub(crate) mod acceleration_limits;
pub(crate) mod bound_conversion;
pub(crate) mod drift_damping;
pub(crate) mod infinity_norm;
pub(crate) mod joint_norm;
pub(crate) mod repetitive;
pub(crate) mod torque_norm;
pub(crate) mod tracking;
pub(crate) mod velocity_limits;

/// What a term adds to the QP's sizes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Footprint {
    /// Extra variables appended after the joint command (and after earlier terms' extras).
    pub variables: usize,
    /// Equality rows of A x = b.
    pub equalities: usize,
    /// Inequality rows of G x <= h.
    pub inequalities: usize,
    /// Whether the term intersects the variable bounds l <= x <= u.
    pub bounds: bool,
}

/// Where a term's block starts in the composed QP.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Slot {
    /// Column of the term's first extra variable.
    pub variable: usize,
    /// The term's first equality row.
    pub equality: usize,
    /// The term's first inequality row.
    pub inequality: usize,
}

/// The arm's state at one instant: time, joint angles, rates and (for a derivative at the
/// acceleration level) accelerations; slices of length n (thetaddot empty where unused).
#[derive(Clone, Copy, Debug)]
pub struct State<'a> {
    /// Time t.
    pub t: f64,
    /// theta.
    pub theta: &'a [f64],
    /// thetadot (at the velocity level: the command whose motion a derivative follows).
    pub thetadot: &'a [f64],
    /// thetaddot (acceleration level, derivative only).
    pub thetaddot: &'a [f64],
}

/// Where a term writes its derivative: dQP/dt in `qp` and the QP's bounds at the instant in
/// `lower`, `upper` (limit terms merge into both, see [`DotOut::merge_lower`]).
pub struct DotOut<'a> {
    /// dQP/dt, zeroed before the first term writes.
    pub qp: &'a mut Qp,
    /// The lower bounds l of the terms merged so far (-inf at the start).
    pub lower: &'a mut [f64],
    /// The upper bounds u of the terms merged so far (+inf at the start).
    pub upper: &'a mut [f64],
}

impl DotOut<'_> {
    /// Merges a lower bound `value` with time derivative `slope` on variable `i`: l_i =
    /// max(l_i, value) and l_i' the slope of the larger; at a tie the larger slope (the
    /// right-hand derivative of the max).
    pub fn merge_lower(&mut self, i: usize, value: f64, slope: f64) {
        if value > self.lower[i] {
            self.lower[i] = value;
            self.qp.lower[i] = slope;
        } else if value == self.lower[i] {
            self.qp.lower[i] = self.qp.lower[i].max(slope);
        }
    }

    /// Merges an upper bound `value` with time derivative `slope` on variable `i`: u_i =
    /// min(u_i, value), at a tie the smaller slope.
    pub fn merge_upper(&mut self, i: usize, value: f64, slope: f64) {
        if value < self.upper[i] {
            self.upper[i] = value;
            self.qp.upper[i] = slope;
        } else if value == self.upper[i] {
            self.qp.upper[i] = self.qp.upper[i].min(slope);
        }
    }
}

/// One term of a scheme (module docs).
pub trait Term: Send + Sync {
    /// The term as a task card prints it: its kind, its parameters and what it writes, e.g.
    /// `velocity-norm (w=1): P[..n, ..n] += w I`.
    fn describe(&self) -> String;

    /// What the term adds to the QP's sizes (constant).
    fn footprint(&self) -> Footprint {
        Footprint::default()
    }

    /// Adds (objective), writes (rows) or intersects (bounds) the term's block of the QP at
    /// `state` (thetaddot unused) into `qp`, which the scheme zeroed. Must not allocate.
    fn write(&self, state: &State<'_>, slot: Slot, qp: &mut Qp);

    /// Whether [`Term::write_dot`] is the exact time derivative (false: the scheme takes the
    /// central difference of its whole QP).
    fn has_dot(&self) -> bool {
        false
    }

    /// Adds the time derivative of the term's block along the motion (see
    /// `scheme`) into `out`, which the scheme zeroed. Called only if
    /// [`Term::has_dot`]. Must not allocate.
    fn write_dot(&self, _state: &State<'_>, _slot: Slot, _out: &mut DotOut<'_>) {}

    /// The joint torque tau = H thetaddot + c + g into `tau` and true, for a term that carries
    /// a dynamics model; false otherwise.
    fn torque(
        &self,
        _theta: &[f64],
        _thetadot: &[f64],
        _thetaddot: &[f64],
        _tau: &mut [f64],
    ) -> bool {
        false
    }
}
