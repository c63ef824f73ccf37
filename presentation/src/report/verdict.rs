//! The verdict paragraph of one paper: what was reproduced, what not, and why, phrased from
//! what crate `analysis` decided ([`analysis::paper_verdict`]), never typed in.

use super::markdown::{percent, sci};
use analysis::claim_verdict::{Claim, Verdict};
use analysis::paper_verdict::{
    assumed_setup, drift_ratios, level_under_setup, ratio_span, sign_agreement, solver_effect,
    CLOSE, SOLVER_MATTERS,
};
use analysis::papers::Papers;
use records::index::Runs;

/// The verdict paragraph of one paper.
pub fn paragraph(paper: &str, claims: &[Claim], runs: &Runs, papers: &Papers) -> String {
    let ratios = drift_ratios(paper, runs, papers);
    let of = |v: Verdict| {
        claims
            .iter()
            .filter(|c| c.verdict == v)
            .map(|c| c.short.as_str())
            .collect::<Vec<_>>()
    };
    let (pass, fail, na) = (
        of(Verdict::Pass),
        of(Verdict::Fail),
        of(Verdict::NotApplicable),
    );
    let mut out = format!(
        "**Verdict: {}.** {} of {} evaluated claims hold",
        level_under_setup(paper, claims, &ratios, papers),
        pass.len(),
        pass.len() + fail.len()
    );
    if !pass.is_empty() {
        out.push_str(&format!(" ({})", pass.join("; ")));
    }
    out.push('.');
    if let Some(assumed) = assumed_setup(paper, papers) {
        out.push_str(&format!(
            " The paper does not print all of its setup; assumed: {assumed}."
        ));
    }
    if !fail.is_empty() {
        out.push_str(&format!(" Not reproduced: {}.", fail.join("; ")));
    }
    if !na.is_empty() {
        out.push_str(&format!(" Not evaluated: {}.", na.join("; ")));
    }
    if let Some(span) = ratio_span(&ratios) {
        let (lo, hi) = (span.lo, span.hi);
        out.push_str(&format!(
            " Magnitudes: over {} published columns our drift norm (the paper's solver) is {} (`{}`) to {} (`{}`) times the paper's: {}.",
            ratios.len(),
            sci(lo.1),
            lo.0,
            sci(hi.1),
            hi.0,
            if span.within { format!("within a factor {CLOSE}") } else { format!("beyond a factor {CLOSE}") }
        ));
        let (same, compared) = sign_agreement(paper, runs, papers);
        out.push_str(&format!(
            " The per-joint drifts have the paper's sign in {same} of {compared} entries."
        ));
    } else {
        out.push_str(" The paper prints no drift table: the verdict rests on the qualitative claims of its figures.");
    }
    if let Some((e, r)) = solver_effect(paper, runs, papers) {
        if e <= SOLVER_MATTERS {
            out.push_str(&format!(
                " The exact column (the QP solved to optimality in the loop) gives the same drift norm within {}, so what differs from the paper comes from the scheme, model and paths as implemented (see Deviations), not from the solver.",
                percent(e, 1)
            ));
        } else {
            out.push_str(&format!(
                " The paper's solver changes the drift norm by up to {} against the exact column (`{} {}`): that part of the drift is the solver's, not the scheme's.",
                percent(e, 0),
                r.experiment,
                r.solver
            ));
        }
    }
    out.push('\n');
    out
}
