//! `results/`: the committed CSV the report and the regression gate read.
//!
//! - `results/runs.csv`: one row per run ([`RunRow`]): identity, outcome, every metric, the
//!   score against the exact optimum, and provenance (integrator, tolerances, steps,
//!   evaluations, wall time, crate version, git revision).
//! - `results/traces/<experiment>/<variant id>__<solver id>.csv`: the thinned time history of
//!   each run for the figures ([`crate::trace`]).
//!
//! This module serialises and checks the rows; crate `store` reads and writes the file (to a
//! temporary name, then renamed, so an interrupted run never leaves a half-written file). Rows
//! are sorted by their [`RunKey`] (ids) so that two runs give
//! byte-identical files except for the timing columns (`wall_s`, `sim_s`, `observe_s`) and `git_rev`.

use crate::error::RowsError;
use crate::failure_kind::FailureKind;
use crate::table;
use serde::{Deserialize, Serialize};
use spec::ids::{ExperimentId, SolverId, VariantId};
use spec::RunKey;
use spec::SolverKind;
use spec::{check_name, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL};

/// One run, as stored in `results/runs.csv` (the engine makes it from a run's record:
/// `simulation::run_row`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRow {
    /// The paper id of the run's experiment file (e.g. `jia2019`).
    pub paper: String,
    /// The experiment's id (with `variant_id` and `solver_id`, the run's [`RunKey`]).
    pub experiment: ExperimentId,
    /// The variant's id (with `experiment` and `solver_id`, the run's [`RunKey`]).
    pub variant_id: VariantId,
    /// The solver's id: `exact`, or the network's id (kind and distinguishing parameters).
    pub solver_id: SolverId,
    /// The variant's label (display only).
    pub variant: String,
    /// The scheme's name as its paper writes it (e.g. `VLTCO`, `MTN`); for a run that could not be
    /// built, the scheme specification's display name with its parameters.
    pub scheme: String,
    /// The solver's label with its parameters (display only).
    pub solver: String,
    /// The solver's kind (stored as its id: `exact`, `lvi-pdnn`, `94lvi`, ...).
    pub solver_kind: SolverKind,
    /// The robot's model name (e.g. `jaco2-pen`).
    pub robot: String,
    /// The path's name (e.g. `four-leaf-clover`).
    pub path: String,
    /// The path's size (m): the experiment's `scale`, else the path's default (docs/paths.md);
    /// empty for a path without one.
    pub path_scale: Option<f64>,
    /// The task duration T (s).
    pub duration: f64,
    /// Whether the run completed (`ok`) or stopped early (`failed`).
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
    /// |theta(T) - theta(0)|_2 (rad); empty for a failed run.
    pub drift_norm: Option<f64>,
    /// |theta(T) - theta_ref|_2 (rad), the drift from the scheme's reference (kong2019's theta*0;
    /// equal to `drift_norm` where the experiment gives no `theta_ref`); empty for a failed run.
    pub drift_ref_norm: Option<f64>,
    /// Largest position error |r*(t) - f(theta(t))|_2 over the accepted steps (m); a failed run's
    /// up to its failure; empty when no step was taken.
    pub max_pos_err: Option<f64>,
    /// Time-weighted RMS of the position error, sqrt((1/T) integral |e|^2 dt) by the trapezoid
    /// rule over the accepted steps (m); empty when no step was taken.
    pub rms_pos_err: Option<f64>,
    /// Position error at the last accepted step (m); empty when no step was taken.
    pub final_pos_err: Option<f64>,
    /// Smallest distance of a joint angle to a finite limit over joints and time (rad; negative:
    /// violated); empty when no limit is finite or no step was taken.
    pub theta_margin: Option<f64>,
    /// Smallest distance of a joint velocity to a finite limit over joints and time (rad/s;
    /// negative: violated); empty when no limit is finite or no step was taken.
    pub thetadot_margin: Option<f64>,
    /// Largest |thetadot|_inf along the run (rad/s); empty when no step was taken.
    pub peak_thetadot: Option<f64>,
    /// Largest |thetaddot|_inf along the run (rad/s^2); acceleration-level schemes only.
    pub peak_thetaddot: Option<f64>,
    /// Largest |tau|_inf along the run (N m); schemes with a dynamics model only.
    pub peak_torque: Option<f64>,
    /// Smallest singular value of the 3 x n position Jacobian along the run (m/rad): the distance
    /// from a singularity; empty when no step was taken.
    pub min_sigma_j: Option<f64>,
    /// Instants scored against the exact optimum; empty when the run was not scored (the exact
    /// column, `scoring = "off"`).
    pub score_samples: Option<usize>,
    /// Largest |x - x*|_inf over the joint command at the scored instants (rad/s at the velocity
    /// level, rad/s^2 at the acceleration level); empty when not scored.
    pub score_max_dx: Option<f64>,
    /// RMS of |x − x*|_inf over the run, time-weighted (rad/s at the velocity level, rad/s^2 at
    /// the acceleration level).
    pub score_rms_dx: Option<f64>,
    /// The same over t >= 1 s only (`simulation::SETTLE_TIME`): after the start-up
    /// transient of a network started from zero. The leaderboard's success test.
    pub score_rms_dx_after_1s: Option<f64>,
    /// Largest relative objective gap (f(x) - f(x*)) / max(1, |f(x*)|) at the scored instants;
    /// empty when not scored.
    pub score_max_obj_gap: Option<f64>,
    /// Largest constraint violation of x at the scored instants; empty when not scored.
    pub score_max_violation: Option<f64>,
    /// Scoring instants where the exact solve failed (left out of the score).
    pub score_failures: usize,
    /// The network's own error norm at T (|Q y - u| for the zeroing networks).
    pub net_error_final: Option<f64>,
    /// Its largest value after t = 1 s (kong2019: "settles within ~1 s").
    pub net_error_max_after_1s: Option<f64>,
    /// The integration method (`bdf`, `esdirk34`, `tr-bdf2`, `dopri5`, `tsit45`); a numerical
    /// run's carries its experiment's exact-column setting, unused; `trajectory` for a scored
    /// trajectory.
    pub integrator: String,
    /// The integrator's relative tolerance (0 for a scored trajectory).
    pub rtol: f64,
    /// The integrator's absolute tolerance (0 for a scored trajectory).
    pub atol: f64,
    /// The integrator's largest step (ode15s's MaxStep), where the run sets one.
    #[serde(default)]
    pub max_step: Option<f64>,
    /// Accepted integrator steps (a numerical run: instants of its fixed-step loop after the
    /// first; a scored trajectory: its samples).
    pub steps: usize,
    /// Steps rejected by the integrator's local error test.
    pub rejected: usize,
    /// Evaluations of the ODE's right-hand side, those of finite-difference Jacobians included.
    pub rhs_evals: usize,
    /// Dense Jacobian evaluations (analytic or finite-difference).
    pub jac_evals: usize,
    /// Exact QPs solved: in the loop for the exact column, to score the other runs.
    pub qp_solves: usize,
    /// Exact QPs the certified active-set solver could not answer (Clarabel did).
    pub qp_fallbacks: usize,
    /// Certified active-set answers also solved by Clarabel (the first and every 100th).
    pub qp_checks: usize,
    /// Largest relative |x_active_set - x_clarabel|_inf over those checks.
    pub qp_check_max_dx: Option<f64>,
    /// A numerical run solver's iterations over the whole run (robio2018 (21) steps; empty for
    /// the exact column and the networks).
    pub solver_iterations: Option<u64>,
    /// Its largest iteration count at one instant.
    pub solver_iterations_max: Option<u64>,
    /// Its work over the run in products with the LVI matrix (the unit of the control
    /// tables: the same on every machine and under any load).
    pub solver_products: Option<u64>,
    /// Wall time of the whole integration.
    pub wall_s: f64,
    /// Wall time of the simulation proper (arm + solver + integrator): `wall_s - observe_s`.
    /// The number to compare solvers by.
    pub sim_s: f64,
    /// Wall time of the observation at accepted steps (metrics, trace, the Clarabel solves that
    /// score a neural run or give the exact column's thetadot).
    pub observe_s: f64,
    /// The version of the code that made the row (the workspace's crate version).
    pub crate_version: String,
    /// The code revision that made the row: the commit (12 hex digits), `<commit>-dirty-<hash>`
    /// when the sources differed from it, `src-<hash>` without git.
    pub git_rev: String,
}

