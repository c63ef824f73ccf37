//! Tests of the desired paths (docs/paths.md): closure, rest at both ends, analytic
//! derivatives against finite differences, corner behaviour, segment timing, construction errors.

use nalgebra::Vector3;
use schemes::paths::{
    build_path, ClosedCurve, CurveShape, GlobalPolyline, Path, PathPoint, StrokePath, DAI, PING,
};
use spec::{default_duration, default_scale, scale_provenance, PathError, PathSpec, PATH_NAMES};
use std::f64::consts::PI;

fn start() -> Vector3<f64> {
    Vector3::new(0.31, -0.22, 0.47)
}

fn spec(name: &str) -> PathSpec {
    PathSpec::new(name, default_duration(name).unwrap())
}

/// The one path that does not end where it starts (the group's butterfly as printed).
const OPEN: &str = "butterfly-as-printed";

fn all_paths() -> Vec<(&'static str, Box<dyn Path>)> {
    PATH_NAMES
        .iter()
        .map(|&n| (n, build_path(&spec(n), start()).unwrap()))
        .collect()
}

/// Interior sample times, skipping those within `guard` of a breakpoint.
fn samples(path: &dyn Path, count: usize, guard: f64) -> Vec<f64> {
    let big_t = path.duration();
    (1..count)
        .map(|i| big_t * (i as f64 + 0.37) / (count as f64 + 1.0))
        .filter(|t| path.breakpoints().iter().all(|b| (t - b).abs() > guard))
        .collect()
}

#[test]
fn every_path_starts_at_start_and_closes() {
    for (name, p) in all_paths() {
        let r0 = p.at(0.0).r;
        let r_t = p.at(p.duration()).r;
        assert!((r0 - start()).norm() < 1e-15, "{name}: r(0) = {r0}");
        if name == OPEN {
            continue;
        }
        assert!(
            (r_t - r0).norm() < 1e-12,
            "{name}: r(T) - r(0) = {}",
            r_t - r0
        );
    }
}

#[test]
fn every_path_rests_at_both_ends() {
    for (name, p) in all_paths() {
        for t in [0.0, p.duration()] {
            let v = p.at(t).rdot.norm();
            assert!(v < 1e-14, "{name}: |rdot({t})| = {v}");
        }
    }
}

#[test]
fn outside_the_interval_paths_rest_at_their_end_points() {
    for (name, p) in all_paths() {
        for (t, end) in [(-1.0, 0.0), (p.duration() + 1.0, p.duration())] {
            let q = p.at(t);
            assert_eq!(q.r, p.at(end).r, "{name} at t = {t}");
            assert_eq!(q.rdot, Vector3::zeros(), "{name} at t = {t}");
            assert_eq!(q.rddot, Vector3::zeros(), "{name} at t = {t}");
        }
    }
}

#[test]
fn derivatives_match_central_differences() {
    for (name, p) in all_paths() {
        assert_derivatives_match(name, p.as_ref());
    }
}

/// rdot and rddot of `p` against central differences of r and rdot at interior samples.
fn assert_derivatives_match(name: &str, p: &dyn Path) {
    let h = 1e-5;
    {
        let ts = samples(p, 400, 3.0 * h);
        assert!(ts.len() > 300, "{name}: too few samples");
        for t in ts {
            let (minus, plus, here) = (p.at(t - h), p.at(t + h), p.at(t));
            let v_fd = (plus.r - minus.r) / (2.0 * h);
            let a_fd = (plus.rdot - minus.rdot) / (2.0 * h);
            assert!(
                (v_fd - here.rdot).norm() < 1e-7 * (1.0 + here.rdot.norm()),
                "{name} t = {t}: rdot {} vs fd {}",
                here.rdot,
                v_fd
            );
            assert!(
                (a_fd - here.rddot).norm() < 1e-6 * (1.0 + here.rddot.norm()),
                "{name} t = {t}: rddot {} vs fd {}",
                here.rddot,
                a_fd
            );
        }
    }
}

