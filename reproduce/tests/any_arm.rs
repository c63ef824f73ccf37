//! Any joint count through the one path: a paper's own arms of 4, 8 and 9 joints, declared by
//! robot files in its folder (`papers/<paper>/robots/*.toml`, read at run time, no rebuild),
//! and the 150-joint n-link arm, each loaded from an experiment file, checked as the loader
//! checks every job, and run with kong2019's ZNN scheme (eq. 22) on a circle, the exact optimum
//! in the loop: every run completes and tracks the circle.

use simulation::run_job;
use simulation::Outcome;
use std::fmt::Write as _;
use std::path::Path;

/// A robot file: a yaw joint (d = 0.3 m, alpha = pi/2), then n - 1 pitch links of 0.9 / (n - 1)
/// m each in the plane the yaw joint turns.
fn arm_file(name: &str, n: usize) -> String {
    let mut s = format!(
        "name = \"{name}\"\nsource = \"a test arm\"\nconvention = \"standard\"\ntool = [0.0, 0.0, 0.0]\n"
    );
    for k in 0..n {
        let (a, alpha, d) = if k == 0 {
            (0.0, std::f64::consts::FRAC_PI_2, 0.3)
        } else {
            (0.9 / (n - 1) as f64, 0.0, 0.0)
        };
        let _ = write!(s, "\n[[joint]]\na = {a:?}\nalpha = {alpha:?}\nd = {d:?}\n");
    }
    s
}

/// A bent, non-singular pose: yaw 0.2, then 1.2 and -2.4 / (n - 1) per pitch joint.
fn pose(n: usize) -> String {
    let angles: Vec<String> = (0..n)
        .map(|k| match k {
            0 => "0.2".to_string(),
            1 => "1.2".to_string(),
            _ => format!("{:?}", -2.4 / (n - 1) as f64),
        })
        .collect();
    format!("[{}]", angles.join(", "))
}

/// One experiment of the ZNN scheme on `robot` (n joints) along a circle of `duration` s.
fn experiment(robot: &str, n: usize, duration: f64) -> String {
    format!(
        r#"
[[experiment]]
id = "kong2019-any-arm-{robot}"
paper_output = "none"
robot = "{robot}"
path = {{ name = "circle", duration = {duration:?} }}
theta0 = {pose}
exact_integrator = {{ method = "bdf", rtol = 1e-8, atol = 1e-10 }}
[[experiment.variant]]
label = "ZNN (eq. 22)"
scheme = {{ kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }}
"#,
        pose = pose(n)
    )
}

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

#[test]
fn arms_of_4_8_9_and_150_joints_run_from_files() {
    let root = inputs::Scratch::unmade("any-arm");
    let robots = root.join("papers/anyarm2026/robots");
    let mut toml = String::from("paper = \"kong2019\"\ntitle = \"any arm\"\n");
    for n in [4, 8, 9] {
        let name = format!("any-arm-{n}");
        write(&robots.join(format!("{name}.toml")), &arm_file(&name, n));
        toml.push_str(&experiment(&name, n, 2.0));
    }
    toml.push_str(&experiment("nlink-150", 150, 0.5));
    write(&root.join("experiments/any-arm.toml"), &toml);

    catalog::register_paper_robots(&root.join("papers"));
    let files =
        reproduce::load_experiments(&root.join("experiments")).expect("the experiments load");
    let jobs: Vec<_> = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
    assert_eq!(jobs.len(), 4);
    for job in &jobs {
        let n = job.theta0.len();
        let record = run_job(job);
        let Outcome::Completed(m) = &record.run.outcome else {
            panic!("{}: {:?}", job.robot, record.run.outcome);
        };
        assert_eq!(m.drift.len(), n, "{}", job.robot);
        assert!(
            m.max_position_error < 1e-6,
            "{}: max position error {}",
            job.robot,
            m.max_position_error
        );
        assert!(
            m.drift_norm.is_finite() && m.min_sigma_j > 0.0,
            "{}",
            job.robot
        );
        assert_eq!(record.run.trace.last().unwrap().theta.len(), n);
    }
}

