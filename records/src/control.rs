//! The result files of the control experiments (crate `control`), one row type each, written
//! as CSV:
//!
//! - `results/control.csv` ([`ControlRow`]): every (task, method, h) run: latency, accuracy,
//!   drift, work per tick;
//! - `results/control-stability.csv` ([`StabilityRow`]): each network's Euler stability limit
//!   beside its gain;
//! - `results/control-claim.csv` ([`ClaimRow`]): zhong2021's efficiency claim, per task
//!   (crate `analysis`, `control_claim`);
//! - `results/cycles.csv` ([`CycleRow`]): the drift after every cycle of the many-cycles runs,
//!   and `results/cycles-trend.csv` ([`TrendRow`]): each run's trend, and its trend under the
//!   rounding-noise probe.
//!
//! The rows are serialised here ([`to_writer`], [`from_reader`]); crate `store` writes the
//! files for the control experiments and reads them back for the report (`store::control`),
//! with the same types, without linking the solvers that made them. The file names are the
//! store's (`store::results_dir`: `CONTROL`, `CONTROL_NOISE`, `CONTROL_STABILITY`,
//! `CONTROL_CLAIM`, `CYCLES`, `CYCLES_TREND`).

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use spec::ids::{ExperimentId, SolverId, VariantId};

/// How a run at a control rate ended (the `status` column).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ControlStatus {
    /// Every tick ran.
    Ok,
    /// The command blew up (`stopped_at` says when).
    Diverged,
    /// The solver failed (`stopped_at` says when).
    Failed,
}

impl std::fmt::Display for ControlStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

impl ControlStatus {
    /// The column's text (`ok`, `diverged`, `failed`).
    pub fn id(self) -> &'static str {
        match self {
            ControlStatus::Ok => "ok",
            ControlStatus::Diverged => "diverged",
            ControlStatus::Failed => "failed",
        }
    }
}

/// Whether a controller run's method is a network or a numerical QP method (the `family`
/// column).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    /// A recurrent network stepped at the control rate.
    Network,
    /// A numerical QP method (the active set, Clarabel, OSQP, robio2018's methods).
    Numerical,
}

/// The class of a many-cycles run's drift sequence (the `class` column; crate `control`'s
/// `trend` module defines the classes and decides them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum TrendClass {
    /// The motion repeats itself.
    #[serde(rename = "limit cycle")]
    LimitCycle,
    /// The drift neither settles to a repeat nor keeps growing.
    #[serde(rename = "bounded")]
    Bounded,
    /// The drift grows with the number of cycles.
    #[serde(rename = "accumulating")]
    Accumulating,
}

impl TrendClass {
    /// The class in words, as the column stores it.
    pub fn label(self) -> &'static str {
        match self {
            TrendClass::LimitCycle => "limit cycle",
            TrendClass::Bounded => "bounded",
            TrendClass::Accumulating => "accumulating",
        }
    }
}

/// zhong2021's efficiency claim's outcome on one task (the `verdict` column of
/// `control-claim.csv`, stored as its label); crate `analysis`'s `control_claim` decides it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum Verdict {
    /// The network is cheaper at the stated accuracy.
    Pass,
    /// The network cannot be cheaper, even before accuracy is asked for.
    Fail,
    /// Neither.
    Undecided,
}

impl Verdict {
    /// `PASS`, `FAIL` or `UNDECIDED`.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Fail => "FAIL",
            Verdict::Undecided => "UNDECIDED",
        }
    }
}

