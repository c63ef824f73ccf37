//! Jaco2 kinematics: check values of `docs/robots.md`, an independent DH transcription, the
//! Jacobian and its time derivative against finite differences, and the joint limits.

use crate::common;

use common::*;
use nalgebra::{Matrix4, Rotation3, SVector, Vector3};
use robots::{Jaco2, Robot, JACO2, JACO2_PEN, JACO2_PEN_EXP2};
use robots::{JACO2_EXP2_WRIST, JACO2_PEN_WRIST};

fn theta0() -> SVector<f64, 6> {
    SVector::from([1.675, 2.79, -3.216, 4.187, -1.71, -2.95])
}

fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < tol, "{what}: got {got:?}, want {want:?}");
    }
}

#[test]
fn names() {
    assert_eq!(Jaco2::pen().name(), JACO2_PEN);
    assert_eq!(Jaco2::kinova().name(), JACO2);
    assert_eq!(JACO2_PEN, "jaco2-pen");
    assert_eq!(JACO2, "jaco2");
    assert_eq!(Jaco2::pen_exp2().name(), JACO2_PEN_EXP2);
    assert_eq!(JACO2_PEN_EXP2, "jaco2-pen-exp2");
}

#[test]
fn pen_check_values() {
    let robot = Jaco2::pen();
    let p = robot.position_n(&theta0());
    assert_close(
        p.as_slice(),
        &[0.250226, -0.366141, 0.024212],
        1e-6,
        "jaco2-pen tip",
    );
    let s = singular_values(&robot.jacobian_n(&theta0()));
    assert_close(
        &s,
        &[0.633203, 0.422549, 0.295221],
        1e-5,
        "jaco2-pen singular values",
    );
}

#[test]
fn kinova_check_values() {
    let p = Jaco2::kinova().position_n(&theta0());
    assert_close(
        p.as_slice(),
        &[0.280261, -0.417131, 0.054383],
        1e-6,
        "jaco2 tool point",
    );
}

/// Pen model: Rx(-0.02) Ry(-0.05) times the D6 = 0.1425 chain, tip (0, -0.075, 0) in frame 6.
fn pen_independent(theta: &SVector<f64, 6>) -> Vector3<f64> {
    let tilt = Rotation3::from_axis_angle(&Vector3::x_axis(), -0.02).to_homogeneous()
        * Rotation3::from_axis_angle(&Vector3::y_axis(), -0.05).to_homogeneous();
    apply(
        &jaco2_frames(0.1425, tilt, theta)[5],
        &Vector3::new(0.0, -0.075, 0.0),
    )
}

