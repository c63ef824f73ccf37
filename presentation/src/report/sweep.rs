//! A published table beside a sweep's runs (`[[sweep_check]]` of a paper's `paper.toml`,
//! `analysis::sweep_check`): where the paper's setup is an assumption the sweep varies, every
//! swept variant is set beside the published column its id matches: per-joint sign agreement
//! with the paper and the drift norm ratio, computed from the rows
//! ([`analysis::sweep_comparison`]).

use super::markdown::{sci, Table};
use analysis::papers::Papers;
use analysis::sweep_check::SweepCheck;
use analysis::sweep_comparison::{swept_runs, Against};
use records::index::Runs;

/// The markdown section; when the sweep was not run (a project that holds a subset of the
/// experiments, said at load), its heading and a line saying so, never nothing.
pub fn section(check: &SweepCheck, runs: &Runs, papers: &Papers) -> String {
    let heading = format!(
        "\n### {} (`{}`)\n\n{}\n\n",
        check.heading, check.experiment, check.text
    );
    if runs.of_experiment(&check.experiment).next().is_none() {
        return format!(
            "{heading}Not run: `results/runs.csv` has no run of `{}`.\n",
            check.experiment
        );
    }
    let mut t = Table::new([
        "variant (exact column)",
        "drift norm",
        "paper's norm",
        "ratio",
        "signs as the paper",
        "peak |θ̇| (rad/s)",
    ]);
    for s in swept_runs(check, runs, papers) {
        t.push(match s.against {
            Against::Failed { t } => [
                s.row.variant.clone(),
                format!("failed at t = {}", sci(t)),
                sci(s.paper_norm),
                String::new(),
                String::new(),
                String::new(),
            ],
            Against::Completed {
                norm,
                ratio,
                same_sign,
                compared,
                peak_thetadot,
            } => [
                s.row.variant.clone(),
                sci(norm),
                sci(s.paper_norm),
                sci(ratio),
                format!("{same_sign} of {compared}"),
                sci(peak_thetadot),
            ],
        });
    }
    format!("{heading}{}", t.render())
}
