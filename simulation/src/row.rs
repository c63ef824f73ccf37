//! A run's record as a row of `results/runs.csv` ([`records::RunRow`]): the job's identity
//! and settings, the outcome (a failed run keeps its metrics up to the failure, but no drift),
//! every metric and the score against the exact optimum, the integrator's counts, the exact
//! QPs' counts and the wall times. The row's schema is records'; what goes in each column from
//! a [`RunRecord`] is the engine's knowledge, so the conversion is here.

use crate::run::RunRecord;
use crate::simulate::Outcome;
use records::{RunRow, Status};

/// The row of the run `r` (module docs), stamped with the code revision `git_rev`.
pub fn run_row(r: &RunRecord, git_rev: &str) -> RunRow {
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
        solver_id: j.key().solver,
        variant: j.variant.clone(),
        scheme: r.run.scheme_name.clone(),
        solver: j.solver.label(),
        solver_kind: j.solver.kind(),
        robot: j.robot.clone(),
        path: j.path.name.clone(),
        path_scale: j.path.scale.or_else(|| spec::default_scale(&j.path.name)),
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
        score_rms_dx_after_1s: score.and_then(|s| s.rms_dx_after_settle),
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
        solver_iterations: r.run.iterations.map(|i| i.total),
        solver_iterations_max: r.run.iterations.map(|i| i.max),
        solver_products: r.run.iterations.and_then(|i| i.products),
        wall_s: r.run.stats.wall_seconds,
        sim_s: (r.run.stats.wall_seconds - r.run.observe_seconds).max(0.0),
        observe_s: r.run.observe_seconds,
        crate_version: env!("CARGO_PKG_VERSION").to_string(),
        git_rev: git_rev.to_string(),
    }
}
