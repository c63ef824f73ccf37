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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paths::build_path;
    use nalgebra::Vector3;
    use spec::PathSpec;

    #[test]
    fn the_cycles_repeat_the_path() {
        let once = || build_path(&PathSpec::new("star-lines", 5.0), Vector3::zeros()).unwrap();
        let inner = once();
        let cyclic = Cyclic::new(once(), 3);
        assert_eq!(cyclic.duration(), 15.0);
        assert_eq!(cyclic.period(), 5.0);
        for t in [0.0, 0.7, 2.5, 4.9] {
            for k in 0..3 {
                let (a, b) = (cyclic.at(t + 5.0 * k as f64), inner.at(t));
                let d = (a.r - b.r).norm() + (a.rdot - b.rdot).norm() + (a.rddot - b.rddot).norm();
                assert!(d < 1e-9, "t = {t}, cycle {k}: {d:e}");
            }
        }
        assert_eq!(cyclic.at(15.0), inner.at(5.0));
        let n = inner.breakpoints().len();
        assert_eq!(cyclic.breakpoints().len(), 3 * n + 2);
        assert!(cyclic.breakpoints().windows(2).all(|w| w[0] < w[1]));
    }
}