#[test]
fn curve_offsets_match_phi_differences_and_vanish_at_zero() {
    let shapes = [
        CurveShape::FourLeafClover,
        CurveShape::FivePointStar,
        CurveShape::Butterfly,
        CurveShape::ButterflyAsPrinted,
        CurveShape::Cardioid,
        CurveShape::Circle,
    ];
    let h = 1e-6;
    for shape in shapes {
        assert!(
            shape.offset(0.1, 0.0)[0].norm() < 1e-16,
            "{shape:?}: dr(0) != 0"
        );
        for i in 0..200 {
            let phi = 2.0 * PI * (i as f64 + 0.5) / 200.0;
            let [_, d1, d2] = shape.offset(0.1, phi);
            let [m, m1, _] = shape.offset(0.1, phi - h);
            let [p, p1, _] = shape.offset(0.1, phi + h);
            assert!(
                ((p - m) / (2.0 * h) - d1).norm() < 1e-8,
                "{shape:?} dr' at {phi}"
            );
            assert!(
                ((p1 - m1) / (2.0 * h) - d2).norm() < 1e-7,
                "{shape:?} dr'' at {phi}"
            );
        }
    }
}

#[test]
fn time_law_runs_phi_from_zero_to_two_pi() {
    let c = ClosedCurve::new(CurveShape::Circle, 0.05, start(), 9.0);
    // Half way phi = pi: the circle r [cos phi - 1, sin phi] is at its far side, 2r from the start.
    let mid = c.at(4.5);
    assert!((mid.r - start() - Vector3::new(-0.1, 0.0, 0.0)).norm() < 1e-15);
    // Peak phidot = pi^2 / T at T/2 and |dr'| = r, so the speed there is r pi^2 / T.
    assert!((mid.rdot.norm() - 0.05 * PI * PI / 9.0).abs() < 1e-15);
    // rddot(0) = dr'(0) phiddot(0) = r [0, 1, 0] pi^3 / T^2.
    let a0 = c.at(0.0).rddot;
    assert!((a0 - Vector3::new(0.0, 0.05 * PI.powi(3) / 81.0, 0.0)).norm() < 1e-15);
}

#[test]
fn butterfly_closes_only_with_the_correction() {
    let a = default_scale("butterfly").unwrap();
    let printed = ClosedCurve::new(CurveShape::ButterflyAsPrinted, a, start(), 8.0);
    let miss = printed.at(8.0).r - printed.at(0.0).r;
    assert!(
        (miss - Vector3::new(0.0, -a / 32.0, 0.0)).norm() < 1e-14,
        "miss = {miss}"
    );
    let corrected = ClosedCurve::new(CurveShape::Butterfly, a, start(), 8.0);
    assert!((corrected.at(8.0).r - corrected.at(0.0).r).norm() < 1e-12);
}

#[test]
fn paths_are_planar() {
    for (name, p) in all_paths() {
        for i in 0..=1000 {
            let q = p.at(p.duration() * i as f64 / 1000.0);
            assert_eq!(q.r.z, start().z, "{name}");
            assert_eq!(q.rdot.z, 0.0, "{name}");
            assert_eq!(q.rddot.z, 0.0, "{name}");
        }
    }
}

#[test]
fn stroke_paths_rest_at_every_corner() {
    for name in ["ping", "dai", "triangle"] {
        let p = build_path(&spec(name), start()).unwrap();
        assert!(!p.breakpoints().is_empty(), "{name}: no corners");
        for &b in p.breakpoints() {
            for t in [b - 1e-9, b, b + 1e-9] {
                let v = p.at(t).rdot.norm();
                assert!(v < 1e-8, "{name}: |rdot| = {v} near corner {b}");
            }
            assert!((p.at(b + 1e-12).r - p.at(b - 1e-12).r).norm() < 1e-12);
        }
    }
}

