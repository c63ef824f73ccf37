//! The [`Orientation`] capability and [`Mounted`] robots against finite differences, at seeded
//! random states: for DH robots (the PUMA 560's file, the Jaco2 Rust model, the Panda's
//! modified table) and a URDF chain (`tests/fixtures/arm6.urdf`), J_w against differences of
//! the tool rotation (the axial vector of dR/dtheta_j R^T) and dJ_w/dt against differences of
//! J_w; for mounted robots (tool offset and base transform) the position Jacobian and its
//! derivative against differences of the position and of J, and the mounted orientation
//! likewise; then the mount's refusals and its dynamics.

use std::path::Path;
use std::sync::Arc;

use nalgebra::{DMatrix, Matrix3, Matrix3xX, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use robots::robot_by_name;
use robots::Chain;
use robots::{read_urdf, ChainEnds};
use robots::{ChainRobot, Dynamics, Orientation, Robot};
use robots::{Mount, Mounted};
use spec::MountError;

const H: f64 = 1e-6;
/// Central differences of step 1e-6 on functions of order 1: truncation ~1e-12, rounding
/// ~1e-10.
const TOL: f64 = 1e-8;

fn random(rng: &mut ChaCha8Rng, n: usize, lim: f64) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-lim..lim)).collect()
}

fn moved(x: &[f64], v: &[f64], s: f64) -> Vec<f64> {
    x.iter().zip(v).map(|(a, b)| a + s * b).collect()
}

fn unit(n: usize, j: usize) -> Vec<f64> {
    (0..n).map(|i| f64::from(u8::from(i == j))).collect()
}

fn angular(o: &dyn Orientation, n: usize, theta: &[f64]) -> Matrix3xX<f64> {
    let mut m = Matrix3xX::zeros(n);
    o.angular_jacobian(theta, m.as_mut_slice());
    m
}

fn angular_dot(o: &dyn Orientation, n: usize, theta: &[f64], thetadot: &[f64]) -> Matrix3xX<f64> {
    let mut m = Matrix3xX::zeros(n);
    o.angular_jacobian_dot(theta, thetadot, m.as_mut_slice());
    m
}

fn assert_close(what: &str, ours: &Matrix3xX<f64>, differences: &Matrix3xX<f64>) {
    let err = (ours - differences).amax();
    assert!(
        err < TOL,
        "{what}: off differences by {err:e}\n{ours}\n{differences}"
    );
}

/// J_w and dJ_w/dt of `robot`'s orientation against differences, at 5 random states; R stays a
/// rotation.
fn check_orientation(what: &str, robot: &dyn Robot, seed: u64) {
    let o = robot
        .orientation()
        .unwrap_or_else(|| panic!("{what} has an orientation"));
    let n = robot.dof();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..5 {
        let theta = random(&mut rng, n, 2.0);
        let thetadot = random(&mut rng, n, 1.0);
        let r = o.tool_rotation(&theta);
        assert!((r.transpose() * r - Matrix3::identity()).amax() < 1e-12);
        assert!((r.determinant() - 1.0).abs() < 1e-12);
        let mut fd = Matrix3xX::zeros(n);
        for j in 0..n {
            let e = unit(n, j);
            let dr = (o.tool_rotation(&moved(&theta, &e, H))
                - o.tool_rotation(&moved(&theta, &e, -H)))
                / (2.0 * H);
            let w = dr * r.transpose();
            fd.set_column(j, &Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]));
        }
        assert_close(&format!("{what}: J_w"), &angular(o, n, &theta), &fd);
        let fd_dot = (angular(o, n, &moved(&theta, &thetadot, H))
            - angular(o, n, &moved(&theta, &thetadot, -H)))
            / (2.0 * H);
        assert_close(
            &format!("{what}: dJ_w/dt"),
            &angular_dot(o, n, &theta, &thetadot),
            &fd_dot,
        );
    }
}

