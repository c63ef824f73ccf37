//! `robots::ChainRobot` and the URDF form of a robot file: a handwritten six-joint URDF
//! (`tests/fixtures/arm6.urdf`) registered from a robot file in a temporary folder, as a
//! [`Robot`] (J and dJ/dt against differences of the position and of J) and a [`Dynamics`]
//! model (the Coriolis matrix: c = C thetadot, Hdot - 2C skew-symmetric, C against the
//! Christoffel symbols of finite differences of H); and the URDF form's refusals, each naming
//! the robot file and the field.

use inputs::Scratch;
use nalgebra::{DMatrix, DVector};
use robots::{register_file, robot_by_name, Kinematics};
use std::path::{Path, PathBuf};

/// The fixture URDF's text.
fn arm6() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/arm6.urdf"))
        .unwrap()
}

/// A robot file of the URDF form for `arm6.urdf`, named `name`, with `extra` lines.
fn robot_file(name: &str, urdf: &str, extra: &str) -> String {
    format!(
        "name = \"{name}\"\nsource = \"handwritten test arm\"\nurdf = \"{urdf}\"\n\
         base = \"base_link\"\ntip = \"tool0\"\ntool = [0.0, 0.0, 0.1]\n{extra}"
    )
}

/// A temporary robots folder `<scratch>/papers/x/robots` holding `arm6.urdf` and the robot
/// files `files`; registers them. The scratch directory is removed when dropped.
fn register(tag: &str, files: &[(&str, String)]) -> (Scratch, PathBuf) {
    let base = Scratch::dir(&format!("chain-robot-{tag}"));
    let dir = base.join("papers/x/robots");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("arm6.urdf"), arm6()).unwrap();
    for (name, text) in files {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        register_file::<&str>(&path, Ok(text));
    }
    (base, dir)
}

fn matrix(n: usize, f: impl Fn(&mut [f64])) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(n, n);
    f(m.as_mut_slice());
    m
}

#[test]
fn a_urdf_robot_file_gives_a_robot_with_consistent_kinematics_and_dynamics() {
    let pose = "stated_pose = [0.2, -0.6, 1.2, -0.8, 0.5, 0.3]\nvelocity_max = [2.0, 2.0, 2.0, 3.0, 3.0, 3.0]\n";
    let (_base, _dir) = register(
        "good",
        &[("urdf-arm6", robot_file("urdf-arm6", "arm6.urdf", pose))],
    );
    let model = robot_by_name("urdf-arm6").unwrap();
    assert_eq!(model.dof(), 6);
    assert_eq!(model.stated_pose, [0.2, -0.6, 1.2, -0.8, 0.5, 0.3]);
    assert!(matches!(&model.kinematics, Kinematics::Urdf { tip, .. } if tip == "tool0"));
    let limits = model.robot.limits();
    assert_eq!(limits.thetadot_max[0], 2.0);
    assert_eq!(limits.thetadot_min[5], -3.0);
    assert_eq!(limits.theta_max[2], 6.0);
    let robot = model.robot.as_ref();
    let dynamics = model.dynamics.clone().expect("every link has an inertial");
    assert!(robots::robots_with_dynamics().contains(&"urdf-arm6".to_string()));
    let n = 6;
    let theta = model.stated_pose.clone();
    let thetadot = [0.7, -0.4, 0.9, 0.3, -1.1, 0.5];
    // J against central differences of the position; dJ/dt against differences of J.
    let h = 1e-6;
    let j = robot.jacobian_matrix(&theta);
    let jdot = robot.jacobian_dot_matrix(&theta, &thetadot);
    let moved = |s: f64| -> Vec<f64> {
        theta
            .iter()
            .zip(&thetadot)
            .map(|(q, v)| q + s * v)
            .collect()
    };
    let jdot_fd =
        (robot.jacobian_matrix(&moved(h)) - robot.jacobian_matrix(&moved(-h))) / (2.0 * h);
    assert!((jdot - jdot_fd).amax() < 1e-7);
    for k in 0..n {
        let mut plus = theta.clone();
        let mut minus = theta.clone();
        plus[k] += h;
        minus[k] -= h;
        let column = (robot.position(&plus) - robot.position(&minus)) / (2.0 * h);
        assert!((column - j.column(k)).amax() < 1e-8, "column {k}");
    }
    assert_eq!(robot.skeleton(&theta).last(), Some(&robot.position(&theta)));
    // H symmetric positive definite; c = C thetadot; Hdot - 2C skew; C = Christoffel.
    let hm = dynamics.inertia_matrix(&theta);
    assert!((&hm - hm.transpose()).amax() < 1e-12);
    assert!(hm.clone().symmetric_eigen().eigenvalues.min() > 0.0);
    let cm = matrix(n, |o| dynamics.coriolis_matrix(&theta, &thetadot, o));
    let mut c = DVector::zeros(n);
    dynamics.coriolis(&theta, &thetadot, c.as_mut_slice());
    assert!((&cm * DVector::from_column_slice(&thetadot) - &c).amax() < 1e-11);
    let dh: Vec<DMatrix<f64>> = (0..n)
        .map(|k| {
            let mut plus = theta.clone();
            let mut minus = theta.clone();
            plus[k] += h;
            minus[k] -= h;
            (dynamics.inertia_matrix(&plus) - dynamics.inertia_matrix(&minus)) / (2.0 * h)
        })
        .collect();
    let hdot = dh
        .iter()
        .zip(&thetadot)
        .fold(DMatrix::zeros(n, n), |acc, (d, v)| acc + d * *v);
    let skew = &hdot - &cm * 2.0;
    assert!((&skew + skew.transpose()).amax() < 1e-7);
    let christoffel = DMatrix::from_fn(n, n, |i, jj| {
        (0..n)
            .map(|k| 0.5 * (dh[k][(i, jj)] + dh[jj][(i, k)] - dh[i][(jj, k)]) * thetadot[k])
            .sum::<f64>()
    });
    assert!((&cm - christoffel).amax() < 1e-7);
    let mut g = DVector::zeros(n);
    dynamics.gravity(&theta, g.as_mut_slice());
    assert!(g.amax() > 1.0, "gravity loads the shoulder");
}