#[test]
fn stroke_durations_are_proportional_to_length() {
    let big_t = 15.0;
    for (name, ch) in [("ping", PING), ("dai", DAI)] {
        let p = ch.path(start(), 0.15, big_t).unwrap();
        let total: f64 = p.segments().iter().map(|s| s.length).sum();
        let sum_durations: f64 = p.segments().iter().map(|s| s.duration()).sum();
        assert!((sum_durations - big_t).abs() < 1e-12, "{name}");
        let peak = 0.5 * PI * total / big_t;
        for s in p.segments() {
            assert!(
                (s.duration() - big_t * s.length / total).abs() < 1e-12,
                "{name}"
            );
            // Same peak speed on every segment, reached at its middle.
            let v = p.at(s.start_time + 0.5 * s.duration()).rdot.norm();
            assert!((v - peak).abs() < 1e-12, "{name}: peak {v} vs {peak}");
        }
        // Repeated tour points would give zero-length segments; none are kept.
        assert!(p.segments().iter().all(|s| s.length > 0.0));
        assert_eq!(p.segments().len(), ch.tour.len() - 1, "{name}");
    }
}

#[test]
fn character_tours_are_closed_and_mapped_from_the_first_point() {
    for ch in [PING, DAI] {
        assert_eq!(ch.tour.first(), ch.tour.last());
        let pts = ch.tour_points(start(), 0.15);
        assert_eq!(pts[0], start());
        // Unit-box x right / y up map to base x / y.
        let p0 = ch.point(ch.tour[0]).unwrap();
        for (name, p) in ch.tour.iter().zip(&pts) {
            let u = ch.point(name).unwrap();
            let expect = start() + 0.15 * Vector3::new(u[0] - p0[0], u[1] - p0[1], 0.0);
            assert!((p - expect).norm() < 1e-15);
        }
        // Every defined point is visited.
        for (name, _) in ch.points {
            assert!(ch.tour.contains(name), "point {name} is never visited");
        }
    }
}

#[test]
fn triangle_has_three_seconds_per_side() {
    let tri = StrokePath::triangle(start(), 0.1, 9.0).unwrap();
    assert_eq!(tri.segments().len(), 3);
    for (k, s) in tri.segments().iter().enumerate() {
        assert!((s.duration() - 3.0).abs() < 1e-12);
        assert!((s.start_time - 3.0 * k as f64).abs() < 1e-12);
        assert!((s.length - 0.1).abs() < 1e-15);
    }
    let apex = tri.at(3.0).r - start();
    assert!((apex - Vector3::new(0.05, 0.05 * 3f64.sqrt(), 0.0)).norm() < 1e-15);
    assert!((tri.at(6.0).r - start() - Vector3::new(0.1, 0.0, 0.0)).norm() < 1e-15);
    let built = build_path(&spec("triangle"), start()).unwrap();
    assert_eq!(built.breakpoints().len(), 2);
    assert!((built.breakpoints()[0] - 3.0).abs() < 1e-12);
    assert!((built.breakpoints()[1] - 6.0).abs() < 1e-12);
}

#[test]
fn zero_length_segments_are_skipped() {
    let a = start();
    let b = a + Vector3::new(0.1, 0.0, 0.0);
    let c = a + Vector3::new(0.0, 0.1, 0.0);
    let clean = StrokePath::new(&[a, b, c, a], 6.0).unwrap();
    let repeated = StrokePath::new(&[a, a, b, b, b, c, a, a], 6.0).unwrap();
    assert_eq!(clean, repeated);
    let g_clean = GlobalPolyline::new(&[a, b, c, a], 6.0).unwrap();
    let g_repeated = GlobalPolyline::new(&[a, b, b, c, c, a], 6.0).unwrap();
    assert_eq!(g_clean, g_repeated);
    for t in [0.0, 1.3, 2.0, 4.4, 6.0] {
        let (p, q) = (repeated.at(t), g_repeated.at(t));
        assert!(p
            .r
            .iter()
            .chain(p.rdot.iter())
            .chain(p.rddot.iter())
            .all(|x| x.is_finite()));
        assert!(q
            .r
            .iter()
            .chain(q.rdot.iter())
            .chain(q.rddot.iter())
            .all(|x| x.is_finite()));
    }
    assert_eq!(
        StrokePath::new(&[a, a, a], 1.0),
        Err(PathError::DegeneratePolyline)
    );
    assert_eq!(
        GlobalPolyline::new(&[a], 1.0),
        Err(PathError::DegeneratePolyline)
    );
}

