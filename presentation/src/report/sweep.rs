//! A published table beside a sweep's runs (`[[sweep_check]]` of a paper's `paper.toml`,
//! `analysis::sweep_check`): where the paper's setup is an assumption the sweep varies, every
//! swept variant is set beside the published column its id matches: per-joint sign agreement
//! with the paper (where both exceed the run's round-off floor) and the drift norm ratio,
//! computed from the rows
//! ([`analysis::sweep_comparison`], held by the report model); where the check names the
//! declared setup's variant, a paragraph below the table states the setup's share of the gap
//! ([`analysis::sweep_comparison::setup_share`]).

use super::markdown::{percent, sci, times, Table};
use analysis::report_model::Sweep;
use analysis::sweep_comparison::{Against, SetupShare};

/// The markdown section; when the sweep was not run (a project that holds a subset of the
/// experiments, said at load), its heading and a line saying so, never nothing.
pub fn section(sweep: &Sweep) -> String {
    let check = sweep.check;
    let heading = format!(
        "\n### {} (`{}`)\n\n{}\n\n",
        check.heading, check.experiment, check.text
    );
    if !sweep.ran {
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
        "signs as the paper (above round-off)",
        "peak |θ̇| (rad/s)",
    ]);
    for s in &sweep.swept {
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
    let share = sweep
        .share
        .as_ref()
        .map(share_paragraph)
        .unwrap_or_default();
    format!("{heading}{}{share}", t.render())
}

/// The setup's share of the gap in words, every number from `s`.
fn share_paragraph(s: &SetupShare) -> String {
    let verdict = if s.closes_gap {
        "That part of the setup alone can carry the whole gap: the setup, not the solver, may explain it."
            .to_string()
    } else {
        format!(
            "No single part of the setup swept here carries more than {} of the gap: the rest of it is not explained by these parts.",
            percent(s.toward_paper, 0)
        )
    };
    format!(
        "\n**The setup's share of the gap.** The setup as declared (`{}`) drifts {}, the paper's column {}: a gap of {}x. The {} other setups move the drift norm by factors from {} to {} of the declared one; the one that goes furthest toward the paper's, {} (x{}), carries {} of the gap on a log scale (ln {} / ln {}). {verdict}\n",
        s.declared.variant_id,
        sci(s.declared_norm),
        sci(s.paper_norm),
        times(s.gap),
        s.setups,
        times(s.range.0),
        times(s.range.1),
        s.nearest.variant,
        times(s.factor),
        percent(s.share, 0),
        times(s.factor),
        times(s.gap),
    )
}
