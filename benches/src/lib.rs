//! Shared setup of driftbench's criterion benches (`cargo bench -p driftbench-benches`).
//!
//! The bench files (`benches/*.rs`) only time things; everything they time is built here, once,
//! from the same sources the reproduction uses:
//!
//! * [`RepresentativeQp`] — one seeded QP of each paper's shape ([`QpShape`]), its time
//!   derivative and its exact optimum, plus a network state near that optimum
//!   ([`RepresentativeQp::network_state`]).
//! * [`paper_networks`] — the networks each paper runs, with the parameters of its experiment file
//!   (`experiments/<paper>.toml`), so the benches never restate a gain.
//! * [`ArmState`] and [`SchemeCase`] — a realistic arm state (an experiment's theta0 nudged, with
//!   nonzero velocity and acceleration) and each paper's scheme built at it as a run builds it.
//! * [`experiment_jobs`], [`find_job`], [`bench_cases`] — jobs of the experiment files, by id;
//!   what the benches run is data (`benches/cases.toml`).
//! * [`allocations_per_call`], [`report_allocations`] — how many allocations one timed call
//!   makes, counted by the workspace's one counting allocator (crate `alloc-count`, which
//!   linking this crate installs in every bench binary).
//! * [`fast_config`], [`whole_run_config`] — criterion settings that keep the full
//!   `cargo bench -p driftbench-benches` to a few minutes on two cores.
//!
//! Beside them, [`telemetry`]: the suite's measurements of itself (its clock, build, phases,
//! profiles and speed-up over earlier revisions; `benches/results/`, `benches/REPORT.md`),
//! kept out of the reproduction's results.

pub mod telemetry;

use std::sync::Arc;
use std::time::Duration;

use criterion::Criterion;
use nalgebra::DVector;
use reproduce::load_experiments;
use robots::{Dynamics, Jaco2, Katana6m180, Robot};
use schemes::build_scheme;
use schemes::paths::{build_path, Path};
use schemes::Scheme;
use settings::SolverSpec;
use solvers::neural::NeuralSolver;
use solvers::{random_qp, ExactSolver, Qp, QpShape};
use spec::RunSpec;
use spec::SolverChoice;

// ---------------------------------------------------------------------------------------------
// Criterion settings
// ---------------------------------------------------------------------------------------------

/// Settings for the micro benches (one network evaluation, one Clarabel solve, one kinematic
/// call): 0.5 s warm-up, 1.5 s measurement, 50 samples. Command-line flags (`--quick`,
/// `--measurement-time`, ...) still override them (criterion applies them after this).
pub fn fast_config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(50)
}

/// Settings for whole runs (0.002 to 0.35 s each): criterion's minimum of 10 samples, 1 s warm-up
/// and 4 s measurement. Use with [`criterion::SamplingMode::Flat`] on the group.
pub fn whole_run_config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4))
        .sample_size(10)
}

// ---------------------------------------------------------------------------------------------
// Representative QPs
// ---------------------------------------------------------------------------------------------

/// Seed of the representative QP of every shape ([`solvers::random_qp()`]); for
/// [`QpShape::Jia2019`] it draws a finite varpi, as the papers' runs have.
pub const QP_SEED: u64 = 1;

/// Time at which networks are evaluated: the exponential gains (VP-RNN-PF, VP-CDNN) are then
/// gamma e, a mid-run value.
pub const EVAL_TIME: f64 = 1.0;

/// One QP of a paper's shape with everything a network evaluation needs.
#[derive(Clone, Debug)]
pub struct RepresentativeQp {
    pub shape: QpShape,
    /// `random_qp(shape, QP_SEED)`.
    pub qp: Qp,
    /// A time derivative with the shape's structure: `random_qp(shape, QP_SEED + 1) - qp`
    /// field by field (structural zeros stay zero), 0 wherever either bound is infinite.
    pub qp_dot: Qp,
    /// Clarabel's optimum of `qp`.
    pub x_star: DVector<f64>,
}

