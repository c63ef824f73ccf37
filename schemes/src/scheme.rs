//! The common interface of the papers' schemes: at every instant a scheme turns
//! (t, theta, thetadot) into one QP (see [`qp::Qp`]) whose decision variable x starts with
//! the joint command: x[..n] is thetadot (velocity level) or thetaddot (acceleration level).
//! The joint count n is a run-time value ([`Scheme::joints`]): theta, thetadot and thetaddot are
//! slices of length n, and every scheme keeps what it needs between calls in scratch space
//! allocated when it is built, so that no call allocates.
//!
//! Besides the QP itself a scheme provides its time derivative along the current motion
//! ([`Scheme::build_dot`]), which the zeroing networks (FP/VP-CDNN, VP-RNN-PF, kong2019's
//! finite-time network) need for their Qdot y and udot terms: with the arm at (theta, thetadot)
//! and the command thetadot (velocity level) or thetaddot (acceleration level),
//!
//! ```text
//! dQP/dt = d/ds QP(t + s, theta + s thetadot, thetadot + s thetaddot) at s = 0
//! ```
//!
//! (at the velocity level the thetadot argument of `build` is unused, so only theta moves). Its
//! default is the central difference of [`qp::difference_quotient`] along that motion
//! ([`central_difference`] with the step [`default_step`]).

use qp::{Qp, QpDims};
use spec::Level;

use qp::{difference_quotient, QpDotScratch, FD_STEP};

/// A redundancy-resolution scheme: QP(t, theta, thetadot).
pub trait Scheme: Send + Sync {
    /// Name as the paper writes it (e.g. `VLTCO`, `MVN-INVM`, `HL-JDF`).
    fn name(&self) -> String;
    /// Whether x[..n] is thetadot (velocity level) or thetaddot (acceleration level).
    fn level(&self) -> Level;
    /// QP sizes (constant along a run).
    fn dims(&self) -> QpDims;
    /// The number of joints n: the length of every joint slice below.
    fn joints(&self) -> usize;
    /// Overwrite `qp` with the QP at (t, theta, thetadot). `thetadot` is ignored at the
    /// velocity level. Must not allocate.
    fn build(&self, t: f64, theta: &[f64], thetadot: &[f64], qp: &mut Qp);

    /// Overwrite `qp_dot` with the time derivative of every QP field (p, q, a, b, g, h, lower,
    /// upper) along the current motion (see the module docs): theta moves at `thetadot`, and at
    /// the acceleration level thetadot moves at `thetaddot` (ignored at the velocity level).
    /// Entries that are infinite (absent bounds, varpi = +inf) get derivative 0.
    ///
    /// Default: central difference [`central_difference`] with the step [`default_step`];
    /// schemes override it with analytic derivatives where cheap.
    /// Does not allocate (`scratch` comes from [`Scheme::new_dot_scratch`]).
    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        thetaddot: &[f64],
        qp_dot: &mut Qp,
        scratch: &mut QpDotScratch,
    ) {
        let h = default_step(self.level(), thetadot, thetaddot);
        central_difference(self, t, theta, thetadot, thetaddot, h, qp_dot, scratch);
    }

    /// Writes the joint torque tau = H(theta) thetaddot + c(theta, thetadot) + g(theta) into
    /// `tau` and returns true, for schemes that carry a dynamics model (zhang2018); false
    /// otherwise (`tau` untouched). Must not allocate.
    fn torque(
        &self,
        _theta: &[f64],
        _thetadot: &[f64],
        _thetaddot: &[f64],
        _tau: &mut [f64],
    ) -> bool {
        false
    }

    /// The scheme's QP term by term, one line per term (what it adds and where), for task
    /// cards; empty for a scheme that is not composed of terms.
    fn terms(&self) -> Vec<String> {
        Vec::new()
    }

    /// A zero QP of this scheme's sizes (allocate once per run, then `build` into it).
    fn new_qp(&self) -> Qp {
        Qp::zeros(self.dims())
    }

    /// Scratch space for [`Scheme::build_dot`] (allocate once per run).
    fn new_dot_scratch(&self) -> QpDotScratch {
        QpDotScratch::new(self.dims(), self.joints())
    }
}

/// The largest magnitude of `v` (0 for an empty slice).
fn amax(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
}

/// The default central-difference step for a state (see [`qp::difference_quotient`]).
pub fn default_step(level: Level, thetadot: &[f64], thetaddot: &[f64]) -> f64 {
    let mut scale = 1.0_f64.max(amax(thetadot));
    if level == Level::Acceleration {
        scale = scale.max(amax(thetaddot));
    }
    if !scale.is_finite() {
        return FD_STEP;
    }
    FD_STEP / scale
}

/// dQP/dt by central difference with step `h` along the motion (see [`qp::difference_quotient`]).
#[allow(clippy::too_many_arguments)]
pub fn central_difference<S: Scheme + ?Sized>(
    scheme: &S,
    t: f64,
    theta: &[f64],
    thetadot: &[f64],
    thetaddot: &[f64],
    h: f64,
    qp_dot: &mut Qp,
    scratch: &mut QpDotScratch,
) {
    let accel = scheme.level() == Level::Acceleration;
    let QpDotScratch {
        plus,
        minus,
        theta: th,
        thetadot: thd,
    } = scratch;
    for (sign, qp) in [(1.0, &mut *plus), (-1.0, &mut *minus)] {
        let s = sign * h;
        for (i, x) in th.iter_mut().enumerate() {
            *x = theta[i] + thetadot[i] * s;
        }
        for (i, x) in thd.iter_mut().enumerate() {
            *x = if accel {
                thetadot[i] + thetaddot[i] * s
            } else {
                thetadot[i]
            };
        }
        scheme.build(t + s, th, thd, qp);
    }
    difference_quotient(plus, minus, 2.0 * h, qp_dot);
}
