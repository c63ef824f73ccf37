//! The n-link family: position against an independent product of homogeneous transforms, the
//! Jacobian and its time derivative against finite differences, reach, names, skeleton, limits,
//! and the conditioning of the home pose for every N = 3..=30.

use crate::common;

use common::*;
use nalgebra::{Rotation3, SVector, Translation3, Vector3};
use robots::{NLink, Robot};
use robots::{NLINK_H0, NLINK_REACH};

/// The arm as a product of 4 x 4 transforms: Rz(theta_1) Tz(h0), then for each pitch joint
/// Ry(-theta_k) Tx(l) (a rotation about the horizontal y axis that raises x by theta_k).
/// Returns the joint-2.. origins and the tip.
fn by_transforms<const N: usize>(theta: &SVector<f64, N>) -> Vec<Vector3<f64>> {
    let l = 1.0 / (N - 1) as f64;
    let mut t = Rotation3::from_axis_angle(&Vector3::z_axis(), theta[0]).to_homogeneous()
        * Translation3::new(0.0, 0.0, 0.3).to_homogeneous();
    let mut points = vec![apply(&t, &Vector3::zeros())];
    for k in 1..N {
        t = t
            * Rotation3::from_axis_angle(&Vector3::y_axis(), -theta[k]).to_homogeneous()
            * Translation3::new(l, 0.0, 0.0).to_homogeneous();
        points.push(apply(&t, &Vector3::zeros()));
    }
    points
}

/// Smallest singular value of J at home().
fn sigma_min_home<const N: usize>() -> f64 {
    let robot = NLink::new(N).unwrap();
    singular_values(&robot.jacobian_n(&nlink_home::<N>()))[2]
}

fn check_family<const N: usize>(seed: u64) {
    let robot = NLink::new(N).unwrap();
    assert_eq!(robot.name(), format!("nlink-{N}"));
    let lim = robot.limits();
    let thetas = random_vectors::<N>(seed, 10, 2.6);
    let rates = random_vectors::<N>(seed + 1, 10, 2.0);
    for (theta, thetadot) in thetas.iter().zip(&rates) {
        assert!((0..N).all(|k| lim.theta_min[k] <= theta[k] && theta[k] <= lim.theta_max[k]));
        // Position and joint origins against the transform product.
        let points = by_transforms(theta);
        let p = robot.position_n(theta);
        assert!((p - points[N - 1]).norm() < 1e-14, "N = {N}");
        let skeleton = robot.skeleton_n(theta);
        assert_eq!(skeleton.len(), N + 1);
        assert_eq!(skeleton[0], Vector3::zeros());
        for (a, b) in skeleton[1..].iter().zip(&points) {
            assert!((a - b).norm() < 1e-14, "N = {N}: skeleton {a:?} vs {b:?}");
        }
        assert!((skeleton[N] - p).norm() < 1e-14);
        // Reach.
        assert!(
            p.norm() <= NLINK_H0 + NLINK_REACH + 1e-12,
            "N = {N}: |p| = {}",
            p.norm()
        );
        // Jacobian.
        let fd = fd_jacobian(|t| robot.position_n(t), theta, 1e-5);
        let jac = robot.jacobian_n(theta);
        let err = (jac - fd).amax() / jac.amax();
        assert!(err < 1e-7, "N = {N}: relative |J - J_fd| = {err:e}");
        // Jdot.
        let fd = fd_directional(|t| robot.jacobian_n(t), theta, thetadot, 1e-5);
        let jdot = robot.jacobian_dot_n(theta, thetadot);
        let err = (jdot - fd).amax() / jdot.amax();
        assert!(err < 1e-7, "N = {N}: relative |Jdot - Jdot_fd| = {err:e}");
        // One singular value is |r|: joint 1 alone moves the tip out of the arm's plane.
        let r = p.xy().norm();
        let s = singular_values(&jac);
        assert!(
            s.iter().any(|x| (x - r).abs() < 1e-9),
            "N = {N}: {s:?} vs r = {r}"
        );
    }
    // Home: position against the transform product, theta_1 = 0 keeps the arm in the x-z plane.
    let home = nlink_home::<N>();
    let p = robot.position_n(&home);
    assert!((p - by_transforms(&home)[N - 1]).norm() < 1e-14);
    assert_eq!(p.y, 0.0);
    assert!(p.x > 0.5 && p.z > 0.05, "N = {N}: home tip {p:?}");
    assert!((0..N).all(|k| lim.theta_min[k] < home[k] && home[k] < lim.theta_max[k]));
}

