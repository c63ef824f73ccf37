#![deny(missing_docs)]
//! driftbench's front door for code: a [`prelude`] of the names a user needs, one module per
//! thing a user does, and a tour of the four things a researcher does first.
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
//! An arm is data: a robot file states its Denavit–Hartenberg table ([`robot::RobotSpec`]
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
//! # Ok::<(), driftbench::robot::RobotFileError>(())
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
//! ## Read the stored runs
//!
//! A reproduction's `results/runs.csv` holds one [`RunRow`](prelude::RunRow) per run: its key,
//! outcome, drift per joint, errors and the score against x*. [`read_runs`] reads it, refusing
//! a file that is not this version's schema rather than returning fewer rows; a paper's runs
//! are [`paper`].
//!
//! ```
//! use driftbench::prelude::*;
//!
//! let root = driftbench::project_root()?;
//! let rows = read_runs(&root.join("results/runs.csv"))?;
//! let kong2019: PaperId = "kong2019".parse().expect("an id");
//! let runs = driftbench::paper(&root, &kong2019)?;
//! assert!(runs.iter().all(|r| rows.iter().any(|row| row.key() == r.key())));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # What is here
//!
//! The [`prelude`] holds the handful of names the tour uses: load a paper's tasks
//! ([`project_root`], [`paper`], [`job`]), run one ([`run_job`](prelude::run_job),
//! [`run_with_network`]), read the runs ([`read_runs`], [`RunRow`](prelude::RunRow)), write and
//! register a solver ([`NeuralSolver`](prelude::NeuralSolver), [`QpSolver`](prelude::QpSolver),
//! [`solver::register`]) and score a trajectory. Beyond it, one module per thing a user does,
//! each re-exporting the suite's own types under one path: [`robot`] (kinematic models and
//! robot files), [`qp`] (the QP and the solver seam), [`solver`] (the QP solvers' registry,
//! the networks and the conformance kit), [`run`] (a run's description, running it, its
//! record), [`results`] (the rows of `results/`) and [`score`] (trajectories made elsewhere).
//! The crates behind them (robots, qp, spec, settings, solvers, catalog, simulation, records,
//! store, inputs) are not re-exported whole: the command line (`reproduce`) and the
//! report are built on them, and what a user of the library needs is named here.

use catalog::PaperFile;
use reproduce::load_experiments;
use spec::ids::PaperId;
use spec::RunSpec;
use std::path::{Path, PathBuf};

pub use store::read_runs;