/// J and dJ/dt of `robot` against differences of its position and of J, at 5 random states.
fn check_position(what: &str, robot: &dyn Robot, seed: u64) {
    let n = robot.dof();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..5 {
        let theta = random(&mut rng, n, 2.0);
        let thetadot = random(&mut rng, n, 1.0);
        let mut fd = Matrix3xX::zeros(n);
        for j in 0..n {
            let e = unit(n, j);
            let d = (robot.position(&moved(&theta, &e, H))
                - robot.position(&moved(&theta, &e, -H)))
                / (2.0 * H);
            fd.set_column(j, &d);
        }
        assert_close(&format!("{what}: J"), &robot.jacobian_matrix(&theta), &fd);
        let fd_dot = (robot.jacobian_matrix(&moved(&theta, &thetadot, H))
            - robot.jacobian_matrix(&moved(&theta, &thetadot, -H)))
            / (2.0 * H);
        assert_close(
            &format!("{what}: dJ/dt"),
            &robot.jacobian_dot_matrix(&theta, &thetadot),
            &fd_dot,
        );
    }
}

/// The handwritten six-joint URDF arm, to its `tool0` link, no tool offset.
fn arm6() -> ChainRobot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/arm6.urdf");
    let ends = ChainEnds {
        base: "base_link",
        tip: "tool0",
        tool: Vector3::zeros(),
    };
    let chain: Chain = read_urdf(&path, inputs::Origin::Named, &ends).unwrap();
    ChainRobot::new("arm6", chain)
}

fn mount() -> Mount {
    Mount::new([0.03, -0.02, 0.12], [0.4, -0.3, 0.8], [0.3, -0.5, 1.1]).unwrap()
}

#[test]
fn dh_and_urdf_robots_have_an_orientation_that_matches_differences() {
    for (k, name) in ["puma560", "jaco2-pen", "panda"].into_iter().enumerate() {
        let model = robot_by_name(name).unwrap();
        check_orientation(name, model.robot.as_ref(), 10 + k as u64);
    }
    check_orientation("arm6.urdf", &arm6(), 20);
    for name in ["katana6m180", "nlink-7"] {
        let model = robot_by_name(name).unwrap();
        assert!(model.robot.orientation().is_none(), "{name}: no tool frame");
    }
}

#[test]
fn the_jaco2_pen_tip_is_fixed_in_the_tool_frame() {
    // The pen tip (0, -0.075, 0) in DH frame 6: f = o_6 + R t, so moving the tool by R t
    // is the same point as the model's with the tip at o_6 plus the tip in frame 6.
    let pen = robot_by_name("jaco2-pen").unwrap().robot;
    let o = pen.orientation().unwrap();
    let theta = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95];
    let tip = Vector3::new(0.0, -0.075, 0.0);
    let mounted = Mounted::new(
        pen.clone(),
        Mount::new([0.0, 0.0, 0.1], [0.0; 3], [0.0; 3]).unwrap(),
    )
    .unwrap();
    let expected = pen.position(&theta) + o.tool_rotation(&theta) * Vector3::new(0.0, 0.0, 0.1);
    assert!((mounted.position(&theta) - expected).norm() < 1e-15);
    // The tool frame's origin is the tip minus R tip.
    let origin = pen.position(&theta) - o.tool_rotation(&theta) * tip;
    assert!((origin - pen.skeleton(&theta)[6]).norm() < 1e-12);
}

