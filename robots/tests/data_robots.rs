//! The data models of `robots/data/*.toml` against the Rust models they transcribe (FK, J and
//! Jdot at seeded random angles, limits), and the PUMA 560, which exists only as data.

use crate::common;

use common::*;
use nalgebra::{DVector, SMatrix, SVector, Vector3};
use robots::{builtin_files, builtin_model, builtin_models, parse_builtin};
use robots::{DataRobot, Jaco2, NLink, Panda, Robot};

const TOL: f64 = 1e-12;

/// The built-in data robot `name`.
fn data(name: &str) -> DataRobot {
    let file_name = format!("{name}.toml");
    let (file, text) = builtin_files()
        .iter()
        .find(|(f, _)| *f == file_name)
        .unwrap_or_else(|| panic!("no robots/data/{file_name}"));
    DataRobot::new(&parse_builtin(file, text).unwrap())
}

/// `|a - b| <= TOL max(1, |a|)`, entrywise on the 3 x N / 3-vectors compared here.
fn close<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> bool {
    (a - b).amax() <= TOL * a.amax().max(1.0)
}

/// Equal limits (infinite where both are unlimited).
fn same_limits(a: &DVector<f64>, b: &DVector<f64>) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b.iter())
            .all(|(x, y)| x == y || (x - y).abs() <= TOL * x.abs().max(1.0))
}

fn assert_same<const N: usize>(rust: &dyn Robot, data: &dyn Robot) {
    assert_eq!((rust.dof(), data.dof()), (N, N));
    let name = rust.name();
    assert_eq!(name, data.name());
    let angles = random_vectors::<N>(20260, 200, 3.0);
    let rates = random_vectors::<N>(20261, 200, 1.0);
    for (theta, thetadot) in angles.iter().zip(&rates) {
        let (f_r, f_d) = (rust.position_n(theta), data.position_n(theta));
        assert!(close(&f_r, &f_d), "{name}: f {f_r} vs {f_d} at {theta}");
        let (j_r, j_d) = (rust.jacobian_n(theta), data.jacobian_n(theta));
        assert!(close(&j_r, &j_d), "{name}: J {j_r} vs {j_d} at {theta}");
        let (jd_r, jd_d) = (
            rust.jacobian_dot_n(theta, thetadot),
            data.jacobian_dot_n(theta, thetadot),
        );
        assert!(close(&jd_r, &jd_d), "{name}: Jdot {jd_r} vs {jd_d}");
    }
    let (l_r, l_d) = (rust.limits(), data.limits());
    assert!(
        same_limits(&l_r.theta_min, &l_d.theta_min),
        "{name}: theta_min"
    );
    assert!(
        same_limits(&l_r.theta_max, &l_d.theta_max),
        "{name}: theta_max"
    );
    assert!(
        same_limits(&l_r.thetadot_min, &l_d.thetadot_min),
        "{name}: thetadot_min"
    );
    assert!(
        same_limits(&l_r.thetadot_max, &l_d.thetadot_max),
        "{name}: thetadot_max"
    );
}

#[test]
fn every_builtin_file_loads_and_is_named_by_its_file() {
    let models = builtin_models();
    assert_eq!(models.len(), builtin_files().len());
    for ((file, _), (stem, model)) in builtin_files().iter().zip(models) {
        let model = model.as_ref().unwrap();
        assert_eq!(format!("{}.toml", model.name()), *file);
        assert_eq!(model.name(), *stem);
        assert_eq!(model.stated_pose().len(), model.dof());
    }
    assert!(builtin_model("puma560").is_some());
    assert!(builtin_model("puma-560").is_none());
}

#[test]
fn jaco2_files_equal_the_rust_models() {
    assert_same::<6>(&Jaco2::pen(), &data("jaco2-pen"));
    assert_same::<6>(&Jaco2::pen_exp2(), &data("jaco2-pen-exp2"));
    assert_same::<6>(&Jaco2::hand(), &data("jaco2-hand"));
    assert_same::<6>(&Jaco2::kinova(), &data("jaco2"));
}