/// One controller run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ControlRow {
    /// The task's label, `<experiment> / <variant>` (display only).
    pub task: String,
    /// The paper id.
    pub paper: String,
    /// The scheme's display name with its parameters (e.g. `VLTCO (phi=0.2, tau=0.4)`).
    pub scheme: String,
    /// The method's label: a numerical method's name (`active set`, `OSQP`, `94LVI`, ...) or a
    /// network's display name with its discrete form and substeps (e.g. `ZNN [Taylor DTZNN]`).
    pub method: String,
    /// Whether the method is a network or a numerical QP method.
    pub family: Family,
    /// The control period h (ms).
    pub h_ms: f64,
    /// Steps of the network's discrete form per tick (step h / substeps); 1 for a numerical
    /// method.
    pub substeps: u32,
    /// How the run ended.
    pub status: ControlStatus,
    /// When it diverged or failed (s); empty otherwise.
    pub stopped_at: Option<f64>,
    /// Ticks run (all of the cycle's unless the run stopped early).
    pub ticks: usize,
    /// Median duration of the solve alone per tick (us).
    pub solve_p50_us: f64,
    /// 99th percentile of the solve's duration per tick (us).
    pub solve_p99_us: f64,
    /// Longest solve (us).
    pub solve_max_us: f64,
    /// Median duration of the whole tick: QP build, solve and arm step (us).
    pub tick_p50_us: f64,
    /// 99th percentile of the tick's duration (us).
    pub tick_p99_us: f64,
    /// Longest tick (us).
    pub tick_max_us: f64,
    /// Largest tracking error |f(theta_k) - r*(t_k)|_2 over the ticks (m).
    pub max_track_err: f64,
    /// RMS of the tracking error over the ticks (m).
    pub rms_track_err: f64,
    /// |x - x*| of the joint command, relative (see `control::control_loop`).
    pub max_dx: f64,
    /// RMS of that relative |x - x*| over the scored ticks.
    pub rms_dx: f64,
    /// max |x - x*| after the first second.
    pub max_dx_settled: f64,
    /// |theta(T) - theta_0|_2 after the cycle (empty when the run stopped early).
    pub drift: Option<f64>,
    /// Mean work per tick in products with the LVI matrix, for the methods built on jia2019's
    /// LVI (the six PLPE methods, LVI-PDNN, S-LVI-PDNN); empty for the others.
    pub products_mean: Option<f64>,
    /// Largest work of one tick in those products; empty as `products_mean`.
    pub products_max: Option<u64>,
    /// Mean iterations (a network: steps) per tick.
    pub iterations_mean: f64,
    /// Largest iterations (a network: steps) of one tick.
    pub iterations_max: u32,
}

/// Read and written as any results table too (the regression gate reads git HEAD's copy).
impl crate::table::Row for ControlRow {}

/// The noise floor of one controller run: the run of the [`ControlRow`] with the same key
/// (task, paper, scheme, method, family, h_ms, substeps) repeated with its joint angles moved by
/// one ulp after every tick (crate `control`'s `rounding` module), and for each deterministic
/// metric m of the row (those that are not wall-clock) the relative change |m' - m| / |m| of the
/// probe's value m' (crate `control`'s `noise_floor` module): 0 when the two are equal (both
/// empty included); empty when only one is empty, either is not a number, or m = 0 != m'.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NoiseRow {
    /// The task's label, `<experiment> / <variant>` (display only), as in `control.csv`.
    pub task: String,
    /// The paper id.
    pub paper: String,
    /// The scheme's display name with its parameters, as in `control.csv`.
    pub scheme: String,
    /// The method's label, as in `control.csv`.
    pub method: String,
    /// Whether the method is a network or a numerical QP method.
    pub family: Family,
    /// The control period h (ms).
    pub h_ms: f64,
    /// Steps of the network's discrete form per tick, as in `control.csv`.
    pub substeps: u32,
    /// How the probe ended.
    pub status_under_noise: ControlStatus,
    /// Relative change of `stopped_at`.
    pub stopped_at_noise: Option<f64>,
    /// Relative change of `ticks`.
    pub ticks_noise: Option<f64>,
    /// Relative change of `max_track_err`.
    pub max_track_err_noise: Option<f64>,
    /// Relative change of `rms_track_err`.
    pub rms_track_err_noise: Option<f64>,
    /// Relative change of `max_dx`.
    pub max_dx_noise: Option<f64>,
    /// Relative change of `rms_dx`.
    pub rms_dx_noise: Option<f64>,
    /// Relative change of `max_dx_settled`.
    pub max_dx_settled_noise: Option<f64>,
    /// Relative change of `drift`.
    pub drift_noise: Option<f64>,
    /// Relative change of `products_mean`.
    pub products_mean_noise: Option<f64>,
    /// Relative change of `products_max`.
    pub products_max_noise: Option<f64>,
    /// Relative change of `iterations_mean`.
    pub iterations_mean_noise: Option<f64>,
    /// Relative change of `iterations_max`.
    pub iterations_max_noise: Option<f64>,
}

