//! The tasks as Python objects: one per (experiment, variant) of the experiment files, with the
//! runs the suite makes of it (the exact column and the papers' networks), everything a
//! network run of the task uses (robot, path, poses, scheme, the variant's network integrator,
//! scoring and network start) and the shape of the QP the scheme poses at every instant.

use crate::error::{NoSolver, TaskError};
use crate::network::PyQpDims;
use pyo3::prelude::*;
use reproduce::load_experiments;
use serde::Serialize;
use simulation::qp_shape;
use spec::Level;
use spec::RunSpec;
use spec::SolverChoice;
use std::path::Path;

/// One task of the suite: a scheme on a path with a robot, as an experiment file's variant
/// defines it. Attributes are read-only; `path`, `scheme` and `integrator` are dicts in the
/// experiment files' own fields.
///
/// At every instant the scheme poses the QP
/// `min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  lower <= x <= upper` with `nx` unknowns,
/// `n_eq` equality rows and `n_in` inequality rows (`dims`, what a network's `state_dim` and
/// `handles` get). x starts with the joint command: its first `dof` entries are thetadot
/// (`level == "velocity"`) or thetaddot (`level == "acceleration"`, zhang2018); the remaining
/// `nx - dof` entries (`n_aux`) are the scheme's auxiliary variables, e.g. the bound
/// p = |thetadot|_inf of the infinity norm on the jia2019 and zhong2021 tasks (nx = dof + 1).
/// Only x[:dof] drives the arm; the score compares x[:dof] with the exact optimum's.
#[pyclass(name = "Task", module = "driftbench", frozen)]
#[derive(Clone)]
pub struct PyTask {
    /// The task as a network run of it: the variant's integrator, scoring and network start.
    pub job: RunSpec,
    /// The suite's own runs of the task, exact column first where it has one.
    pub runs: Vec<RunSpec>,
    /// The sizes of the scheme's QP.
    pub dims: PyQpDims,
    /// Whether x starts with thetadot or thetaddot.
    pub level: Level,
}

/// A value the experiment files serialise, as the Python object JSON makes of it.
fn to_py<'py>(py: Python<'py>, value: &impl Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

