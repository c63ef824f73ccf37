//! `results/`: the committed CSV the report and the regression gate read.
//!
//! - `results/runs.csv`: one row per run ([`RunRow`]): identity, outcome, every metric, the
//!   score against the exact optimum, and provenance (integrator, tolerances, steps,
//!   evaluations, wall time, crate version, git revision).
//! - `results/traces/<experiment>/<variant id>__<solver id>.csv`: the thinned time history of
//!   each run for the figures.
//!
//! Files are written to a temporary name and renamed, so an interrupted run never leaves a
//! half-written file. Rows are sorted by their [`RunKey`] (ids) so that two runs give
//! byte-identical files except for the timing columns (`wall_s`, `sim_s`, `observe_s`) and `git_rev`.

use crate::error::{RowsError, RunsError};
use crate::table;
use catalog::naming::{check_name, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL};
use catalog::run_key::RunKey;
use serde::{Deserialize, Serialize};
use simulation::error::FailureKind;
use simulation::run::RunRecord;
use simulation::simulate::Outcome;
use std::path::Path;

/// One run, as stored in `results/runs.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRow {
    pub paper: String,
    pub experiment: String,
    /// The variant's id (with `experiment` and `solver_id`, the run's [`RunKey`]).
    pub variant_id: String,
    /// The solver's id: `exact`, or the network's id (kind and distinguishing parameters).
    pub solver_id: String,
    /// The variant's label (display only).
    pub variant: String,
    pub scheme: String,
    /// The solver's label with its parameters (display only).
    pub solver: String,
    /// The solver's kind: `exact`, or the network's kind as experiment files name it
    /// (`lvi-pdnn`, ...).
    pub solver_kind: String,
    pub robot: String,
    pub path: String,
    pub path_scale: Option<f64>,
    pub duration: f64,
    pub status: Status,
    /// Why the run failed, in words (empty when it completed).
    pub failure: String,
    /// The failure's category (empty when the run completed).
    pub failure_kind: Option<FailureKind>,
    /// Why the experiment file expects this run to fail (empty: it should complete).
    pub expected_failure: String,
    /// Last accepted instant of a failed run (the failure message names the instant of the
    /// evaluation that failed, which may lie inside the next step).
    pub failed_at: Option<f64>,
    /// theta(T) - theta(0) per joint (n entries for an n-joint arm; none for a failed run):
    /// the columns `drift_1 .. drift_K` (see [`crate::table`]).
    #[serde(skip)]
    pub drift: Vec<f64>,
    pub drift_norm: Option<f64>,
    pub drift_ref_norm: Option<f64>,
    pub max_pos_err: Option<f64>,
    pub rms_pos_err: Option<f64>,
    pub final_pos_err: Option<f64>,
    pub theta_margin: Option<f64>,
    pub thetadot_margin: Option<f64>,
    pub peak_thetadot: Option<f64>,
    pub peak_thetaddot: Option<f64>,
    pub peak_torque: Option<f64>,
    pub min_sigma_j: Option<f64>,
    pub score_samples: Option<usize>,
    pub score_max_dx: Option<f64>,
    pub score_rms_dx: Option<f64>,
    pub score_max_obj_gap: Option<f64>,
    pub score_max_violation: Option<f64>,
    pub score_failures: usize,
    /// The network's own error norm at T (|Q y - u| for the zeroing networks).
    pub net_error_final: Option<f64>,
    /// Its largest value after t = 1 s (kong2019: "settles within ~1 s").
    pub net_error_max_after_1s: Option<f64>,
    pub integrator: String,
    pub rtol: f64,
    pub atol: f64,
    /// The integrator's largest step (ode15s's MaxStep), where the run sets one.
    #[serde(default)]
    pub max_step: Option<f64>,
    pub steps: usize,
    pub rejected: usize,
    pub rhs_evals: usize,
    pub jac_evals: usize,
    pub qp_solves: usize,
    /// Exact QPs the certified active-set solver could not answer (Clarabel did).
    pub qp_fallbacks: usize,
    /// Certified active-set answers also solved by Clarabel (the first and every 100th).
    pub qp_checks: usize,
    /// Largest relative |x_active_set - x_clarabel|_inf over those checks.
    pub qp_check_max_dx: Option<f64>,
    /// Wall time of the whole integration.
    pub wall_s: f64,
    /// Wall time of the simulation proper (arm + solver + integrator): `wall_s - observe_s`.
    /// The number to compare solvers by.
    pub sim_s: f64,
    /// Wall time of the observation at accepted steps (metrics, trace, the Clarabel solves that
    /// score a neural run or give the exact column's thetadot).
    pub observe_s: f64,
    pub crate_version: String,
    pub git_rev: String,
}

