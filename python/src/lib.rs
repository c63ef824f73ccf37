//! driftbench for Python (`import driftbench`): the library's tasks, a run of a network written
//! in Python, and the leaderboard, as bindings (PyO3) to the Rust crates, not a second
//! implementation.
//!
//! - `tasks` / `task` / `standard_tasks`: every (experiment, variant) of the experiment
//!   files as a `Task` (`task_set::PyTask`); the standard task set is the leaderboard's
//!   (`analysis::leaderboard::standard_tasks` over `results/runs.csv`). The project root is
//!   `root=` (a checkout) where given, else the data the package carries (`packaged`).
//! - `simulate`: one run of a task with a Python network (`network`) or one of the suite's
//!   own solvers (by id). Arm, scheme, integrator and the score against the exact optimum are
//!   `simulation::run`'s; the result is the run's `results/runs.csv` row
//!   (`records::RunRow`) as a dict, with the drift and the trace as numpy arrays and the
//!   cost of the Python calls.
//! - `leaderboard`: Python networks on the standard task set, ranked with the suite's own runs
//!   by `analysis::leaderboard::leaderboard`, rows in `results/leaderboard.csv`'s schema. A
//!   network ranks on the tasks it handles (`handles(dims)`, or `NotApplicable` raised while it
//!   is built); the rest are N/A, as for the suite's zeroing networks.
//!
//! Errors of the library are raised as `driftbench.DriftbenchError` with the library's message;
//! an exception raised inside a network's method is raised again once the run stops (with the
//! method and instant as context).

mod arrays;
mod budget;
mod error;
mod network;
mod packaged;
mod qp_solver;
mod task_set;

use arrays::real_array;
use error::{IntoResultsError, Panicked, RootError, SealedOutDir, UnknownTask};
use inputs::trajectory::{read, Trajectory};
use network::{network_name, Callbacks, PyNetwork, PyQpDims, SharedCallbacks};
use numpy::ndarray::{Ix1, Ix2};
use numpy::IntoPyArray;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use records::score_row;
use records::FailureKind;
use records::TracePoint;
use records::{RunRow, Status};
use simulation::run_row;
use simulation::score_trajectory;
use simulation::Outcome;
use simulation::RunError;
use simulation::{run_job, run_job_with_network, RunRecord};
use solvers::neural::NeuralSolver;
use spec::Scoring;
use spec::SetupError;
use std::path::{Path, PathBuf};
use std::time::Duration;
use task_set::{load_tasks, PyTask};

create_exception!(
    driftbench,
    DriftbenchError,
    PyException,
    "An error of the driftbench library (the message is the library's own)."
);

create_exception!(
    driftbench,
    NotApplicable,
    DriftbenchError,
    "A network does not handle a task's QP: raised by the network itself (from `handles(dims)` or \
     `state_dim(dims)`) or by driftbench where `handles(dims)` returns False. `simulate` raises \
     it; `leaderboard` counts the task as N/A for the network, as for the suite's networks on \
     tasks they do not handle."
);

/// The prefix of a Python network's solver id (`python-<name>`); its rows' kind is `SolverKind::Python`.
const PYTHON_KIND: &str = "python";

/// The name of `value`'s type, for messages.
fn type_name(value: &Bound<'_, PyAny>) -> String {
    value
        .get_type()
        .name()
        .map_or_else(|_| "an object".to_string(), |n| n.to_string())
}

fn lib_err(e: impl std::fmt::Display) -> PyErr {
    DriftbenchError::new_err(e.to_string())
}

/// The solver id of a Python network called `name`: `python-<slug(name)>`, an error when that
/// is no valid id (a name without a letter or digit, or too long).
fn python_solver_id(name: &str) -> Result<spec::ids::SolverId, spec::ids::IdError> {
    spec::ids::SolverId::new(format!("{PYTHON_KIND}-{}", settings::slug(name)))
}

/// Runs the body of one of the module's functions, a panic of the library (a bug: no input
/// should reach one) raised as `DriftbenchError` ([`Panicked`]) instead of pyo3's
/// `PanicException`, which `except Exception` does not catch.
fn guarded<T>(body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(body))
        .unwrap_or_else(|payload| Err(lib_err(Panicked::from_payload(payload.as_ref()))))
}

/// The project root of a call: `root` (a checkout, or any directory with
/// `experiments/*.toml`) where given, else the data the package carries ([`packaged`]). The
/// working directory plays no part: a folder called `experiments/` above it is not taken for
/// driftbench's.
fn project_root(root: Option<PathBuf>) -> PyResult<PathBuf> {
    let Some(root) = root else {
        return packaged::root().map_err(lib_err);
    };
    let experiments = root.join("experiments");
    if !experiments.is_dir() {
        return Err(lib_err(RootError::NoExperiments { root }));
    }
    let has_file = std::fs::read_dir(&experiments)
        .map_err(|e| lib_err(format!("root={}: {e}", root.display())))?
        .filter_map(Result::ok)
        .any(|e| e.path().extension().is_some_and(|x| x == "toml"));
    if !has_file {
        return Err(lib_err(RootError::NoFiles { root }));
    }
    Ok(root)
}

/// The directory of the project data the package carries (the experiment files, `papers/`
/// and the committed results), unpacked into the user's cache: the root used where `root=`
/// is not given.
#[pyfunction]
fn data_root() -> PyResult<PathBuf> {
    guarded(|| packaged::root().map_err(lib_err))
}

