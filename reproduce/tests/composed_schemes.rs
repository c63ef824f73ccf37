//! Schemes of one's own terms, from experiment files, through the one path:
//!
//! - a velocity-level scheme that no preset combines (velocity norm + infinity norm through an
//!   auxiliary variable + sign-power repetitive term + tracking feedback + bound conversion,
//!   every bound as rows of G) on the Jaco2 runs to the end and tracks the path, and at sampled
//!   instants of its run the exact path's answer (certified active set) equals Clarabel's and
//!   its auxiliary variable is the infinity norm of the command;
//! - a 5-joint planar arm (a robot file in the paper's folder) with the planar task: the
//!   certified active set answers every instant (no Clarabel fallback) and the run tracks the
//!   path; with the 3-D task on the same arm (a zero row of J) the active set falls back;
//! - the pose task (position and orientation, 6 rows) on the 7-joint Panda keeps the tool
//!   frame's orientation at the start pose's while the tool follows the path, its exact answer
//!   is Clarabel's, its dQP/dt is the central difference of its QP; on a robot without a tool
//!   frame, or in a preset scheme, the file is refused naming the file and the field.

use robots::robot_by_name;
use schemes::orientation_error;
use simulation::Outcome;
use simulation::{build_cyclic_parts, job_robot, run_job};
use solvers::ExactPath;
use solvers::ExactSolver;
use spec::RunSpec;
use std::path::Path;

fn write(path: &Path, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

/// The jobs of `experiments` (with `robots`: robot files of the paper's folder), in a fresh
/// directory named for `tag`.
fn jobs(tag: &str, robots: &[(&str, String)], experiments: &str) -> Vec<RunSpec> {
    load(tag, robots, experiments).expect("the experiments load")
}

/// The jobs of `experiments` or the load's error message, as [`jobs`].
fn load(tag: &str, robots: &[(&str, String)], experiments: &str) -> Result<Vec<RunSpec>, String> {
    let root = inputs::Scratch::unmade(tag);
    for (name, text) in robots {
        write(
            &root.join(format!("papers/composed2026/robots/{name}.toml")),
            text,
        );
    }
    write(&root.join("experiments/composed.toml"), experiments);
    catalog::register_paper_robots(&root.join("papers"));
    let files = reproduce::load_experiments(&root.join("experiments"));
    drop(root);
    files
        .map(|files| files.iter().flat_map(|f| f.jobs().unwrap()).collect())
        .map_err(|e| e.to_string())
}

const OWN_SCHEME: &str = r#"
paper = "kong2019"
title = "a scheme of one's own terms"

[[experiment]]
id = "kong2019-own-terms"
paper_output = "none"
robot = "jaco2-pen"
path = { name = "circle", duration = 3.0 }
theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]
exact_integrator = { method = "bdf", rtol = 1e-8, atol = 1e-10 }

[[experiment.variant]]
label = "own"

[experiment.variant.scheme]
kind = "composed"
level = "velocity"
name = "own (inf-norm + sign-power + feedback)"
bounds = "rows"

[[experiment.variant.scheme.terms]]
kind = "velocity-norm"
weight = 0.5

[[experiment.variant.scheme.terms]]
kind = "infinity-norm"
weight = 0.3

[[experiment.variant.scheme.terms]]
kind = "repetitive"
form = "sign-power"
lambda = 1.0
alpha = 0.5

[[experiment.variant.scheme.terms]]
kind = "tracking"
k_p = 5.0

[[experiment.variant.scheme.terms]]
kind = "bound-conversion"
gain = 20.0
"#;

#[test]
fn a_scheme_of_own_terms_runs_and_its_exact_answer_is_clarabels() {
    let jobs = jobs("kong2019-own-terms", &[], OWN_SCHEME);
    assert_eq!(jobs.len(), 1);
    let job = &jobs[0];
    let record = run_job(job);
    let Outcome::Completed(m) = &record.run.outcome else {
        panic!("{:?}", record.run.outcome);
    };
    assert!(m.max_position_error < 1e-5, "{}", m.max_position_error);
    assert_eq!(record.run.qp.fallbacks, 0, "{:?}", record.run.qp);

    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let (_, scheme) = build_cyclic_parts(job, robot, None, 1).unwrap();
    assert_eq!(scheme.name(), "own (inf-norm + sign-power + feedback)");
    let n = job.theta0.len();
    let mut qp = scheme.new_qp();
    let trace = &record.run.trace;
    let mut clarabel = ExactSolver::new();
    let mut checked = 0;
    for point in trace.iter().step_by((trace.len() / 25).max(1)) {
        scheme.build(point.t, &point.theta, &point.thetadot, &mut qp);
        let reference = clarabel.solve(&qp).expect("Clarabel solves the QP");
        let mut path = ExactPath::new(&qp);
        let x = path.solve(&qp).unwrap().clone();
        assert_eq!(path.stats.fallbacks, 0, "t = {}", point.t);
        let dx = (&x - &reference.x).amax();
        assert!(
            dx < 1e-6 * reference.x.amax().max(1.0),
            "t = {}: {dx}",
            point.t
        );
        // s = |thetadot|_inf at the optimum (its weight is positive).
        let inf = x.rows(0, n).amax();
        assert!(
            (x[n] - inf).abs() < 1e-8,
            "t = {}: s {} vs {inf}",
            point.t,
            x[n]
        );
        checked += 1;
    }
    assert!(checked >= 20, "{checked} instants");
}