impl RepresentativeQp {
    /// Builds the QP of `shape`, its derivative and its optimum (panics if Clarabel fails,
    /// which the seeds are chosen not to make it do).
    pub fn new(shape: QpShape) -> Self {
        let qp = random_qp(shape, QP_SEED);
        let next = random_qp(shape, QP_SEED + 1);
        let diff = |a: f64, b: f64| {
            if a.is_finite() && b.is_finite() {
                b - a
            } else {
                0.0
            }
        };
        let mut qp_dot = qp.clone();
        qp_dot.p.zip_apply(&next.p, |a, b| *a = diff(*a, b));
        qp_dot.q.zip_apply(&next.q, |a, b| *a = diff(*a, b));
        qp_dot.a.zip_apply(&next.a, |a, b| *a = diff(*a, b));
        qp_dot.b.zip_apply(&next.b, |a, b| *a = diff(*a, b));
        qp_dot.g.zip_apply(&next.g, |a, b| *a = diff(*a, b));
        qp_dot.h.zip_apply(&next.h, |a, b| *a = diff(*a, b));
        qp_dot.lower.zip_apply(&next.lower, |a, b| *a = diff(*a, b));
        qp_dot.upper.zip_apply(&next.upper, |a, b| *a = diff(*a, b));
        let x_star = ExactSolver::new()
            .solve(&qp)
            .unwrap_or_else(|e| panic!("representative {} QP: Clarabel failed: {e}", shape.paper()))
            .x;
        Self {
            shape,
            qp,
            qp_dot,
            x_star,
        }
    }

    /// All four shapes, in [`QpShape::ALL`] order.
    pub fn all() -> Vec<Self> {
        QpShape::ALL.iter().map(|&s| Self::new(s)).collect()
    }

    /// A state of `net` mid-convergence: the primal part is the optimum offset by 1e-3 * sin(i+1)
    /// (so no projection or penalty sits exactly on a kink), the multipliers are at their initial
    /// value 0.
    pub fn network_state(&self, net: &dyn NeuralSolver) -> Vec<f64> {
        let mut y = vec![0.0; net.state_dim(self.qp.dims())];
        for (i, x) in self.x_star.iter().enumerate() {
            y[i] = x + 1e-3 * ((i + 1) as f64).sin();
        }
        y
    }

    /// The derivative to hand to `net.rhs` / `net.jacobian`: `Some` only if the network needs it.
    pub fn qp_dot_for(&self, net: &dyn NeuralSolver) -> Option<&Qp> {
        net.needs_qp_dot().then_some(&self.qp_dot)
    }
}

// ---------------------------------------------------------------------------------------------
// Networks and jobs of the experiment files
// ---------------------------------------------------------------------------------------------

/// Every job of every file in `experiments/` (panics on an unreadable file: the reproduction's
/// own tests report those).
pub fn experiment_jobs() -> Vec<RunSpec> {
    let dir = catalog::root_from_current_dir()
        .unwrap()
        .join("experiments");
    load_experiments(&dir)
        .unwrap_or_else(|e| panic!("loading {}: {e}", dir.display()))
        .iter()
        .flat_map(|f| f.jobs().expect("the runs of the experiment files"))
        .collect()
}

/// The job with key `experiment / variant / solver` (ids, e.g. `jia2019-star / vltco /
/// exact`).
pub fn find_job(jobs: &[RunSpec], experiment: &str, variant: &str, solver: &str) -> RunSpec {
    let key = spec::RunKey::from_ids(experiment, variant, solver)
        .unwrap_or_else(|e| panic!("{experiment} / {variant} / {solver}: {e}"));
    jobs.iter()
        .find(|j| j.key() == key)
        .cloned()
        .unwrap_or_else(|| panic!("no job {experiment} / {variant} / {solver} in experiments/"))
}

/// A benchmark id for a display name: `VP-RNN-PF (power-sigmoid)` -> `VP-RNN-PF-power-sigmoid`,
/// `FP-CDNN (perturbed A_D=1, A_s=1.5)` -> `FP-CDNN-perturbed`, `exact (Clarabel)` ->
/// `exact-Clarabel`.
pub fn bench_id(display_name: &str) -> String {
    let s = display_name.replace(" (", "-").replace(')', "");
    s.split([' ', ',']).next().unwrap_or_default().to_string()
}

/// The networks of the paper whose shape is `shape`, each once (first occurrence by display name,
/// in file order) with the parameters its experiment file gives: LVI-PDNN for jia2019;
/// VP-RNN-PF (linear, sinh, power-sigmoid) and S-LVI-PDNN for zhong2021; FP-CDNN and the
/// perturbed FP-/VP-CDNN for zhang2018; FTNN and ZNN for kong2019.
pub fn paper_networks(jobs: &[RunSpec], shape: QpShape) -> Vec<(String, SolverSpec)> {
    let mut out: Vec<(String, SolverSpec)> = Vec::new();
    // The paper's own experiments, not the parameter sweeps beside them.
    for j in jobs
        .iter()
        .filter(|j| j.paper == shape.paper() && !j.experiment.ends_with("-sweep"))
    {
        if let SolverChoice::Neural(spec) = &j.solver {
            let name = spec.display_name();
            if !out.iter().any(|(n, _)| *n == name) {
                out.push((name, spec.clone()));
            }
        }
    }
    out
}