#[test]
fn star_lines_is_the_pentagram_with_one_global_law() {
    let r = 0.08;
    let big_t = 5.0;
    let star = GlobalPolyline::pentagram(start(), r, big_t).unwrap();
    // Five equal chords 2 R sin(2 pi / 5).
    let chord = 2.0 * r * (2.0 * PI / 5.0).sin();
    assert!((star.length() - 5.0 * chord).abs() < 1e-14);
    let centre = start() - Vector3::new(0.0, r, 0.0);
    let order = [2usize, 4, 1, 3];
    assert_eq!(star.breakpoints().len(), 4);
    for (k, (&b, &v)) in star.breakpoints().iter().zip(&order).enumerate() {
        // Corner k + 1 is reached when phi = 2 pi (k + 1) / 5.
        let s = (PI * b / (2.0 * big_t)).sin().powi(2);
        assert!((s - (k as f64 + 1.0) / 5.0).abs() < 1e-14);
        let (sn, cs) = (2.0 * PI * v as f64 / 5.0).sin_cos();
        let vertex = centre + r * Vector3::new(sn, cs, 0.0);
        assert!((star.at(b).r - vertex).norm() < 1e-14, "vertex V{v}");
        // Passed at speed: the speed is continuous, the direction jumps.
        let (before, after) = (star.at(b - 1e-9).rdot, star.at(b + 1e-9).rdot);
        assert!((before.norm() - after.norm()).abs() < 1e-6);
        assert!(before.norm() > 0.01);
        assert!((before - after).norm() > 0.01);
    }
    // Speed is L phidot / 2 pi everywhere.
    for t in [0.3, 1.7, 2.5, 4.1] {
        let v = star.at(t).rdot.norm();
        assert!((v - star.length() * PI / (2.0 * big_t) * (PI * t / big_t).sin()).abs() < 1e-14);
    }
}

#[test]
fn scale_overrides_the_default_size() {
    let mut s = spec("circle");
    s.scale = Some(0.1);
    let p = build_path(&s, start()).unwrap();
    assert!(((p.at(4.5).r - start()).norm() - 0.2).abs() < 1e-15);
    let mut s = spec("triangle");
    s.scale = Some(0.18);
    let p = build_path(&s, start()).unwrap();
    assert!((p.at(6.0).r - start() - Vector3::new(0.18, 0.0, 0.0)).norm() < 1e-15);
}

#[test]
fn every_name_has_a_size_provenance_and_duration() {
    for &n in PATH_NAMES {
        assert!(default_scale(n).unwrap() > 0.0);
        assert!(default_duration(n).unwrap() > 0.0);
        assert!(["assumed", "group's code", "paper"].contains(&scale_provenance(n).unwrap()));
    }
    assert_eq!(default_scale("five-point-star"), Some(0.08));
    assert_eq!(scale_provenance("five-point-star"), Some("group's code"));
    assert_eq!(scale_provenance("four-leaf-clover"), Some("assumed"));
    assert_eq!(scale_provenance("circle"), Some("paper"));
    assert_eq!(default_scale("spiral"), None);
    assert_eq!(scale_provenance("spiral"), None);
}

#[test]
fn bad_specs_are_rejected_naming_the_field() {
    let bad_name = PathSpec::new("spiral", 5.0);
    let err = build_path(&bad_name, start()).err().unwrap();
    assert_eq!(err, PathError::UnknownName("spiral".into()));
    let msg = err.to_string();
    assert!(msg.contains("name") && msg.contains("spiral"));
    for n in PATH_NAMES {
        assert!(msg.contains(n), "message lacks {n}: {msg}");
    }
    for d in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300, 1e6] {
        let mut s = spec("circle");
        s.duration = d;
        let err = build_path(&s, start()).err().unwrap();
        assert!(matches!(err, PathError::DurationOutOfRange(_)));
        assert!(err.to_string().contains("duration"));
    }
    for sc in [0.0, -0.1, f64::NAN, 1e308, 10.5] {
        let mut s = spec("ping");
        s.scale = Some(sc);
        let err = build_path(&s, start()).err().unwrap();
        assert!(matches!(err, PathError::ScaleOutOfRange(_)));
        assert!(err.to_string().contains("scale"));
    }
    let nan_start = Vector3::new(f64::NAN, 0.0, 0.0);
    assert_eq!(
        build_path(&spec("circle"), nan_start).err(),
        Some(PathError::NonFinitePoint)
    );
    let boxed: Box<dyn std::error::Error> = Box::new(err);
    assert!(boxed.to_string().contains("spiral"));
}