/// A planar arm of `n` links of 0.3 m in the x-y plane (every z axis parallel), with joint
/// limits +-3 rad and velocity limits +-2 rad/s.
fn planar_arm(name: &str, n: usize) -> String {
    let mut s = format!(
        "name = \"{name}\"\nsource = \"a test arm\"\nconvention = \"standard\"\ntool = [0.0, 0.0, 0.0]\n"
    );
    for _ in 0..n {
        s.push_str(
            "\n[[joint]]\na = 0.3\nalpha = 0.0\nd = 0.0\ntheta_min = -3.0\ntheta_max = 3.0\n\
             velocity_min = -2.0\nvelocity_max = 2.0\n",
        );
    }
    s
}

/// An experiment of the planar arm with the tracking task `task`.
fn planar_experiment(id: &str, task: &str) -> String {
    format!(
        r#"
[[experiment]]
id = "{id}"
paper_output = "none"
robot = "planar-5"
path = {{ name = "circle", duration = 2.0 }}
theta0 = [0.2, 0.5, 0.4, 0.3, 0.2]
exact_integrator = {{ method = "bdf", rtol = 1e-8, atol = 1e-10 }}

[[experiment.variant]]
label = "{task}"

[experiment.variant.scheme]
kind = "composed"
level = "velocity"

[[experiment.variant.scheme.terms]]
kind = "velocity-norm"

[[experiment.variant.scheme.terms]]
kind = "repetitive"
lambda = 2.0

[[experiment.variant.scheme.terms]]
kind = "tracking"
task = "{task}"
k_p = 5.0

[[experiment.variant.scheme.terms]]
kind = "bound-conversion"
gain = 10.0
"#
    )
}

#[test]
fn a_planar_arm_with_the_planar_task_is_solved_by_the_active_set_alone() {
    let text = format!(
        "paper = \"kong2019\"\ntitle = \"a planar arm\"\n{}{}",
        planar_experiment("kong2019-planar-task", "planar"),
        planar_experiment("kong2019-position-task", "position")
    );
    let jobs = jobs(
        "planar-arm",
        &[("planar-5", planar_arm("planar-5", 5))],
        &text,
    );
    assert_eq!(jobs.len(), 2);
    let planar = run_job(&jobs[0]);
    let Outcome::Completed(m) = &planar.run.outcome else {
        panic!("{:?}", planar.run.outcome);
    };
    assert!(planar.run.qp.solves > 100, "{:?}", planar.run.qp);
    assert_eq!(planar.run.qp.fallbacks, 0, "{:?}", planar.run.qp);
    assert!(m.max_position_error < 1e-6, "{}", m.max_position_error);
    // The 3-D task on the same arm: J's z row is zero, and the certified active set gives up.
    let spatial = run_job(&jobs[1]);
    assert!(spatial.run.qp.fallbacks > 0, "{:?}", spatial.run.qp);
}

/// A pose task (`task = "pose"`, orientation the start pose's unless `extra` says otherwise)
/// on `robot` from `theta0`, with a velocity norm and the bound conversion.
fn pose_experiment(robot: &str, theta0: &str, extra: &str) -> String {
    format!(
        r#"
paper = "kong2019"
title = "a pose task"

[[experiment]]
id = "kong2019-pose-task"
paper_output = "none"
robot = "{robot}"
path = {{ name = "circle", duration = 3.0 }}
theta0 = {theta0}
exact_integrator = {{ method = "bdf", rtol = 1e-8, atol = 1e-10 }}

[[experiment.variant]]
label = "pose"

[experiment.variant.scheme]
kind = "composed"
level = "velocity"

[[experiment.variant.scheme.terms]]
kind = "velocity-norm"

[[experiment.variant.scheme.terms]]
kind = "tracking"
task = "pose"
k_p = 5.0
{extra}

[[experiment.variant.scheme.terms]]
kind = "bound-conversion"
gain = 10.0
"#
    )
}

