//! Closed curves r*(t) = r_start + dr(phi(t)), phi = 2 pi sin^2(pi t / (2T)).
//!
//! Each shape gives dr, dr' = d dr / d phi and dr'' analytically; with size a (or r):
//!
//! - four-leaf clover: dr = a sin(2 phi) [cos phi, sin phi, 0] (polar rose rho = a sin 2phi);
//! - five-point star (5-cusp hypocycloid):
//!   dr = a [cos phi + cos(4 phi)/4 - 5/4, sin phi - sin(4 phi)/4, 0];
//! - butterfly: f = e^(cos phi) - 2 cos(4 phi) - sin^5(phi/12),
//!   dr = [a sin(phi) f, a (cos(phi) f - (e - 2)) + a (phi / 2 pi) / 32, 0]. The last term is the
//!   closing correction: as printed in the group's code (f(2 pi) = e - 2 - 1/32) the curve ends a/32
//!   below its start; [`CurveShape::ButterflyAsPrinted`] keeps the printed form for comparison;
//! - cardioid: dr = a (1 - cos phi) [cos phi, sin phi, 0] (starts at the cusp);
//! - circle: dr = r [cos phi - 1, sin phi, 0] (passes through the start point).
//!
//! The polar shapes use rho(phi) [cos phi, sin phi]: derivative [rho' c - rho s, rho' s + rho c],
//! second derivative [(rho'' - rho) c - 2 rho' s, (rho'' - rho) s + 2 rho' c].
//! Time derivatives follow by the chain rule: rdot = dr' phidot, rddot = dr'' phidot^2 + dr' phiddot.

use super::time_law::RestToRest;
use super::{Path, PathPoint};
use nalgebra::Vector3;
use std::f64::consts::{E, PI};

/// The shape of a closed curve dr(phi), phi in [0, 2 pi].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveShape {
    /// Four-petal rose a sin(2 phi) [cos phi, sin phi].
    FourLeafClover,
    /// Five-cusp hypocycloid (the group's "star").
    FivePointStar,
    /// The group's butterfly with the closing correction a (phi / 2 pi) / 32 in y.
    Butterfly,
    /// The butterfly exactly as the group's code prints it: misses closing by a/32 in y.
    ButterflyAsPrinted,
    /// Cardioid a (1 - cos phi) [cos phi, sin phi] from its cusp.
    Cardioid,
    /// Circle of radius r through the start point.
    Circle,
}

/// Planar offset and its first two phi-derivatives.
type Jet = [Vector3<f64>; 3];

/// rho [cos phi, sin phi] and its phi-derivatives from rho, rho', rho''.
fn polar(phi: f64, rho: [f64; 3]) -> Jet {
    let (s, c) = phi.sin_cos();
    let [p, dp, ddp] = rho;
    [
        Vector3::new(p * c, p * s, 0.0),
        Vector3::new(dp * c - p * s, dp * s + p * c, 0.0),
        Vector3::new(
            (ddp - p) * c - 2.0 * dp * s,
            (ddp - p) * s + 2.0 * dp * c,
            0.0,
        ),
    ]
}

/// The butterfly offset; `correct` adds the closing term a phi / (64 pi) to y.
fn butterfly(a: f64, phi: f64, correct: bool) -> Jet {
    let (s, c) = phi.sin_cos();
    let (s4, c4) = (4.0 * phi).sin_cos();
    let (q, cq) = (phi / 12.0).sin_cos();
    let ecos = c.exp();
    let q4 = q.powi(4);
    let f = ecos - 2.0 * c4 - q4 * q;
    let df = -s * ecos + 8.0 * s4 - (5.0 / 12.0) * q4 * cq;
    let ddf = (s * s - c) * ecos + 32.0 * c4 - (5.0 / 144.0) * (4.0 * q * q * q * cq * cq - q4 * q);
    let (shift, dshift) = if correct {
        (a * phi / (64.0 * PI), a / (64.0 * PI))
    } else {
        (0.0, 0.0)
    };
    [
        Vector3::new(a * s * f, a * (c * f - (E - 2.0)) + shift, 0.0),
        Vector3::new(a * (c * f + s * df), a * (c * df - s * f) + dshift, 0.0),
        Vector3::new(
            a * (s * ddf + 2.0 * c * df - s * f),
            a * (c * ddf - 2.0 * s * df - c * f),
            0.0,
        ),
    ]
}

impl CurveShape {
    /// dr(phi), dr'(phi), dr''(phi) for size `a` (the radius for the circle).
    pub fn offset(self, a: f64, phi: f64) -> [Vector3<f64>; 3] {
        match self {
            Self::FourLeafClover => {
                let (s2, c2) = (2.0 * phi).sin_cos();
                polar(phi, [a * s2, 2.0 * a * c2, -4.0 * a * s2])
            }
            Self::FivePointStar => {
                let (s, c) = phi.sin_cos();
                let (s4, c4) = (4.0 * phi).sin_cos();
                [
                    Vector3::new(a * (c + 0.25 * c4 - 1.25), a * (s - 0.25 * s4), 0.0),
                    Vector3::new(-a * (s + s4), a * (c - c4), 0.0),
                    Vector3::new(-a * (c + 4.0 * c4), a * (4.0 * s4 - s), 0.0),
                ]
            }
            Self::Butterfly => butterfly(a, phi, true),
            Self::ButterflyAsPrinted => butterfly(a, phi, false),
            Self::Cardioid => {
                let (s, c) = phi.sin_cos();
                polar(phi, [a * (1.0 - c), a * s, a * c])
            }
            Self::Circle => {
                let (s, c) = phi.sin_cos();
                [
                    Vector3::new(a * (c - 1.0), a * s, 0.0),
                    Vector3::new(-a * s, a * c, 0.0),
                    Vector3::new(-a * c, -a * s, 0.0),
                ]
            }
        }
    }
}

/// A closed curve r_start + dr(phi(t)) driven by the group's time law.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedCurve {
    shape: CurveShape,
    size: f64,
    start: Vector3<f64>,
    law: RestToRest,
}

impl ClosedCurve {
    /// `shape` of size `size` starting (and, except `ButterflyAsPrinted`, ending) at `start`,
    /// run in `duration` seconds. Arguments are validated by [`super::build_path`].
    pub fn new(shape: CurveShape, size: f64, start: Vector3<f64>, duration: f64) -> Self {
        Self {
            shape,
            size,
            start,
            law: RestToRest::new(duration),
        }
    }

    /// The shape.
    pub fn shape(&self) -> CurveShape {
        self.shape
    }

    /// The size (a, or r for the circle).
    pub fn size(&self) -> f64 {
        self.size
    }
}

impl Path for ClosedCurve {
    fn duration(&self) -> f64 {
        self.law.duration()
    }

    fn at(&self, t: f64) -> PathPoint {
        let phi = self.law.phi(t);
        let [d, d1, d2] = self.shape.offset(self.size, phi.s);
        PathPoint {
            r: self.start + d,
            rdot: d1 * phi.sdot,
            rddot: d2 * (phi.sdot * phi.sdot) + d1 * phi.sddot,
        }
    }
}
