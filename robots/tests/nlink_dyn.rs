//! The n-link arm at run-time joint counts: its J and Jdot against central finite differences
//! at n = 7, 100 and 200, and the family's range of joint counts.

use nalgebra::{DVector, Matrix3xX};
use robots::{NLink, Robot};

/// A deterministic state: theta = home + 0.3 sin(1.7 (k + 1)), thetadot_k = cos(0.9 (k + 1)).
fn state(arm: &NLink) -> (DVector<f64>, DVector<f64>) {
    let home = arm.home();
    let theta = DVector::from_fn(arm.dof(), |k, _| {
        home[k] + 0.3 * (1.7 * (k + 1) as f64).sin()
    });
    let thetadot = DVector::from_fn(arm.dof(), |k, _| (0.9 * (k + 1) as f64).cos());
    (theta, thetadot)
}

/// Central differences of f along each joint (columns) and of J along thetadot.
fn finite_differences(
    arm: &NLink,
    theta: &DVector<f64>,
    thetadot: &DVector<f64>,
    h: f64,
) -> (Matrix3xX<f64>, Matrix3xX<f64>) {
    let n = arm.dof();
    let mut jac = Matrix3xX::zeros(n);
    for k in 0..n {
        let mut plus = theta.clone();
        let mut minus = theta.clone();
        plus[k] += h;
        minus[k] -= h;
        jac.set_column(
            k,
            &((arm.position(plus.as_slice()) - arm.position(minus.as_slice())) / (2.0 * h)),
        );
    }
    let jdot = (arm.jacobian_matrix((theta + thetadot * h).as_slice())
        - arm.jacobian_matrix((theta - thetadot * h).as_slice()))
        / (2.0 * h);
    (jac, jdot)
}

#[test]
fn jacobians_match_finite_differences_at_7_100_and_200_joints() {
    for n in [7, 100, 200] {
        let arm = NLink::new(n).unwrap();
        let (theta, thetadot) = state(&arm);
        let (fd_jac, fd_jdot) = finite_differences(&arm, &theta, &thetadot, 1e-5);
        let jac = arm.jacobian_matrix(theta.as_slice());
        let err = (&jac - fd_jac).amax() / jac.amax();
        assert!(err < 1e-7, "N = {n}: relative |J - J_fd| = {err:e}");
        let jdot = arm.jacobian_dot_matrix(theta.as_slice(), thetadot.as_slice());
        let err = (&jdot - fd_jdot).amax() / jdot.amax();
        assert!(err < 1e-6, "N = {n}: relative |Jdot - Jdot_fd| = {err:e}");
        // The home tip stays in front of the yaw axis, above the base, within reach.
        let p = arm.position(arm.home().as_slice());
        assert!(
            p.x > 0.5 && p.z > 0.05 && p.y == 0.0,
            "N = {n}: home tip {p:?}"
        );
    }
}

#[test]
fn the_family_spans_two_to_a_thousand_joints() {
    assert!(NLink::new(1).is_none());
    assert!(NLink::new(robots::NLINK_MAX + 1).is_none());
    for n in [2, 3, 4, 8, 9, 150, 1000] {
        let arm = NLink::new(n).unwrap();
        assert_eq!((arm.dof(), arm.limits().dof(), arm.home().len()), (n, n, n));
        assert_eq!(arm.name(), format!("nlink-{n}"));
    }
}