/// Registers a robot file (`<name>.toml`, of the DH or the URDF form), a paper folder's
/// `robots/*.toml` or a folder's `*.toml`, read now (no rebuild), so that the experiment files
/// of `root=` may name them; returns their names. An invalid file raises, naming the file and
/// the field.
#[pyfunction]
fn add_robots(path: PathBuf) -> PyResult<Vec<String>> {
    guarded(|| catalog::register_path(&path).map_err(lib_err))
}

/// Every task of the experiment files (`<root>/experiments`; without `root`, the packaged
/// ones), in file order.
#[pyfunction]
#[pyo3(signature = (root=None))]
fn tasks(root: Option<PathBuf>) -> PyResult<Vec<PyTask>> {
    guarded(|| load_tasks(&project_root(root)?).map_err(lib_err))
}

/// The task `"<experiment> / <variant>"`.
#[pyfunction]
#[pyo3(signature = (id, root=None))]
fn task(id: &str, root: Option<PathBuf>) -> PyResult<PyTask> {
    guarded(|| {
        let all = tasks(root)?;
        find_task(&all, id, "").cloned()
    })
}

/// The task of `all` whose id is `id`; the error lists the ids of `all` (`set` names it).
fn find_task<'a>(all: &'a [PyTask], id: &str, set: &'static str) -> PyResult<&'a PyTask> {
    let key = spec::TaskKey::parse(id).ok();
    all.iter()
        .find(|t| Some(t.job.task()) == key)
        .ok_or_else(|| {
            lib_err(UnknownTask {
                id: id.to_string(),
                set,
                valid: all.iter().map(|t| t.job.task().to_string()).collect(),
            })
        })
}

/// The rows of `<root>/results/runs.csv`.
fn stored_runs(root: &Path) -> PyResult<Vec<RunRow>> {
    store::read_runs(
        &root
            .join(store::results_dir::DIR)
            .join(store::results_dir::RUNS),
    )
    .map_err(lib_err)
}

/// The leaderboard's standard task set (the cross experiment's tasks whose exact column
/// completed in `<root>/results/runs.csv`).
#[pyfunction]
#[pyo3(signature = (root=None))]
fn standard_tasks(root: Option<PathBuf>) -> PyResult<Vec<PyTask>> {
    guarded(|| {
        let root = project_root(root)?;
        let all = load_tasks(&root).map_err(lib_err)?;
        analysis::leaderboard::standard_tasks(&stored_runs(&root)?)
        .iter()
        .map(|s| {
            all.iter()
                .find(|t| t.job.experiment == s.experiment && t.job.variant_id == s.variant)
                .cloned()
                .ok_or_else(|| {
                    lib_err(format!(
                        "results/runs.csv has the standard task \"{} / {}\", the experiment files do not",
                        s.experiment, s.variant
                    ))
                })
        })
        .collect()
    })
}

/// Parses CSV text (a header, then rows) into dicts: empty fields None, integers int, numbers
/// float, the rest str.
fn csv_dicts<'py>(py: Python<'py>, bytes: &[u8]) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let mut reader = csv::Reader::from_reader(bytes);
    let header = reader.headers().map_err(lib_err)?.clone();
    let mut out = Vec::new();
    for record in reader.records() {
        let record = record.map_err(lib_err)?;
        let d = PyDict::new(py);
        for (key, field) in header.iter().zip(record.iter()) {
            if field.is_empty() {
                d.set_item(key, py.None())?;
            } else if let Ok(i) = field.parse::<i64>() {
                d.set_item(key, i)?;
            } else if let Ok(f) = field.parse::<f64>() {
                d.set_item(key, f)?;
            } else {
                d.set_item(key, field)?;
            }
        }
        out.push(d);
    }
    Ok(out)
}

/// The run as a dict: its runs.csv columns, `drift` (per joint), `trace` (arrays over the
/// thinned trace) and the Python calls' count and time.
fn result_dict<'py>(
    py: Python<'py>,
    record: &RunRecord,
    row: &RunRow,
    calls: &Callbacks,
) -> PyResult<Bound<'py, PyDict>> {
    let bytes = records::runs_csv(std::slice::from_ref(row)).map_err(lib_err)?;
    let d = csv_dicts(py, &bytes)?
        .pop()
        .ok_or_else(|| lib_err("no row"))?;
    d.set_item("drift", row.drift.clone().into_pyarray(py))?;
    let trace = &record.run.trace;
    let n = record.job.theta0.len();
    let rows = |f: &dyn Fn(&TracePoint) -> Vec<f64>, width: usize| {
        let flat: Vec<f64> = trace.iter().flat_map(f).collect();
        numpy::ndarray::Array2::from_shape_vec((trace.len(), width), flat)
            .map(|a| a.into_pyarray(py))
            .map_err(lib_err)
    };
    let t = PyDict::new(py);
    let column =
        |f: &dyn Fn(&TracePoint) -> f64| trace.iter().map(f).collect::<Vec<f64>>().into_pyarray(py);
    t.set_item("t", column(&|p| p.t))?;
    t.set_item("theta", rows(&|p| p.theta.clone(), n)?)?;
    t.set_item("thetadot", rows(&|p| p.thetadot.clone(), n)?)?;
    t.set_item("desired", rows(&|p| p.desired.to_vec(), 3)?)?;
    t.set_item("actual", rows(&|p| p.actual.to_vec(), 3)?)?;
    t.set_item("score_dx", column(&|p| p.score_dx.unwrap_or(f64::NAN)))?;
    d.set_item("trace", t)?;
    d.set_item("python_calls", calls.calls)?;
    d.set_item("python_seconds", calls.seconds)?;
    Ok(d)
}