const PANDA_READY: &str = "[0.0, -0.7853981633974483, 0.0, -2.356194490192345, 0.0, 1.5707963267948966, 0.7853981633974483]";

#[test]
fn a_pose_task_on_the_panda_holds_the_orientation_and_its_answer_is_clarabels() {
    let jobs = jobs("pose-task", &[], &pose_experiment("panda", PANDA_READY, ""));
    let job = &jobs[0];
    let record = run_job(job);
    let Outcome::Completed(m) = &record.run.outcome else {
        panic!("{:?}", record.run.outcome);
    };
    assert!(m.max_position_error < 1e-5, "{}", m.max_position_error);
    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let o = robot.orientation().expect("the Panda has a tool frame");
    let target = o.tool_rotation(&job.theta0);
    let (_, scheme) = build_cyclic_parts(job, robot.clone(), None, 1).unwrap();
    assert_eq!(
        scheme.dims().n_eq,
        6,
        "3 position rows and 3 orientation rows"
    );
    assert!(scheme.terms().iter().any(|t| t.contains("log(R_d R^T)")));
    let trace = &record.run.trace;
    // The arm moved (the orientation was held along a path, not at rest).
    let last = &trace.last().unwrap().theta;
    let moved = last
        .iter()
        .zip(&job.theta0)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(moved > 0.05, "the arm moved {moved} rad");
    let mut worst: f64 = 0.0;
    for point in trace {
        worst = worst.max(orientation_error(o, &target, &point.theta).norm());
    }
    assert!(worst < 1e-5, "orientation error {worst} rad");

    let mut qp = scheme.new_qp();
    let mut clarabel = ExactSolver::new();
    let mut checked = 0;
    for point in trace.iter().step_by((trace.len() / 20).max(1)) {
        scheme.build(point.t, &point.theta, &point.thetadot, &mut qp);
        let reference = clarabel.solve(&qp).expect("Clarabel solves the QP");
        let mut path = ExactPath::new(&qp);
        let x = path.solve(&qp).unwrap().clone();
        let dx = (&x - &reference.x).amax();
        assert!(
            dx < 1e-6 * reference.x.amax().max(1.0),
            "t = {}: {dx}",
            point.t
        );
        checked += 1;
    }
    assert!(checked >= 15, "{checked} instants");
}

/// The tracking term caches the position Jacobian between a QP and its derivative at the same
/// instant; a pose task's rows overwrite that buffer with the angular Jacobian, so dQP/dt
/// asked twice at one instant (or after a QP at another) must be what a fresh evaluation gives.
#[test]
fn the_pose_tasks_derivative_asked_again_at_one_instant_is_the_same() {
    let jobs = jobs(
        "pose-again",
        &[],
        &pose_experiment("panda", PANDA_READY, ""),
    );
    let job = &jobs[0];
    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let (_, scheme) = build_cyclic_parts(job, robot, None, 1).unwrap();
    let theta: Vec<f64> = job.theta0.iter().map(|a| a + 0.2).collect();
    let thetadot = [0.3, -0.2, 0.25, 0.1, -0.15, 0.05, 0.2];
    let t = 0.4;
    let dot_at = |scratch: &mut _| {
        let mut dot = scheme.new_qp();
        scheme.build_dot(t, &theta, &thetadot, &[], &mut dot, scratch);
        dot
    };
    let mut scratch = scheme.new_dot_scratch();
    let first = dot_at(&mut scratch);
    let again = dot_at(&mut scratch);
    let mut qp = scheme.new_qp();
    scheme.build(t + 0.1, &theta, &thetadot, &mut qp);
    let after_another = dot_at(&mut scratch);
    for (name, other) in [("again", &again), ("after another instant", &after_another)] {
        assert_eq!(first.a, other.a, "Adot {name}");
        assert_eq!(first.b, other.b, "bdot {name}");
    }
}

