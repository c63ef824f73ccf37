//! Tests of the desired paths (shared/spec/paths.md): closure, rest at both ends, analytic
//! derivatives against finite differences, corner behaviour, segment timing, construction errors.

use nalgebra::Vector3;
use schemes::paths::{
    build_path, default_duration, default_scale, scale_provenance, ClosedCurve, CurveShape,
    GlobalPolyline, Path, PathError, PathSpec, StrokePath, DAI, PATH_NAMES, PING,
};
use std::f64::consts::PI;

fn start() -> Vector3<f64> {
    Vector3::new(0.31, -0.22, 0.47)
}

fn spec(name: &str) -> PathSpec {
    PathSpec {
        name: name.to_string(),
        duration: default_duration(name).unwrap(),
        scale: None,
        reverse: false,
    }
}

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
    let h = 1e-5;
    for (name, p) in all_paths() {
        let ts = samples(p.as_ref(), 400, 3.0 * h);
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
    let bad_name = PathSpec {
        name: "spiral".into(),
        duration: 5.0,
        scale: None,
        reverse: false,
    };
    let err = build_path(&bad_name, start()).err().unwrap();
    assert_eq!(err, PathError::UnknownName("spiral".into()));
    let msg = err.to_string();
    assert!(msg.contains("name") && msg.contains("spiral"));
    for n in PATH_NAMES {
        assert!(msg.contains(n), "message lacks {n}: {msg}");
    }
    for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let mut s = spec("circle");
        s.duration = d;
        let err = build_path(&s, start()).err().unwrap();
        assert!(matches!(err, PathError::NonPositiveDuration(_)));
        assert!(err.to_string().contains("duration"));
    }
    for sc in [0.0, -0.1, f64::NAN] {
        let mut s = spec("ping");
        s.scale = Some(sc);
        let err = build_path(&s, start()).err().unwrap();
        assert!(matches!(err, PathError::NonPositiveScale(_)));
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
    assert_eq!(
        s,
        PathSpec {
            name: "dai".into(),
            duration: 15.0,
            scale: None,
            reverse: false,
        }
    );
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
            (rev.at(0.0).r - start()).norm() < 1e-12 && (rev.at(t_end).r - start()).norm() < 1e-12,
            "{name}"
        );
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
