#![deny(missing_docs)]
//! driftbench's front door for code: the crates of the suite behind one name, with a
//! [`prelude`] and the three things a researcher does first.
//!
//! driftbench regenerates the tables of papers on drift-free redundancy resolution of robot arms
//! and scores each paper's recurrent "neural" or numerical QP solver against the exact optimum
//! x*(t) of the scheme's QP along the run. A *task* is an (experiment, variant) of the experiment
//! files: a robot, a path r*(t), a scheme (the QP min x'Px/2 + q'x s.t. A x = b, G x <= h,
//! l <= x <= u built at every (t, theta)) and a start pose theta(0). A run integrates the arm
//! thetadot = x[..n] coupled with its solver; its drift is theta(T) - theta(0) after one cycle
//! of a closed path, and its score is the distance |x - x*| at every accepted step.
//!
//! # A tour
//!
//! ## Declare a robot
//!
//! An arm is data: a robot file states its Denavit–Hartenberg table (`robots::robot_file`
//! states the format and its mathematics). The model's Jacobian is the geometric one,
//! J_j = z_{j-1} x (f - o_{j-1}); here it is checked against a central difference of f.
//!
//! ```
//! use driftbench::prelude::*;
//!
//! let text = r#"
//! name = "yaw-and-four-pitch"
//! source = "a doctest"
//! convention = "standard"
//! tool = [0.0, 0.0, 0.0]
//! [[joint]]
//! a = 0.0
//! alpha = 1.5707963267948966
//! d = 0.3
//! [[joint]]
//! a = 0.25
//! alpha = 0.0
//! d = 0.0
//! [[joint]]
//! a = 0.25
//! alpha = 0.0
//! d = 0.0
//! [[joint]]
//! a = 0.25
//! alpha = 0.0
//! d = 0.0
//! [[joint]]
//! a = 0.25
//! alpha = 0.0
//! d = 0.0
//! "#;
//! let spec = RobotSpec::parse("yaw-and-four-pitch.toml", text)?;
//! let arm = DataRobot::new(&spec);
//! assert_eq!(arm.dof(), 5);
//! let theta = [0.3, 1.2, -0.75, -0.75, -0.75];
//! let j = arm.jacobian_matrix(&theta);
//! let h = 1e-6;
//! for k in 0..5 {
//!     let (mut plus, mut minus) = (theta, theta);
//!     plus[k] += h;
//!     minus[k] -= h;
//!     let fd = (arm.position(&plus) - arm.position(&minus)) / (2.0 * h);
//!     assert!((fd - j.column(k)).norm() < 1e-8);
//! }
//! // A non-finite number is refused, naming the file and the field.
//! let bad = text.replacen("d = 0.3", "d = nan", 1);
//! assert!(RobotSpec::parse("bad.toml", &bad).is_err());
//! # Ok::<(), driftbench::robots::RobotFileError>(())
//! ```
//!
//! ## Run a network of your own on a task
//!
//! A network implements [`NeuralSolver`](prelude::NeuralSolver): its state y, and the
//! right-hand side ydot = F(t, y; QP). This one is a gradient network on the penalised energy
//! E(x) = x'Px/2 + q'x + (rho/2) |A x - b|^2, ydot = -gamma grad E(y), whose equilibrium is
//! within O(1/rho) of x*. [`run_with_network`] runs it on kong2019's ZNN scheme (eq. 22) along
//! the circle on the Katana, as the suite runs the paper's own networks: coupled with the arm,
//! integrated as the experiment file says, and scored against x* at every accepted step.
//!
//! ```
//! use driftbench::prelude::*;
//!
//! struct Gradient { gamma: f64, rho: f64, residual: DVector<f64> }
//!
//! impl NeuralSolver for Gradient {
//!     fn name(&self) -> String { "gradient (doctest)".into() }
//!     fn state_dim(&self, dims: QpDims) -> usize { dims.nx }
//!     fn rhs(&mut self, _t: f64, y: &[f64], qp: &Qp, _: Option<&Qp>, ydot: &mut [f64]) {
//!         let x = DVectorView::from_slice(y, y.len());
//!         self.residual.copy_from(&qp.b);
//!         self.residual.gemv(1.0, &qp.a, &x, -1.0); // A x - b
//!         let mut g = DVectorViewMut::from_slice(ydot, y.len());
//!         g.copy_from(&qp.q);
//!         g.gemv(1.0, &qp.p, &x, 1.0);
//!         g.gemv_tr(self.rho, &qp.a, &self.residual, 1.0);
//!         g *= -self.gamma;
//!     }
//! }
//!
//! let root = driftbench::project_root()?;
//! let job = driftbench::job(&root, "kong2019-circle", "znn-eq22", "znn")?;
//! let record = run_with_network(&job, &|dims: QpDims| -> Result<Box<dyn NeuralSolver>, _> {
//!     Ok(Box::new(Gradient { gamma: 1e3, rho: 1e2, residual: DVector::zeros(dims.n_eq) }))
//! });
//! let Outcome::Completed(m) = &record.run.outcome else { panic!("{:?}", record.run.outcome) };
//! let score = m.score.expect("the task is scored");
//! assert!(m.drift_norm.is_finite() && score.max_dx.is_finite());
//! # Ok::<(), driftbench::Error>(())
//! ```
//!
//! ## Score a trajectory made elsewhere
//!
//! A [`Trajectory`](prelude::Trajectory) is samples (t_k, theta_k) from MATLAB, Python or a
//! real arm; [`score_trajectory`](prelude::score_trajectory) gives it a run's metrics and its
//! distance to x*. The exact column's own trace scores with the run's drift, exactly.
//!
//! ```
//! use driftbench::prelude::*;
//!
//! let root = driftbench::project_root()?;
//! let job = driftbench::job(&root, "kong2019-circle", "znn-eq22", "exact")?;
//! let run = run_job(&job).run;
//! let trajectory = Trajectory {
//!     t: run.trace.iter().map(|p| p.t).collect(),
//!     theta: run.trace.iter().map(|p| p.theta.clone()).collect(),
//!     thetadot: None,
//! };
//! let scored = score_trajectory(&job, &trajectory).expect("a well-formed trajectory");
//! match (&run.outcome, &scored.run.outcome) {
//!     (Outcome::Completed(a), Outcome::Completed(b)) => assert_eq!(a.drift, b.drift),
//!     other => panic!("{other:?}"),
//! }
//! # Ok::<(), driftbench::Error>(())
//! ```
//!
//! # The crates behind it
//!
//! [`robots`] (kinematic models and robot files), [`spec`] (schemes and paths as data),
//! [`schemes`] (paths, the papers' schemes and their QPs), [`settings`] (the solvers' settings as data: network specifications, integrator
//! settings), [`solvers`] (the exact QP solvers, the papers' networks, the integrators),
//! [`catalog`] (experiment files, run ids), [`simulation`] (the engine:
//! runs and scoring) and [`records`] (the results files' rows). The command line (`reproduce`) and
//! the report are built on the same crates.