/// A URDF arm, no rebuild: a handwritten six-joint URDF (`robots/tests/fixtures/arm6.urdf`,
/// with inertials) and its robot file of the URDF form in a paper's `robots/` folder, run by an
/// experiment file through the one path, the exact optimum in the loop: kong2019's ZNN
/// (velocity level) and zhang2018's HL-JDF (acceleration level, the chain's H, c and g) on a
/// circle; both runs complete and track the circle.
#[test]
fn a_urdf_arm_runs_from_files() {
    let root = inputs::Scratch::unmade("urdf-arm");
    let robots = root.join("papers/urdfarm2026/robots");
    let urdf = Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots/tests/fixtures/arm6.urdf");
    write(
        &robots.join("arm6.urdf"),
        &std::fs::read_to_string(urdf).unwrap(),
    );
    write(
        &robots.join("sim-urdf-arm.toml"),
        "name = \"sim-urdf-arm\"\nsource = \"handwritten test arm\"\nurdf = \"arm6.urdf\"\n\
         base = \"base_link\"\ntip = \"tool0\"\ntool = [0.0, 0.0, 0.1]\n",
    );
    let toml =
        experiment("sim-urdf-arm", 6, 2.0).replace(&pose(6), "[0.2, -0.6, 1.2, -0.8, 0.5, 0.3]");
    let dynamic = as_hl_jdf(&toml, "kong2019-any-arm", "zhang2018-any-arm");
    write(
        &root.join("experiments/urdf-arm.toml"),
        &format!("paper = \"kong2019\"\ntitle = \"a URDF arm\"\n{toml}"),
    );
    write(
        &root.join("experiments/urdf-arm-dynamics.toml"),
        &format!("paper = \"zhang2018\"\ntitle = \"a URDF arm, torques\"\n{dynamic}"),
    );
    catalog::register_paper_robots(&root.join("papers"));
    let model = robots::robot_by_name("sim-urdf-arm").unwrap();
    assert!(model.has_dynamics());
    let files =
        reproduce::load_experiments(&root.join("experiments")).expect("the experiment loads");
    let jobs: Vec<_> = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
    assert_eq!(jobs.len(), 2);
    for job in &jobs {
        let record = run_job(job);
        let Outcome::Completed(m) = &record.run.outcome else {
            panic!("{}: {:?}", job.experiment, record.run.outcome);
        };
        assert_eq!(m.drift.len(), 6);
        assert!(
            m.max_position_error < 1e-6,
            "{}: max position error {}",
            job.experiment,
            m.max_position_error
        );
        assert!(m.drift_norm.is_finite() && m.min_sigma_j > 0.0);
    }
}

