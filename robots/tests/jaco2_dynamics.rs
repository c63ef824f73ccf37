//! Jaco2 dynamics: H symmetric positive definite, g = dU/dtheta, Hdot - 2C skew-symmetric,
//! C equal to the Christoffel sum of finite-difference dH/dtheta, c = C thetadot, RNEA
//! consistency, and the kinetic energy from independently computed link velocities.
//! Link poses for U and T come from the independent DH transcription in `common`.

use crate::common;

use common::*;
use nalgebra::{Matrix3, Matrix4, SMatrix, SVector, Vector3};
use robots::jaco2_bodies;
use robots::Jaco2;

type V6 = SVector<f64, 6>;

fn samples(seed: u64) -> Vec<(V6, V6, V6)> {
    let q = random_vectors::<6>(seed, 10, 4.0);
    let qd = random_vectors::<6>(seed + 100, 10, 1.5);
    let qdd = random_vectors::<6>(seed + 200, 10, 3.0);
    q.into_iter()
        .zip(qd)
        .zip(qdd)
        .map(|((a, b), c)| (a, b, c))
        .collect()
}

/// World pose (rotation, centre of mass) of every link on the D6 = 0.16 chain.
fn link_poses(theta: &V6) -> [(Matrix3<f64>, Vector3<f64>); 6] {
    let frames = jaco2_frames(0.16, Matrix4::identity(), theta);
    let bodies = jaco2_bodies();
    std::array::from_fn(|i| (rot(&frames[i]), apply(&frames[i], &bodies[i].com)))
}

/// U = -sum m_i g0 . p_ci with g0 = (0, 0, -9.81).
fn potential(theta: &V6) -> f64 {
    let g0 = Vector3::new(0.0, 0.0, -9.81);
    let bodies = jaco2_bodies();
    link_poses(theta)
        .iter()
        .zip(&bodies)
        .map(|((_, p), b)| -b.mass * g0.dot(p))
        .sum()
}

/// T = sum 1/2 m |v_c|^2 + 1/2 w' I_w w with v_c and w from finite differences of the poses.
fn kinetic_energy(theta: &V6, thetadot: &V6) -> f64 {
    let h = 1e-6;
    let plus = link_poses(&(theta + thetadot * h));
    let minus = link_poses(&(theta - thetadot * h));
    let now = link_poses(theta);
    let bodies = jaco2_bodies();
    (0..6)
        .map(|i| {
            let v = (plus[i].1 - minus[i].1) / (2.0 * h);
            let w_hat = (plus[i].0 - minus[i].0) / (2.0 * h) * now[i].0.transpose();
            let w = Vector3::new(w_hat[(2, 1)], w_hat[(0, 2)], w_hat[(1, 0)]);
            let iw = now[i].0 * bodies[i].inertia * now[i].0.transpose();
            0.5 * bodies[i].mass * v.norm_squared() + 0.5 * w.dot(&(iw * w))
        })
        .sum()
}

#[test]
fn inertia_is_symmetric_positive_definite() {
    let robot = Jaco2::kinova();
    for (q, _, _) in samples(21) {
        let h = robot.inertia_n(&q);
        assert!((h - h.transpose()).amax() < 1e-14);
        let eig = h.symmetric_eigenvalues();
        assert!(eig.min() > 1e-6, "eigenvalues {eig:?}");
    }
}

#[test]
fn gravity_is_the_gradient_of_the_potential() {
    let robot = Jaco2::kinova();
    for (q, _, _) in samples(22) {
        let fd = fd_jacobian(|t| SVector::<f64, 1>::new(potential(t)), &q, 1e-5).transpose();
        let err = (robot.gravity_n(&q) - fd).amax();
        assert!(err < 1e-7, "|g - dU/dtheta| = {err:e}");
    }
}

#[test]
fn kinetic_energy_matches_link_velocities() {
    let robot = Jaco2::kinova();
    for (q, qd, _) in samples(23) {
        let from_h = 0.5 * qd.dot(&(robot.inertia_n(&q) * qd));
        let direct = kinetic_energy(&q, &qd);
        assert!(
            (from_h - direct).abs() < 1e-8 * (1.0 + direct),
            "T: {from_h} vs {direct}"
        );
    }
}

#[test]
fn rnea_equals_h_qdd_plus_c_plus_g() {
    let robot = Jaco2::kinova();
    for (q, qd, qdd) in samples(24) {
        let tau = robot.rigid_chain().inverse_dynamics(&q, &qd, &qdd);
        let model = robot.inertia_n(&q) * qdd + robot.coriolis_n(&q, &qd) + robot.gravity_n(&q);
        assert!(
            (tau - model).amax() < 1e-12,
            "|tau - (H qdd + c + g)| = {:e}",
            (tau - model).amax()
        );
    }
}

#[test]
fn coriolis_matrix_reproduces_c() {
    let robot = Jaco2::kinova();
    for (q, qd, _) in samples(25) {
        let err = (robot.coriolis_matrix_n(&q, &qd) * qd - robot.coriolis_n(&q, &qd)).amax();
        assert!(err < 1e-12, "|C qd - c| = {err:e}");
    }
}

#[test]
fn hdot_minus_2c_is_skew_symmetric() {
    let robot = Jaco2::kinova();
    for (q, qd, _) in samples(26) {
        let hdot = fd_directional(|t| robot.inertia_n(t), &q, &qd, 1e-5);
        let n = hdot - robot.coriolis_matrix_n(&q, &qd) * 2.0;
        let err = (n + n.transpose()).amax();
        assert!(err < 1e-8, "|N + N'| = {err:e}");
    }
}

#[test]
fn coriolis_matrix_equals_christoffel_symbols() {
    let robot = Jaco2::kinova();
    for (q, qd, _) in samples(27) {
        let dh: [SMatrix<f64, 6, 6>; 6] = std::array::from_fn(|k| {
            let mut e = V6::zeros();
            e[k] = 1.0;
            fd_directional(|t| robot.inertia_n(t), &q, &e, 1e-5)
        });
        let christoffel = SMatrix::<f64, 6, 6>::from_fn(|i, j| {
            (0..6)
                .map(|k| 0.5 * (dh[k][(i, j)] + dh[j][(i, k)] - dh[i][(j, k)]) * qd[k])
                .sum()
        });
        let err = (robot.coriolis_matrix_n(&q, &qd) - christoffel).amax();
        assert!(err < 1e-8, "|C - C_christoffel| = {err:e}");
    }
}

#[test]
fn pen_model_has_the_physical_arms_dynamics() {
    let (pen, kinova) = (Jaco2::pen(), Jaco2::kinova());
    for (q, qd, _) in samples(28) {
        assert_eq!(pen.inertia_n(&q), kinova.inertia_n(&q));
        assert_eq!(pen.coriolis_n(&q, &qd), kinova.coriolis_n(&q, &qd));
        assert_eq!(
            pen.coriolis_matrix_n(&q, &qd),
            kinova.coriolis_matrix_n(&q, &qd)
        );
        assert_eq!(pen.gravity_n(&q), kinova.gravity_n(&q));
    }
}
