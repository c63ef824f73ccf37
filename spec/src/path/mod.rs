//! Paths as data: the serde-readable description of a desired path, the table of path names
//! with their default sizes and durations, and the checks of its fields. The engine builds the
//! path (`schemes::paths::build_path`: each figure's r*(t), rdot*(t), rddot*(t)).
//!
//! | name | built as | default scale (m) | provenance of the scale | T in docs/paths.md (s) |
//! |---|---|---|---|---|
//! | `four-leaf-clover` | `CurveShape::FourLeafClover`, a | 0.15 | assumed | 5 |
//! | `five-point-star` | `CurveShape::FivePointStar`, a | 0.08 | group's code | 5 |
//! | `star-lines` | `GlobalPolyline::pentagram`, R | 0.08 | assumed | 5 |
//! | `ping` | `PING` strokes, box size s | 0.15 | assumed | 15 |
//! | `dai` | `DAI` strokes, box size s | 0.15 | assumed | 15 |
//! | `butterfly` | `CurveShape::Butterfly` (closing correction), a | 0.035 | group's code | 8 |
//! | `butterfly-as-printed` | `CurveShape::ButterflyAsPrinted` (ends a/32 short in y), a | 0.035 | group's code | 8 |
//! | `cardioid` | `CurveShape::Cardioid`, a | 0.05 | assumed | 8 |
//! | `triangle` | `StrokePath::triangle`, side | 0.1 | paper | 9 |
//! | `circle` | `CurveShape::Circle`, r | 0.05 | paper | 9 |
//!
//! `scale`, when given, replaces the default size (a, R, s, side or r).
//!
//! **Bounds** ([`PathSpec::validate`]): `duration` within [[`MIN_DURATION`], [`MAX_DURATION`]]
//! = [1e-3, 1e5] s and the size (the default or `scale`, the figure's only length: every
//! point of it is a multiple of the size from the start point) within (0, [`crate::MAX_OFFSET`]]
//! = (0, 10] m, the bound of an experiment's tool and base offsets. Every experiment of the
//! papers is well inside (5 to 15 s; 0.035 to 0.2 m); past them the path's velocity and
//! acceleration (r*/T, r*/T^2) overflow or dwarf the arm's, and an implicit integrator can
//! spend its time in one step, where its step limit and budgets are not checked.
//!
//! **Pose** (the papers do not state where or how the figure is drawn; these make it a sweepable
//! parameter). With every field at its default the figure lies in the base x-y plane through
//! the start point, starts where its definition starts, and the path is built exactly as
//! without these fields.
//! - `rotation`, `tilt_x`, `tilt_y` (rad): offsets from the start point are mapped by
//!   R = Ry(tilt_y) Rx(tilt_x) Rz(rotation), so the drawing plane has normal R e_z (see
//!   `schemes::paths::pose`); applies to every path.
//! - `phase` (fraction of the cycle in [0, 1)): the tip starts a fraction `phase` further along
//!   the closed figure, dr_p(phi) = dr(phi + 2 pi phase) - dr(2 pi phase) for the closed curves
//!   (`ClosedCurve::with_phase`), the arc-length shift of the tour for `star-lines`
//!   (`schemes::paths::shift_closed_loop`); the start (and end) point is unchanged,
//!   the curve is placed differently around it. Not defined (an error) for the stroke paths
//!   and `butterfly-as-printed`.
//!
//! `reverse` is applied last (it commutes with the pose).

mod error;
mod names;

pub use error::PathError;
pub use names::PATH_NAMES;

/// The shortest path duration accepted (s): a millisecond, a step of the papers' fixed-step
/// loops.
pub const MIN_DURATION: f64 = 1e-3;

/// The longest path duration accepted (s): about a day.
pub const MAX_DURATION: f64 = 1e5;