/// A tool offset and a base per experiment (`tool`, `base`; `robots::mounted`): the Jaco2 of
/// the papers holding its pen 0.1 m further along its tool frame's z, standing 0.2 m aside and
/// turned about x and z, runs kong2019's ZNN on a circle from an experiment file; the path starts
/// at the mounted pen tip, the run tracks it. A variant's own `tool` replaces the experiment's.
/// zhang2018's HL-JDF (dynamics) runs under a yaw and is refused under a tilt, naming `base`;
/// a tool offset on the Katana's closed form (no tool frame) is refused, naming `tool`.
#[test]
fn an_experiment_mounts_its_robot_with_a_tool_offset_and_a_base() {
    let theta0 = "[1.675, 2.79, -3.216, 4.187, -1.71, -2.95]";
    let mounted = |robot: &str, mount: &str, paper: &str| {
        let text = experiment(robot, 6, 2.0)
            .replace(&pose(6), theta0)
            .replace("id = \"kong2019-", &format!("id = \"{paper}-"))
            .replace(
                &format!("robot = \"{robot}\"\n"),
                &format!("robot = \"{robot}\"\n{mount}\n"),
            );
        format!("paper = \"{paper}\"\ntitle = \"mounted\"\n{text}")
    };
    let mount = "tool = [0.0, 0.0, 0.1]\nbase = { xyz = [0.2, 0.0, 0.0], rpy = [0.3, 0.0, 0.5] }";
    let file = reproduce::experiments_from_toml(&mounted("jaco2-pen", mount, "kong2019"))
        .expect("a mounted experiment loads");
    let job = &file.jobs().unwrap()[0];
    let pen = robots::robot_by_name("jaco2-pen").unwrap().robot;
    let theta: Vec<f64> = vec![1.675, 2.79, -3.216, 4.187, -1.71, -2.95];
    let tip = pen.position(&theta)
        + pen.orientation().unwrap().tool_rotation(&theta) * nalgebra::Vector3::new(0.0, 0.0, 0.1);
    let base = robots::Frame::from_xyz_rpy([0.2, 0.0, 0.0], [0.3, 0.0, 0.5]);
    let model = simulation::job_model(job).unwrap();
    assert!((model.robot.position(&theta) - base.transform_point(&tip)).norm() < 1e-14);
    let record = run_job(job);
    let Outcome::Completed(m) = &record.run.outcome else {
        panic!("mounted jaco2-pen: {:?}", record.run.outcome);
    };
    assert!(m.max_position_error < 1e-6, "{}", m.max_position_error);

    // A variant's tool replaces the experiment's.
    let text = mounted("jaco2-pen", mount, "kong2019").replace(
        "label = \"ZNN (eq. 22)\"",
        "label = \"ZNN (eq. 22)\"\ntool = [0.0, 0.05, 0.0]",
    );
    let file = reproduce::experiments_from_toml(&text).unwrap();
    assert_eq!(
        file.jobs().unwrap()[0].mount.unwrap().tool,
        [0.0, 0.05, 0.0]
    );

    // Dynamics: a yaw keeps gravity vertical, a tilt does not.
    let dynamic = |mount: &str| {
        mounted("jaco2-pen", mount, "zhang2018")
            .replace("ZNN (eq. 22)", "HL-JDF (zeta=0.6)")
            .replace(
                "{ kind = \"kong2019-znn\", mu = 1.0, k_p = 1.0 }",
                "{ kind = \"hl-jdf\", zeta = 0.6, alpha = 20.0, beta = 20.0, rho_v = 20.0, rho_p = 20.0 }",
            )
    };
    let yaw = "tool = [0.0, 0.0, 0.05]\nbase = { xyz = [0.1, 0.1, 0.0], rpy = [0.0, 0.0, 1.0] }";
    let file = reproduce::experiments_from_toml(&dynamic(yaw)).expect("a yaw loads");
    let record = run_job(&file.jobs().unwrap()[0]);
    assert!(
        matches!(record.run.outcome, Outcome::Completed(_)),
        "{:?}",
        record.run.outcome
    );
    let err = reproduce::experiments_from_toml(&dynamic(mount))
        .unwrap_err()
        .to_string();
    assert!(err.contains("base") && err.contains("gravity"), "{err}");

    // No tool frame, no tool offset; an out-of-range base is refused at load.
    let katana = experiment("katana6m180", 5, 2.0)
        .replace(&pose(5), "[1.2566, 1.5708, 0.0, -0.5236, 1.0472]");
    let katana = katana.replace(
        "robot = \"katana6m180\"\n",
        "robot = \"katana6m180\"\ntool = [0.0, 0.0, 0.1]\n",
    );
    let err =
        reproduce::experiments_from_toml(&format!("paper = \"kong2019\"\ntitle = \"t\"\n{katana}"))
            .unwrap_err()
            .to_string();
    assert!(
        err.contains("`tool`") && err.contains("katana6m180"),
        "{err}"
    );
    let far = mounted("jaco2-pen", "base = { xyz = [0.0, 0.0, 20.0] }", "kong2019");
    let err = reproduce::experiments_from_toml(&far)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("field `base`") || err.contains("base.xyz[2]"),
        "{err}"
    );
    assert!(err.contains("must be within [-10, 10] m"), "{err}");
}

