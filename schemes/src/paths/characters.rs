//! The Chinese characters "ping" (平) and "dai" (呆) as stroke tours (proposal; docs/paths.md).
//!
//! Each character is a set of named points in a unit box (x right, y up) and a closed tour through
//! them (pen down throughout, retracing strokes where needed). A tour point p maps to the base
//! frame as r_start + s [p.x - p0.x, p.y - p0.y, 0], with p0 the tour's first point and s the box
//! size, and is drawn as a [`StrokePath`] (rest-to-rest per segment, durations proportional to
//! length).

use super::stroke::StrokePath;
use nalgebra::Vector3;
use spec::PathError;

/// A character: named points in the unit box and a closed tour through them by name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Character {
    /// Named points (x right, y up) in the unit box.
    pub points: &'static [(&'static str, [f64; 2])],
    /// The tour, by point name; starts and ends at the same point.
    pub tour: &'static [&'static str],
}

/// 平: top bar A-B, two dots P1-E1 and P2-E2 hanging from it, middle bar G-H, vertical C-J.
pub const PING: Character = Character {
    points: &[
        ("C", [0.5, 0.9]),
        ("A", [0.15, 0.9]),
        ("B", [0.85, 0.9]),
        ("P1", [0.32, 0.9]),
        ("E1", [0.40, 0.62]),
        ("P2", [0.68, 0.9]),
        ("E2", [0.60, 0.62]),
        ("I", [0.5, 0.45]),
        ("G", [0.0, 0.45]),
        ("H", [1.0, 0.45]),
        ("J", [0.5, 0.0]),
    ],
    tour: &[
        "C", "P1", "E1", "P1", "A", "C", "P2", "E2", "P2", "B", "C", "I", "G", "H", "I", "J", "I",
        "C",
    ],
};

/// 呆: the box Q1-Q2-Q3-Q4 (口) above the tree 木 (bar G-H, legs M-Lf and M-Rf, trunk K-J).
pub const DAI: Character = Character {
    points: &[
        ("K", [0.5, 0.6]),
        ("Q1", [0.25, 0.6]),
        ("Q2", [0.25, 1.0]),
        ("Q3", [0.75, 1.0]),
        ("Q4", [0.75, 0.6]),
        ("M", [0.5, 0.42]),
        ("G", [0.0, 0.42]),
        ("H", [1.0, 0.42]),
        ("Lf", [0.1, 0.05]),
        ("Rf", [0.9, 0.05]),
        ("J", [0.5, 0.0]),
    ],
    tour: &[
        "K", "Q1", "Q2", "Q3", "Q4", "K", "M", "G", "H", "M", "Lf", "M", "Rf", "M", "J", "M", "K",
    ],
};

impl Character {
    /// The unit-box coordinates of the named point, if it is defined.
    pub fn point(&self, name: &str) -> Option<[f64; 2]> {
        self.points
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, p)| p)
    }

    /// The tour mapped to the base x-y plane: first point at `start`, box size `size`.
    ///
    /// # Panics
    /// If the tour names an undefined point (a defect of the constant tables, caught by tests).
    pub fn tour_points(&self, start: Vector3<f64>, size: f64) -> Vec<Vector3<f64>> {
        let unit = |name: &str| {
            self.point(name)
                .unwrap_or_else(|| panic!("character tour names undefined point {name}"))
        };
        let p0 = unit(self.tour[0]);
        self.tour
            .iter()
            .map(|name| {
                let p = unit(name);
                start + size * Vector3::new(p[0] - p0[0], p[1] - p0[1], 0.0)
            })
            .collect()
    }

    /// The character drawn as a stroke path of box size `size` in `duration` seconds.
    pub fn path(
        &self,
        start: Vector3<f64>,
        size: f64,
        duration: f64,
    ) -> Result<StrokePath, PathError> {
        StrokePath::new(&self.tour_points(start, size), duration)
    }
}