/// `e` with the task named in front of its message (`task "<id>": ...`), of the same type
/// where the type can be built from a message (else a `RuntimeError`); the cause is `e`'s own
/// cause, or `e` itself where it has none (so a network's own exception and its traceback stay
/// reachable as `__cause__`).
fn in_task(py: Python<'_>, e: PyErr, task: &str) -> PyErr {
    let message = format!("task \"{task}\": {}", e.value(py));
    let cause = e.cause(py).unwrap_or_else(|| e.clone_ref(py));
    let renamed = e
        .get_type(py)
        .call1((message.clone(),))
        .ok()
        .filter(|v| v.is_instance_of::<pyo3::exceptions::PyBaseException>())
        .map(PyErr::from_value)
        .unwrap_or_else(|| pyo3::exceptions::PyRuntimeError::new_err(message));
    renamed.set_cause(py, Some(cause));
    renamed
}

/// A run of a Python network: its record and its row (named after the network), the cost of
/// its calls, and the exception the network's own code raised, if it did (the run then went on
/// with the network frozen: `network`'s module docs).
struct PythonRun {
    record: RunRecord,
    row: RunRow,
    calls: Callbacks,
    raised: Option<PyErr>,
}

/// Runs `task` (as `job`: the task's job, possibly with other integrator settings) with the
/// Python network `network`, within `budget` of wall time where one is given (`budget`'s
/// module docs). Raises the library's error when the run could not be set up, with the task
/// named ([`in_task`]); a network whose `handles(dims)` returns False, or that raises
/// `NotApplicable` while it is built, raises `NotApplicable`. What the network raised during
/// the run is returned in [`PythonRun::raised`], for the caller to raise or record.
fn run_python(
    py: Python<'_>,
    task: &PyTask,
    job: &spec::RunSpec,
    network: &Bound<'_, PyAny>,
    budget: Option<f64>,
) -> PyResult<PythonRun> {
    let id = task.job.task().to_string();
    run_python_unnamed(py, task, job, network, budget).map_err(|e| in_task(py, e, &id))
}

/// [`run_python`] without the task in its errors.
fn run_python_unnamed(
    py: Python<'_>,
    task: &PyTask,
    job: &spec::RunSpec,
    network: &Bound<'_, PyAny>,
    budget: Option<f64>,
) -> PyResult<PythonRun> {
    let name = network_name(network)?;
    if let Some(handles) = network.getattr_opt("handles")? {
        if !handles.call1((task.dims,))?.is_truthy()? {
            return Err(NotApplicable::new_err(format!(
                "{name} does not handle this task's QP ({}): its handles(dims) returned False",
                task.dims.describe()
            )));
        }
    }
    let callbacks = SharedCallbacks::default();
    let build = |dims| {
        PyNetwork::new(network, dims, callbacks.clone())
            .map(|n| Box::new(n) as Box<dyn NeuralSolver>)
            .map_err(|e| {
                let message = e.to_string();
                callbacks
                    .lock()
                    .unwrap_or_else(|p| p.into_inner())
                    .keep_error(e);
                SetupError::CustomNetwork(message)
            })
    };
    let record = match budget {
        None => run_job_with_network(job, &build),
        Some(seconds) => {
            let mut job = job.clone();
            job.integrator.max_wall_s = seconds;
            budget::watched(py, Duration::from_secs_f64(seconds), || {
                run_job_with_network(&job, &build)
            })?
        }
    };
    let mut calls = std::mem::take(&mut *callbacks.lock().unwrap_or_else(|p| p.into_inner()));
    let raised = match calls.take_error() {
        // NotApplicable raised while the network was built: N/A, not a failure of the run.
        Some(e) if e.is_instance_of::<NotApplicable>(py) => return Err(e),
        None => {
            check_setup(&record)?;
            None
        }
        raised => raised,
    };
    let mut row = run_row(&record, reproduce::REVISION);
    row.solver_id = python_solver_id(&name).map_err(lib_err)?;
    row.solver = name;
    row.solver_kind = spec::SolverKind::Python;
    Ok(PythonRun {
        record,
        row,
        calls,
        raised,
    })
}

/// The longest `failure` text of a run whose network raised (a network's message is its
/// own, possibly long or multi-line): the first this many characters, on one line.
const MAX_FAILURE_CHARS: usize = 400;

/// `e` as one line of at most [`MAX_FAILURE_CHARS`]: `<where>: <Type>: <message>` for an
/// exception of a network's method (the library's wrapper names the method and the instant,
/// its cause is the network's own exception), `<Type>: <message>` for one raised while the
/// network was built.
fn describe_raised(py: Python<'_>, e: &PyErr) -> String {
    let typed = |x: &PyErr| {
        let kind = x
            .get_type(py)
            .name()
            .map_or_else(|_| "an exception".to_string(), |n| n.to_string());
        format!("{kind}: {}", x.value(py))
    };
    let text = match e.cause(py) {
        Some(cause) => format!("{}: {}", e.value(py), typed(&cause)),
        None => typed(e),
    };
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .chars()
        .take(MAX_FAILURE_CHARS)
        .collect()
}

/// `row` as a failed run of `kind`, `failure` in words: no drift (theta(T) of a run whose
/// network stopped is not the network's), no failed_at (the failure names its instant).
fn mark_failed(row: &mut RunRow, kind: FailureKind, failure: String) {
    row.status = Status::Failed;
    row.failure = failure;
    row.failure_kind = Some(kind);
    row.failed_at = None;
    row.drift.clear();
    row.drift_norm = None;
    row.drift_ref_norm = None;
}