/// A network's Euler stability limit on a task.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StabilityRow {
    /// The task's label, `<experiment> / <variant>` (display only).
    pub task: String,
    /// The network's display name.
    pub network: String,
    /// The network's solver id (its identity).
    pub solver_id: SolverId,
    /// The gain's name as the papers write it (`gamma`, `beta`, `gamma (x exp t)`).
    pub gain_name: String,
    /// The paper's gain.
    pub gain: f64,
    /// Largest stable Euler step (s), smallest over the sampled states; empty when the
    /// network gives no Jacobian.
    pub euler_limit_s: Option<f64>,
    /// The instant the smallest limit was found at.
    pub limit_at_s: Option<f64>,
    /// gain x limit (dimensionless).
    pub gain_x_limit: Option<f64>,
    /// The largest control period of the sweep at which the network ran (Euler, one step per
    /// tick) without diverging; empty when it diverged at every period.
    pub largest_stable_h_ms: Option<f64>,
}

/// Euler steps per tick a network needs to be stable at the control period `h` (s) with its
/// Euler stability limit `limit` (s): n = ceil(h / limit), at least 1 (the `steps_needed`
/// column of [`ClaimCheck`] and [`ClaimRow`]).
pub fn steps_needed(h: f64, limit: f64) -> u64 {
    (h / limit).ceil().max(1.0) as u64
}

/// What the control experiments measure for the efficiency claim on one task: a network's check
/// run and the numerical method it is compared with (crate `control` runs it; crate
/// `analysis`'s `control_claim` turns it into a [`ClaimRow`], deciding the verdict). The
/// fields are those of [`ClaimRow`] that are measured, not decided.
#[derive(Clone, Debug, PartialEq)]
pub struct ClaimCheck {
    /// The task's label (`<experiment> / <variant>`, display only).
    pub task: String,
    /// The network's display name.
    pub network: String,
    /// The task's experiment id.
    pub experiment: ExperimentId,
    /// The task's variant id.
    pub variant_id: VariantId,
    /// The network's solver id.
    pub solver_id: SolverId,
    /// The control period h (ms).
    pub h_ms: f64,
    /// The network's work per Euler step, in products with the LVI matrix.
    pub products_per_step: u64,
    /// The network's Euler stability limit on the task (s).
    pub euler_limit_s: f64,
    /// Euler steps per tick the network needs to be stable at all ([`steps_needed`]).
    pub steps_needed: u64,
    /// The check run's Euler steps per tick.
    pub check_steps: u64,
    /// Ticks of the check run.
    pub check_ticks: usize,
    /// How the check run ended.
    pub check_status: ControlStatus,
    /// The check run's largest relative |x - x*|_inf.
    pub check_max_dx: f64,
    /// The check run's median solve latency (us).
    pub check_solve_p50_us: f64,
    /// The numerical method compared (its name).
    pub numerical: String,
    /// Its mean work per tick, in products with the LVI matrix.
    pub numerical_products_mean: f64,
    /// Its largest work of one tick.
    pub numerical_products_max: u64,
    /// Its largest relative |x - x*|_inf.
    pub numerical_max_dx: f64,
    /// Its median solve latency (us).
    pub numerical_solve_p50_us: f64,
}