#[test]
fn position_matches_independent_transcription() {
    let pen = Jaco2::pen();
    let kinova = Jaco2::kinova();
    for theta in random_vectors::<6>(1, 20, 4.0) {
        assert!((pen.position_n(&theta) - pen_independent(&theta)).norm() < 1e-12);
        let hand = apply(
            &jaco2_frames(0.16, Matrix4::identity(), &theta)[5],
            &Vector3::zeros(),
        );
        assert!((kinova.position_n(&theta) - hand).norm() < 1e-12);
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    for robot in [Jaco2::pen(), Jaco2::kinova(), Jaco2::pen_exp2()] {
        for theta in random_vectors::<6>(2, 10, 4.0) {
            let fd = fd_jacobian(|t| robot.position_n(t), &theta, 1e-5);
            let err = (robot.jacobian_n(&theta) - fd).amax();
            assert!(err < 1e-7, "{}: |J - J_fd| = {err:e}", robot.name());
        }
    }
}

#[test]
fn every_joint_moves_the_pen_tip() {
    let robot = Jaco2::pen();
    for theta in random_vectors::<6>(3, 10, 4.0) {
        let jac = robot.jacobian_n(&theta);
        for k in 0..6 {
            assert!(
                jac.column(k).norm() > 1e-3,
                "column {k} vanishes at {theta:?}"
            );
        }
    }
}

#[test]
fn jacobian_dot_matches_finite_differences() {
    for robot in [Jaco2::pen(), Jaco2::kinova(), Jaco2::pen_exp2()] {
        let thetas = random_vectors::<6>(4, 10, 4.0);
        let rates = random_vectors::<6>(5, 10, 1.5);
        for (theta, thetadot) in thetas.iter().zip(&rates) {
            let fd = fd_directional(|t| robot.jacobian_n(t), theta, thetadot, 1e-5);
            let err = (robot.jacobian_dot_n(theta, thetadot) - fd).amax();
            assert!(err < 1e-7, "{}: |Jdot - Jdot_fd| = {err:e}", robot.name());
        }
    }
}

#[test]
fn pen_limits_match_the_groups_code_and_the_papers_table() {
    let robot = Jaco2::pen();
    let lim = robot.limits();
    let deg = std::f64::consts::PI / 180.0;
    let upper = [1e4, 223.0, 71.0, 1e4, 1e4, 1e4];
    let lower = [-1e4, -137.0, -289.0, -1e4, -1e4, -1e4];
    for k in 0..6 {
        assert!((lim.theta_max[k] - upper[k] * deg).abs() < 1e-12);
        assert!((lim.theta_min[k] - lower[k] * deg).abs() < 1e-12);
    }
    // The papers' Table 1 in rad: theta2 in [-2.389, 3.892], theta3 in [-5.044, 1.239]. The
    // group's -137 deg is -2.3911 rad, so the papers' -2.389 only agrees to 2.2e-3.
    assert!((lim.theta_min[1] - -2.389).abs() < 2.5e-3 && (lim.theta_max[1] - 3.892).abs() < 1e-3);
    assert!((lim.theta_min[2] - -5.044).abs() < 1e-3 && (lim.theta_max[2] - 1.239).abs() < 1e-3);
    assert_eq!(lim.thetadot_max, SVector::<f64, 6>::repeat(1.5));
    assert_eq!(lim.thetadot_min, SVector::<f64, 6>::repeat(-1.5));
}

#[test]
fn kinova_limits() {
    let robot = Jaco2::kinova();
    let lim = robot.limits();
    assert_eq!((lim.theta_min[1], lim.theta_max[1]), (-0.7505, 3.8921));
    assert_eq!((lim.theta_min[2], lim.theta_max[2]), (-4.3808, 1.2392));
    for k in [0, 3, 4, 5] {
        assert!(lim.theta_min[k] == f64::NEG_INFINITY && lim.theta_max[k] == f64::INFINITY);
    }
    assert_eq!(
        lim.thetadot_max,
        SVector::<f64, 6>::from([0.6283, 0.6283, 0.6283, 0.8378, 0.8378, 0.8378])
    );
    assert_eq!(lim.thetadot_min, -&lim.thetadot_max);
}

/// The group's EXP2 chain (docs/group-code.md) transcribed independently: D4 = D5 = 0.07433,
/// D6 = 0.13, aa = 11 pi / 72, k = sin(aa) / sin(2 aa); pen tip and tilt as jaco2-pen.
fn exp2_independent(theta: &SVector<f64, 6>) -> Vector3<f64> {
    use std::f64::consts::PI;
    let (d1, d2, d3, d4, d5, d6, e2) = (0.2755, 0.41, 0.2073, 0.07433, 0.07433, 0.13, 0.0098);
    let aa = 11.0 * PI / 72.0;
    let k = aa.sin() / (2.0 * aa).sin();
    let table = [
        (0.0, PI / 2.0, d1),
        (d2, PI, 0.0),
        (0.0, PI / 2.0, -e2),
        (0.0, 2.0 * aa, -(d3 + k * d4)),
        (0.0, 2.0 * aa, -k * (d4 + d5)),
        (0.0, PI, -(k * d5 + d6)),
    ];
    let mut t = Rotation3::from_axis_angle(&Vector3::x_axis(), -0.02).to_homogeneous()
        * Rotation3::from_axis_angle(&Vector3::y_axis(), -0.05).to_homogeneous();
    for (i, (a, alpha, d)) in table.iter().enumerate() {
        t *= dh4(*a, *alpha, *d, theta[i]);
    }
    apply(&t, &Vector3::new(0.0, -0.075, 0.0))
}

#[test]
fn exp2_variant_is_the_groups_chain_and_pen_with_pens_wrist_is_jaco2_pen() {
    let exp2 = Jaco2::pen_exp2();
    let pen = Jaco2::pen();
    let same = Jaco2::pen_with_wrist(JACO2_PEN, JACO2_PEN_WRIST);
    assert_eq!(same, pen);
    assert_eq!(
        Jaco2::pen_with_wrist(JACO2_PEN_EXP2, JACO2_EXP2_WRIST),
        exp2
    );
    for theta in random_vectors::<6>(6, 20, 4.0) {
        assert!((exp2.position_n(&theta) - exp2_independent(&theta)).norm() < 1e-12);
        assert_eq!(same.position_n(&theta), pen.position_n(&theta));
        assert!((same.position_n(&theta) - pen_independent(&theta)).norm() < 1e-12);
    }
    assert_eq!(exp2.limits(), pen.limits());
    assert_eq!(exp2.tip(), pen.tip());
}

/// Check value of jaco2-pen-exp2 at the group's EXP2 theta0: the tip, printed, and its distance
/// from jaco2-pen's tip at the same pose: 29.5 mm, which the changes account for (d6 of the DH
/// table shorter by 13.4 mm, d5 by 1.8 mm, and the two wrist twists 2aa smaller by 5 deg each,
/// each swinging the ~0.2 m wrist-to-pen lever by ~15 mm).
#[test]
fn exp2_check_value_at_its_theta0() {
    let theta0 = SVector::from([1.670, 2.845, -3.218, 4.182, -1.715, -2.655]);
    let p = Jaco2::pen_exp2().position_n(&theta0);
    let q = Jaco2::pen().position_n(&theta0);
    let d = (p - q).norm();
    println!(
        "jaco2-pen-exp2 tip at theta0 = ({:.6}, {:.6}, {:.6}); jaco2-pen = ({:.6}, {:.6}, {:.6}); |difference| = {:.3} mm",
        p.x, p.y, p.z, q.x, q.y, q.z, d * 1e3
    );
    assert!((p - exp2_independent(&theta0)).norm() < 1e-12);
    assert_close(
        p.as_slice(),
        &[0.216772, -0.374490, -0.022114],
        1e-6,
        "jaco2-pen-exp2 tip at the EXP2 theta0",
    );
    assert!(d > 1e-2 && d < 5e-2, "|difference| = {d}");
    let sv = singular_values(&Jaco2::pen_exp2().jacobian_n(&theta0));
    assert!(sv[2] > 1e-2, "EXP2 theta0 is singular: {sv:?}");
}
