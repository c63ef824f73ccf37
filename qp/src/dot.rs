//! dQP/dt by central difference: the quotient and its scratch space ([`difference_quotient`]
//! states the mathematics).

use crate::{Qp, QpDims};
use nalgebra::{Dim, Matrix, RawStorage, RawStorageMut};

/// Largest change of t and of any joint coordinate in a central-difference step (~eps^(1/3)).
pub const FD_STEP: f64 = 6e-6;

/// Preallocated QPs at the two ends of the central difference.
#[derive(Clone, Debug)]
pub struct QpDotScratch {
    /// The QP at the +h end of the difference (the velocity-level schemes borrow its A as a
    /// Jacobian buffer).
    pub plus: Qp,
    /// The QP at the -h end of the difference.
    pub minus: Qp,
    /// The joint angles at either end.
    pub theta: Vec<f64>,
    /// The joint rates at either end.
    pub thetadot: Vec<f64>,
}

impl QpDotScratch {
    /// Two zero QPs of the given sizes and two joint vectors of `joints` entries (allocate once
    /// per run).
    pub fn new(dims: QpDims, joints: usize) -> Self {
        Self {
            plus: Qp::zeros(dims),
            minus: Qp::zeros(dims),
            theta: vec![0.0; joints],
            thetadot: vec![0.0; joints],
        }
    }
}

/// out = (plus - minus) / denom entrywise over every field, the quotient of dQP/dt:
///
/// With s the time offset, the motion is
/// `t + s`, `theta + s thetadot` and (acceleration level) `thetadot + s thetaddot`, and
///
/// ```text
/// dQP/dt ~ (QP(+h) - QP(-h)) / (2h)          (error O(h^2) where the data are smooth)
/// ```
///
/// for every field of [`Qp`] entrywise. The step is `h = FD_STEP / max(1, |thetadot|_inf)` at the
/// velocity level and `h = FD_STEP / max(1, |thetadot|_inf, |thetaddot|_inf)` at the
/// acceleration level, so neither t nor any joint coordinate moves by more than
/// `FD_STEP = 6e-6` (about eps^(1/3), which balances the O(h^2) truncation against the
/// O(eps/h) rounding error: ~1e-10 relative). Entries equal at both ends (constants, and
/// infinite bounds such as varpi = +inf, where the difference would be inf - inf = NaN) get
/// derivative exactly 0; an entry that is infinite at only one end also gets 0. Where the data
/// have a kink (the min/max of the merged joint bounds) the central difference returns the mean
/// of the two one-sided slopes — schemes with such kinks (jia2019, zhong2021) override
/// `build_dot` analytically.
///
/// The step and the difference along a scheme's motion are the scheme's (`schemes::default_step`,
/// `schemes::central_difference`), the default of `Scheme::build_dot`. Nothing here
/// allocates after [`QpDotScratch::new`].
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
