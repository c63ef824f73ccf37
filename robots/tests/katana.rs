//! Katana 6M180: check values of `docs/robots.md`, an independent transcription of kong2019's
//! eq. (2), the Jacobian and its time derivative against finite differences, the wrist roll,
//! the stretched singular pose and the (unenforced) limits.

use crate::common;

use std::f64::consts::PI;

use common::*;
use nalgebra::{SVector, Vector3};
use robots::{Katana6m180, Robot, KATANA6M180};

fn theta_star0() -> SVector<f64, 5> {
    SVector::from([2.0 * PI / 5.0, PI / 2.0, 0.0, -PI / 6.0, PI / 3.0])
}

/// Eq. (2) written out term by term, lengths typed in again.
fn eq2(t: &SVector<f64, 5>) -> Vector3<f64> {
    let (l1, l2, l3, l4, l5) = (0.2015, 0.19, 0.139, 0.1523, 0.1505);
    let h = l2 * t[1].cos() + l3 * (t[1] + t[2]).cos() + (l4 + l5) * (t[1] + t[2] + t[3]).sin();
    Vector3::new(
        t[0].cos() * h,
        t[0].sin() * h,
        l1 - (l4 + l5) * (t[1] + t[2] + t[3]).cos() + l2 * t[1].sin() + l3 * (t[1] + t[2]).sin(),
    )
}

#[test]
fn name() {
    assert_eq!(Katana6m180::new().name(), KATANA6M180);
    assert_eq!(KATANA6M180, "katana6m180");
}

#[test]
fn check_values() {
    let robot = Katana6m180::new();
    let p = robot.position_n(&theta_star0());
    let want = [0.081034, 0.249398, 0.379100];
    for k in 0..3 {
        assert!(
            (p[k] - want[k]).abs() < 1e-6,
            "position {p:?}, want {want:?}"
        );
    }
    let s = singular_values(&robot.jacobian_n(&theta_star0()));
    let want = [0.454295, 0.262232, 0.233519];
    for k in 0..3 {
        assert!(
            (s[k] - want[k]).abs() < 1e-5,
            "singular values {s:?}, want {want:?}"
        );
    }
}

#[test]
fn position_matches_eq2() {
    let robot = Katana6m180::new();
    for theta in random_vectors::<5>(11, 50, 4.0) {
        assert!((robot.position_n(&theta) - eq2(&theta)).norm() < 1e-14);
    }
}

#[test]
fn wrist_roll_never_moves_the_position() {
    let robot = Katana6m180::new();
    for theta in random_vectors::<5>(12, 20, 4.0) {
        let mut rolled = theta;
        rolled[4] += 1.234;
        assert_eq!(robot.position_n(&theta), robot.position_n(&rolled));
        assert_eq!(robot.jacobian_n(&theta).column(4).norm(), 0.0);
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    let robot = Katana6m180::new();
    for theta in random_vectors::<5>(13, 10, 4.0) {
        let fd = fd_jacobian(|t| robot.position_n(t), &theta, 1e-5);
        let err = (robot.jacobian_n(&theta) - fd).amax();
        assert!(err < 1e-7, "|J - J_fd| = {err:e}");
    }
}

#[test]
fn jacobian_dot_matches_finite_differences() {
    let robot = Katana6m180::new();
    let thetas = random_vectors::<5>(14, 10, 4.0);
    let rates = random_vectors::<5>(15, 10, 1.5);
    for (theta, thetadot) in thetas.iter().zip(&rates) {
        let fd = fd_directional(|t| robot.jacobian_n(t), theta, thetadot, 1e-5);
        let err = (robot.jacobian_dot_n(theta, thetadot) - fd).amax();
        assert!(err < 1e-7, "|Jdot - Jdot_fd| = {err:e}");
    }
}

#[test]
fn stretched_pose_is_singular() {
    let robot = Katana6m180::new();
    let s = singular_values(&robot.jacobian_n(&SVector::from([0.0, 0.0, 0.0, PI / 2.0, 0.7])));
    assert!(s[2] < 1e-12, "singular values {s:?}");
    assert!(singular_values(&robot.jacobian_n(&theta_star0()))[2] > 0.1);
}

#[test]
fn limits_are_unenforced() {
    let robot = Katana6m180::new();
    let lim = robot.limits();
    assert!(lim
        .theta_min
        .iter()
        .chain(lim.thetadot_min.iter())
        .all(|&x| x == f64::NEG_INFINITY));
    assert!(lim
        .theta_max
        .iter()
        .chain(lim.thetadot_max.iter())
        .all(|&x| x == f64::INFINITY));
}

/// The shared evaluation gives the numbers of the two separate ones, bit for bit (the tracking
/// term relies on it: results stay the same whichever it calls).
#[test]
fn position_jacobian_is_position_and_jacobian_bit_for_bit() {
    let robot = Katana6m180::new();
    for k in 0..20 {
        let theta: Vec<f64> = (0..5).map(|i| 0.37 * (k * 5 + i) as f64 - 3.0).collect();
        let (mut shared, mut alone) = ([0.0; 15], [0.0; 15]);
        let f = robot.position_jacobian(&theta, &mut shared);
        robot.jacobian(&theta, &mut alone);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(f.as_slice()), bits(robot.position(&theta).as_slice()));
        assert_eq!(bits(&shared), bits(&alone));
    }
}
