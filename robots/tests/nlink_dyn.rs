//! The dynamic-size n-link arm: equal to the fixed-size `NLink<7>` (position, J, Jdot, home),
//! and its J and Jdot against central finite differences at N = 7, 100 and 200, where no
//! fixed-size arm exists.

use crate::common;

use common::*;
use nalgebra::{DVector, Matrix3xX, SVector};
use robots::{NLink, NLinkDyn, Robot};

/// A deterministic state: theta = home + 0.3 sin(1.7 (k + 1)), thetadot_k = cos(0.9 (k + 1)).
fn state(arm: &NLinkDyn) -> (DVector<f64>, DVector<f64>) {
    let home = arm.home();
    let theta = DVector::from_fn(arm.joints(), |k, _| {
        home[k] + 0.3 * (1.7 * (k + 1) as f64).sin()
    });
    let thetadot = DVector::from_fn(arm.joints(), |k, _| (0.9 * (k + 1) as f64).cos());
    (theta, thetadot)
}

/// Central differences of f along each joint (columns) and of J along thetadot.
fn finite_differences(
    arm: &NLinkDyn,
    theta: &DVector<f64>,
    thetadot: &DVector<f64>,
    h: f64,
) -> (Matrix3xX<f64>, Matrix3xX<f64>) {
    let n = arm.joints();
    let mut jac = Matrix3xX::zeros(n);
    for k in 0..n {
        let mut plus = theta.clone();
        let mut minus = theta.clone();
        plus[k] += h;
        minus[k] -= h;
        jac.set_column(
            k,
            &((arm.position(&plus) - arm.position(&minus)) / (2.0 * h)),
        );
    }
    let jdot =
        (arm.jacobian(&(theta + thetadot * h)) - arm.jacobian(&(theta - thetadot * h))) / (2.0 * h);
    (jac, jdot)
}

#[test]
fn the_dynamic_arm_is_the_fixed_size_one_at_n_7() {
    let fixed = NLink::<7>::new();
    let arm = NLinkDyn::new(7).unwrap();
    assert_eq!(arm.name(), fixed.name());
    assert_eq!(arm.home().as_slice(), NLink::<7>::home().as_slice());
    for (seed, (theta, thetadot)) in random_vectors::<7>(71, 5, 2.6)
        .into_iter()
        .zip(random_vectors::<7>(72, 5, 2.0))
        .enumerate()
    {
        let (dt, dtd) = (
            DVector::from_column_slice(theta.as_slice()),
            DVector::from_column_slice(thetadot.as_slice()),
        );
        assert_eq!(arm.position(&dt), fixed.position(&theta), "state {seed}");
        assert_eq!(
            arm.jacobian(&dt).as_slice(),
            fixed.jacobian(&theta).as_slice()
        );
        assert_eq!(
            arm.jacobian_dot(&dt, &dtd).as_slice(),
            fixed.jacobian_dot(&theta, &thetadot).as_slice()
        );
    }
    let zero = SVector::<f64, 7>::zeros();
    assert_eq!(
        arm.jacobian(&DVector::zeros(7)).as_slice(),
        fixed.jacobian(&zero).as_slice()
    );
}

#[test]
fn jacobians_match_finite_differences_at_7_100_and_200_joints() {
    for n in [7, 100, 200] {
        let arm = NLinkDyn::new(n).unwrap();
        let (theta, thetadot) = state(&arm);
        let (fd_jac, fd_jdot) = finite_differences(&arm, &theta, &thetadot, 1e-5);
        let jac = arm.jacobian(&theta);
        let err = (&jac - fd_jac).amax() / jac.amax();
        assert!(err < 1e-7, "N = {n}: relative |J - J_fd| = {err:e}");
        let jdot = arm.jacobian_dot(&theta, &thetadot);
        let err = (&jdot - fd_jdot).amax() / jdot.amax();
        assert!(err < 1e-6, "N = {n}: relative |Jdot - Jdot_fd| = {err:e}");
        // The home tip stays in front of the yaw axis, above the base, within reach.
        let p = arm.position(&arm.home());
        assert!(
            p.x > 0.5 && p.z > 0.05 && p.y == 0.0,
            "N = {n}: home tip {p:?}"
        );
    }
}

#[test]
fn fewer_than_three_joints_is_not_an_arm() {
    assert!(NLinkDyn::new(2).is_none());
    assert_eq!(NLinkDyn::new(3).map(|a| a.joints()), Some(3));
}