/// The row of a run whose call into the network was stopped by the wall budget's watchdog
/// (`e`, raised inside the call): a `wall-time` failure naming the call.
fn budget_failure(py: Python<'_>, row: &mut RunRow, e: &PyErr, seconds: f64) {
    let call = if e.is_instance_of::<budget::WallBudgetExceeded>(py) {
        "the network's construction".to_string()
    } else {
        e.value(py).to_string()
    };
    mark_failed(
        row,
        FailureKind::WallTime,
        format!(
            "wall-time budget of {seconds} s used up inside {call}, a call into the network \
             that had not returned (wall_budget)"
        ),
    );
}

/// `wall_budget=` in seconds: positive and finite.
fn check_budget(seconds: f64) -> PyResult<f64> {
    if seconds > 0.0 && seconds.is_finite() {
        Ok(seconds)
    } else {
        Err(pyo3::exceptions::PyValueError::new_err(format!(
            "wall_budget must be positive and finite (seconds of wall time per run), got {seconds}"
        )))
    }
}

/// A run that could not be set up raises the library's error.
fn check_setup(record: &RunRecord) -> PyResult<()> {
    match &record.run.outcome {
        Outcome::Failed {
            error: e @ RunError::Setup(_),
            ..
        } => Err(lib_err(e)),
        _ => Ok(()),
    }
}

/// `scoring`: None (the task's), "every-step", "off", or a number of instants.
fn parse_scoring(value: &Bound<'_, PyAny>) -> PyResult<Scoring> {
    let says = "scoring must be \"every-step\", \"off\" or a number of instants (an int >= 0)";
    if value.is_instance_of::<pyo3::types::PyInt>() {
        return value
            .extract::<usize>()
            .map(Scoring::MaxInstants)
            .map_err(|_| pyo3::exceptions::PyValueError::new_err(format!("{says}, got {value}")));
    }
    let Ok(text) = value.extract::<String>() else {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{says}, got {}",
            type_name(value)
        )));
    };
    match text.as_str() {
        "every-step" => Ok(Scoring::EveryStep),
        "off" => Ok(Scoring::Off),
        other => Err(lib_err(format!("{says}, got \"{other}\""))),
    }
}

/// Simulates `task` with `network`: a Python network (see the package docs), the label of
/// one of the task's own solvers by id (`task.solvers`, e.g. "exact"), or the id of a
/// registered QP solver (`register_qp_solver`, or a built-in one such as "clarabel") run at
/// every instant of the fixed-step numerical loop. Keyword arguments
/// override the task's integrator tolerances and step limit, the scoring ("every-step", "off"
/// or a number of instants) and where the network starts ("zero" or "exact"); `wall_budget`
/// (seconds) bounds a Python network's run: past it the run is a failed run (`failure_kind`
/// "wall-time"), even inside a call into the network that does not return (`budget`'s module
/// docs). Returns the run's runs.csv columns as a dict, with `drift` and `trace` as numpy
/// arrays. What the network raised is raised, the task named.
#[pyfunction]
#[pyo3(signature = (task, network, *, rtol=None, atol=None, max_step=None, scoring=None, network_init=None, wall_budget=None))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    task: &PyTask,
    network: &Bound<'py, PyAny>,
    rtol: Option<f64>,
    atol: Option<f64>,
    max_step: Option<f64>,
    scoring: Option<&Bound<'py, PyAny>>,
    network_init: Option<&str>,
    wall_budget: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    guarded(|| {
        let wall_budget = wall_budget.map(check_budget).transpose()?;
        let builtin = network.extract::<String>().ok();
        let mut job = match &builtin {
            Some(id) => match task.run_of(id) {
                Ok(job) => job.clone(),
                Err(no_run) => registered_qp_run(task, id).ok_or_else(|| lib_err(no_run))?,
            },
            None => task.job.clone(),
        };
        job.integrator.rtol = rtol.unwrap_or(job.integrator.rtol);
        job.integrator.atol = atol.unwrap_or(job.integrator.atol);
        job.integrator.max_step = max_step.or(job.integrator.max_step);
        job.integrator.validate().map_err(lib_err)?;
        if let Some(s) = scoring {
            job.scoring = parse_scoring(s)?;
        }
        if let Some(init) = network_init {
            job.network_init = serde_json::from_value(serde_json::Value::String(init.to_string()))
                .map_err(|_| {
                    lib_err(format!(
                        "network_init must be \"zero\" or \"exact\", got \"{init}\""
                    ))
                })?;
        }
        let (record, row, calls) = if builtin.is_some() {
            let record = run_job(&job);
            check_setup(&record)?;
            let row = run_row(&record, reproduce::REVISION);
            (record, row, Callbacks::default())
        } else {
            let mut run = run_python(py, task, &job, network, wall_budget)?;
            match (run.raised.take(), wall_budget) {
                (None, _) => {}
                (Some(e), Some(seconds)) if budget::is_exceeded(py, &e) => {
                    budget_failure(py, &mut run.row, &e, seconds)
                }
                (Some(e), _) => return Err(in_task(py, e, &task.job.task().to_string())),
            }
            (run.record, run.row, run.calls)
        };
        result_dict(py, &record, &row, &calls)
    })
}

/// The tasks of `tasks=`: each a `Task` or an id (`"<experiment> / <variant>"`), every one in
/// the standard task set `standard`; the error lists the standard ids.
fn chosen_tasks(standard: &[PyTask], given: &Bound<'_, PyAny>) -> PyResult<Vec<PyTask>> {
    if given.is_instance_of::<pyo3::types::PyString>() {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "tasks= takes a list of tasks or ids, not one id: write tasks=[\"<experiment> / <variant>\"]",
        ));
    }
    let items = given.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(
            "tasks= takes a list of Task objects or ids (\"<experiment> / <variant>\")",
        )
    })?;
    items
        .map(|item| {
            let item = item?;
            let id = if let Ok(t) = item.cast::<PyTask>() {
                t.get().job.task().to_string()
            } else if let Ok(id) = item.extract::<String>() {
                id
            } else {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "tasks= takes Task objects or ids (\"<experiment> / <variant>\"), got {}",
                    type_name(&item)
                )));
            };
            find_task(standard, &id, "standard ").cloned()
        })
        .collect()
}

