//! driftbench's analysis: the papers as data, and every verdict drawn from the records against
//! them. Crate `records` holds what runs leave behind (schemas and the store); this crate
//! decides; the report (crate `presentation`) only renders what is decided here.
//!
//! - [`papers`]: the papers as data (`papers/<paper>/`): metadata, published numbers and which
//!   run each one is compared with; what a paper folder must satisfy (ids, one-line texts,
//!   unique mappings, checked values, at most [`MAX_CLAIMS`] claims), checked before anything
//!   runs; that a paper names only runs that exist ([`check_paper_runs`]); the metrics a
//!   paper's numbers may name ([`PUBLISHED_METRICS`]); that a text reaching the report is one
//!   line ([`is_one_line`]).
//! - [`claims`]: a paper's claims as data (a metric of a selection of runs against a threshold
//!   or another selection).
//! - a published table set beside a sweep's runs, compared in [`sweep_comparison`]; [`published_table`]: a published table beside ours (its columns,
//!   quantities and ratios).
//! - [`leaderboard`]: every velocity-level solver on the standard task set, scored as
//!   qpbenchmark scores QP solvers (`results/leaderboard.csv`); [`leaderboard_reading`]: what its
//!   text says (the best per measure, the spread of the timings).
//! - [`gate`]: the regression gate (fresh rows against committed ones).
//! - [`control_claim`]: zhong2021's efficiency claim decided from the control experiments'
//!   numbers; [`control_track`]: the control-rate track (success, its leaderboard); what their
//!   noise floor under the rounding-noise probe says ([`NoiseSummary`], module
//!   `control_noise`, built into the report model).
//! - [`inference_verdict`]: the setup inference's verdicts in words.
//! - [`claim_verdict`]: each paper's claims evaluated from the stored runs (PASS, FAIL or N/A,
//!   with the numbers as evidence); [`cost_ratio`]: zhong2021's compute-time ratios, one of
//!   which decides a claim.
//! - [`misprints`]: a published column whose printed norm contradicts its printed entries, and
//!   the single misprints (one exponent, digit, sign, swapped entry) that would reconcile it.
//! - [`paper_verdict`]: each paper's verdict level (reproduced, qualitatively, partly, not)
//!   from its claims and drift ratios.
//! - [`drift_attribution`]: what the drift attribution and the tolerance ladder say (the share
//!   of each term, the runs at MATLAB's default tolerances).
//! - [`cross_best`]: the best solver of each column of the cross experiment.
//! - [`sweep_summary`]: the runs the report holds, read in bounded memory, and a large
//!   sweep's summary aggregated row by row (counts, extremes, failures, per-parameter ranges,
//!   heat map, distribution), for its page and figure.
//! - [`performance`]: what the measurements of the solvers' cost and the runs' times say,
//!   against their targets (the suite's measurements of itself are crate
//!   `driftbench-benches`'s).
//! - [`fits`]: the growth exponents of cost against the number of joints, and the size where
//!   faer's dense LU overtakes nalgebra's.
//! - [`sci`]: the one way numbers are written in words (evidence and the report).
//! - [`report_model`]: the report's decided content as one typed model, built once per render
//!   (the papers' verdicts, tables, contradictions and sweep checks, the leaderboard and its
//!   reading, the control claim and track, the MATLAB times, the cross experiment's bests,
//!   the sweep summaries, the setup inference's verdicts, every paper's drift attribution
//!   and tolerance ladder, the Performance page's costs, fits and targets).
//!
//! The verdict modules are public modules, each a vocabulary of its own (their types,
//! constants and deciding functions by short names); `presentation/tests/report_model.rs`
//! tells the report's use of their types from calls of their functions by module. The paper
//! folders' checks and the number format are items at the root.

pub mod claim_verdict;
pub mod claims;
pub mod control_claim;
mod control_noise;
pub mod control_track;
pub mod cost_ratio;
pub mod cross_best;
pub mod drift_attribution;
pub mod fits;
pub mod gate;
pub mod inference_verdict;
pub mod leaderboard;
pub mod leaderboard_reading;
pub mod misprints;
mod number;
mod paper_rules;
mod paper_runs;
pub mod paper_verdict;
pub mod papers;
pub mod performance;
mod published_metrics;
pub mod published_table;
pub mod report_model;
mod report_text;
mod sweep_check;
pub mod sweep_comparison;
pub mod sweep_summary;
pub use control_noise::{NoiseSummary, LISTED as NOISE_LISTED};
pub use number::sci;
pub use paper_rules::{GROUP as GROUP_PAPER, MAX_CLAIMS};
pub use paper_runs::{check_runs as check_paper_runs, Absent as AbsentRun};
pub use published_metrics::PUBLISHED_METRICS;
pub use report_text::is_one_line;