#[test]
fn path_spec_reads_from_toml() {
    let s: PathSpec = toml::from_str("name = \"dai\"\nduration = 15.0\n").unwrap();
    assert_eq!(s, PathSpec::new("dai", 15.0));
    let s: PathSpec = toml::from_str("name = \"circle\"\nduration = 9.0\nscale = 0.1\n").unwrap();
    assert_eq!(s.scale, Some(0.1));
    assert!(
        toml::from_str::<PathSpec>("name = \"circle\"\nduration = 9.0\nsclae = 0.1\n").is_err()
    );
}

#[test]
fn a_reversed_path_is_the_same_curve_travelled_backwards() {
    for name in PATH_NAMES {
        let fwd = build_path(&spec(name), start()).unwrap();
        let rev = build_path(
            &PathSpec {
                reverse: true,
                ..spec(name)
            },
            start(),
        )
        .unwrap();
        let t_end = fwd.duration();
        assert!(
            (rev.at(0.0).r - fwd.at(t_end).r).norm() < 1e-15
                && (rev.at(t_end).r - start()).norm() < 1e-15,
            "{name}"
        );
        if *name != OPEN {
            assert!((rev.at(0.0).r - start()).norm() < 1e-12, "{name}");
        }
        for k in 1..50 {
            let t = t_end * k as f64 / 50.0;
            let (f, r) = (fwd.at(t_end - t), rev.at(t));
            assert!(
                (f.r - r.r).norm() < 1e-15
                    && (f.rdot + r.rdot).norm() < 1e-15
                    && (f.rddot - r.rddot).norm() < 1e-15,
                "{name} at {t}"
            );
        }
        let expected: Vec<f64> = fwd.breakpoints().iter().rev().map(|b| t_end - b).collect();
        assert_eq!(rev.breakpoints(), expected.as_slice(), "{name}");
    }
}

// ---- pose: rotation, tilt and phase -------------------------------------------------------

/// Paths a non-zero `phase` applies to (closed curves and star-lines).
const PHASEABLE: [&str; 6] = [
    "four-leaf-clover",
    "five-point-star",
    "star-lines",
    "butterfly",
    "cardioid",
    "circle",
];

/// R = Ry(ty) Rx(tx) Rz(rz), written out (independently of the crate's construction).
fn rotation_matrix(rz: f64, tx: f64, ty: f64) -> nalgebra::Matrix3<f64> {
    let (sz, cz) = rz.sin_cos();
    let (sx, cx) = tx.sin_cos();
    let (sy, cy) = ty.sin_cos();
    let z = nalgebra::Matrix3::new(cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0);
    let x = nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx);
    let y = nalgebra::Matrix3::new(cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy);
    y * x * z
}

fn posed(name: &str, rotation: f64, tilt_x: f64, tilt_y: f64, phase: f64) -> PathSpec {
    PathSpec {
        rotation,
        tilt_x,
        tilt_y,
        phase,
        ..spec(name)
    }
}

/// (rotation, tilt_x, tilt_y, phase) combinations; phase only for [`PHASEABLE`] names.
fn poses(name: &str) -> Vec<(f64, f64, f64, f64)> {
    let mut v = vec![
        (0.7, 0.0, 0.0, 0.0),
        (0.0, 0.4, -0.3, 0.0),
        (-2.1, 1.1, 0.6, 0.0),
    ];
    if PHASEABLE.contains(&name) {
        v.extend([(0.0, 0.0, 0.0, 0.37), (0.7, 0.4, -0.3, 0.81)]);
    }
    v
}