/// The directory of the `example-robot-data` package's URDFs, asked of the interpreter in
/// `$DRIFTBENCH_PYTHON` (default `python3`); `None` after a SKIPPED line where it has no such
/// package, unless `DRIFTBENCH_REQUIRE_PINOCCHIO=1` (CI), where the test fails.
fn example_robot_data() -> Option<std::path::PathBuf> {
    let python = std::env::var("DRIFTBENCH_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let required = std::env::var("DRIFTBENCH_REQUIRE_PINOCCHIO").is_ok_and(|v| v == "1");
    let locate = "import importlib.metadata as m; print(m.distribution('example-robot-data')\
                  .locate_file('cmeel.prefix/share/example-robot-data/robots'))";
    let found = std::process::Command::new(&python)
        .args(["-c", locate])
        .output()
        .ok()
        .filter(|out| out.status.success())
        .map(|out| std::path::PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()))
        .filter(|dir| dir.join("ur_description/urdf/ur5_robot.urdf").is_file());
    if found.is_none() {
        assert!(
            !required,
            "DRIFTBENCH_REQUIRE_PINOCCHIO=1 but {python} has no example-robot-data"
        );
        use std::io::Write as _;
        let _ = writeln!(
            std::io::stderr().lock(),
            "SKIPPED: the UR5 of example-robot-data through the engine: {python} has no \
             example-robot-data (set DRIFTBENCH_PYTHON to an interpreter with it)"
        );
    }
    found
}

/// A URDF arm of `example-robot-data` (the UR5, `ur5_robot.urdf`, copied into a paper's
/// `robots/` folder beside its robot file of the URDF form), run from experiment files through
/// the engine with kong2019's ZNN (velocity level) and zhang2018's HL-JDF (acceleration level,
/// on the UR5's inertials), with a tool offset: both runs complete and track the circle.
#[test]
fn an_example_robot_data_ur5_runs_from_a_robot_file() {
    let Some(erd) = example_robot_data() else {
        return;
    };
    let root = inputs::Scratch::unmade("ur5");
    let robots = root.join("papers/ur5paper/robots");
    let urdf = std::fs::read_to_string(erd.join("ur_description/urdf/ur5_robot.urdf")).unwrap();
    write(&robots.join("ur5_robot.urdf"), &urdf);
    write(
        &robots.join("erd-ur5.toml"),
        "name = \"erd-ur5\"\nsource = \"example-robot-data's ur5_robot.urdf\"\n\
         urdf = \"ur5_robot.urdf\"\nbase = \"base_link\"\ntip = \"tool0\"\n",
    );
    let theta0 = "[0.3, -1.2, 1.5, -1.0, -1.4, 0.2]";
    let znn = experiment("erd-ur5", 6, 2.0)
        .replace(&pose(6), theta0)
        .replace(
            "robot = \"erd-ur5\"\n",
            "robot = \"erd-ur5\"\ntool = [0.0, 0.0, 0.1]\n",
        );
    let dynamic = as_hl_jdf(&znn, "id = \"kong2019-", "id = \"zhang2018-");
    write(
        &root.join("experiments/ur5.toml"),
        &format!("paper = \"kong2019\"\ntitle = \"UR5\"\n{znn}"),
    );
    write(
        &root.join("experiments/ur5-dynamics.toml"),
        &format!("paper = \"zhang2018\"\ntitle = \"UR5, torques\"\n{dynamic}"),
    );
    catalog::register_paper_robots(&root.join("papers"));
    let model = robots::robot_by_name("erd-ur5").unwrap();
    assert_eq!(model.dof(), 6);
    assert!(model.has_dynamics(), "the UR5's links carry inertials");
    let files =
        reproduce::load_experiments(&root.join("experiments")).expect("the experiments load");
    let jobs: Vec<_> = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
    assert_eq!(jobs.len(), 2);
    for job in &jobs {
        let record = run_job(job);
        let Outcome::Completed(m) = &record.run.outcome else {
            panic!("{}: {:?}", job.experiment, record.run.outcome);
        };
        assert!(
            m.max_position_error < 1e-6,
            "{}: max position error {}",
            job.experiment,
            m.max_position_error
        );
        assert!(m.drift_norm.is_finite() && m.min_sigma_j > 0.0);
    }
}

/// The ZNN experiment `znn` (kong2019 (22)) as zhang2018's HL-JDF, a torque scheme that needs the
/// arm's dynamics: its ids renamed from `from` to `to`, its name and scheme replaced.
fn as_hl_jdf(znn: &str, from: &str, to: &str) -> String {
    znn.replace(from, to)
        .replace("ZNN (eq. 22)", "HL-JDF (zeta=0.6)")
        .replace(
            "{ kind = \"kong2019-znn\", mu = 1.0, k_p = 1.0 }",
            "{ kind = \"hl-jdf\", zeta = 0.6, alpha = 20.0, beta = 20.0, rho_v = 20.0, rho_p = 20.0 }",
        )
}