#[test]
fn family_matches_transforms_and_finite_differences() {
    check_family::<3>(31);
    check_family::<4>(33);
    check_family::<7>(35);
    check_family::<12>(37);
    check_family::<30>(39);
}

#[test]
fn home_positions() {
    // The home tip, computed by hand from the discrete arc: link angles 1.2 - 3 i / (N - 1),
    // i = 0..N-2, each of length 1 / (N - 1), above h0 = 0.3.
    fn arc<const N: usize>() -> Vector3<f64> {
        let n = (N - 1) as f64;
        let (mut x, mut z) = (0.0, 0.3);
        for i in 0..N - 1 {
            let a = 1.2 - 3.0 * i as f64 / n;
            x += a.cos() / n;
            z += a.sin() / n;
        }
        Vector3::new(x, 0.0, z)
    }
    assert!((NLink::new(3).unwrap().position_n(&nlink_home::<3>()) - arc::<3>()).norm() < 1e-15);
    assert!((NLink::new(12).unwrap().position_n(&nlink_home::<12>()) - arc::<12>()).norm() < 1e-14);
    assert!((NLink::new(30).unwrap().position_n(&nlink_home::<30>()) - arc::<30>()).norm() < 1e-14);
    // N = 3: links at 1.2 and -0.3 rad, each 0.5 m.
    let p3 = NLink::new(3).unwrap().position_n(&nlink_home::<3>());
    let want = Vector3::new(
        0.5 * (1.2f64.cos() + 0.3f64.cos()),
        0.0,
        0.3 + 0.5 * (1.2f64.sin() - 0.3f64.sin()),
    );
    assert!((p3 - want).norm() < 1e-15, "{p3:?} vs {want:?}");
}

macro_rules! sigma_table {
    ($($n:literal)*) => { [$((($n), sigma_min_home::<$n>(), {
        let p = NLink::new($n).unwrap().position_n(&nlink_home::<$n>());
        (p - Vector3::new(0.0, 0.0, NLINK_H0)).norm()
    })),*] };
}

#[test]
fn home_is_well_conditioned_for_every_n() {
    let table = sigma_table!(3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27
        28 29 30);
    let mut smallest = f64::INFINITY;
    for (n, sigma, reach) in table {
        println!("N = {n}: sigma_min = {sigma:.6}, |tip - joint 2| = {reach:.6}");
        assert!(sigma > 0.05, "N = {n}: sigma_min = {sigma}");
        assert!((0.3..=0.8).contains(&reach), "N = {n}: reach {reach}");
        smallest = smallest.min(sigma);
    }
    println!("smallest sigma_min over N = 3..=30: {smallest:.6}");
    assert!((smallest - 0.298909).abs() < 1e-6, "smallest {smallest}");
    assert_eq!(table[0].1, smallest, "the smallest is at N = 3");
}

#[test]
fn limits() {
    let robot = NLink::new(7).unwrap();
    let lim = robot.limits();
    assert_eq!(lim.theta_max[0], std::f64::consts::PI);
    assert_eq!(lim.theta_min[0], -std::f64::consts::PI);
    for k in 1..7 {
        assert_eq!((lim.theta_min[k], lim.theta_max[k]), (-2.6, 2.6));
    }
    for k in 0..7 {
        assert_eq!((lim.thetadot_min[k], lim.thetadot_max[k]), (-2.0, 2.0));
    }
}