#[test]
fn posed_paths_keep_the_path_properties() {
    for &name in PATH_NAMES {
        for (rz, tx, ty, ph) in poses(name) {
            let label = format!("{name} pose ({rz}, {tx}, {ty}, phase {ph})");
            let p = build_path(&posed(name, rz, tx, ty, ph), start()).unwrap();
            let big_t = p.duration();
            assert!((p.at(0.0).r - start()).norm() < 1e-15, "{label}: r(0)");
            if name != OPEN {
                assert!((p.at(big_t).r - start()).norm() < 1e-12, "{label}: r(T)");
            }
            for t in [0.0, big_t] {
                assert!(p.at(t).rdot.norm() < 1e-14, "{label}: rdot({t})");
            }
            for (t, end) in [(-1.0, 0.0), (big_t + 1.0, big_t)] {
                let q = p.at(t);
                assert_eq!(q.r, p.at(end).r, "{label} at t = {t}");
                assert_eq!(q.rdot, Vector3::zeros(), "{label} at t = {t}");
                assert_eq!(q.rddot, Vector3::zeros(), "{label} at t = {t}");
            }
            assert_derivatives_match(&label, p.as_ref());
        }
    }
}

#[test]
fn rotation_and_tilt_map_offsets_by_r_and_keep_distances() {
    for &name in PATH_NAMES {
        let flat = build_path(&spec(name), start()).unwrap();
        for (rz, tx, ty) in [(0.7, 0.0, 0.0), (0.0, 0.4, -0.3), (-2.1, 1.1, 0.6)] {
            let rot = rotation_matrix(rz, tx, ty);
            let normal = rot * Vector3::z();
            let p = build_path(&posed(name, rz, tx, ty, 0.0), start()).unwrap();
            assert_eq!(p.breakpoints(), flat.breakpoints(), "{name}");
            for i in 0..=200 {
                let t = p.duration() * i as f64 / 200.0;
                let (q, f) = (p.at(t), flat.at(t));
                let (d, df) = (q.r - start(), f.r - start());
                // Distances from the start point and speeds are preserved.
                assert!((d.norm() - df.norm()).abs() < 1e-15, "{name} t = {t}");
                assert!(
                    (q.rdot.norm() - f.rdot.norm()).abs() < 1e-14,
                    "{name} t = {t}"
                );
                // The offsets (and velocity, acceleration) are R times the flat ones ...
                assert!((d - rot * df).norm() < 1e-15, "{name} t = {t}");
                assert!((q.rdot - rot * f.rdot).norm() < 1e-14, "{name} t = {t}");
                assert!((q.rddot - rot * f.rddot).norm() < 1e-13, "{name} t = {t}");
                // ... hence orthogonal to the plane normal R e_z.
                assert!(d.dot(&normal).abs() < 1e-15, "{name} t = {t}");
                assert!(q.rdot.dot(&normal).abs() < 1e-14, "{name} t = {t}");
                assert!(q.rddot.dot(&normal).abs() < 1e-13, "{name} t = {t}");
            }
        }
    }
    // A tilt takes the figure out of the base x-y plane: z moves.
    let tilted = build_path(&posed("circle", 0.0, 0.0, 0.5, 0.0), start()).unwrap();
    assert!((tilted.at(4.5).r.z - start().z).abs() > 0.01);
    // The crate's R is the documented one.
    let r = schemes::paths::pose_rotation(-2.1, 1.1, 0.6);
    assert!((r - rotation_matrix(-2.1, 1.1, 0.6)).amax() < 1e-15);
}