impl RunRow {
    /// The step of a fixed-step loop over the run (a numerical method's, robio2018
    /// Algorithm 1): h = duration / steps, with at least one step.
    pub fn fixed_step(&self) -> f64 {
        self.duration / self.steps.max(1) as f64
    }

    /// The run's identity (ids; also the sort key).
    pub fn key(&self) -> RunKey {
        RunKey::new(
            self.experiment.clone(),
            self.variant_id.clone(),
            self.solver_id.clone(),
        )
    }

    /// A completed row with this identity and every measurement empty or zero (paper `test`,
    /// robot `jaco2-pen`, BDF at 1e-6 / 1e-8; labels equal to the ids): the starting point of
    /// rows built by hand, as in tests of what reads results.
    pub fn blank(key: &RunKey, solver_kind: SolverKind) -> Self {
        RunRow {
            paper: "test".into(),
            experiment: key.experiment.clone(),
            variant_id: key.variant.clone(),
            solver_id: key.solver.clone(),
            variant: key.variant.to_string(),
            scheme: key.variant.to_string(),
            solver: key.solver.to_string(),
            solver_kind,
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
            score_rms_dx_after_1s: None,
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
            solver_iterations: None,
            solver_iterations_max: None,
            solver_products: None,
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
        self.solver_kind == SolverKind::Exact
    }
}

crate::drift_columns!(
    RunRow,
    drift,
    "drift_norm",
    [
        "solver_iterations",
        "solver_iterations_max",
        "solver_products",
        "score_rms_dx_after_1s"
    ]
);

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

/// Serialises rows as CSV (see [`crate::table`]: as many drift columns as the most joints).
pub fn runs_csv(rows: &[RunRow]) -> Result<Vec<u8>, csv::Error> {
    table::to_csv(rows)
}

/// Checks what a results file says before any of it becomes a path: every row's paper id can
/// name a file (its run key's ids were checked as they were read: `spec::ids`), its labels
/// are within their limits, and no run is listed twice. The error names the line (the header is line 1).
pub fn check_rows(rows: &[RunRow]) -> Result<(), RowsError> {
    let mut seen = std::collections::HashMap::with_capacity(rows.len());
    for (i, r) in rows.iter().enumerate() {
        let line = i + 2;
        check_names(r, line)?;
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

/// Checks that the names of the row at `line` can name files (see [`check_rows`]).
pub fn check_names(r: &RunRow, line: usize) -> Result<(), RowsError> {
    check_name(&r.paper, MAX_EXPERIMENT_ID)
        .and_then(|()| check_name(&r.variant, MAX_VARIANT_LABEL))
        .and_then(|()| check_name(&r.solver, MAX_SOLVER_LABEL))
        .map_err(|error| RowsError::Name { line, error })
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