/// What the benches run, declared in `benches/`[`CASES_FILE`] by the experiment files' ids.
#[derive(Clone, Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BenchCases {
    /// The whole runs `runs.rs` times (`experiment / variant / solver`).
    pub runs: Vec<String>,
    /// The Jaco2 schemes `kinematics.rs` builds.
    pub jaco2_schemes: Vec<SchemeRef>,
    /// The Katana schemes `kinematics.rs` builds.
    pub katana_schemes: Vec<SchemeRef>,
}

/// A scheme bench: its label and the task (`experiment / variant`) whose scheme it builds.
#[derive(Clone, Debug, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SchemeRef {
    pub label: String,
    pub task: String,
}

/// The benches' cases file, relative to the project root.
pub const CASES_FILE: &str = "benches/cases.toml";

/// The cases of [`CASES_FILE`] (panics with the file's name when it is missing or malformed:
/// benches have no user to report to).
pub fn bench_cases() -> BenchCases {
    let path = catalog::root_from_current_dir().unwrap().join(CASES_FILE);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("reading {}: {e}", path.display()));
    toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The job of a run key written `experiment / variant / solver`.
pub fn find_run(jobs: &[RunSpec], key: &str) -> RunSpec {
    let k = spec::RunKey::parse(key).unwrap_or_else(|e| panic!("{CASES_FILE}: {key:?}: {e}"));
    find_job(jobs, &k.experiment, &k.variant, &k.solver)
}

