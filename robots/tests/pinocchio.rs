//! `robots::urdf` and `robots::chain` against Pinocchio, the outside reference: the URDFs of the
//! `example-robot-data` package (UR5, Panda to its hand and to its prismatic finger, Kinova
//! Jaco2 with continuous joints, Unitree Z1, xArm7), at seeded random states. The script
//! `tests/pinocchio_reference.py` prints Pinocchio's tool pose, LOCAL_WORLD_ALIGNED Jacobian
//! and its time derivative, H, c and g; this test loads the same URDF through `robots::read_urdf` and compares, entry by
//! entry, to 1e-12 relative to max(1, |value|). The same chain without its tool and base, as a
//! `ChainRobot` with the tool offset and base as an experiment's mount (`robots::mounted`), is
//! compared the same way through the `Robot` and `Orientation` traits: task point, position
//! Jacobian and its derivative, tool rotation, angular Jacobian and its derivative.
//!
//! The interpreter is `$DRIFTBENCH_PYTHON` (default `python3`). Where it cannot import
//! `pinocchio`, the test prints a SKIPPED line (on the terminal, past the test harness's
//! capture) and passes, unless `DRIFTBENCH_REQUIRE_PINOCCHIO=1` (CI), where it fails.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

use std::sync::Arc;

use nalgebra::{Matrix3, Matrix3xX, Rotation3, Vector3};
use robots::Chain;
use robots::Frame;
use robots::{read_urdf, ChainEnds};
use robots::{ChainRobot, Robot};
use robots::{Mount, Mounted};
use serde::Deserialize;

const TOL: f64 = 1e-12;

#[derive(Deserialize)]
struct Reference {
    pinocchio: String,
    example_robot_data: String,
    case: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    name: String,
    urdf: PathBuf,
    base: String,
    tip: String,
    tool: [f64; 3],
    joints: Vec<String>,
    base_rotation: [[f64; 3]; 3],
    base_translation: [f64; 3],
    sample: Vec<Sample>,
}

#[derive(Deserialize)]
struct Sample {
    theta: Vec<f64>,
    thetadot: Vec<f64>,
    position: [f64; 3],
    rotation: [[f64; 3]; 3],
    jacobian: Vec<Vec<f64>>,
    jacobian_dot: Vec<Vec<f64>>,
    inertia: Vec<Vec<f64>>,
    coriolis: Vec<f64>,
    gravity: Vec<f64>,
}

fn rows3(m: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| m[i][j])
}

/// Asserts `|ours - theirs| <= TOL max(1, |theirs|)` entrywise; `what` names the quantity.
fn compare(
    what: &str,
    ours: impl IntoIterator<Item = f64>,
    theirs: impl IntoIterator<Item = f64>,
) -> f64 {
    let ours: Vec<f64> = ours.into_iter().collect();
    let theirs: Vec<f64> = theirs.into_iter().collect();
    assert_eq!(
        ours.len(),
        theirs.len(),
        "{what}: {} values vs Pinocchio's {}",
        ours.len(),
        theirs.len()
    );
    let mut worst = 0.0_f64;
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        let err = (a - b).abs() / b.abs().max(1.0);
        assert!(
            err <= TOL,
            "{what}[{k}]: {a} vs Pinocchio's {b} (relative error {err:e})"
        );
        worst = worst.max(err);
    }
    worst
}