#[test]
fn the_pose_tasks_derivative_is_the_central_difference_of_its_qp() {
    let jobs = jobs("pose-dot", &[], &pose_experiment("panda", PANDA_READY, ""));
    let job = &jobs[0];
    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let (_, scheme) = build_cyclic_parts(job, robot, None, 1).unwrap();
    // Away from the start pose, so that the orientation error is not zero.
    let theta: Vec<f64> = job
        .theta0
        .iter()
        .zip([0.3, -0.2, 0.25, 0.1, -0.3, 0.2, 0.4])
        .map(|(a, b)| a + b)
        .collect();
    let thetadot = [0.3, -0.2, 0.25, 0.1, -0.15, 0.05, 0.2];
    let t = 0.7;
    let mut dot = scheme.new_qp();
    let mut scratch = scheme.new_dot_scratch();
    scheme.build_dot(t, &theta, &thetadot, &[], &mut dot, &mut scratch);
    let h = 1e-6;
    let at = |s: f64| {
        let th: Vec<f64> = theta
            .iter()
            .zip(&thetadot)
            .map(|(a, v)| a + s * v)
            .collect();
        let mut qp = scheme.new_qp();
        scheme.build(t + s, &th, &thetadot, &mut qp);
        qp
    };
    let (plus, minus) = (at(h), at(-h));
    let da = (&plus.a - &minus.a) / (2.0 * h);
    let db = (&plus.b - &minus.b) / (2.0 * h);
    assert!(
        (&da - &dot.a).amax() < 1e-6,
        "Adot {}",
        (&da - &dot.a).amax()
    );
    assert!(
        (&db - &dot.b).amax() < 1e-6,
        "bdot {}",
        (&db - &dot.b).amax()
    );
    assert!(
        dot.b.rows(3, 3).amax() > 1e-2,
        "the orientation rows move: {}",
        dot.b
    );
}

#[test]
fn a_pose_task_without_a_tool_frame_or_in_a_preset_is_refused_naming_file_and_field() {
    let err = load(
        "pose-nlink",
        &[],
        &pose_experiment("nlink-3", "[0.3, 0.4, 0.5]", ""),
    )
    .expect_err("nlink-3 has no tool frame");
    for part in [
        "composed.toml",
        "scheme",
        "task",
        "pose",
        "nlink-3",
        "panda",
    ] {
        assert!(err.contains(part), "{part} not in: {err}");
    }
    let err = load(
        "pose-given",
        &[],
        &pose_experiment("panda", PANDA_READY, "orientation = [0.1, 0.0, nan]"),
    )
    .expect_err("a rotation vector of finite numbers");
    assert!(
        err.contains("composed.toml") && err.contains("'orientation' = NaN"),
        "{err}"
    );
    let err = load(
        "pose-without-task",
        &[],
        &pose_experiment("panda", PANDA_READY, "orientation = [0.1, 0.0, 0.0]")
            .replace("task = \"pose\"", "task = \"position\""),
    )
    .expect_err("orientation needs the pose task");
    assert!(
        err.contains("composed.toml") && err.contains("'orientation'"),
        "{err}"
    );
    // A preset has no task field: the valid fields are listed.
    let preset = pose_experiment("panda", PANDA_READY, "")
        .split("[[experiment.variant.scheme.terms]]")
        .next()
        .unwrap()
        .replace(
            "kind = \"composed\"\nlevel = \"velocity\"",
            "kind = \"velocity-rmp\"\ntask = \"pose\"",
        );
    let err = load("pose-preset", &[], &preset).expect_err("presets take no task");
    assert!(
        err.contains("composed.toml") && err.contains("task") && err.contains("k_p"),
        "{err}"
    );
}

#[test]
fn a_given_orientation_is_reached_at_the_rate_of_k_p() {
    // Start 0.1 rad (about z) away from the given orientation: the error decays as exp(-k_p t).
    let jobs = jobs(
        "pose-given-run",
        &[],
        &pose_experiment("panda", PANDA_READY, ""),
    );
    let job = &jobs[0];
    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let o = robot.orientation().unwrap();
    let target = schemes::rotation_exp(&nalgebra::Vector3::new(0.0, 0.0, 0.1))
        * o.tool_rotation(&job.theta0);
    let phi = schemes::rotation_log(&target);
    let text = pose_experiment(
        "panda",
        PANDA_READY,
        &format!("orientation = [{}, {}, {}]", phi.x, phi.y, phi.z),
    );
    let jobs = self::jobs("pose-given-run2", &[], &text);
    let record = run_job(&jobs[0]);
    let Outcome::Completed(m) = &record.run.outcome else {
        panic!("{:?}", record.run.outcome);
    };
    assert!(m.max_position_error < 1e-5, "{}", m.max_position_error);
    for point in record.run.trace.iter().step_by(10) {
        let e = orientation_error(o, &target, &point.theta).norm();
        let expected = 0.1 * (-5.0 * point.t).exp();
        assert!(
            (e - expected).abs() < 1e-5,
            "t = {}: {e} vs {expected}",
            point.t
        );
    }
}