/// The exact column's job of each scheme reference.
fn scheme_jobs<'a>(
    jobs: &'a [RunSpec],
    refs: &'a [SchemeRef],
) -> impl Iterator<Item = (&'a str, RunSpec)> + 'a {
    refs.iter().map(|r| {
        let t = spec::TaskKey::parse(&r.task)
            .unwrap_or_else(|e| panic!("{CASES_FILE}: {:?}: {e}", r.task));
        (
            r.label.as_str(),
            find_job(jobs, &t.experiment, &t.variant, spec::EXACT_ID),
        )
    })
}

// ---------------------------------------------------------------------------------------------
// Arm states and schemes
// ---------------------------------------------------------------------------------------------

/// A realistic arm state: an experiment's theta0 moved by 0.05 sin(i+1) rad, with
/// thetadot_i = 0.2 sin(i+1) rad/s and thetaddot_i = 0.5 cos(i+1) rad/s^2 (the papers' joint
/// speeds are of this order), at t = [`EVAL_TIME`].
#[derive(Clone, Debug, PartialEq)]
pub struct ArmState {
    pub t: f64,
    pub theta: Vec<f64>,
    pub thetadot: Vec<f64>,
    pub thetaddot: Vec<f64>,
}

impl ArmState {
    /// The state near `job.theta0` (one entry per joint of the job's robot).
    pub fn near_start(job: &RunSpec) -> Self {
        let n = job.theta0.len();
        let s = |i: usize| ((i + 1) as f64).sin();
        Self {
            t: EVAL_TIME,
            theta: (0..n).map(|i| job.theta0[i] + 0.05 * s(i)).collect(),
            thetadot: (0..n).map(|i| 0.2 * s(i)).collect(),
            thetaddot: (0..n).map(|i| 0.5 * ((i + 1) as f64).cos()).collect(),
        }
    }
}

/// The Jaco2 model an experiment names (`jaco2-pen`, `jaco2`, `jaco2-hand`), as `run_job` builds it.
pub fn jaco2_model(name: &str) -> Jaco2 {
    match name {
        "jaco2-pen" => Jaco2::pen(),
        "jaco2" => Jaco2::kinova(),
        "jaco2-hand" => Jaco2::hand(),
        other => panic!("not a Jaco2 model: {other}"),
    }
}

/// A paper's scheme built as `run_job` builds it (robot, path starting at f(theta_ref), scheme of
/// the job's spec), with a realistic state to build its QP at.
pub struct SchemeCase {
    /// Bench id, e.g. `jia2019-VLTCO`.
    pub label: String,
    pub scheme: Box<dyn Scheme>,
    pub state: ArmState,
}

impl SchemeCase {
    /// Builds the scheme of `job` on `robot` (and `dynamics`, for zhang2018), named `label`.
    pub fn new(
        label: &str,
        job: &RunSpec,
        robot: Arc<dyn Robot>,
        dynamics: Option<Arc<dyn Dynamics>>,
    ) -> Self {
        let theta_ref = &job.theta_ref;
        let path: Arc<dyn Path> = Arc::from(
            build_path(&job.path, robot.position(theta_ref))
                .unwrap_or_else(|e| panic!("{}: {e}", job.key())),
        );
        let scheme = build_scheme(&job.scheme, robot, dynamics, path, theta_ref)
            .unwrap_or_else(|e| panic!("{}: {e}", job.key()));
        Self {
            label: label.to_string(),
            scheme,
            state: ArmState::near_start(job),
        }
    }

    /// Overwrites `qp` with the scheme's QP at the case's state.
    pub fn build(&self, qp: &mut Qp) {
        let s = &self.state;
        self.scheme.build(s.t, &s.theta, &s.thetadot, qp);
    }

    /// Overwrites `qp_dot` with the QP's time derivative at the case's state.
    pub fn build_dot(&self, qp_dot: &mut Qp, scratch: &mut qp::QpDotScratch) {
        let s = &self.state;
        self.scheme
            .build_dot(s.t, &s.theta, &s.thetadot, &s.thetaddot, qp_dot, scratch);
    }
}

/// The Jaco2 schemes of [`BenchCases::jaco2_schemes`], each with the Jaco2 model its job names.
pub fn jaco2_scheme_cases(jobs: &[RunSpec]) -> Vec<SchemeCase> {
    let cases = bench_cases();
    scheme_jobs(jobs, &cases.jaco2_schemes)
        .map(|(label, job)| {
            let arm = Arc::new(jaco2_model(&job.robot));
            SchemeCase::new(label, &job, arm.clone(), Some(arm))
        })
        .collect()
}

/// The Katana schemes of [`BenchCases::katana_schemes`].
pub fn katana_scheme_cases(jobs: &[RunSpec]) -> Vec<SchemeCase> {
    let cases = bench_cases();
    scheme_jobs(jobs, &cases.katana_schemes)
        .map(|(label, job)| SchemeCase::new(label, &job, Arc::new(Katana6m180::new()), None))
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Allocation counting
// ---------------------------------------------------------------------------------------------

/// Allocations per call of `f` on this thread, averaged over 10 calls after one uncounted
/// call ([`alloc_count::count`]; linking this crate installs its counting allocator).
pub fn allocations_per_call(mut f: impl FnMut()) -> f64 {
    f();
    let n = alloc_count::count(|| {
        for _ in 0..10 {
            f();
        }
    });
    n as f64 / 10.0
}

/// Prints `allocations/call <id>: n` to stderr (criterion's report goes to stdout).
pub fn report_allocations(id: &str, f: impl FnMut()) {
    eprintln!("allocations/call {id}: {}", allocations_per_call(f));
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    #[test]
    fn every_shape_has_its_networks_and_they_evaluate() {
        let jobs = experiment_jobs();
        let expected = [
            (QpShape::Jia2019, 1),
            (QpShape::Zhong2021, 4),
            (QpShape::Zhang2018, 3),
            (QpShape::Kong2019, 3),
        ];
        for (shape, n) in expected {
            let rep = RepresentativeQp::new(shape);
            let nets = paper_networks(&jobs, shape);
            assert_eq!(nets.len(), n, "{shape:?}: {nets:?}");
            for (name, spec) in nets {
                let mut net = solvers::neural::build_solver(&spec, rep.qp.dims()).unwrap();
                let y = rep.network_state(net.as_ref());
                let mut ydot = vec![0.0; y.len()];
                net.rhs(
                    EVAL_TIME,
                    &y,
                    &rep.qp,
                    rep.qp_dot_for(net.as_ref()),
                    &mut ydot,
                );
                assert!(ydot.iter().all(|v| v.is_finite()), "{name}: {ydot:?}");
                let mut jac = DMatrix::zeros(y.len(), y.len());
                assert!(
                    net.jacobian(
                        EVAL_TIME,
                        &y,
                        &rep.qp,
                        rep.qp_dot_for(net.as_ref()),
                        &mut jac
                    ),
                    "{name}"
                );
            }
        }
    }

    #[test]
    fn run_cases_and_schemes_exist() {
        let jobs = experiment_jobs();
        for key in bench_cases().runs {
            find_run(&jobs, &key);
        }
        assert_eq!(jaco2_scheme_cases(&jobs).len(), 3);
        assert_eq!(katana_scheme_cases(&jobs).len(), 2);
    }

    #[test]
    fn bench_ids() {
        assert_eq!(
            bench_id("VP-RNN-PF (power-sigmoid)"),
            "VP-RNN-PF-power-sigmoid"
        );
        assert_eq!(
            bench_id("FP-CDNN (perturbed A_D=1, A_s=1.5)"),
            "FP-CDNN-perturbed"
        );
        assert_eq!(bench_id("exact (Clarabel)"), "exact-Clarabel");
        assert_eq!(bench_id("LVI-PDNN"), "LVI-PDNN");
    }
}
