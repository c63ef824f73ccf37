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
//!
//! **Phase** ([`ClosedCurve::with_phase`]). A phase p in [0, 1) starts the tip a fraction p of the
//! cycle further along the same closed curve, keeping the start point fixed (the placement of the
//! curve relative to the start point): with phi0 = 2 pi p,
//! dr_p(phi) = dr(w(phi + phi0)) - dr(phi0), w(psi) = psi - 2 pi if psi >= 2 pi, else psi,
//! so dr_p(0) = 0 = dr_p(2 pi) and the derivatives are dr'(w(phi + phi0)), dr''(w(phi + phi0)).
//! For the periodic shapes (clover, star, cardioid, circle) the wrap w changes nothing
//! (dr(psi - 2 pi) = dr(psi)) and dr_p is as smooth as dr. The butterfly is closed
//! (dr(2 pi) = dr(0)) but its tangent is not periodic (sin^5(phi/12) and the closing term are
//! not): phased, it passes its original start point with a velocity jump, reported as a
//! breakpoint at the instant phi(t) = 2 pi (1 - p), t = (2T / pi) asin(sqrt(1 - p)). The
//! as-printed butterfly does not close, so it has no phase. p = 0 is the unphased curve itself
//! (no shift is applied at all).

use super::time_law::RestToRest;
use super::{Path, PathPoint};
use nalgebra::Vector3;
use spec::PathError;
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
    /// Whether dr and its phi-derivatives are 2 pi-periodic (the curve closes smoothly, so any
    /// point of it can be the start without a corner).
    pub fn is_periodic(self) -> bool {
        !matches!(self, Self::Butterfly | Self::ButterflyAsPrinted)
    }

    /// Whether dr(2 pi) = dr(0) (the curve ends where it starts).
    pub fn is_closed(self) -> bool {
        self != Self::ButterflyAsPrinted
    }

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

/// The start shift of a phased curve: phi0 = 2 pi p and the offset dr(phi0) it subtracts.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PhaseShift {
    phi0: f64,
    offset0: Vector3<f64>,
}

/// A closed curve r_start + dr(phi(t)) driven by the group's time law.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedCurve {
    shape: CurveShape,
    size: f64,
    start: Vector3<f64>,
    law: RestToRest,
    /// `None`: the curve from phi = 0 (computed exactly as without a phase).
    phase: Option<PhaseShift>,
    /// The wrap instant of a phased non-periodic curve (empty otherwise).
    breakpoints: Vec<f64>,
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
            phase: None,
            breakpoints: Vec::new(),
        }
    }

    /// The same curve started a fraction `phase` of the cycle later (see the module docs):
    /// dr_p(phi) = dr(w(phi + 2 pi phase)) - dr(2 pi phase). `phase` = 0 returns the curve
    /// unchanged. Errors if `phase` is not in [0, 1) or the shape does not close
    /// ([`CurveShape::ButterflyAsPrinted`]).
    pub fn with_phase(mut self, phase: f64) -> Result<Self, PathError> {
        if !(0.0..1.0).contains(&phase) {
            return Err(PathError::PhaseOutOfRange(phase));
        }
        if !self.shape.is_closed() {
            return Err(PathError::PhaseNotSupported(format!("{:?}", self.shape)));
        }
        if phase == 0.0 {
            self.phase = None;
            self.breakpoints.clear();
            return Ok(self);
        }
        let phi0 = 2.0 * PI * phase;
        self.phase = Some(PhaseShift {
            phi0,
            offset0: self.shape.offset(self.size, phi0)[0],
        });
        self.breakpoints = if self.shape.is_periodic() {
            Vec::new()
        } else {
            let big_t = self.law.duration();
            vec![2.0 * big_t / PI * (1.0 - phase).sqrt().asin()]
        };
        Ok(self)
    }

    /// The phase p (0 for an unphased curve).
    pub fn phase(&self) -> f64 {
        self.phase.map_or(0.0, |p| p.phi0 / (2.0 * PI))
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
        let [d, d1, d2] = match self.phase {
            None => self.shape.offset(self.size, phi.s),
            Some(PhaseShift { phi0, offset0 }) => {
                let mut psi = phi.s + phi0;
                if psi >= 2.0 * PI {
                    psi -= 2.0 * PI;
                }
                let [d, d1, d2] = self.shape.offset(self.size, psi);
                [d - offset0, d1, d2]
            }
        };
        PathPoint {
            r: self.start + d,
            rdot: d1 * phi.sdot,
            rddot: d2 * (phi.sdot * phi.sdot) + d1 * phi.sddot,
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
}