/// An acceleration-level scheme of terms on the Jaco2's cardioid (zhang2018's arm and path)
/// with the acceleration-limits term `limits` (TOML fields).
fn acceleration_experiment(limits: &str) -> String {
    format!(
        r#"
paper = "zhang2018"
title = "acceleration limits"

[[experiment]]
id = "zhang2018-acceleration-limits"
paper_output = "none"
robot = "jaco2-pen"
path = {{ name = "cardioid", duration = 8.0 }}
theta0 = [1.68, 2.81, -3.22, 4.19, -1.71, -2.65]

[[experiment.variant]]
label = "limited"

[experiment.variant.scheme]
kind = "composed"
level = "acceleration"

[[experiment.variant.scheme.terms]]
kind = "acceleration-norm"

[[experiment.variant.scheme.terms]]
kind = "drift-damping"
alpha = 20.0
beta = 20.0

[[experiment.variant.scheme.terms]]
kind = "tracking"
rho_v = 20.0
rho_p = 20.0

[[experiment.variant.scheme.terms]]
kind = "acceleration-limits"
{limits}
"#
    )
}

#[test]
fn acceleration_limits_bound_the_command_and_the_answer_is_clarabels() {
    // Without a binding limit the scheme's peak |thetaddot|; then a limit 10 % below it.
    let free = jobs(
        "acceleration-free",
        &[],
        &acceleration_experiment("a_max = 1e6"),
    );
    let free = run_job(&free[0]);
    let Outcome::Completed(f) = &free.run.outcome else {
        panic!("{:?}", free.run.outcome);
    };
    let a_max = 0.9 * f.peak_thetaddot.expect("an acceleration-level run");
    let jobs = jobs(
        "acceleration-limits",
        &[],
        &acceleration_experiment(&format!("a_max = {a_max}\nvelocity_gain = 10.0")),
    );
    let job = &jobs[0];
    let record = run_job(job);
    let Outcome::Completed(m) = &record.run.outcome else {
        panic!("{:?}", record.run.outcome);
    };
    assert!(m.max_position_error < 1e-4, "{}", m.max_position_error);
    let peak = m.peak_thetaddot.unwrap();
    assert!(peak <= a_max * (1.0 + 1e-9), "peak {peak} > a {a_max}");
    let model = robot_by_name(&job.robot).unwrap();
    let robot = job_robot(job, model.robot, model.dynamics.is_some()).unwrap();
    let (_, scheme) = build_cyclic_parts(job, robot, None, 1).unwrap();
    assert!(scheme
        .terms()
        .iter()
        .any(|t| t.starts_with("acceleration-limits (a=")));
    let n = job.theta0.len();
    let mut qp = scheme.new_qp();
    let mut clarabel = ExactSolver::new();
    let (mut checked, mut active) = (0, 0);
    let trace = &record.run.trace;
    for point in trace.iter().step_by((trace.len() / 200).max(1)) {
        scheme.build(point.t, &point.theta, &point.thetadot, &mut qp);
        let reference = clarabel.solve(&qp).expect("Clarabel solves the QP");
        let mut path = ExactPath::new(&qp);
        let x = path.solve(&qp).unwrap().clone();
        let dx = (&x - &reference.x).amax();
        assert!(
            dx < 1e-6 * reference.x.amax().max(1.0),
            "t = {}: {dx}",
            point.t
        );
        let peak = x.rows(0, n).amax();
        assert!(peak <= a_max + 1e-9, "t = {}: |thetaddot| {peak}", point.t);
        if peak > a_max - 1e-9 {
            active += 1;
        }
        checked += 1;
    }
    assert!(checked >= 100, "{checked} instants");
    assert!(active > 0, "the limit never binds at the sampled instants");
}

#[test]
fn acceleration_limits_are_refused_out_of_range_or_at_the_velocity_level() {
    let err = load("acc-zero", &[], &acceleration_experiment("a_max = 0.0")).unwrap_err();
    assert!(
        err.contains("composed.toml") && err.contains("'a_max' = 0"),
        "{err}"
    );
    let err = load(
        "acc-mu",
        &[],
        &acceleration_experiment("a_max = 1.0\nvelocity_gain = -1.0"),
    )
    .unwrap_err();
    assert!(err.contains("'velocity_gain' = -1"), "{err}");
    let velocity = pose_experiment("panda", PANDA_READY, "").replace("task = \"pose\"\n", "")
        + "\n[[experiment.variant.scheme.terms]]\nkind = \"acceleration-limits\"\na_max = 1.0\n";
    let err = load("acc-level", &[], &velocity).unwrap_err();
    assert!(
        err.contains("acceleration-limits") && err.contains("velocity level"),
        "{err}"
    );
}