/// The leaderboard's wall budget of one run (s) unless `wall_budget=` says otherwise: about
/// 100 times the slowest numpy run of the standard task set (the numpy GNN's runs take
/// 0.1-1 s on the development machine; python/README.md), so a slow but working network
/// ranks, and an entry that hangs costs two minutes a task, not the whole call.
const DEFAULT_WALL_BUDGET: f64 = 120.0;

/// Scores Python networks on the standard task set (or on `tasks`, a subset of it, as Task
/// objects or ids) the way the leaderboard scores the suite's own networks: each runs every
/// task it handles, its rows join the stored `results/runs.csv`, and
/// `analysis::leaderboard::leaderboard` ranks them all. A task a network does not handle
/// (`handles(dims)` False, or `NotApplicable` raised while it is built) is N/A for it: no row,
/// so it is ranked on the tasks it ran, as the suite's zeroing networks are. An entry whose own
/// code fails on a task (an exception in a method, a NaN or malformed result) or whose run
/// exceeds `wall_budget` seconds of wall time ([`DEFAULT_WALL_BUDGET`]; a call that does not
/// return included) has a failed run there, the reason in its row (`failure`, `failure_kind`
/// "network" or "wall-time"), and the others go on and are ranked; Ctrl-C
/// (`KeyboardInterrupt`) still stops the call. `entries` is a dict name -> network or a list
/// of networks (named by their `name`, else their class). Returns {"leaderboard": rows,
/// "runs": the networks' rows (with `python_calls` and `python_seconds`), "not_applicable" (the
/// N/A tasks) and "failed" (the failed runs, whatever stopped them): lists of {"solver",
/// "task", "reason"}}, the rows dicts in the schema of
/// results/leaderboard.csv and results/runs.csv; with `out_dir`, writes both files there.
#[pyfunction]
#[pyo3(signature = (entries, *, tasks=None, root=None, out_dir=None, wall_budget=DEFAULT_WALL_BUDGET))]
fn leaderboard<'py>(
    py: Python<'py>,
    entries: &Bound<'py, PyAny>,
    tasks: Option<&Bound<'py, PyAny>>,
    root: Option<PathBuf>,
    out_dir: Option<PathBuf>,
    wall_budget: f64,
) -> PyResult<Bound<'py, PyDict>> {
    guarded(|| {
        let wall_budget = check_budget(wall_budget)?;
        if let Some(out) = &out_dir {
            check_out_dir(out)?;
        }
        let root = project_root(root)?;
        let stored = stored_runs(&root)?;
        let standard = standard_tasks(Some(root.clone()))?;
        let chosen = match tasks {
            None => standard,
            Some(given) => chosen_tasks(&standard, given)?,
        };
        if chosen.is_empty() {
            return Err(pyo3::exceptions::PyValueError::new_err(
            "tasks= is empty: give the tasks to run (Task objects or ids), or leave it out for \
             the standard task set",
        ));
        }
        let named = named_entries(entries)?;
        let entered = run_entries(py, &named, &chosen, &stored, wall_budget)?;
        let (fresh, costs) = (entered.rows, entered.costs);
        let mut all = stored;
        all.extend(fresh.iter().cloned());
        let timings = store::timing::read(&root.join(store::results_dir::DIR)).map_err(lib_err)?;
        let board = analysis::leaderboard::leaderboard(&all, &timings);
        let board_csv = analysis::leaderboard::leaderboard_csv(&board).map_err(lib_err)?;
        let runs_csv = records::runs_csv(&fresh).map_err(lib_err)?;
        if let Some(dir) = &out_dir {
            write_leaderboard_tables(dir, &board_csv, &runs_csv)?;
        }
        let runs = csv_dicts(py, &runs_csv)?;
        for (d, calls) in runs.iter().zip(&costs) {
            d.set_item("python_calls", calls.calls)?;
            d.set_item("python_seconds", calls.seconds)?;
        }
        let out = PyDict::new(py);
        out.set_item("leaderboard", PyList::new(py, csv_dicts(py, &board_csv)?)?)?;
        out.set_item("runs", PyList::new(py, runs)?)?;
        out.set_item("not_applicable", entered.not_applicable)?;
        out.set_item("failed", entered.failed)?;
        Ok(out)
    })
}

/// [`leaderboard`]'s `entries` as (name, network): a dict's keys (str) are the names, a list's
/// networks are named by their `name`, else their class.
fn named_entries<'py>(entries: &Bound<'py, PyAny>) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
    match entries.cast::<PyDict>() {
        Ok(d) => d
            .iter()
            .map(|(k, v)| {
                let name = k.extract::<String>().map_err(|_| {
                    pyo3::exceptions::PyTypeError::new_err(format!(
                        "leaderboard's entries: the keys are the networks' names (str), got {}",
                        type_name(&k)
                    ))
                })?;
                Ok((name, v))
            })
            .collect::<PyResult<_>>(),
        Err(_) => entries
            .try_iter()
            .map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err(
                    "leaderboard's entries: a dict name -> network, or a list of networks",
                )
            })?
            .map(|n| {
                let n = n?;
                Ok((network_name(&n)?, n))
            })
            .collect::<PyResult<_>>(),
    }
}