#[test]
fn default_pose_reproduces_the_path_exactly() {
    for &name in PATH_NAMES {
        let plain = build_path(&spec(name), start()).unwrap();
        let zeros = build_path(&posed(name, 0.0, -0.0, 0.0, 0.0), start()).unwrap();
        assert_eq!(plain.breakpoints(), zeros.breakpoints(), "{name}");
        for i in 0..=300 {
            let t = plain.duration() * i as f64 / 300.0;
            let (a, b): (PathPoint, PathPoint) = (plain.at(t), zeros.at(t));
            assert_eq!(a, b, "{name} at {t}");
        }
    }
    let c = ClosedCurve::new(CurveShape::Butterfly, 0.035, start(), 8.0);
    assert_eq!(c.clone().with_phase(0.0).unwrap(), c);
    let g = GlobalPolyline::pentagram(start(), 0.08, 5.0).unwrap();
    let g0 = GlobalPolyline::pentagram_with_phase(start(), 0.08, 5.0, 0.0).unwrap();
    assert_eq!(g, g0);
}

/// The time at which the sin^2 law has covered the fraction `s` of the cycle.
fn time_of_fraction(s: f64, big_t: f64) -> f64 {
    2.0 * big_t / PI * s.sqrt().asin()
}

#[test]
fn a_phased_path_is_the_path_started_later_minus_its_offset() {
    for name in PHASEABLE {
        let plain = build_path(&spec(name), start()).unwrap();
        let big_t = plain.duration();
        for phase in [0.1, 0.25, 0.6] {
            let p = build_path(&posed(name, 0.0, 0.0, 0.0, phase), start()).unwrap();
            let offset = plain.at(time_of_fraction(phase, big_t)).r - start();
            for i in 0..=100 {
                let t = big_t * i as f64 / 100.0;
                let s = (PI * t / (2.0 * big_t)).sin().powi(2);
                let later = plain.at(time_of_fraction((s + phase) % 1.0, big_t)).r;
                let want = later - offset;
                assert!(
                    (p.at(t).r - want).norm() < 1e-9,
                    "{name} phase {phase} t = {t}: {} vs {want}",
                    p.at(t).r
                );
            }
        }
    }
}

#[test]
fn a_quarter_phase_circle_starts_a_quarter_turn_later() {
    let (r, big_t) = (0.05, 9.0);
    let p = build_path(&posed("circle", 0.0, 0.0, 0.0, 0.25), start()).unwrap();
    assert!(p.breakpoints().is_empty());
    for i in 0..=90 {
        let t = big_t * i as f64 / 90.0;
        let phi = 2.0 * PI * (PI * t / (2.0 * big_t)).sin().powi(2);
        let phidot = PI * PI / big_t * (PI * t / big_t).sin();
        // dr(phi + pi/2) - dr(pi/2) with dr = r [cos - 1, sin]: r [-sin phi, cos phi - 1].
        let want = start() + r * Vector3::new(-phi.sin(), phi.cos() - 1.0, 0.0);
        let want_v = r * phidot * Vector3::new(-phi.cos(), -phi.sin(), 0.0);
        let q = p.at(t);
        assert!((q.r - want).norm() < 1e-15, "t = {t}: {} vs {want}", q.r);
        assert!((q.rdot - want_v).norm() < 1e-14, "t = {t}");
    }
    // The unphased circle goes -x first, the quarter-phased one -y first (centre below).
    assert!((p.at(4.5).r - start() - Vector3::new(0.0, -0.1, 0.0)).norm() < 1e-15);
}

#[test]
fn phased_butterfly_and_star_lines_report_their_new_corners() {
    let b = build_path(&posed("butterfly", 0.0, 0.0, 0.0, 0.3), start()).unwrap();
    assert_eq!(b.breakpoints().len(), 1);
    let tb = b.breakpoints()[0];
    // There phi = 2 pi (1 - 0.3): the tip passes the original start point ...
    let a = default_scale("butterfly").unwrap();
    let back = ClosedCurve::new(CurveShape::Butterfly, a, start(), 8.0)
        .at(time_of_fraction(0.3, 8.0))
        .r;
    assert!((b.at(tb).r - (2.0 * start() - back)).norm() < 1e-12);
    // ... where the butterfly's tangent is not periodic: the velocity jumps.
    assert!((b.at(tb - 1e-9).rdot - b.at(tb + 1e-9).rdot).norm() > 1e-4);
    // star-lines from inside its first chord: V0 becomes a fifth corner.
    let s = build_path(&posed("star-lines", 0.0, 0.0, 0.0, 0.1), start()).unwrap();
    assert_eq!(s.breakpoints().len(), 5);
    let unphased_corners = build_path(&spec("star-lines"), start()).unwrap();
    assert_eq!(unphased_corners.breakpoints().len(), 4);
}