impl RunRow {
    pub fn from_record(r: &RunRecord, git_rev: &str) -> Self {
        let j = &r.job;
        // A failed run keeps its metrics up to the failure (peaks, errors, margins), but no
        // drift: theta(T) was never reached.
        let (status, failure, failure_kind, failed_at, m, completed) = match &r.run.outcome {
            Outcome::Completed(m) => (Status::Ok, String::new(), None, None, Some(m), true),
            Outcome::Failed { t, error, partial } => (
                Status::Failed,
                error.to_string(),
                Some(error.kind()),
                Some(*t),
                partial.as_ref(),
                false,
            ),
        };
        let score = m.and_then(|m| m.score);
        RunRow {
            paper: j.paper.clone(),
            experiment: j.experiment.clone(),
            variant_id: j.variant_id.clone(),
            solver_id: j.solver.id(),
            variant: j.variant.clone(),
            scheme: r.run.scheme_name.clone(),
            solver: j.solver.label(),
            solver_kind: j.solver.kind().to_string(),
            robot: j.robot.clone(),
            path: j.path.name.clone(),
            path_scale: j
                .path
                .scale
                .or_else(|| schemes::paths::default_scale(&j.path.name)),
            duration: j.path.duration,
            status,
            failure,
            failure_kind,
            expected_failure: j.expected_failure.clone().unwrap_or_default(),
            failed_at,
            drift: m
                .filter(|_| completed)
                .map(|m| m.drift.clone())
                .unwrap_or_default(),
            drift_norm: m.filter(|_| completed).map(|m| m.drift_norm),
            drift_ref_norm: m.filter(|_| completed).map(|m| m.drift_ref_norm),
            max_pos_err: m.map(|m| m.max_position_error),
            rms_pos_err: m.map(|m| m.rms_position_error),
            final_pos_err: m.map(|m| m.final_position_error),
            theta_margin: m.map(|m| m.theta_margin).filter(|v| v.is_finite()),
            thetadot_margin: m.map(|m| m.thetadot_margin).filter(|v| v.is_finite()),
            peak_thetadot: m.map(|m| m.peak_thetadot),
            peak_thetaddot: m.and_then(|m| m.peak_thetaddot),
            peak_torque: m.and_then(|m| m.peak_torque),
            min_sigma_j: m.map(|m| m.min_sigma_j),
            score_samples: score.map(|s| s.samples),
            score_max_dx: score.map(|s| s.max_dx),
            score_rms_dx: score.map(|s| s.rms_dx),
            score_max_obj_gap: score.map(|s| s.max_objective_gap),
            score_max_violation: score.map(|s| s.max_violation),
            score_failures: r.run.score_failures,
            net_error_final: m.and_then(|m| m.network_error).map(|e| e.final_value),
            net_error_max_after_1s: m.and_then(|m| m.network_error).map(|e| e.max_after_settle),
            integrator: j.integrator.method.label().to_string(),
            rtol: j.integrator.rtol,
            atol: j.integrator.atol,
            max_step: j.integrator.max_step,
            steps: r.run.stats.steps,
            rejected: r.run.stats.rejected,
            rhs_evals: r.run.stats.rhs_evals,
            jac_evals: r.run.stats.jac_evals,
            qp_solves: r.run.qp.solves,
            qp_fallbacks: r.run.qp.fallbacks,
            qp_checks: r.run.qp.checks,
            qp_check_max_dx: (r.run.qp.checks > 0).then_some(r.run.qp.check_max_dx),
            wall_s: r.run.stats.wall_seconds,
            sim_s: (r.run.stats.wall_seconds - r.run.observe_seconds).max(0.0),
            observe_s: r.run.observe_seconds,
            crate_version: env!("CARGO_PKG_VERSION").to_string(),
            git_rev: git_rev.to_string(),
        }
    }