#[test]
fn a_broken_urdf_robot_file_is_refused_naming_the_file_and_field() {
    let outside = Scratch::dir("chain-robot-outside");
    std::fs::write(outside.join("arm6.urdf"), arm6()).unwrap();
    // From `<tmp>/driftbench-chain-robot-bad-<pid>/papers/x/robots` up to `<tmp>`, and into
    // `<tmp>/driftbench-chain-robot-outside-<pid>`.
    let escape = format!(
        "../../../../{}/arm6.urdf",
        outside.file_name().unwrap().to_str().unwrap()
    );
    let files = [
        (
            "urdf-missing",
            robot_file("urdf-missing", "no-such.urdf", ""),
        ),
        ("urdf-escape", robot_file("urdf-escape", &escape, "")),
        (
            "urdf-badtip",
            robot_file("urdf-badtip", "arm6.urdf", "").replace("tool0\"", "hand\""),
        ),
        (
            "urdf-pose",
            robot_file("urdf-pose", "arm6.urdf", "stated_pose = [0.0, 0.1]\n"),
        ),
        (
            "urdf-speed",
            robot_file(
                "urdf-speed",
                "arm6.urdf",
                "velocity_max = [1.0, 1.0, 1.0, 1.0, 1.0, 0.0]\n",
            ),
        ),
        (
            "urdf-field",
            robot_file("urdf-field", "arm6.urdf", "convention = \"standard\"\n"),
        ),
        ("urdf-other", robot_file("urdf-named", "arm6.urdf", "")),
    ];
    let (_base, dir) = register("bad", &files);
    let expect = [
        ("urdf-missing", "`urdf`"),
        ("urdf-escape", "`urdf`"),
        ("urdf-badtip", "\"hand\""),
        ("urdf-pose", "stated_pose has 2 entries"),
        ("urdf-speed", "velocity_max[5] = 0"),
        ("urdf-field", "convention"),
        ("urdf-other", "differs from the file's stem"),
    ];
    for (name, field) in expect {
        let error = robot_by_name(name).unwrap_err().to_string();
        let file = dir.join(format!("{name}.toml")).display().to_string();
        assert!(
            error.contains(&file) && error.contains(field),
            "{name}: {error}"
        );
        assert!(
            !error.contains("<robot"),
            "{name}: the URDF is never quoted: {error}"
        );
    }
    let missing = robot_by_name("urdf-missing").unwrap_err().to_string();
    assert!(missing.contains("no-such.urdf"), "{missing}");
    let escape = robot_by_name("urdf-escape").unwrap_err().to_string();
    assert!(
        escape.contains("outside"),
        "refused as out of the folder: {escape}"
    );
    eprintln!("{missing}\n{escape}");
}

/// A URDF arm's shared p and J evaluation is its separate ones, bit for bit.
#[test]
fn a_urdf_robot_shares_its_position_and_jacobian_bit_for_bit() {
    let _scratch = register(
        "shared",
        &[(
            "urdf-arm6-shared",
            robot_file("urdf-arm6-shared", "arm6.urdf", ""),
        )],
    );
    let model = robot_by_name("urdf-arm6-shared").unwrap();
    assert!(matches!(&model.kinematics, Kinematics::Urdf { .. }));
    crate::position_jacobian::assert_shared_is_separate(model.robot.as_ref());
}
