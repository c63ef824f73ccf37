//! Jaco2 kinematics: check values of `robots.md`, an independent DH transcription, the
//! Jacobian and its time derivative against finite differences, and the joint limits.

mod common;

use common::*;
use nalgebra::{Matrix4, Rotation3, SVector, Vector3};
use robots::{Jaco2, Robot, JACO2, JACO2_PEN};

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
}

#[test]
fn pen_check_values() {
    let robot = Jaco2::pen();
    let p = robot.position(&theta0());
    assert_close(
        p.as_slice(),
        &[0.250226, -0.366141, 0.024212],
        1e-6,
        "jaco2-pen tip",
    );
    let s = singular_values(&robot.jacobian(&theta0()));
    assert_close(
        &s,
        &[0.633203, 0.422549, 0.295221],
        1e-5,
        "jaco2-pen singular values",
    );
}

#[test]
fn kinova_check_values() {
    let p = Jaco2::kinova().position(&theta0());
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
        assert!((pen.position(&theta) - pen_independent(&theta)).norm() < 1e-12);
        let hand = apply(
            &jaco2_frames(0.16, Matrix4::identity(), &theta)[5],
            &Vector3::zeros(),
        );
        assert!((kinova.position(&theta) - hand).norm() < 1e-12);
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    for robot in [Jaco2::pen(), Jaco2::kinova()] {
        for theta in random_vectors::<6>(2, 10, 4.0) {
            let fd = fd_jacobian(|t| robot.position(t), &theta, 1e-5);
            let err = (robot.jacobian(&theta) - fd).amax();
            assert!(err < 1e-7, "{}: |J - J_fd| = {err:e}", robot.name());
        }
    }
}

#[test]
fn every_joint_moves_the_pen_tip() {
    let robot = Jaco2::pen();
    for theta in random_vectors::<6>(3, 10, 4.0) {
        let jac = robot.jacobian(&theta);
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
    for robot in [Jaco2::pen(), Jaco2::kinova()] {
        let thetas = random_vectors::<6>(4, 10, 4.0);
        let rates = random_vectors::<6>(5, 10, 1.5);
        for (theta, thetadot) in thetas.iter().zip(&rates) {
            let fd = fd_directional(|t| robot.jacobian(t), theta, thetadot, 1e-5);
            let err = (robot.jacobian_dot(theta, thetadot) - fd).amax();
            assert!(err < 1e-7, "{}: |Jdot - Jdot_fd| = {err:e}", robot.name());
        }
    }
}

#[test]
fn pen_limits_match_the_groups_code_and_the_papers_table() {
    let lim = Jaco2::pen().limits();
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
    let lim = Jaco2::kinova().limits();
    assert_eq!((lim.theta_min[1], lim.theta_max[1]), (-0.7505, 3.8921));
    assert_eq!((lim.theta_min[2], lim.theta_max[2]), (-4.3808, 1.2392));
    for k in [0, 3, 4, 5] {
        assert!(lim.theta_min[k] == f64::NEG_INFINITY && lim.theta_max[k] == f64::INFINITY);
    }
    assert_eq!(
        lim.thetadot_max,
        SVector::<f64, 6>::from([0.6283, 0.6283, 0.6283, 0.8378, 0.8378, 0.8378])
    );
    assert_eq!(lim.thetadot_min, -lim.thetadot_max);
}
