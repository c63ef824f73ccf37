//! Franka Emika Panda: the flange centre against an independent 4 x 4 transcription of Franka's
//! modified-DH table, the Jacobian and its time derivative against finite differences at
//! in-limit poses, the Jacobian's singular values at the ready pose, skeleton and limits.

use crate::common;

use std::f64::consts::PI;

use common::*;
use nalgebra::{Matrix4, Rotation3, SVector, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use robots::{Panda, Robot, PANDA};

/// Franka's table typed in again, rows `(a, d, alpha)`; the last row is the flange.
const TABLE: [(f64, f64, f64); 8] = [
    (0.0, 0.333, 0.0),
    (0.0, 0.0, -PI / 2.0),
    (0.0, 0.316, PI / 2.0),
    (0.0825, 0.0, PI / 2.0),
    (-0.0825, 0.384, -PI / 2.0),
    (0.0, 0.0, PI / 2.0),
    (0.088, 0.0, PI / 2.0),
    (0.0, 0.107, 0.0),
];

/// Modified (Craig) DH link transform, the literal product Rx(alpha) Tx(a) Rz(theta) Tz(d).
fn mdh4(a: f64, alpha: f64, d: f64, theta: f64) -> Matrix4<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), alpha).to_homogeneous()
        * Translation3::new(a, 0.0, 0.0).to_homogeneous()
        * Rotation3::from_axis_angle(&Vector3::z_axis(), theta).to_homogeneous()
        * Translation3::new(0.0, 0.0, d).to_homogeneous()
}

/// Flange centre: origin of `M_1 ... M_7 F`.
fn flange_by_hand(q: &SVector<f64, 7>) -> Vector3<f64> {
    let mut t = Matrix4::identity();
    for (i, &(a, d, alpha)) in TABLE.iter().enumerate() {
        let theta = if i < 7 { q[i] } else { 0.0 };
        t *= mdh4(a, alpha, d, theta);
    }
    apply(&t, &Vector3::zeros())
}

/// Seeded poses uniform inside Franka's joint limits.
fn in_limit_poses(seed: u64, count: usize) -> Vec<SVector<f64, 7>> {
    let robot = Panda::model();
    let lim = robot.limits();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| SVector::from_fn(|k, _| rng.gen_range(lim.theta_min[k]..lim.theta_max[k])))
        .collect()
}

fn assert_close(got: &Vector3<f64>, want: [f64; 3], tol: f64, what: &str) {
    for k in 0..3 {
        assert!(
            (got[k] - want[k]).abs() < tol,
            "{what}: {got:?}, want {want:?}"
        );
    }
}

#[test]
fn name() {
    assert_eq!(Panda::model().name(), PANDA);
    assert_eq!(PANDA, "panda");
}

#[test]
fn flange_at_zero_and_ready() {
    let robot = Panda::model();
    let zero = SVector::<f64, 7>::zeros();
    // q = 0: upright, the two 0.0825 offsets cancel, 0.088 forward, flange pointing down.
    assert_close(
        &flange_by_hand(&zero),
        [0.088, 0.0, 0.926],
        1e-15,
        "by hand, q = 0",
    );
    assert_close(
        &robot.position_n(&zero),
        [0.088, 0.0, 0.926],
        1e-15,
        "q = 0",
    );
    let ready = SVector::<f64, 7>::from(Panda::READY);
    let want = [0.306890566593, 0.0, 0.590282052303];
    assert_close(&flange_by_hand(&ready), want, 1e-9, "by hand, READY");
    assert_close(&robot.position_n(&ready), want, 1e-9, "READY");
}

#[test]
fn position_matches_the_modified_dh_product() {
    let robot = Panda::model();
    for q in in_limit_poses(21, 50)
        .iter()
        .chain(&random_vectors::<7>(22, 50, 6.0))
    {
        let err = (robot.position_n(q) - flange_by_hand(q)).norm();
        assert!(err < 1e-14, "|f - f_hand| = {err:e}");
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    let robot = Panda::model();
    for q in in_limit_poses(23, 20) {
        let fd = fd_jacobian(|t| robot.position_n(t), &q, 1e-5);
        let jac = robot.jacobian_n(&q);
        let err = (jac - fd).amax() / jac.amax();
        assert!(err < 1e-7, "relative |J - J_fd| = {err:e}");
    }
}

#[test]
fn jacobian_dot_matches_finite_differences() {
    let robot = Panda::model();
    let qdot_max = SVector::from(robots::PANDA_QDOT_MAX);
    let rates = random_vectors::<7>(25, 20, 1.0);
    for (q, r) in in_limit_poses(24, 20).iter().zip(&rates) {
        let qdot = r.component_mul(&qdot_max);
        let fd = fd_directional(|t| robot.jacobian_n(t), q, &qdot, 1e-5);
        let jdot = robot.jacobian_dot_n(q, &qdot);
        let err = (jdot - fd).amax() / jdot.amax();
        assert!(err < 1e-7, "relative |Jdot - Jdot_fd| = {err:e}");
    }
}

#[test]
fn singular_values_at_ready() {
    let s = singular_values(&Panda::model().jacobian_n(&SVector::<f64, 7>::from(Panda::READY)));
    println!("singular values at READY: {s:.12?}");
    let want = [0.581091162405, 0.514564079411, 0.255511614757];
    for k in 0..3 {
        assert!(
            (s[k] - want[k]).abs() < 1e-9,
            "singular values {s:?}, want {want:?}"
        );
    }
}

#[test]
fn skeleton_runs_from_the_base_to_the_flange() {
    let robot = Panda::model();
    for q in in_limit_poses(26, 20) {
        let points = robot.skeleton_n(&q);
        assert!(points.len() >= 8, "{} points", points.len());
        assert_eq!(points.len(), 9);
        assert_eq!(points[0], Vector3::zeros());
        assert!((points[1] - Vector3::new(0.0, 0.0, 0.333)).norm() < 1e-15);
        assert!((points[8] - robot.position_n(&q)).norm() < 1e-15);
        assert!(((points[8] - points[7]).norm() - 0.107).abs() < 1e-14);
    }
}

#[test]
fn limits_are_ordered_and_ready_is_inside() {
    let robot = Panda::model();
    let lim = robot.limits();
    let ready = SVector::<f64, 7>::from(Panda::READY);
    for k in 0..7 {
        assert!(lim.theta_min[k] < lim.theta_max[k], "joint {}", k + 1);
        assert!(lim.thetadot_min[k] < 0.0 && lim.thetadot_max[k] > 0.0);
        assert_eq!(lim.thetadot_min[k], -lim.thetadot_max[k]);
        assert!(lim.theta_min[k] < ready[k] && ready[k] < lim.theta_max[k]);
    }
    assert_eq!(lim.theta_max[3], -0.0698);
    assert_eq!(lim.theta_min[5], -0.0175);
    assert_eq!(lim.thetadot_max[6], 2.61);
}
