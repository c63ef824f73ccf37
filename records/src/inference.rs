//! `results/inference.csv` and `results/inference-entries.csv`: the setup inference's rows
//! (crate `explain`, module `inference`), which fits the setup a paper leaves open (path pose
//! and plane tilt, size, direction, RMP reading; robot variant and how the drift is computed,
//! [`Integration`]) to one published drift table.
//!
//! With a setup s and the published per-joint drifts d_paper, a column c's residual is
//! r_c(s) = || d(s)[c, :] - d_paper[c, :] || / || d_paper[c, :] || and the table's
//! r(s) = sqrt( mean_c r_c(s)^2 ). An [`InferenceRow`] is one setup of a table: its kind
//! ([`DECLARED`], [`BEST`], [`HYPOTHESIS`], [`LOCAL`], a profile point [`PROFILE`]), the
//! objective its `rel_residual` measures ([`TABLE`]: r, or a column's name: its r_c), the setup
//! itself and its residuals. An [`EntryRow`] is one published entry beside ours under a reported
//! setup.

use serde::{Deserialize, Serialize};
use settings::{IntegratorSettings, Method};

/// Penalty residual of a setup whose run fails (an unreachable pose, an infeasible QP); the
/// report prints such points as failed, and crate `analysis`'s `inference_verdict` leaves them out.
pub const FAILED: f64 = 10.0;

/// How a setup's drift is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integration {
    /// The scheme's exact optimum in the loop at tight tolerances (the exact column).
    Exact,
    /// The paper's network integrated by BDF (ode15s's method) at MATLAB's default tolerances,
    /// RelTol 1e-3 / AbsTol 1e-6.
    NetworkMatlabDefault,
    /// The paper's network integrated as the experiment states (the papers' RelTol 1e-6 /
    /// AbsTol 1e-8).
    NetworkStated,
}

impl Integration {
    /// The network run's integrator (the exact column's is set by the problem).
    pub fn integrator(self, stated: &IntegratorSettings) -> IntegratorSettings {
        match self {
            Integration::NetworkMatlabDefault => IntegratorSettings {
                method: Method::Bdf,
                rtol: 1e-3,
                atol: 1e-6,
                ..*stated
            },
            Integration::Exact | Integration::NetworkStated => *stated,
        }
    }

    /// Words for the report.
    pub fn describe(self) -> &'static str {
        match self {
            Integration::Exact => "exact column (scheme's optimum, tight tolerances)",
            Integration::NetworkMatlabDefault => {
                "paper's network at MATLAB's default tolerances (BDF, RelTol 1e-3 / AbsTol 1e-6)"
            }
            Integration::NetworkStated => "paper's network at the stated tolerances",
        }
    }
}

/// Names of the continuous coordinates (the size factor is searched as its logarithm).
pub const ROTATION: &str = "rotation";
/// Name of the start-phase coordinate ([`InferenceRow::phase`]).
pub const PHASE: &str = "phase";
/// Name of the size-factor coordinate ([`InferenceRow::scale_factor`]).
pub const SCALE: &str = "scale_factor";
/// Name of the x-tilt coordinate ([`InferenceRow::tilt_x`]).
pub const TILT_X: &str = "tilt_x";
/// Name of the y-tilt coordinate ([`InferenceRow::tilt_y`]).
pub const TILT_Y: &str = "tilt_y";

/// `objective` of the rows of the whole table.
pub const TABLE: &str = "table";
/// Row kinds.
pub const DECLARED: &str = "declared";
/// Kind of the setup with the least residual of its objective over every setup searched.
pub const BEST: &str = "best fit";
/// Kind of the best setup of one hypothesis (a robot and an [`Integration`]).
pub const HYPOTHESIS: &str = "hypothesis best";
/// Kind of the end point of one local search.
pub const LOCAL: &str = "local optimum";
/// Prefix of a profile row's kind: `profile (re-fitted): <parameter>` or
/// `profile (slice): <parameter>`.
pub const PROFILE: &str = "profile";