/// Prints `line` on the terminal even while the harness captures the test's output.
fn visible(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Runs the reference script; `None` (after a SKIPPED line) when Pinocchio is not there and
/// not required.
fn reference() -> Option<String> {
    let python = std::env::var("DRIFTBENCH_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let required = std::env::var("DRIFTBENCH_REQUIRE_PINOCCHIO").is_ok_and(|v| v == "1");
    let probe = Command::new(&python)
        .args(["-c", "import pinocchio"])
        .output();
    let missing = match probe {
        Ok(out) if out.status.success() => None,
        Ok(out) => Some(format!(
            "{python} cannot import pinocchio: {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .last()
                .unwrap_or("")
        )),
        Err(e) => Some(format!("{python} cannot be run: {e}")),
    };
    if let Some(why) = missing {
        assert!(!required, "DRIFTBENCH_REQUIRE_PINOCCHIO=1 but {why}");
        visible(&format!(
            "SKIPPED: robots' Pinocchio comparison: {why} (set DRIFTBENCH_PYTHON to an interpreter with `pin` and `example-robot-data`)"
        ));
        return None;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/pinocchio_reference.py");
    let out = Command::new(&python)
        .arg(&script)
        .output()
        .expect("run the reference script");
    assert!(
        out.status.success(),
        "{} failed: {}",
        script.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Some(String::from_utf8(out.stdout).expect("UTF-8 from the reference script"))
}

#[test]
fn urdf_chains_match_pinocchio() {
    let Some(text) = reference() else { return };
    let reference: Reference = toml::from_str(&text).expect("the reference script's TOML");
    assert!(reference.case.len() >= 2, "at least UR5 and Panda");
    for case in &reference.case {
        let ends = ChainEnds {
            base: &case.base,
            tip: &case.tip,
            tool: Vector3::from(case.tool),
        };
        let chain: Chain = read_urdf(&case.urdf, inputs::Origin::Named, &ends)
            .unwrap_or_else(|e| panic!("{}: {e}", case.name))
            .with_base(Frame {
                rot: rows3(&case.base_rotation),
                origin: Vector3::from(case.base_translation),
            });
        let mounted = mounted_robot(case);
        let oriented = mounted
            .orientation()
            .expect("a URDF robot has an orientation");
        let names: Vec<&str> = chain.joints().iter().map(|j| j.name.as_str()).collect();
        assert_eq!(names, case.joints, "{}: the path's joints", case.name);
        let n = chain.dof();
        let mut ws = chain.workspace();
        let mut worst = 0.0_f64;
        for (k, s) in case.sample.iter().enumerate() {
            let what = |q: &str| format!("{} sample {k}: {q}", case.name);
            let (theta, qd) = (s.theta.as_slice(), s.thetadot.as_slice());
            let pose = chain.tool_pose(&mut ws, theta);
            worst = worst.max(compare(
                &what("position"),
                pose.origin.iter().copied(),
                s.position,
            ));
            let rot = rows3(&s.rotation);
            worst = worst.max(compare(
                &what("rotation"),
                pose.rot.iter().copied(),
                rot.iter().copied(),
            ));
            let jac = chain.jacobian(&mut ws, theta).clone();
            let theirs = (0..n).flat_map(|j| (0..6).map(move |i| s.jacobian[i][j]));
            worst = worst.max(compare(&what("jacobian"), jac.iter().copied(), theirs));
            let jac_dot = chain.jacobian_dot(&mut ws, theta, qd).clone();
            let theirs = (0..n).flat_map(|j| (0..6).map(move |i| s.jacobian_dot[i][j]));
            worst = worst.max(compare(
                &what("jacobian_dot"),
                jac_dot.iter().copied(),
                theirs,
            ));
            let h = chain.inertia(&mut ws, theta).clone();
            let theirs = (0..n).flat_map(|j| (0..n).map(move |i| s.inertia[i][j]));
            worst = worst.max(compare(&what("H"), h.iter().copied(), theirs));
            let c = chain.coriolis(&mut ws, theta, qd).clone();
            worst = worst.max(compare(
                &what("c"),
                c.iter().copied(),
                s.coriolis.iter().copied(),
            ));
            let g = chain.gravity_torques(&mut ws, theta).clone();
            worst = worst.max(compare(
                &what("g"),
                g.iter().copied(),
                s.gravity.iter().copied(),
            ));
            // The mounted robot through the traits: rows 0..3 and 3..6 of the Jacobians.
            let rows = |m: &[Vec<f64>], first: usize| -> Vec<f64> {
                (0..n)
                    .flat_map(|j| (first..first + 3).map(move |i| m[i][j]))
                    .collect()
            };
            let mut three = Matrix3xX::zeros(n);
            worst = worst.max(compare(
                &what("mounted position"),
                mounted.position(theta).iter().copied(),
                s.position,
            ));
            worst = worst.max(compare(
                &what("mounted rotation"),
                oriented.tool_rotation(theta).iter().copied(),
                rot.iter().copied(),
            ));
            mounted.jacobian(theta, three.as_mut_slice());
            worst = worst.max(compare(
                &what("mounted J"),
                three.iter().copied(),
                rows(&s.jacobian, 0),
            ));
            mounted.jacobian_dot(theta, qd, three.as_mut_slice());
            worst = worst.max(compare(
                &what("mounted dJ/dt"),
                three.iter().copied(),
                rows(&s.jacobian_dot, 0),
            ));
            oriented.angular_jacobian(theta, three.as_mut_slice());
            worst = worst.max(compare(
                &what("mounted J_w"),
                three.iter().copied(),
                rows(&s.jacobian, 3),
            ));
            oriented.angular_jacobian_dot(theta, qd, three.as_mut_slice());
            worst = worst.max(compare(
                &what("mounted dJ_w/dt"),
                three.iter().copied(),
                rows(&s.jacobian_dot, 3),
            ));
        }
        visible(&format!(
            "pinocchio {} / example-robot-data {}: {} ({n} joints, {} states): worst relative error {worst:.1e}",
            reference.pinocchio,
            reference.example_robot_data,
            case.name,
            case.sample.len()
        ));
    }
}

/// The case's chain read without a tool, as a `ChainRobot` mounted with the case's tool offset
/// and base placement (its rotation as roll, pitch, yaw).
fn mounted_robot(case: &Case) -> Mounted<dyn Robot> {
    let ends = ChainEnds {
        base: &case.base,
        tip: &case.tip,
        tool: Vector3::zeros(),
    };
    let bare = read_urdf(&case.urdf, inputs::Origin::Named, &ends)
        .unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let (roll, pitch, yaw) =
        Rotation3::from_matrix_unchecked(rows3(&case.base_rotation)).euler_angles();
    let mount = Mount::new(case.tool, case.base_translation, [roll, pitch, yaw])
        .unwrap_or_else(|e| panic!("{}: {e}", case.name));
    Mounted::new(Arc::new(ChainRobot::new(&case.name, bare)), mount)
        .unwrap_or_else(|e| panic!("{}: {e}", case.name))
}
