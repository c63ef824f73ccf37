//! A closed path repeated: K cycles of a path of duration T run back to back, for the many-cycles
//! experiments (a repetitive task done again and again, as a robot does it).
//!
//! r*(t) = r*_inner(t - k T) for k = min(floor(t / T), K - 1), so the cyclic path lasts K T. The
//! papers' paths rest at both ends (s(0) = 0, s(T) = 1 with zero speed) and close
//! (r*(T) = r*(0)), so the repetition is continuous in r and rdot; rddot jumps at each k T
//! (from rddot*(T) to rddot*(0)), and those instants are breakpoints, with the inner path's own
//! breakpoints shifted into every cycle.

use super::{Path, PathPoint};

/// `cycles` repetitions of `inner` (see the module docs).
pub struct Cyclic {
    inner: Box<dyn Path>,
    cycles: usize,
    breakpoints: Vec<f64>,
}

impl Cyclic {
    /// `inner` repeated `cycles` (at least 1) times.
    pub fn new(inner: Box<dyn Path>, cycles: usize) -> Self {
        let cycles = cycles.max(1);
        let period = inner.duration();
        let mut breakpoints = Vec::new();
        for k in 0..cycles {
            let start = k as f64 * period;
            if k > 0 {
                breakpoints.push(start);
            }
            breakpoints.extend(inner.breakpoints().iter().map(|b| start + b));
        }
        Cyclic {
            inner,
            cycles,
            breakpoints,
        }
    }

    /// The inner path's duration T.
    pub fn period(&self) -> f64 {
        self.inner.duration()
    }
}

impl Path for Cyclic {
    fn duration(&self) -> f64 {
        self.cycles as f64 * self.inner.duration()
    }

    fn at(&self, t: f64) -> PathPoint {
        let period = self.inner.duration();
        let k = ((t / period).floor().max(0.0) as usize).min(self.cycles - 1);
        self.inner.at(t - k as f64 * period)
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }
}