#[test]
fn butterfly_as_printed_misses_closing_by_a_32nd() {
    assert!(PATH_NAMES.contains(&OPEN));
    assert_eq!(default_scale(OPEN), Some(0.035));
    assert_eq!(scale_provenance(OPEN), Some("group's code"));
    assert_eq!(default_duration(OPEN), Some(8.0));
    let a = 0.035;
    let p = build_path(&spec(OPEN), start()).unwrap();
    let miss = p.at(8.0).r - p.at(0.0).r;
    assert!(
        (miss - Vector3::new(0.0, -a / 32.0, 0.0)).norm() < 1e-14,
        "miss = {miss}"
    );
    // Until the end it is the corrected butterfly minus a (phi / 2 pi) / 32 in y.
    let corrected = build_path(&spec("butterfly"), start()).unwrap();
    for t in [1.0, 3.3, 6.1] {
        let s = (PI * t / 16.0).sin().powi(2);
        let d = corrected.at(t).r - p.at(t).r;
        assert!(
            (d - Vector3::new(0.0, a * s / 32.0, 0.0)).norm() < 1e-15,
            "t = {t}"
        );
    }
}

#[test]
fn bad_poses_are_rejected_naming_the_field() {
    for name in ["ping", "dai", "triangle", OPEN] {
        let err = build_path(&posed(name, 0.0, 0.0, 0.0, 0.5), start())
            .err()
            .unwrap();
        assert_eq!(err, PathError::PhaseNotSupported(name.into()));
        let msg = err.to_string();
        assert!(msg.contains("`phase`") && msg.contains(name), "{msg}");
        // Rotation and tilt apply to them.
        assert!(build_path(&posed(name, 0.3, 0.2, 0.1, 0.0), start()).is_ok());
    }
    for phase in [1.0, -0.1, 1.5, f64::NAN, f64::INFINITY] {
        let err = build_path(&posed("circle", 0.0, 0.0, 0.0, phase), start())
            .err()
            .unwrap();
        assert!(matches!(err, PathError::PhaseOutOfRange(_)), "{err:?}");
        assert!(err.to_string().contains("`phase`"));
    }
    for (field, spec) in [
        ("rotation", posed("circle", f64::NAN, 0.0, 0.0, 0.0)),
        ("tilt_x", posed("ping", 0.0, f64::INFINITY, 0.0, 0.0)),
        (
            "tilt_y",
            posed("star-lines", 0.0, 0.0, f64::NEG_INFINITY, 0.0),
        ),
    ] {
        let err = build_path(&spec, start()).err().unwrap();
        assert!(
            matches!(err, PathError::NonFinitePose { field: f, .. } if f == field),
            "{err:?}"
        );
        assert!(err.to_string().contains(&format!("`{field}`")));
    }
}

#[test]
fn pose_fields_read_from_toml_and_are_left_out_at_their_defaults() {
    let s: PathSpec = toml::from_str(
        "name = \"circle\"\nduration = 9.0\nrotation = 0.5\ntilt_x = 0.1\ntilt_y = -0.2\nphase = 0.25\n",
    )
    .unwrap();
    assert_eq!(s, posed("circle", 0.5, 0.1, -0.2, 0.25));
    assert_eq!(
        toml::from_str::<PathSpec>(&toml::to_string(&s).unwrap()).unwrap(),
        s
    );
    let plain = toml::to_string(&spec("circle")).unwrap();
    for field in ["rotation", "tilt_x", "tilt_y", "phase"] {
        assert!(!plain.contains(field), "{plain}");
    }
    assert!(
        toml::from_str::<PathSpec>("name = \"circle\"\nduration = 9.0\ntilt_z = 0.1\n").is_err()
    );
}