#[test]
fn panda_file_equals_the_rust_model() {
    let panda = data("panda");
    assert_same::<7>(&Panda::model(), &panda);
    assert_eq!(panda.stated_pose(), &Panda::READY);
}

fn nlink_same<const N: usize>() {
    let arm = data(&format!("nlink-{N}"));
    assert_same::<N>(&NLink::new(N).unwrap(), &arm);
    assert!(
        close(
            &SVector::<f64, N>::from_column_slice(arm.stated_pose()),
            &nlink_home::<N>()
        ),
        "nlink-{N} home"
    );
}

#[test]
fn nlink_files_equal_the_rust_models() {
    nlink_same::<3>();
    nlink_same::<5>();
    nlink_same::<6>();
    nlink_same::<7>();
    nlink_same::<10>();
    nlink_same::<15>();
    nlink_same::<20>();
    nlink_same::<30>();
}

fn puma() -> DataRobot {
    let puma = builtin_model("puma560")
        .expect("puma560 is a built-in")
        .clone();
    assert_eq!(puma.dof(), 6);
    puma
}

#[test]
fn puma560_jacobian_and_jdot_match_finite_differences() {
    let robot = puma();
    let angles = random_vectors::<6>(560, 100, 3.0);
    let rates = random_vectors::<6>(561, 100, 1.5);
    for (theta, thetadot) in angles.iter().zip(&rates) {
        let fd = fd_jacobian(|t| robot.position_n(t), theta, 1e-6);
        let err = (robot.jacobian_n(theta) - fd).amax();
        assert!(err < 1e-8, "|J - J_fd| = {err:e} at {theta}");
        let fd = fd_directional(|t| robot.jacobian_n(t), theta, thetadot, 1e-6);
        let err = (robot.jacobian_dot_n(theta, thetadot) - fd).amax();
        assert!(err < 1e-7, "|Jdot - Jdot_fd| = {err:e} at {theta}");
    }
}

#[test]
fn puma560_joint6_cannot_move_the_tool_point() {
    let robot = puma();
    for theta in random_vectors::<6>(562, 100, 3.0) {
        let j6 = robot.jacobian_n(&theta).column(5).norm();
        assert!(j6 <= 1e-15, "|J_6| = {j6:e} at {theta}");
        // Joints 4 and 5 do move it (off the wrist singularity theta_5 = 0).
        if theta[4].sin().abs() > 0.1 {
            assert!(robot.jacobian_n(&theta).column(3).norm() > 1e-3);
        }
        assert!(robot.jacobian_n(&theta).column(4).norm() > 0.05);
    }
}

#[test]
fn puma560_check_values() {
    let robot = puma();
    // Corke's toolbox: fkine(qz) = transl(0.4521, -0.15005, 0.4318) with identity rotation
    // (wiki Arm-robot-examples prints -0.15), so the tool 0.05625 m along z6 is 0.05625 higher.
    let tip0 = robot.position_n(&SVector::<f64, 6>::zeros());
    let expected = Vector3::new(0.4521, -0.15005, 0.4318 + 0.05625);
    assert!((tip0 - expected).norm() < 1e-12, "f(0) = {tip0}");

    let theta = SVector::<f64, 6>::from_column_slice(robot.stated_pose());
    let pi = std::f64::consts::PI;
    let paper = SVector::<f64, 6>::from([0.0, -pi / 4.0, 0.0, pi / 2.0, -pi / 4.0, 0.0]);
    assert_eq!(theta, paper);
    let limits = robot.limits();
    assert!((0..6).all(|i| limits.theta_min[i] < theta[i] && theta[i] < limits.theta_max[i]));
    let tip = robot.position_n(&theta);
    let sv = singular_values(&robot.jacobian_n(&theta));
    println!(
        "puma560 at stated_pose {:?}: tip = ({:.12}, {:.12}, {:.12}) m, singular values of J = \
         {:.12}, {:.12}, {:.12}",
        theta.as_slice(),
        tip.x,
        tip.y,
        tip.z,
        sv[0],
        sv[1],
        sv[2]
    );
    assert!(sv[2] > 0.01, "stated_pose is not singular: {sv:?}");
}