/// The efficiency claim on one task (crate `analysis`'s `control_claim` decides it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// The task's label (`<experiment> / <variant>`, display only).
    pub task: String,
    /// The network's display name.
    pub network: String,
    /// The task's experiment and variant ids, and the network's solver id: the run of
    /// `results/runs.csv` the claim is about.
    pub experiment: ExperimentId,
    /// The task's variant id.
    pub variant_id: VariantId,
    /// The network's solver id.
    pub solver_id: SolverId,
    /// The control period h (ms): [`spec::MAIN_H`].
    pub h_ms: f64,
    /// The accuracy asked for: |x - x*|_inf / max(1, |x*|_inf) at every tick
    /// (`analysis::control_claim::ACCURACY`).
    pub accuracy: f64,
    /// The network's work per Euler step, in products with the LVI matrix.
    pub products_per_step: u64,
    /// The network's Euler stability limit on the task (s).
    pub euler_limit_s: f64,
    /// Euler steps per tick the network needs to be stable at all ([`steps_needed`]).
    pub steps_needed: u64,
    /// Products per tick at that step count (a lower bound on the network's cost).
    pub network_products: f64,
    /// The check run: steps per tick, its largest |x - x*| and its solve latency p50.
    pub check_steps: u64,
    /// Ticks of the check run.
    pub check_ticks: usize,
    /// How the check run ended.
    pub check_status: ControlStatus,
    /// The check run's largest relative |x - x*|_inf.
    pub check_max_dx: f64,
    /// The check run's median solve latency (us).
    pub check_solve_p50_us: f64,
    /// The numerical method compared: of robio2018's methods that completed the task at h, the
    /// one of least mean work per tick (its name).
    pub numerical: String,
    /// Its mean work per tick, in products with the LVI matrix.
    pub numerical_products_mean: f64,
    /// Its largest work of one tick.
    pub numerical_products_max: u64,
    /// Its largest relative |x - x*|_inf.
    pub numerical_max_dx: f64,
    /// Its median solve latency (us).
    pub numerical_solve_p50_us: f64,
    /// network products per tick over the numerical method's mean.
    pub cost_ratio: f64,
    /// `PASS`, `FAIL` or `UNDECIDED` in the file.
    pub verdict: Verdict,
}

/// The drift after one cycle of a many-cycles run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CycleRow {
    /// The task's label, `<experiment> / <variant>` (display only).
    pub task: String,
    /// The scheme's display name with its parameters (e.g. `VLTCO (phi=0.2, tau=0.4)`).
    pub scheme: String,
    /// The method's label, as in `control.csv`; `exact (continuous)` for the exact optimum
    /// integrated in continuous time.
    pub method: String,
    /// The control period; empty for a continuous-time run.
    pub h_ms: Option<f64>,
    /// The cycle c, from 1.
    pub cycle: usize,
    /// |theta(c T) - theta_0|_2 after cycle c (rad).
    pub drift: f64,
    /// |theta(c T) - theta((c - 1) T)|_2: the change over cycle c alone (rad).
    pub change: f64,
}

/// The trend of one many-cycles run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrendRow {
    /// The task's label, `<experiment> / <variant>` (display only).
    pub task: String,
    /// The scheme's display name with its parameters (e.g. `VLTCO (phi=0.2, tau=0.4)`).
    pub scheme: String,
    /// The method's label, as in `cycles.csv`.
    pub method: String,
    /// The control period; empty for a continuous-time run.
    pub h_ms: Option<f64>,
    /// How the run ended.
    pub status: ControlStatus,
    /// Why the run stopped before its last cycle, in words (empty when it completed).
    pub failure: Option<String>,
    /// Cycles completed.
    pub cycles: usize,
    /// The drift after the first cycle (rad); empty when none completed.
    pub drift_first: Option<f64>,
    /// The drift after the last completed cycle (rad); empty when none completed.
    pub drift_last: Option<f64>,
    /// rad/cycle, fitted over the second half.
    pub rate: Option<f64>,
    /// Empty with fewer than three cycles.
    pub class: Option<TrendClass>,
    /// The class of the same run with its joint angles moved by one ulp after every tick (in
    /// continuous time: theta_0 moved once; crate `control`'s `rounding` module); empty with
    /// fewer than three cycles of that run.
    pub class_under_noise: Option<TrendClass>,
    /// The relative change |b' - b| / |b| of `rate` under the same probe (as the columns of
    /// [`NoiseRow`]: 0 when equal, empty when undefined).
    pub rate_noise: Option<f64>,
}

/// Serialises `rows` to `out` as CSV: a header of the row type's fields, then a line per row.
pub fn to_writer<T: Serialize>(out: impl std::io::Write, rows: &[T]) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    for r in rows {
        w.serialize(r)?;
    }
    w.flush()?;
    Ok(())
}

/// The rows of the CSV `input` (a header, then a line per row), each parsed as `T`.
pub fn from_reader<T: DeserializeOwned>(input: impl std::io::Read) -> Result<Vec<T>, csv::Error> {
    csv::Reader::from_reader(input).deserialize().collect()
}