    /// The run's identity (ids; also the sort key).
    pub fn key(&self) -> RunKey {
        RunKey::new(&self.experiment, &self.variant_id, &self.solver_id)
    }

    /// A completed row with this identity and every measurement empty or zero (paper `test`,
    /// robot `jaco2-pen`, BDF at 1e-6 / 1e-8; labels equal to the ids): the starting point of
    /// rows built by hand, as in tests of what reads results.
    pub fn blank(experiment: &str, variant: &str, solver: &str, solver_kind: &str) -> Self {
        RunRow {
            paper: "test".into(),
            experiment: experiment.into(),
            variant_id: variant.into(),
            solver_id: solver.into(),
            variant: variant.into(),
            scheme: variant.into(),
            solver: solver.into(),
            solver_kind: solver_kind.into(),
            robot: "jaco2-pen".into(),
            path: "circle".into(),
            path_scale: None,
            duration: 5.0,
            status: Status::Ok,
            failure: String::new(),
            failure_kind: None,
            expected_failure: String::new(),
            failed_at: None,
            drift: Vec::new(),
            drift_norm: None,
            drift_ref_norm: None,
            max_pos_err: None,
            rms_pos_err: None,
            final_pos_err: None,
            theta_margin: None,
            thetadot_margin: None,
            peak_thetadot: None,
            peak_thetaddot: None,
            peak_torque: None,
            min_sigma_j: None,
            score_samples: None,
            score_max_dx: None,
            score_rms_dx: None,
            score_max_obj_gap: None,
            score_max_violation: None,
            score_failures: 0,
            net_error_final: None,
            net_error_max_after_1s: None,
            integrator: "bdf".into(),
            rtol: 1e-6,
            atol: 1e-8,
            max_step: None,
            steps: 0,
            rejected: 0,
            rhs_evals: 0,
            jac_evals: 0,
            qp_solves: 0,
            qp_fallbacks: 0,
            qp_checks: 0,
            qp_check_max_dx: None,
            wall_s: 0.0,
            sim_s: 0.0,
            observe_s: 0.0,
            crate_version: env!("CARGO_PKG_VERSION").to_string(),
            git_rev: "test".into(),
        }
    }

    /// Whether the run completed.
    pub fn completed(&self) -> bool {
        self.status == Status::Ok
    }

    /// Whether the run is the exact column (the optimum in the loop).
    pub fn is_exact(&self) -> bool {
        self.solver_kind == catalog::experiment::EXACT_KIND
    }
}

crate::drift_columns!(RunRow, drift, "drift_norm");

/// Whether a run reached its path's end.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Status {
    /// Completed: drift and every metric over the whole task.
    Ok,
    /// Stopped early (see `failure` and `failure_kind`).
    Failed,
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Status::Ok => "ok",
            Status::Failed => "failed",
        })
    }
}

/// Writes `bytes` to `path` atomically: to a temporary file unique to this call (process id and
/// a counter, so concurrent writers of the same file never share one), then renamed over `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let unique = format!(
        "{}.{}.tmp",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    );
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".");
    name.push(unique);
    let tmp = path.with_file_name(name);
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// Serialises rows as CSV (see [`crate::table`]: as many drift columns as the most joints).
pub fn runs_csv(rows: &[RunRow]) -> Result<Vec<u8>, csv::Error> {
    table::to_csv(rows)
}

