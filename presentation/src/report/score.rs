//! The score against the exact optimum: for every neural run, how far the network's output
//! is from the exact minimiser x* of the same QP along the network's own trajectory.
//!
//! Scores are taken at every accepted integrator step: max and RMS of |x_nn − x*|_inf over
//! the joint command, the largest objective gap and the largest constraint violation.

use super::markdown::{sci_opt, Table};
use analysis::sweep_summary::SweepSummary;
use records::index::{is_neural, status_text, Runs};

/// What the score means, printed once above the tables.
pub const NOTE: &str =
    "Every network starts from the zero state, so the max includes the initial transient \
(x_nn = 0 against x*(0)); the RMS is taken over accepted integrator steps, which cluster where the \
dynamics are fast. VP-RNN-PF's equilibrium is the exponential-penalty optimum, not x*: its score \
measures the penalty approximation (p, sigma), not a fault of the network.";

/// The score table of one paper's neural runs (empty when it has none; of a large sweep of
/// `sweeps`, the neural runs of its sample: [`super::tables::shown`]).
pub fn score_table(runs: &Runs, sweeps: &[SweepSummary], paper: &str) -> String {
    let mut t = Table::new([
        "experiment",
        "variant",
        "solver",
        "samples",
        "max |x − x*|",
        "RMS |x − x*|",
        "max objective gap",
        "max violation",
        "exact solves failed",
        "status",
    ]);
    let (rows, left_out) = super::tables::shown(
        runs.of_paper(paper).filter(|r| is_neural(r)),
        sweeps.iter().filter(|s| s.paper == paper),
        SweepSummary::neural_left_out,
    );
    for r in rows {
        t.push([
            r.experiment.to_string(),
            r.variant.clone(),
            r.solver.clone(),
            r.score_samples
                .map(|n| n.to_string())
                .unwrap_or_else(|| super::markdown::MISSING.to_string()),
            sci_opt(r.score_max_dx),
            sci_opt(r.score_rms_dx),
            sci_opt(r.score_max_obj_gap),
            sci_opt(r.score_max_violation),
            r.score_failures.to_string(),
            status_text(r),
        ]);
    }
    if t.is_empty() {
        String::new()
    } else {
        t.render() + &super::tables::left_out_note(left_out)
    }
}