/// A path as experiment files describe it.
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct PathSpec {
    /// One of [`PATH_NAMES`].
    pub name: String,
    /// Task duration T in seconds.
    pub duration: f64,
    /// Size override (a, R, s, side or r in metres); `None` uses [`default_scale`].
    #[serde(default)]
    pub scale: Option<f64>,
    /// Travel the path backwards (same curve, opposite orientation; `schemes::paths::Reversed`).
    #[serde(default)]
    pub reverse: bool,
    /// In-plane rotation (rad) of the figure about the plane normal (e_z before tilting).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rotation: f64,
    /// Tilt (rad) of the drawing plane about the base x axis (applied after `rotation`).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub tilt_x: f64,
    /// Tilt (rad) of the drawing plane about the base y axis (applied last):
    /// R = Ry(tilt_y) Rx(tilt_x) Rz(rotation), plane normal R e_z; the default plane is the
    /// base x-y plane.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub tilt_y: f64,
    /// Where on a closed figure the tip starts, as a fraction of the cycle in [0, 1).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub phase: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl PathSpec {
    /// The path `name` run in `duration` seconds at its default size, pose and direction.
    pub fn new(name: impl Into<String>, duration: f64) -> Self {
        Self {
            name: name.into(),
            duration,
            scale: None,
            reverse: false,
            rotation: 0.0,
            tilt_x: 0.0,
            tilt_y: 0.0,
            phase: 0.0,
        }
    }

    /// Checks the fields (errors name the offending one and its range): a known `name`, a
    /// `duration` within [[`MIN_DURATION`], [`MAX_DURATION`]] s, a size (`scale`, or the
    /// name's default) within (0, [`crate::MAX_OFFSET`]] m, finite `rotation`, `tilt_x` and
    /// `tilt_y`, a `phase` in [0, 1) and zero for a path without a cycle to shift
    /// ([`phase_supported`]).
    pub fn validate(&self) -> Result<(), PathError> {
        if default_scale(&self.name).is_none() {
            return Err(PathError::UnknownName(self.name.clone()));
        }
        if !(MIN_DURATION..=MAX_DURATION).contains(&self.duration) {
            return Err(PathError::DurationOutOfRange(self.duration));
        }
        let size = self.size();
        if !(size > 0.0 && size <= crate::MAX_OFFSET) {
            return Err(PathError::ScaleOutOfRange(size));
        }
        for (field, value) in [
            ("rotation", self.rotation),
            ("tilt_x", self.tilt_x),
            ("tilt_y", self.tilt_y),
        ] {
            if !value.is_finite() {
                return Err(PathError::NonFinitePose { field, value });
            }
        }
        if !(0.0..1.0).contains(&self.phase) {
            return Err(PathError::PhaseOutOfRange(self.phase));
        }
        if self.phase != 0.0 && !phase_supported(&self.name) {
            return Err(PathError::PhaseNotSupported(self.name.clone()));
        }
        Ok(())
    }

    /// The figure's size: `scale`, else the name's [`default_scale`] (NaN for an unknown name).
    pub fn size(&self) -> f64 {
        self.scale
            .or_else(|| default_scale(&self.name))
            .unwrap_or(f64::NAN)
    }

    /// Whether `rotation`, `tilt_x` and `tilt_y` are all zero (no pose wrapper is built).
    pub fn is_unrotated(&self) -> bool {
        self.rotation == 0.0 && self.tilt_x == 0.0 && self.tilt_y == 0.0
    }
}

/// (name, default scale, provenance of the scale, duration in docs/paths.md), in
/// [`PATH_NAMES`] order.
const TABLE: [(&str, f64, &str, f64); 10] = [
    ("four-leaf-clover", 0.15, "assumed", 5.0),
    ("five-point-star", 0.08, "group's code", 5.0),
    ("star-lines", 0.08, "assumed", 5.0),
    ("ping", 0.15, "assumed", 15.0),
    ("dai", 0.15, "assumed", 15.0),
    ("butterfly", 0.035, "group's code", 8.0),
    ("butterfly-as-printed", 0.035, "group's code", 8.0),
    ("cardioid", 0.05, "assumed", 8.0),
    ("triangle", 0.1, "paper", 9.0),
    ("circle", 0.05, "paper", 9.0),
];

fn entry(name: &str) -> Option<&'static (&'static str, f64, &'static str, f64)> {
    TABLE.iter().find(|e| e.0 == name)
}

/// The size docs/paths.md gives the path (a, R, s, side or r in metres), `None` for an unknown name.
pub fn default_scale(name: &str) -> Option<f64> {
    entry(name).map(|e| e.1)
}

/// Where the default size comes from: `"assumed"` (a free parameter of the reproduction, to be
/// swept), `"group's code"` or `"paper"`; `None` for an unknown name.
pub fn scale_provenance(name: &str) -> Option<&'static str> {
    entry(name).map(|e| e.2)
}

/// The duration T docs/paths.md lists for the path, `None` for an unknown name.
pub fn default_duration(name: &str) -> Option<f64> {
    entry(name).map(|e| e.3)
}

/// Whether a non-zero `phase` is accepted for the path `name`: the closed figures (not the
/// stroke paths ping, dai, triangle, nor the butterfly as printed, which does not close).
pub fn phase_supported(name: &str) -> bool {
    !matches!(name, "ping" | "dai" | "triangle" | "butterfly-as-printed")
}