/// What the front door's own helpers can fail with; each wraps the layer that failed.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No project (a directory with `experiments/`) above the current directory.
    #[error(transparent)]
    Root(#[from] catalog::RootNotFound),
    /// An experiment file did not load.
    #[error(transparent)]
    Experiments(#[from] catalog::ExperimentFileError),
    /// No experiment file belongs to this paper.
    #[error("no experiment file of paper {paper} in experiments/ (the papers: {known})")]
    UnknownPaper {
        /// The paper asked for.
        paper: PaperId,
        /// The papers of the experiment files, comma-separated.
        known: String,
    },
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
    Ok(catalog::root_from_current_dir()?)
}

/// Every run (job) of the experiment files in `root/experiments/`, each file checked as the
/// command line checks it before anything runs: read and validated as data by crate
/// `catalog`, then every run built by the engine's setup, a failure placed at its field (the
/// command line's own loader, `reproduce::load_experiments`). The papers' own
/// robot files, `root/papers/<paper>/robots/*.toml`, are registered first.
pub fn jobs(root: &Path) -> Result<Vec<RunSpec>, Error> {
    Ok(files(root)?
        .iter()
        .flat_map(PaperFile::iter_jobs)
        .collect::<Result<_, _>>()?)
}

/// The runs of the experiment files of `paper` (as [`jobs`] reads them); a paper that no file
/// belongs to is an error naming the papers there are.
pub fn paper(root: &Path, paper: &PaperId) -> Result<Vec<RunSpec>, Error> {
    let files = files(root)?;
    let of_paper: Vec<&PaperFile> = files.iter().filter(|f| f.paper == paper.as_str()).collect();
    if of_paper.is_empty() {
        let mut known: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
        known.sort_unstable();
        known.dedup();
        return Err(Error::UnknownPaper {
            paper: paper.clone(),
            known: known.join(", "),
        });
    }
    Ok(of_paper
        .into_iter()
        .flat_map(PaperFile::iter_jobs)
        .collect::<Result<_, _>>()?)
}

/// The experiment files of `root/experiments/`, each checked as the command line checks it,
/// the papers' own robot files registered first.
fn files(root: &Path) -> Result<Vec<PaperFile>, Error> {
    catalog::register_paper_robots(&root.join("papers"));
    Ok(load_experiments(&root.join("experiments"))?)
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
/// (`simulation::run::run_job_with_network`).
pub fn run_with_network(job: &RunSpec, network: run::NetworkBuilder<'_>) -> run::RunRecord {
    simulation::run_job_with_network(job, network)
}

/// The names the tour uses, in one import: `use driftbench::prelude::*;`. Load a paper's
/// tasks, run one, read the runs, write and register a solver, score a trajectory; and the
/// vectors and matrices a network's right-hand side is written with.
pub mod prelude {
    pub use crate::qp::{Qp, QpDims, QpSolver, QpStatus};
    pub use crate::results::RunRow;
    pub use crate::robot::{DataRobot, Robot, RobotSpec};
    pub use crate::run::{run_job, Outcome, Run, RunKey, RunRecord, RunSpec};
    pub use crate::score::{score_trajectory, Trajectory};
    pub use crate::solver::NeuralSolver;
    pub use crate::{job, paper, project_root, read_runs, run_with_network};
    pub use nalgebra::{DMatrix, DVector, DVectorView, DVectorViewMut};
    pub use spec::ids::PaperId;
}

pub mod robot {
    //! Robots: the model every run drives ([`Robot`]), arms stated as data (a robot file's
    //! Denavit-Hartenberg table, [`RobotSpec`], made a model by [`DataRobot`]; a URDF chain,
    //! [`ChainRobot`]) and the suite's built-in arms.

    pub use robots::{ChainRobot, DataRobot, Jaco2, JointLimits, Katana6m180, NLink, Panda, Robot};
    pub use robots::{RobotFileError, RobotSpec};
}

pub mod qp {
    //! The QP of every instant, min x'Px/2 + q'x s.t. A x = b, G x <= h, l <= x <= u ([`Qp`], its
    //! sizes [`QpDims`], multipliers and KKT residuals), and the one seam a QP solver implements
    //! ([`QpSolver`]).

    pub use ::qp::{
        KktResiduals, Qp, QpDims, QpDuals, QpSolve, QpSolver, QpSolverError, QpStatus, SolverId,
    };
}

pub mod solver {
    //! Solvers of your own: a QP solver registered by id ([`register`], after which experiment
    //! files may name it), a recurrent network ([`NeuralSolver`]), and the conformance kit both
    //! are held to ([`conformance`]).

    pub use solvers::conformance;
    pub use solvers::neural::NeuralSolver;
    pub use solvers::registry::{
        register, BoxedQpSolver, Constructor, QpSolverInfo, QpSolverSettings, RegistryError,
    };
    pub use solvers::{random_qp, QpShape};
}

pub mod run {
    //! A run: its description ([`RunSpec`], keyed by [`RunKey`]: experiment, variant and solver
    //! ids), running it ([`run_job`]; with a network of your own, [`crate::run_with_network`]) and
    //! what it gives ([`RunRecord`]: the [`Run`] with its [`Outcome`]).

    pub use settings::IntegratorSettings;
    pub use settings::SolverSpec;
    pub use simulation::{run_job, NetworkBuilder, RunRecord};
    pub use simulation::{Outcome, Run};
    pub use spec::ids::{ExperimentId, IdError, PaperId, SolverId, VariantId};
    pub use spec::SolverKind;
    pub use spec::{RunKey, TaskKey};
    pub use spec::{RunSpec, SetupError, SolverChoice};
}

pub mod results {
    //! The rows of `results/`: a run's row of `runs.csv` ([`RunRow`]), read by [`read_runs`].

    pub use crate::read_runs;
    pub use records::RunRow;
    pub use store::RunsError;
}

pub mod score {
    //! A trajectory made elsewhere (MATLAB, Python, a real arm): samples (t_k, theta_k)
    //! ([`Trajectory`], read from CSV or a MAT-file by [`read`]) scored as a run is
    //! ([`score_trajectory`]).

    pub use inputs::trajectory::{read, ReadError, Trajectory};
    pub use simulation::{score_trajectory, TrajectoryError};
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

    #[test]
    fn a_paper_is_its_files_runs_and_an_unknown_one_names_the_papers() {
        let root = crate::project_root().expect("the tests run inside the project");
        let kong2019 = "kong2019".parse().unwrap();
        let runs = crate::paper(&root, &kong2019).unwrap();
        let all = crate::jobs(&root).unwrap();
        let of_paper: Vec<_> = all.iter().filter(|j| j.paper == "kong2019").collect();
        assert!(!runs.is_empty());
        assert_eq!(runs.len(), of_paper.len());
        let err = crate::paper(&root, &"nosuchpaper".parse().unwrap()).unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("nosuchpaper") && text.contains("jia2019, kong2019"),
            "{text}"
        );
    }
}