/// What the networks of [`leaderboard`] produced: their rows (named after them), the cost of
/// their Python calls (one per row), the tasks each does not handle, and the failed runs.
struct Entered<'py> {
    rows: Vec<RunRow>,
    costs: Vec<Callbacks>,
    /// {"solver", "task", "reason"} per task a network does not handle.
    not_applicable: Bound<'py, PyList>,
    /// {"solver", "task", "reason"} per failed run (the network's own code, the budget, or
    /// the run itself: diverged, ...).
    failed: Bound<'py, PyList>,
}

/// {"solver", "task", "reason"} as a dict.
fn task_note<'py>(
    py: Python<'py>,
    solver: &str,
    task: &PyTask,
    reason: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("solver", solver)?;
    d.set_item("task", task.job.task().to_string())?;
    d.set_item("reason", reason)?;
    Ok(d)
}

/// Runs every named network on every `chosen` task, its rows named `python-<slug(name)>`; a name
/// a `stored` row or an earlier entry already has is refused, a task a network does not
/// handle (`NotApplicable`) is listed, not run, and a run the network's own code failed
/// (raised, returned NaN, used up `budget`) is a failed row, also listed. An exception that is
/// not an `Exception` (Ctrl-C's `KeyboardInterrupt`) stops the call.
fn run_entries<'py>(
    py: Python<'py>,
    named: &[(String, Bound<'py, PyAny>)],
    chosen: &[PyTask],
    stored: &[RunRow],
    budget: f64,
) -> PyResult<Entered<'py>> {
    let mut fresh = Vec::new();
    let mut costs = Vec::new();
    let not_applicable = PyList::empty(py);
    let failed = PyList::empty(py);
    for (name, network) in named {
        // The name is shown in the report's tables as it is: no markup, no line break.
        spec::check_name(name, spec::MAX_SOLVER_LABEL)
            .map_err(|e| lib_err(format!("leaderboard's entry name: {e}")))?;
        let id = python_solver_id(name).map_err(lib_err)?;
        if stored
            .iter()
            .any(|r| r.solver == *name || r.solver_id == id)
            || fresh
                .iter()
                .any(|r: &RunRow| r.solver == *name || r.solver_id == id)
        {
            return Err(lib_err(format!(
                "a solver called \"{name}\" is already on the leaderboard; give the network another name"
            )));
        }
        for t in chosen {
            match run_python(py, t, &t.job, network, Some(budget)) {
                Ok(mut run) => {
                    match run.raised.take() {
                        None => {}
                        Some(e) if budget::is_exceeded(py, &e) => {
                            budget_failure(py, &mut run.row, &e, budget)
                        }
                        Some(e) if !e.is_instance_of::<pyo3::exceptions::PyException>(py) => {
                            return Err(e)
                        }
                        Some(e) => {
                            mark_failed(&mut run.row, FailureKind::Network, describe_raised(py, &e))
                        }
                    }
                    if run.row.status == Status::Failed {
                        failed.append(task_note(py, name, t, &run.row.failure)?)?;
                    }
                    run.row.solver = name.clone();
                    run.row.solver_id = id.clone();
                    fresh.push(run.row);
                    costs.push(run.calls);
                }
                Err(e) if e.is_instance_of::<NotApplicable>(py) => {
                    let reason = e.value(py).str()?.to_string();
                    not_applicable.append(task_note(py, name, t, &reason)?)?;
                }
                Err(e) => return Err(e),
            }
        }
    }
    Ok(Entered {
        rows: fresh,
        costs,
        not_applicable,
        failed,
    })
}

/// Writes [`leaderboard`]'s tables into `dir` (atomically, each resolved inside it): the
/// leaderboard and the networks' rows, under `results/`'s names.
fn write_leaderboard_tables(dir: &Path, board_csv: &[u8], runs_csv: &[u8]) -> PyResult<()> {
    let owned = store::OwnedDir::open(dir).map_err(lib_err)?;
    for (name, bytes) in [
        (store::results_dir::LEADERBOARD, board_csv),
        (store::results_dir::RUNS, runs_csv),
    ] {
        let path = owned.resolve(Path::new(name)).map_err(lib_err)?;
        store::write_atomic(&path, bytes)
            .map_err(|e| lib_err(format!("{}: {e}", path.display())))?;
    }
    Ok(())
}

/// Refuses an `out_dir=` that is, or lies inside, a directory driftbench seals with a manifest
/// (results/, report/, a shard directory; `store::integrity::sealed_by`): files written there
/// would pass for the program's own.
fn check_out_dir(out: &Path) -> PyResult<()> {
    match store::integrity::sealed_by(out) {
        Some(sealed) => Err(lib_err(SealedOutDir {
            out: out.to_path_buf(),
            sealed,
        })),
        None => Ok(()),
    }
}

/// The tables the package's scripts write into `results/` (`into_results`).
const SCRIPT_TABLES: [&str; 2] = [
    store::results_dir::LEADERBOARD_PYTHON,
    store::results_dir::PYTHON_CALL_COST,
];

/// Seals the table `file` (written by one of the package's scripts: `leaderboard-python.csv`
/// from `python/examples/leaderboard.py`, `python-call-cost.csv` from
/// `python/bench/call_cost.py`, by file name) into `<root>/results/` the way `reproduce`
/// writes there: read as an input (a regular file, at most 64 MiB), checked against its
/// schema, written under the results directory's lock (refused when its files differ from
/// `results/manifest.toml`) and recorded in the manifest, so the next `reproduce report` takes
/// it. Returns the path written.
#[pyfunction]
#[pyo3(signature = (file, *, root))]
fn into_results(file: PathBuf, root: PathBuf) -> PyResult<PathBuf> {
    guarded(|| {
        let root = project_root(Some(root))?;
        seal_into_results(&file, &root).map_err(lib_err)
    })
}

