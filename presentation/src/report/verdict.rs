//! The verdict paragraph of one paper: what was reproduced, what not, and why, phrased from
//! what crate `analysis` decided ([`analysis::paper_verdict`], held by the report model),
//! never typed in.

use super::markdown::{percent, sci};
use analysis::claim_verdict::Verdict;
use analysis::misprints::Contradiction;
use analysis::paper_verdict::SOLVER_MATTERS;
use analysis::report_model::PaperModel;

/// The verdict paragraph of one paper.
pub fn paragraph(paper: &PaperModel) -> String {
    let (claims, decision) = (&paper.claims, &paper.decision);
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
        "**Verdict: {}.** The rule ([verdicts](../docs/reference/verdicts.md)) decided it from: {decision}. {} of {} evaluated claims hold",
        paper.level,
        pass.len(),
        pass.len() + fail.len()
    );
    if !pass.is_empty() {
        out.push_str(&format!(" ({})", pass.join("; ")));
    }
    out.push('.');
    if let Some(assumed) = paper.assumed_setup {
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
    if let Some((lo, hi)) = &paper.ratio_span {
        out.push_str(&format!(
            " Magnitudes: over {} counted published numbers (the run each mapping names) ours is {} (`{}`) to {} (`{}`) times the paper's.",
            decision.ratios.len(),
            sci(lo.1),
            lo.0,
            sci(hi.1),
            hi.0,
        ));
    } else {
        out.push_str(
            " No published magnitude is counted: the verdict rests on the signs and the claims.",
        );
    }
    if let Some((e, r)) = paper.solver_effect {
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

/// How many misprint hypotheses a contradicted column lists (the nearest).
const SHOWN_HYPOTHESES: usize = 3;

/// The published columns whose printed numbers contradict each other, each with the single
/// misprints that would reconcile it ([`analysis::misprints`]), as hypotheses beside the
/// printed numbers; empty when none does.
pub fn contradictions(found: &[Contradiction]) -> String {
    if found.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "\n### Printed numbers that contradict each other\n\nIn these columns the printed norm is not the norm of the printed joint drifts, within the printed digits. Below each, the single misprints (one exponent, one digit, one sign, one entry exchanged with another column's) under which the column is consistent: hypotheses, not corrections. The tables above show the printed numbers; every ratio of these columns in that table rests on a contradicted number (marked ‡), and the verdict does not count their drift norms.\n\n",
    );
    for c in found {
        out.push_str(&format!(
            "- Table {} `{}` {}: printed norm {}, norm of the printed entries {}. ",
            c.table.trim_start_matches('T'),
            c.experiment,
            c.column,
            sci(c.printed_norm),
            sci(c.norm_of_entries)
        ));
        if c.hypotheses.is_empty() {
            out.push_str("No single misprint reconciles them.\n");
        } else {
            let h: Vec<String> = c
                .hypotheses
                .iter()
                .take(SHOWN_HYPOTHESES)
                .map(|h| format!("{h}"))
                .collect();
            out.push_str(&format!("Consistent if: {}", h.join("; or ")));
            let more = c.hypotheses.len().saturating_sub(SHOWN_HYPOTHESES);
            if more > 0 {
                out.push_str(&format!(
                    " (nearest first; {more} further single misprint{} also reconcile{} them)",
                    if more == 1 { "" } else { "s" },
                    if more == 1 { "s" } else { "" }
                ));
            }
            out.push_str(".\n");
        }
    }
    out
}
