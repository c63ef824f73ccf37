//! A path travelled backwards: r_rev(t) = r*(T - t), rdot_rev(t) = -rdot*(T - t),
//! rddot_rev(t) = rddot*(T - t). For a closed path it starts and ends at the same point and
//! traces the same curve with the opposite orientation, which (to first order) flips the sign of
//! the joint drift a non-repetitive scheme accumulates: the check of a path's unknown direction.

use super::{Path, PathPoint};

/// `inner` travelled from t = T back to t = 0.
pub struct Reversed {
    inner: Box<dyn Path>,
    breakpoints: Vec<f64>,
}

impl Reversed {
    /// `inner` run backwards; its breakpoints b become T - b, still ascending.
    pub fn new(inner: Box<dyn Path>) -> Self {
        let t = inner.duration();
        let mut breakpoints: Vec<f64> = inner.breakpoints().iter().map(|b| t - b).collect();
        breakpoints.reverse();
        Self { inner, breakpoints }
    }
}

impl Path for Reversed {
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    fn at(&self, t: f64) -> PathPoint {
        let p = self.inner.at(self.inner.duration() - t);
        PathPoint {
            r: p.r,
            rdot: -p.rdot,
            rddot: p.rddot,
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
}