/// [`into_results`]'s work, with typed errors.
fn seal_into_results(file: &Path, root: &Path) -> Result<PathBuf, IntoResultsError> {
    let name = file
        .file_name()
        .and_then(|n| n.to_str())
        .filter(|n| SCRIPT_TABLES.contains(n))
        .ok_or_else(|| IntoResultsError::Name {
            file: file.to_path_buf(),
            valid: SCRIPT_TABLES.to_vec(),
        })?;
    let bytes = inputs::read(file, inputs::Kind::ScriptTable, inputs::Origin::Named)?;
    let table = |source| IntoResultsError::Table {
        file: file.to_path_buf(),
        source,
    };
    // Every text of every row, as the report will show it: plain (`check_plain`).
    let texts: Vec<Vec<(&'static str, String)>> = if name == store::results_dir::LEADERBOARD_PYTHON
    {
        records::table::from_reader::<analysis::leaderboard::LeaderboardRow, _>(bytes.as_slice())
            .map_err(table)?
            .into_iter()
            .map(|r| vec![("task_set", r.task_set), ("solver", r.solver)])
            .collect()
    } else {
        records::table::from_reader::<presentation::report::python::CallCostRow, _>(
            bytes.as_slice(),
        )
        .map_err(table)?
        .into_iter()
        .map(|r| {
            vec![
                ("network", r.network),
                ("task", r.task),
                ("twin", r.twin),
                ("python", r.python),
                ("numpy", r.numpy),
                ("machine", r.machine),
            ]
        })
        .collect()
    };
    check_plain(file, &texts)?;
    let (results, _) = store::results_dir::ResultsDir::open(
        &root.join(store::results_dir::DIR),
        reproduce::REVISION,
        store::Edits::Refuse,
    )?;
    results.tracked().write(Path::new(name), &bytes)?;
    results.save()?;
    Ok(results.path().join(name))
}

/// That no text of `rows` (a table's rows, each its (column, text) pairs; the header is line 1)
/// holds markup or a line break (`spec::has_markup`): the report shows them as they
/// are, and a sealed table is trusted.
fn check_plain(file: &Path, rows: &[Vec<(&'static str, String)>]) -> Result<(), IntoResultsError> {
    for (k, row) in rows.iter().enumerate() {
        if let Some((column, _)) = row
            .iter()
            .find(|(_, t)| spec::has_markup(t) || t.contains(char::is_control))
        {
            return Err(IntoResultsError::Markup {
                file: file.to_path_buf(),
                line: k + 2,
                column,
            });
        }
    }
    Ok(())
}

/// The run of `task` whose solver is the registered QP solver `id` (not one of the task's own
/// runs: one registered from Python, `register_qp_solver`, or any other of the registry) at
/// its defaults, at every instant of the fixed-step numerical loop; None when `id` is not
/// registered.
fn registered_qp_run(task: &PyTask, id: &str) -> Option<spec::RunSpec> {
    settings::qp_solver::lookup(id).ok()?;
    let spec: spec::NumericalSpec =
        serde_json::from_value(serde_json::json!({ "method": id })).ok()?;
    Some(spec::RunSpec {
        solver: spec::SolverChoice::Numerical(spec),
        ..task.job.clone()
    })
}

/// Registers a QP solver written in Python (`python/src/qp_solver.rs`): `factory(dims)` builds
/// an object whose `solve(P, q, A, b, G, h, lower, upper)` returns a dict with `x` and the
/// multipliers `lambda`, `mu`, `z_lower`, `z_upper` (or a failure `status`). From then on `id`
/// is a run's solver as any built-in one (`simulate(task, id)`) and an experiment file's
/// `numerical = [{ method = id }]`. Errors: an id that is not a slug or is taken.
#[pyfunction]
#[pyo3(signature = (id, factory, *, name=None))]
fn register_qp_solver(id: &str, factory: Py<PyAny>, name: Option<&str>) -> PyResult<()> {
    guarded(|| qp_solver::register(id, name.unwrap_or(id), factory).map_err(lib_err))
}

/// The conformance kit (`solvers::conformance::check_qp_solver`) on the solvers `factory(dims)`
/// builds, against Clarabel: the QP shapes of the papers' schemes (with `equality_only`, the
/// equality-only ones) and random feasible QPs with bounds (not with `equality_only`),
/// `seeds` QPs each; cold and warm agreement to 1e-6 in x and in the KKT residuals of the
/// solver's own multipliers, failures reported by status (infeasible, NaN, other sizes),
/// degenerate input. Returns the violations as text (empty: the solver conforms). No
/// allocation check (Python allocates).
#[pyfunction]
#[pyo3(signature = (factory, *, equality_only=false, seeds=10))]
fn check_qp_solver(factory: Py<PyAny>, equality_only: bool, seeds: u64) -> PyResult<Vec<String>> {
    use solvers::conformance::Conformance;
    use solvers::QpShape;
    guarded(|| {
        let id = qp::SolverId::builtin("python-qp-solver");
        let make =
            |dims| -> Box<dyn qp::QpSolver> { Box::new(qp_solver::build(&factory, &id, dims)) };
        let spec = Conformance {
            seeds,
            shapes: if equality_only {
                &[QpShape::Zhang2018, QpShape::Kong2019]
            } else {
                &QpShape::ALL
            },
            random_feasible: !equality_only,
            ..Conformance::default()
        };
        Ok(solvers::conformance::check_qp_solver(&make, &spec, None)
            .iter()
            .map(|v| v.to_string())
            .collect())
    })
}

/// Scores a trajectory produced elsewhere on `task` with the metrics and the score of a run
/// (`simulation::score_trajectory`). `trajectory` is a CSV file (columns t, theta_1..n,
/// optionally thetadot_1..n) or a dict of arrays `t` (m), `theta` (m x n) and optionally
/// `thetadot` (m x n). With `out_dir` (a file only), writes `scores.csv`, the trace and the
/// figure there as `reproduce score` does. Returns the row as `simulate` does.
#[pyfunction]
#[pyo3(signature = (task, trajectory, *, out_dir=None))]
fn score<'py>(
    py: Python<'py>,
    task: &PyTask,
    trajectory: &Bound<'py, PyAny>,
    out_dir: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    guarded(|| {
        let git_rev = reproduce::REVISION;
        let (record, row) = if let Ok(file) = trajectory.extract::<PathBuf>() {
            score_file(task, &file, out_dir.as_deref())?
        } else {
            if out_dir.is_some() {
                return Err(lib_err("out_dir is for a trajectory file"));
            }
            let d = trajectory.cast::<PyDict>().map_err(|_| {
                pyo3::exceptions::PyTypeError::new_err(format!(
                    "trajectory must be a file (a path: str or os.PathLike) or a dict of arrays \
                 {{\"t\", \"theta\"[, \"thetadot\"]}}, got {}",
                    type_name(trajectory)
                ))
            })?;
            let record = score_trajectory(&task.job, &trajectory_of_dict(d)?).map_err(lib_err)?;
            let row = score_row(
                run_row(&record, git_rev),
                "arrays",
                &records::trajectory_id(),
            );
            (record, row)
        };
        result_dict(py, &record, &row, &Callbacks::default())
    })
}

/// [`score`] of a trajectory file: with `out_dir`, as `reproduce score` scores it (the row,
/// trace and figure written there); without, scored in memory.
fn score_file(task: &PyTask, file: &Path, out_dir: Option<&Path>) -> PyResult<(RunRecord, RunRow)> {
    let git_rev = reproduce::REVISION;
    match out_dir {
        Some(out) => {
            let s = reproduce::score_file(
                &task.job,
                file,
                None,
                records::TRAJECTORY_KIND,
                out,
                git_rev,
            )
            .map_err(lib_err)?;
            Ok((s.record, s.row))
        }
        None => {
            let record = score_trajectory(
                &task.job,
                &read(file, task.job.theta0.len(), None).map_err(lib_err)?,
            )
            .map_err(|e| lib_err(format!("{}: {e}", file.display())))?;
            let row = score_row(
                run_row(&record, git_rev),
                &file.display().to_string(),
                &records::trajectory_id(),
            );
            Ok((record, row))
        }
    }
}

/// The trajectory of [`score`]'s dict of arrays: `t` (m), `theta` (m x n) and optionally
/// `thetadot` (m x n), no other key, one row per instant.
fn trajectory_of_dict<'py>(d: &Bound<'py, PyDict>) -> PyResult<Trajectory> {
    const KEYS: [&str; 3] = ["t", "theta", "thetadot"];
    for key in d.keys() {
        let known = key
            .extract::<String>()
            .is_ok_and(|k| KEYS.contains(&k.as_str()));
        if !known {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "the trajectory dict has the key {}; its keys are \"t\", \"theta\" and \
             optionally \"thetadot\"",
                key.repr()?
            )));
        }
    }
    let required = |key: &str| -> PyResult<Bound<'py, PyAny>> {
        d.get_item(key)?.ok_or_else(|| {
            pyo3::exceptions::PyValueError::new_err(format!(
                "the trajectory dict needs \"{key}\" (keys: \"t\", \"theta\", optionally \
             \"thetadot\")"
            ))
        })
    };
    let rows = |v: &Bound<'py, PyAny>, key: &str| -> PyResult<Vec<Vec<f64>>> {
        let what = format!("trajectory[\"{key}\"] (m x n: a row per instant, a column per joint)");
        Ok(real_array::<Ix2>(v, &what)?
            .rows()
            .into_iter()
            .map(|r| r.to_vec())
            .collect())
    };
    let t: Vec<f64> = real_array::<Ix1>(&required("t")?, "trajectory[\"t\"]")?.to_vec();
    let theta = rows(&required("theta")?, "theta")?;
    let thetadot = d
        .get_item("thetadot")?
        .map(|v| rows(&v, "thetadot"))
        .transpose()?;
    let lengths = std::iter::once(("theta", theta.len()))
        .chain(thetadot.as_ref().map(|v| ("thetadot", v.len())));
    for (key, m) in lengths {
        if m != t.len() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "trajectory[\"{key}\"] has {m} rows, trajectory[\"t\"] {} instants: one row \
                 per instant",
                t.len()
            )));
        }
    }
    Ok(Trajectory { t, theta, thetadot })
}

#[pymodule]
fn _driftbench(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("DriftbenchError", m.py().get_type::<DriftbenchError>())?;
    m.add("NotApplicable", m.py().get_type::<NotApplicable>())?;
    m.add_class::<PyTask>()?;
    m.add_class::<PyQpDims>()?;
    m.add_function(wrap_pyfunction!(add_robots, m)?)?;
    m.add_function(wrap_pyfunction!(tasks, m)?)?;
    m.add_function(wrap_pyfunction!(task, m)?)?;
    m.add_function(wrap_pyfunction!(standard_tasks, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(leaderboard, m)?)?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    m.add_function(wrap_pyfunction!(data_root, m)?)?;
    m.add_function(wrap_pyfunction!(into_results, m)?)?;
    m.add_function(wrap_pyfunction!(register_qp_solver, m)?)?;
    m.add_function(wrap_pyfunction!(check_qp_solver, m)?)?;
    Ok(())
}