#[pymethods]
impl PyTask {
    /// `"<experiment> / <variant>"` (ids): what `driftbench.task` takes.
    #[getter]
    fn id(&self) -> String {
        self.job.task().to_string()
    }
    #[getter]
    fn paper(&self) -> &str {
        &self.job.paper
    }
    #[getter]
    fn experiment(&self) -> &str {
        &self.job.experiment
    }
    #[getter]
    fn variant(&self) -> &str {
        &self.job.variant
    }
    /// The robot's registry name (`jaco2-pen`, `katana6m180`, ...).
    #[getter]
    fn robot(&self) -> &str {
        &self.job.robot
    }
    /// Joint count: the joint command is x[:dof].
    #[getter]
    fn dof(&self) -> usize {
        self.job.theta0.len()
    }
    /// Unknowns of the QP: the joint command x[:dof], then `n_aux` auxiliary variables.
    #[getter]
    fn nx(&self) -> usize {
        self.dims.nx
    }
    /// Equality rows of the QP (A x = b).
    #[getter]
    fn n_eq(&self) -> usize {
        self.dims.n_eq
    }
    /// Inequality rows of the QP (G x <= h).
    #[getter]
    fn n_in(&self) -> usize {
        self.dims.n_in
    }
    /// Auxiliary variables of the QP: `nx - dof` (1 on the jia2019 and zhong2021 tasks: the
    /// infinity norm's bound p = |thetadot|_inf).
    #[getter]
    fn n_aux(&self) -> usize {
        self.dims.nx - self.job.theta0.len()
    }
    /// The QP's sizes as a `QpDims` (what `state_dim(dims)` and `handles(dims)` get).
    #[getter]
    fn dims(&self) -> PyQpDims {
        self.dims
    }
    /// `"velocity"` (x[:dof] is thetadot) or `"acceleration"` (x[:dof] is thetaddot).
    #[getter]
    fn level(&self) -> &'static str {
        match self.level {
            Level::Velocity => "velocity",
            Level::Acceleration => "acceleration",
        }
    }
    /// The path: name, duration and the pose fields (rotation, phase, scale, ...).
    #[getter]
    fn path<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.job.path)
    }
    /// Duration T of the task (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.job.path.duration
    }
    #[getter]
    fn theta0(&self) -> Vec<f64> {
        self.job.theta0.clone()
    }
    /// The scheme's joint reference (the path starts at f(theta_ref)).
    #[getter]
    fn theta_ref(&self) -> Vec<f64> {
        self.job.theta_ref.clone()
    }
    /// The scheme: `kind` and its parameters.
    #[getter]
    fn scheme<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.job.scheme)
    }
    /// The scheme's display name with its parameters (`VLTCO (phi=0.2, tau=0.4)`).
    #[getter]
    fn scheme_name(&self) -> String {
        self.job.scheme.display_name()
    }
    /// The integrator of a network run: method, tolerances, budgets.
    #[getter]
    fn integrator<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.job.integrator)
    }
    /// Where a network run is scored against the exact optimum.
    #[getter]
    fn scoring<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.job.scoring)
    }
    /// Where a network's state starts (`zero` or `exact`).
    #[getter]
    fn network_init<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.job.network_init)
    }
    /// The ids of the suite's own solvers of the task (`exact`, `znn`, ...): each can be given
    /// to `simulate` in place of a Python network.
    #[getter]
    fn solvers(&self) -> Vec<String> {
        self.runs.iter().map(|j| j.solver.id()).collect()
    }
    fn __repr__(&self) -> String {
        format!(
            "Task('{}', robot='{}', path='{}', T={} s, scheme='{}', nx={}, n_eq={}, n_in={})",
            self.id(),
            self.job.robot,
            self.job.path.name,
            self.job.path.duration,
            self.scheme_name(),
            self.dims.nx,
            self.dims.n_eq,
            self.dims.n_in
        )
    }
}

impl PyTask {
    /// The suite's run of this task whose solver id is `id`.
    pub fn run_of(&self, id: &str) -> Result<&RunSpec, NoSolver> {
        self.runs
            .iter()
            .find(|j| j.solver.id() == id)
            .ok_or_else(|| NoSolver {
                task: self.id(),
                label: id.to_string(),
                solvers: self.solvers(),
            })
    }
}

/// Every task of the experiment files under `root/experiments`, in file order (the papers' own
/// robot files, `root/papers/<paper>/robots/*.toml`, registered first).
pub fn load_tasks(root: &Path) -> Result<Vec<PyTask>, TaskError> {
    catalog::register_paper_robots(&root.join("papers"));
    let files = load_experiments(&root.join("experiments"))?;
    let mut tasks = Vec::new();
    for file in &files {
        for (index, e) in file.experiments.iter().enumerate() {
            for i in 0..e.variants.len() {
                let v = file
                    .variant(index, i)
                    .map_err(|error| file.in_file(error))?;
                let runs: Vec<RunSpec> = file.variant_jobs(e, &v);
                let Some(first) = runs.first() else {
                    continue;
                };
                // A network run of the variant, as the experiment file makes its networks'.
                let job = RunSpec {
                    solver: SolverChoice::Exact,
                    integrator: v.integrator.unwrap_or(e.integrator),
                    network_init: v.network_init,
                    expected_failure: None,
                    ..first.clone()
                };
                let (dims, level) = qp_shape(&job).map_err(|source| TaskError::Shape {
                    task: job.task().to_string(),
                    source,
                })?;
                tasks.push(PyTask {
                    job,
                    runs,
                    dims: dims.into(),
                    level,
                });
            }
        }
    }
    Ok(tasks)
}