/// The path at one instant: r*(t) and its first two derivatives (what a task card shows).
#[derive(Clone, Debug, PartialEq)]
pub struct PathSample {
    /// The instant t (s).
    pub t: f64,
    /// Desired position r*(t) (m).
    pub r: [f64; 3],
    /// Desired velocity rdot*(t) (m/s).
    pub rdot: [f64; 3],
    /// Desired acceleration rddot*(t) (m/s^2).
    pub rddot: [f64; 3],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_has_a_size_a_duration_and_a_provenance() {
        for name in PATH_NAMES {
            let spec = PathSpec::new(*name, default_duration(name).expect("listed"));
            assert_eq!(spec.validate(), Ok(()), "{name}");
            assert_eq!(spec.size(), default_scale(name).expect("listed"));
            assert!(scale_provenance(name).is_some(), "{name}");
        }
        assert_eq!(TABLE.len(), PATH_NAMES.len());
    }

    #[test]
    fn each_check_names_its_field() {
        let ok = PathSpec::new("circle", 9.0);
        let with = |f: &dyn Fn(&mut PathSpec)| {
            let mut s = ok.clone();
            f(&mut s);
            s.validate().unwrap_err()
        };
        assert!(matches!(
            with(&|s| s.name = "spiral".into()),
            PathError::UnknownName(_)
        ));
        assert!(matches!(
            with(&|s| s.duration = 0.0),
            PathError::DurationOutOfRange(_)
        ));
        assert!(matches!(
            with(&|s| s.scale = Some(f64::NAN)),
            PathError::ScaleOutOfRange(_)
        ));
        assert!(matches!(
            with(&|s| s.tilt_x = f64::INFINITY),
            PathError::NonFinitePose {
                field: "tilt_x",
                ..
            }
        ));
        assert!(matches!(
            with(&|s| s.phase = 1.0),
            PathError::PhaseOutOfRange(_)
        ));
        let triangle = PathSpec {
            phase: 0.5,
            ..PathSpec::new("triangle", 9.0)
        };
        assert!(matches!(
            triangle.validate(),
            Err(PathError::PhaseNotSupported(_))
        ));
        let mut phased = ok.clone();
        phased.phase = 0.5;
        assert_eq!(
            phased.validate(),
            Ok(()),
            "a closed curve may start elsewhere"
        );
    }

    #[test]
    fn duration_and_size_are_bounded_at_both_ends() {
        let ok = PathSpec::new("circle", 9.0);
        let with = |f: &dyn Fn(&mut PathSpec)| {
            let mut s = ok.clone();
            f(&mut s);
            s.validate()
        };
        // The ends are accepted.
        for d in [MIN_DURATION, MAX_DURATION] {
            assert_eq!(with(&|s| s.duration = d), Ok(()), "{d}");
        }
        assert_eq!(with(&|s| s.scale = Some(crate::MAX_OFFSET)), Ok(()));
        assert_eq!(with(&|s| s.scale = Some(1e-9)), Ok(()));
        // Past them (the red team's 1e-300 s and 1e308 m hung a run inside one BDF step).
        for d in [
            1e-300,
            0.999e-3,
            1.0001e5,
            1e300,
            0.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let err = with(&|s| s.duration = d).unwrap_err();
            assert!(
                matches!(err, PathError::DurationOutOfRange(x) if x.to_bits() == d.to_bits()),
                "{d}: {err:?}"
            );
            let msg = err.to_string();
            assert!(
                msg.contains("path `duration`") && msg.contains("[0.001, 100000] s"),
                "{msg}"
            );
        }
        for sc in [1e308, 10.000001, 0.0, -0.1, f64::NAN, f64::INFINITY] {
            let err = with(&|s| s.scale = Some(sc)).unwrap_err();
            assert!(
                matches!(err, PathError::ScaleOutOfRange(x) if x.to_bits() == sc.to_bits()),
                "{sc}: {err:?}"
            );
            let msg = err.to_string();
            assert!(
                msg.contains("path `scale`") && msg.contains("(0, 10] m"),
                "{msg}"
            );
        }
        // Extreme values are written with an exponent, not 300 digits.
        let msg = with(&|s| s.duration = 1e-300).unwrap_err().to_string();
        assert!(msg.ends_with("got 1e-300"), "{msg}");
        let msg = with(&|s| s.scale = Some(1e308)).unwrap_err().to_string();
        assert!(msg.ends_with("got 1e308"), "{msg}");
        // Every default duration and size is inside.
        for name in PATH_NAMES {
            let d = default_duration(name).expect("listed");
            let sc = default_scale(name).expect("listed");
            assert!((MIN_DURATION..=MAX_DURATION).contains(&d), "{name}");
            assert!(sc > 0.0 && sc <= crate::MAX_OFFSET, "{name}");
        }
    }
}
