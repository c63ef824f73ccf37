//! Time derivative of a scheme's QP along the current motion, by central difference.
//!
//! With s the time offset, the motion is
//! `t + s`, `theta + s thetadot` and (acceleration level) `thetadot + s thetaddot`, and
//!
//! ```text
//! dQP/dt ~ (QP(+h) - QP(-h)) / (2h)          (error O(h^2) where the data are smooth)
//! ```
//!
//! for every field of [`Qp`] entrywise. The step is `h = FD_STEP / max(1, |thetadot|_inf)` at the
//! velocity level and `h = FD_STEP / max(1, |thetadot|_inf, |thetaddot|_inf)` at the
//! acceleration level, so neither t nor any joint coordinate moves by more than
//! `FD_STEP = 6e-6` (about eps^(1/3), which balances the O(h^2) truncation against the
//! O(eps/h) rounding error: ~1e-10 relative). Entries equal at both ends (constants, and
//! infinite bounds such as varpi = +inf, where the difference would be inf - inf = NaN) get
//! derivative exactly 0; an entry that is infinite at only one end also gets 0. Where the data
//! have a kink (the min/max of the merged joint bounds) the central difference returns the mean
//! of the two one-sided slopes — schemes with such kinks (jia2019, zhong2021) override
//! `build_dot` analytically.
//!
//! Nothing here allocates after [`QpDotScratch::new`].

use crate::qp::{Qp, QpDims};
use nalgebra::{Dim, Matrix, RawStorage, RawStorageMut, SVector};

use crate::scheme::{Level, Scheme};

/// Largest change of t and of any joint coordinate in a central-difference step (~eps^(1/3)).
pub const FD_STEP: f64 = 6e-6;

/// Preallocated QPs at the two ends of the central difference.
#[derive(Clone, Debug)]
pub struct QpDotScratch {
    /// The QP at the +h end of the difference (the velocity-level n-link ZNN scheme borrows its A
    /// as a Jacobian buffer).
    pub plus: Qp,
    /// The QP at the -h end of the difference.
    pub minus: Qp,
}

impl QpDotScratch {
    /// Two zero QPs of the given sizes (allocate once per run).
    pub fn new(dims: QpDims) -> Self {
        Self {
            plus: Qp::zeros(dims),
            minus: Qp::zeros(dims),
        }
    }
}

/// The default central-difference step for a state (see the module docs).
pub fn default_step<const N: usize>(
    level: Level,
    thetadot: &SVector<f64, N>,
    thetaddot: &SVector<f64, N>,
) -> f64 {
    let mut scale = 1.0_f64.max(thetadot.amax());
    if level == Level::Acceleration {
        scale = scale.max(thetaddot.amax());
    }
    if !scale.is_finite() {
        return FD_STEP;
    }
    FD_STEP / scale
}

/// dQP/dt by central difference with step `h` along the motion (see the module docs).
#[allow(clippy::too_many_arguments)]
pub fn central_difference<const N: usize, S: Scheme<N> + ?Sized>(
    scheme: &S,
    t: f64,
    theta: &SVector<f64, N>,
    thetadot: &SVector<f64, N>,
    thetaddot: &SVector<f64, N>,
    h: f64,
    qp_dot: &mut Qp,
    scratch: &mut QpDotScratch,
) {
    let accel = scheme.level() == Level::Acceleration;
    for (sign, qp) in [(1.0, &mut scratch.plus), (-1.0, &mut scratch.minus)] {
        let s = sign * h;
        let th = theta + thetadot * s;
        let thd = if accel {
            thetadot + thetaddot * s
        } else {
            *thetadot
        };
        scheme.build(t + s, &th, &thd, qp);
    }
    difference_quotient(&scratch.plus, &scratch.minus, 2.0 * h, qp_dot);
}

/// out = (plus - minus) / denom entrywise over every field, with the infinite-entry rule of
/// the module docs.
pub fn difference_quotient(plus: &Qp, minus: &Qp, denom: f64, out: &mut Qp) {
    let inv = 1.0 / denom;
    dq(&plus.p, &minus.p, inv, &mut out.p);
    dq(&plus.q, &minus.q, inv, &mut out.q);
    dq(&plus.a, &minus.a, inv, &mut out.a);
    dq(&plus.b, &minus.b, inv, &mut out.b);
    dq(&plus.g, &minus.g, inv, &mut out.g);
    dq(&plus.h, &minus.h, inv, &mut out.h);
    dq(&plus.lower, &minus.lower, inv, &mut out.lower);
    dq(&plus.upper, &minus.upper, inv, &mut out.upper);
}

fn dq<R: Dim, C: Dim, S1, S2, S3>(
    plus: &Matrix<f64, R, C, S1>,
    minus: &Matrix<f64, R, C, S2>,
    inv: f64,
    out: &mut Matrix<f64, R, C, S3>,
) where
    S1: RawStorage<f64, R, C>,
    S2: RawStorage<f64, R, C>,
    S3: RawStorageMut<f64, R, C>,
{
    assert_eq!(plus.shape(), out.shape(), "qp_dot has the wrong dimensions");
    assert_eq!(
        minus.shape(),
        out.shape(),
        "qp_dot has the wrong dimensions"
    );
    for ((o, &a), &b) in out.iter_mut().zip(plus.iter()).zip(minus.iter()) {
        *o = if a == b || !a.is_finite() || !b.is_finite() {
            0.0
        } else {
            (a - b) * inv
        };
    }
}