/// One row of `results/inference.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InferenceRow {
    /// The paper id.
    pub paper: String,
    /// The published table fitted (`T2`, `T3`, ...).
    pub table: String,
    /// [`DECLARED`], [`BEST`], [`HYPOTHESIS`], [`LOCAL`] or a profile (see [`PROFILE`]).
    pub kind: String,
    /// What the row's `rel_residual` measures: [`TABLE`] (r) or a column's name (its r_c).
    pub objective: String,
    /// The robot model of the setup.
    pub robot: String,
    /// How the setup's drift is computed.
    pub integration: Integration,
    /// In-plane rotation of every path of the table (rad).
    pub rotation: f64,
    /// Start phase on the closed curves (fraction of the cycle).
    pub phase: f64,
    /// Factor on every path's size (1: the declared size).
    pub scale_factor: f64,
    /// Tilt of the drawing plane about the base x axis (rad).
    pub tilt_x: f64,
    /// Tilt of the drawing plane about the base y axis (rad).
    pub tilt_y: f64,
    /// Whether the paths are travelled backwards.
    pub reverse: bool,
    /// How the RMP term's coefficient was read (stored by its serde name: `printed`, ...).
    pub rmp: spec::RmpReading,
    /// The row's objective at this setup: r, or the column's r_c ([`FAILED`] when a run failed).
    pub rel_residual: f64,
    /// r of the whole table at this setup.
    pub table_residual: f64,
    /// r_c of every column at this setup, in column order, `;`-separated.
    pub column_residuals: String,
    /// Largest |d - d_paper| / |d_paper| over the objective's entries; empty for local optima and
    /// profile points.
    pub max_entry_error: Option<f64>,
    /// Entries of the objective whose sign is the paper's; empty as `max_entry_error`.
    pub signs_matched: Option<usize>,
    /// Entries of the objective (published per-joint drifts); empty as `max_entry_error`.
    pub entries: Option<usize>,
    /// Setups evaluated by the whole search (on the table's best-fit row; 0 on the others).
    pub evaluations: usize,
    /// Wall time of the whole search (s; on the table's best-fit row; 0 on the others).
    pub wall_s: f64,
}

impl crate::table::Row for InferenceRow {}

impl InferenceRow {
    /// The profiled parameter and whether the others were re-fitted, for a profile row.
    pub fn profile(&self) -> Option<(&str, bool)> {
        let rest = self.kind.strip_prefix(PROFILE)?;
        if let Some(name) = rest.strip_prefix(" (re-fitted): ") {
            Some((name, true))
        } else {
            rest.strip_prefix(" (slice): ").map(|name| (name, false))
        }
    }

    /// The value of parameter `name` (a coordinate's name) in this row.
    pub fn parameter(&self, name: &str) -> f64 {
        match name {
            ROTATION => self.rotation,
            PHASE => self.phase,
            SCALE => self.scale_factor,
            TILT_X => self.tilt_x,
            _ => self.tilt_y,
        }
    }

    /// r_c of every column, parsed back.
    pub fn columns(&self) -> Vec<f64> {
        self.column_residuals
            .split(';')
            .filter_map(|v| v.parse().ok())
            .collect()
    }
}

/// One entry of a reported setup, for `results/inference-entries.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EntryRow {
    /// The paper id.
    pub paper: String,
    /// The published table (`T2`, `T3`, ...).
    pub table: String,
    /// [`DECLARED`], [`BEST`] (the joint fit) or [`COLUMN_FIT`] (that column alone).
    pub setup: String,
    /// The table's column, as the paper's values (`papers/<paper>/values.csv`) name it.
    pub column: String,
    /// The joint, numbered from 1.
    pub joint: usize,
    /// Our drift of that joint under the setup (rad).
    pub ours: f64,
    /// The published drift (rad).
    pub paper_value: f64,
    /// |ours - paper_value| / |paper_value|.
    pub rel_error: f64,
    /// Whether `ours` has the published value's sign.
    pub sign_matched: bool,
}

/// `setup` of the entries of a column's own fit.
pub const COLUMN_FIT: &str = "column fit";

impl crate::table::Row for EntryRow {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matlab_defaults_keep_the_stated_step_limit() {
        let stated = IntegratorSettings {
            max_step: Some(0.05),
            ..IntegratorSettings::default()
        };
        let m = Integration::NetworkMatlabDefault.integrator(&stated);
        assert_eq!((m.method, m.rtol, m.atol), (Method::Bdf, 1e-3, 1e-6));
        assert_eq!(m.max_step, Some(0.05));
        assert_eq!(Integration::NetworkStated.integrator(&stated), stated);
    }
}