/// Reads `results/runs.csv`. Any problem is an error naming the file, the line and how to
/// recover, never a silently shorter list: an unreadable file, a header that is not this
/// version's columns (an old schema: a missing or an unknown column), a row that does not
/// parse, a name that cannot name a file ([`check_rows`]) or a run listed twice. An empty file
/// has no rows.
pub fn read_runs(path: &Path) -> Result<Vec<RunRow>, RunsError> {
    let rows = table::read(path).map_err(|error| RunsError::Table {
        path: path.to_path_buf(),
        error,
    })?;
    check_rows(&rows).map_err(|error| RunsError::Rows {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(rows)
}

/// Checks what a results file says before any of it becomes a path: every row's paper id and
/// run key can name a file ([`RunKey::check`]), its labels are within their limits, and no run
/// is listed twice. The error names the line (the header is line 1).
pub fn check_rows(rows: &[RunRow]) -> Result<(), RowsError> {
    let mut seen = std::collections::HashMap::with_capacity(rows.len());
    for (i, r) in rows.iter().enumerate() {
        let line = i + 2;
        check_name(&r.paper, MAX_EXPERIMENT_ID)
            .and_then(|()| r.key().check())
            .and_then(|()| check_name(&r.variant, MAX_VARIANT_LABEL))
            .and_then(|()| check_name(&r.solver, MAX_SOLVER_LABEL))
            .map_err(|error| RowsError::Name { line, error })?;
        if let Some(first) = seen.insert(r.key(), line) {
            return Err(RowsError::Twice {
                line,
                key: r.key().to_string(),
                first,
            });
        }
    }
    Ok(())
}

/// Checks that files can be created in `dir` (created if absent): writes and removes a probe
/// file. The error names the directory.
pub fn check_writable(dir: &Path) -> Result<(), RunsError> {
    let fail = |source| RunsError::NotWritable {
        dir: dir.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    let probe = dir.join(format!(".write-probe.{}.tmp", std::process::id()));
    std::fs::write(&probe, b"").map_err(fail)?;
    std::fs::remove_file(&probe).map_err(fail)
}

/// Merges freshly computed rows into the stored ones: a fresh row replaces the stored row with
/// the same key; other stored rows are kept (so running one paper does not erase the others).
/// Linear in the rows (a set of the fresh keys), then one sort.
pub fn merge(stored: Vec<RunRow>, fresh: Vec<RunRow>) -> Vec<RunRow> {
    let fresh_keys: std::collections::HashSet<_> = fresh.iter().map(RunRow::key).collect();
    let mut all: Vec<RunRow> = stored
        .into_iter()
        .filter(|s| !fresh_keys.contains(&s.key()))
        .collect();
    all.extend(fresh);
    all.sort_by_key(|r| r.key());
    all
}

/// A run's trace as CSV: t, theta_i, thetadot_i, [thetaddot_i, tau_i], desired and actual
/// position, position error, score dx.
pub fn trace_csv(r: &RunRecord) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let Some(first) = r.run.trace.first() else {
        return w.into_inner().map_err(|e| csv::Error::from(e.into_error()));
    };
    let n = first.theta.len();
    let mut header = vec!["t".to_string()];
    header.extend((1..=n).map(|i| format!("theta_{i}")));
    header.extend((1..=n).map(|i| format!("thetadot_{i}")));
    if first.thetaddot.is_some() {
        header.extend((1..=n).map(|i| format!("thetaddot_{i}")));
    }
    if first.torque.is_some() {
        header.extend((1..=n).map(|i| format!("tau_{i}")));
    }
    header.extend(
        [
            "rx_des",
            "ry_des",
            "rz_des",
            "rx",
            "ry",
            "rz",
            "pos_err",
            "score_dx",
            "net_error",
        ]
        .map(String::from),
    );
    w.write_record(&header)?;
    for p in &r.run.trace {
        let mut rec: Vec<String> = vec![p.t.to_string()];
        rec.extend(p.theta.iter().chain(&p.thetadot).map(f64::to_string));
        if let Some(a) = &p.thetaddot {
            rec.extend(a.iter().map(f64::to_string));
        }
        if let Some(a) = &p.torque {
            rec.extend(a.iter().map(f64::to_string));
        }
        rec.extend(p.desired.iter().chain(&p.actual).map(f64::to_string));
        let err = ((p.desired[0] - p.actual[0]).powi(2)
            + (p.desired[1] - p.actual[1]).powi(2)
            + (p.desired[2] - p.actual[2]).powi(2))
        .sqrt();
        rec.push(err.to_string());
        rec.push(p.score_dx.map(|v| v.to_string()).unwrap_or_default());
        rec.push(p.network_error.map(|v| v.to_string()).unwrap_or_default());
        w.write_record(&rec)?;
    }
    w.into_inner().map_err(|e| csv::Error::from(e.into_error()))
}
