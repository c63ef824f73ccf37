//! The rest-to-rest time law of the group's code.
//!
//! s(t) = sin^2(pi t / (2T)) on [0, T], hence
//! sdot(t) = (pi / (2T)) sin(pi t / T) and sddot(t) = (pi^2 / (2T^2)) cos(pi t / T).
//! s runs 0 -> 1 with sdot(0) = sdot(T) = 0. The curve parameter is phi = 2 pi s, i.e.
//! phi(t) = 2 pi sin^2(pi t / (2T)), phidot = (pi^2 / T) sin(pi t / T), phiddot = (pi^3 / T^2) cos(pi t / T).
//! Outside [0, T] the law rests: s = 0 before, s = 1 after, sdot = sddot = 0.

use std::f64::consts::PI;

/// A scalar and its first two time derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fraction {
    /// Value.
    pub s: f64,
    /// First time derivative.
    pub sdot: f64,
    /// Second time derivative.
    pub sddot: f64,
}

impl Fraction {
    /// The fraction multiplied by a constant `k` (value and both derivatives).
    pub fn scaled(self, k: f64) -> Self {
        Self {
            s: k * self.s,
            sdot: k * self.sdot,
            sddot: k * self.sddot,
        }
    }
}

/// The sin^2 rest-to-rest law over a duration T > 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestToRest {
    duration: f64,
}

impl RestToRest {
    /// The law over `duration` (must be positive; checked by the constructors that use it).
    pub fn new(duration: f64) -> Self {
        Self { duration }
    }

    /// Duration T.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// s(t), sdot(t), sddot(t); rest (s = 0 or 1, zero derivatives) outside [0, T].
    pub fn fraction(&self, t: f64) -> Fraction {
        let big_t = self.duration;
        if t < 0.0 {
            return Fraction {
                s: 0.0,
                sdot: 0.0,
                sddot: 0.0,
            };
        }
        if t > big_t {
            return Fraction {
                s: 1.0,
                sdot: 0.0,
                sddot: 0.0,
            };
        }
        let half = (PI * t / (2.0 * big_t)).sin();
        let w = PI / big_t;
        Fraction {
            s: half * half,
            sdot: 0.5 * w * (w * t).sin(),
            sddot: 0.5 * w * w * (w * t).cos(),
        }
    }

    /// phi(t) = 2 pi s(t) with phidot, phiddot (the group's time law).
    pub fn phi(&self, t: f64) -> Fraction {
        self.fraction(t).scaled(2.0 * PI)
    }
}