pub use catalog;
pub use records;
pub use robots;
pub use schemes;
pub use settings;
pub use simulation;
pub use solvers;
pub use spec;

use catalog::experiment::{load_dir, PaperFile};
use spec::RunSpec;
use std::path::{Path, PathBuf};

/// What the front door's own helpers can fail with; each wraps the layer that failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No project (a directory with `experiments/`) above the current directory.
    #[error(transparent)]
    Root(#[from] catalog::root::RootNotFound),
    /// An experiment file did not load.
    #[error(transparent)]
    Experiments(#[from] catalog::error::ExperimentFileError),
    /// No run of the experiment files has this key.
    #[error("no run {experiment} / {variant} / {solver} in the experiment files (that experiment's runs: {known})")]
    UnknownRun {
        /// The experiment id asked for.
        experiment: String,
        /// The variant id asked for.
        variant: String,
        /// The solver id asked for.
        solver: String,
        /// The runs of that experiment, as `variant / solver`, comma-separated (none: the
        /// experiment itself is unknown).
        known: String,
    },
}

/// The project root above the current directory: the directory holding `experiments/`,
/// `results/` and `report/`.
pub fn project_root() -> Result<PathBuf, Error> {
    Ok(catalog::root::from_current_dir()?)
}

/// Every run (job) of the experiment files in `root/experiments/`, each file checked as the
/// command line checks it before anything runs (the papers' own robot files,
/// `root/papers/<paper>/robots/*.toml`, registered first).
pub fn jobs(root: &Path) -> Result<Vec<RunSpec>, Error> {
    catalog::robot_files::register_paper_robots(&root.join("papers"));
    let files = load_dir(&root.join("experiments"), simulation::check_job)?;
    Ok(files.iter().flat_map(PaperFile::jobs).collect())
}

/// The run of the experiment files keyed (experiment id, variant id, solver id), its
/// [`RunKey`](spec::RunKey); the error lists the experiment's runs by their ids.
pub fn job(root: &Path, experiment: &str, variant: &str, solver: &str) -> Result<RunSpec, Error> {
    let all = jobs(root)?;
    let of_experiment: Vec<&RunSpec> = all.iter().filter(|j| j.experiment == experiment).collect();
    of_experiment
        .iter()
        .find(|j| j.variant_id == variant && j.solver.id() == solver)
        .map(|j| (*j).clone())
        .ok_or_else(|| Error::UnknownRun {
            experiment: experiment.to_string(),
            variant: variant.to_string(),
            solver: solver.to_string(),
            known: of_experiment
                .iter()
                .map(|j| format!("{} / {}", j.variant_id, j.solver.id()))
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// Runs the task of `job` with the network `network` builds in place of the job's own solver
/// (`simulation::run_job_with_network`).
pub fn run_with_network(
    job: &RunSpec,
    network: simulation::NetworkBuilder<'_>,
) -> simulation::RunRecord {
    simulation::run_job_with_network(job, network)
}

/// The names most code needs, in one import: `use driftbench::prelude::*;`.
pub mod prelude {
    pub use crate::run_with_network;
    pub use inputs::trajectory::Trajectory;
    pub use nalgebra::{DMatrix, DVector, DVectorView, DVectorViewMut, SMatrix, SVector, Vector3};
    pub use qp::{Qp, QpDims};
    pub use records::RunRow;
    pub use robots::DataRobot;
    pub use robots::RobotSpec;
    pub use robots::{JointLimits, Robot};
    pub use schemes::Scheme;
    pub use settings::IntegratorSettings;
    pub use settings::SolverSpec;
    pub use simulation::score_trajectory;
    pub use simulation::{run_job, RunRecord};
    pub use simulation::{Outcome, Run};
    pub use solvers::neural::NeuralSolver;
    pub use solvers::{QpSolver, QpStatus, SolverId};
    pub use spec::RunKey;
    pub use spec::RunSpec;
    pub use spec::SolverChoice;
    pub use spec::SolverKind;
}

#[cfg(test)]
mod tests {
    #[test]
    fn an_unknown_run_is_an_error_listing_the_experiments_runs() {
        let root = crate::project_root().expect("the tests run inside the project");
        let err = crate::job(&root, "kong2019-circle", "ZNN (eq. 22)", "znn")
            .expect_err("a variant is named by its id, not its label");
        let text = err.to_string();
        assert!(text.contains("znn-eq22 / znn"), "{text}");
        assert!(crate::job(&root, "kong2019-circle", "znn-eq22", "znn").is_ok());
        let none = crate::job(&root, "no-such-experiment", "v", "s").unwrap_err();
        assert!(matches!(none, crate::Error::UnknownRun { ref known, .. } if known.is_empty()));
    }
}