#[test]
fn mounted_robots_match_differences() {
    let mounted = |robot: Arc<dyn Robot>| Mounted::new(robot, mount()).unwrap();
    for (k, name) in ["puma560", "jaco2-pen", "panda"].into_iter().enumerate() {
        let m = mounted(robot_by_name(name).unwrap().robot);
        check_position(&format!("mounted {name}"), &m, 30 + k as u64);
        check_orientation(&format!("mounted {name}"), &m, 40 + k as u64);
    }
    let m = mounted(Arc::new(arm6()));
    check_position("mounted arm6.urdf", &m, 50);
    check_orientation("mounted arm6.urdf", &m, 51);
    // A base alone needs no orientation: the Katana's closed form, turned and moved.
    let katana = robot_by_name("katana6m180").unwrap().robot;
    let base = Mount::new([0.0; 3], [0.1, 0.2, -0.3], [0.2, 0.4, -0.6]).unwrap();
    let m = Mounted::new(katana.clone(), base).unwrap();
    check_position("katana on a base", &m, 60);
    let theta = [0.3, 0.2, -0.4, 0.9, 0.1];
    let expected = base.base().transform_point(&katana.position(&theta));
    assert!((m.position(&theta) - expected).norm() < 1e-15);
    assert_eq!(m.skeleton(&theta).len(), katana.skeleton(&theta).len());
}

#[test]
fn a_mount_is_refused_for_what_it_cannot_do() {
    let katana = robot_by_name("katana6m180").unwrap().robot;
    let err = Mounted::new(katana, mount()).err().unwrap();
    assert!(matches!(&err, MountError::NoOrientation { robot } if robot == "katana6m180"));
    assert!(
        err.to_string().starts_with("`tool`: robot \"katana6m180\""),
        "{err}"
    );
    type Case = ([f64; 3], [f64; 3], [f64; 3], &'static str);
    let cases: [Case; 4] = [
        (
            [f64::NAN, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            "`tool[0]` is not a finite number",
        ),
        (
            [0.0; 3],
            [0.0, 11.0, 0.0],
            [0.0; 3],
            "`base.xyz[1]` = 11: must be within [-10, 10] m",
        ),
        (
            [0.0; 3],
            [0.0; 3],
            [0.0, 0.0, 7.0],
            "`base.rpy[2]` = 7: must be within",
        ),
        (
            [0.0; 3],
            [0.0; 3],
            [f64::INFINITY, 0.0, 0.0],
            "`base.rpy[0]` is not a finite number",
        ),
    ];
    for (tool, xyz, rpy, message) in cases {
        let err = Mount::new(tool, xyz, rpy).unwrap_err().to_string();
        assert!(err.starts_with(message), "{err}");
    }
}

#[test]
fn mounted_dynamics_are_the_models_under_a_yaw_and_refused_under_a_tilt() {
    let model = robot_by_name("jaco2-pen").unwrap();
    let dynamics = model.dynamics.clone().unwrap();
    let tilted = Mounted::with_dynamics(dynamics.clone(), mount())
        .err()
        .unwrap();
    assert!(
        matches!(tilted, MountError::TiltedGravity { .. }),
        "{tilted}"
    );
    let yaw = Mount::new([0.0, 0.0, 0.05], [0.5, 0.0, 0.2], [0.0, 0.0, 2.0]).unwrap();
    let m = Mounted::with_dynamics(dynamics.clone(), yaw).unwrap();
    let theta = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95];
    let thetadot = [0.3, -0.2, 0.5, 0.1, -0.4, 0.6];
    let n = 6;
    let (mut ours, mut theirs) = (DMatrix::zeros(n, n), DMatrix::zeros(n, n));
    m.inertia(&theta, ours.as_mut_slice());
    dynamics.inertia(&theta, theirs.as_mut_slice());
    assert_eq!(ours, theirs);
    m.coriolis_matrix(&theta, &thetadot, ours.as_mut_slice());
    dynamics.coriolis_matrix(&theta, &thetadot, theirs.as_mut_slice());
    assert_eq!(ours, theirs);
    let (mut c, mut g) = (vec![0.0; n], vec![0.0; n]);
    m.coriolis(&theta, &thetadot, &mut c);
    m.gravity(&theta, &mut g);
    let (mut c0, mut g0) = (vec![0.0; n], vec![0.0; n]);
    dynamics.coriolis(&theta, &thetadot, &mut c0);
    dynamics.gravity(&theta, &mut g0);
    assert_eq!((c, g), (c0, g0));
    // Its kinematics are the mounted ones.
    check_position("mounted jaco2-pen dynamics", &m, 70);
}
