//! The ReScience-style verdict of one paper: what was reproduced, what not, and why —
//! phrased from the evaluated claims and the published-vs-ours ratios, never typed in.
//!
//! The level is "reproduced" when every evaluated claim holds and our drift norms are within
//! a factor [`CLOSE`] of the paper's, "reproduced qualitatively" when every claim holds but
//! magnitudes differ more, "partly reproduced" when at least as many claims hold as fail,
//! and "not reproduced" otherwise.

use super::claims::{Claim, Verdict};
use super::markdown::sci;
use records::index::{metric, Runs, EXACT};
use records::papers::{Mapping, Papers};
use records::runs::RunRow;

/// Magnitudes within this factor of the paper's count as agreeing.
pub const CLOSE: f64 = 3.0;

/// Relative difference between the paper's solver and the exact column above which the
/// solver is said to move the drift.
const SOLVER_MATTERS: f64 = 0.05;

/// The verdict level alone (for the summary table).
pub fn level(claims: &[Claim], ratios: &[(String, f64)]) -> &'static str {
    let count = |v: Verdict| claims.iter().filter(|c| c.verdict == v).count();
    let (pass, fail) = (count(Verdict::Pass), count(Verdict::Fail));
    let close = ratios
        .iter()
        .all(|(_, r)| (1.0 / CLOSE..=CLOSE).contains(r));
    match (pass, fail) {
        (0, 0) => "not evaluated",
        (_, 0) if close => "reproduced",
        (_, 0) => "reproduced qualitatively",
        (p, f) if p >= f => "partly reproduced",
        _ => "not reproduced",
    }
}

/// What of `paper`'s setup was substituted (paper.toml's `assumed_setup`), if anything.
pub fn assumed_setup<'a>(paper: &str, papers: &'a Papers) -> Option<&'a str> {
    papers
        .papers
        .iter()
        .find(|p| p.id == paper)
        .and_then(|p| p.assumed_setup.as_deref())
}

/// The verdict level, with ", under an assumed setup" where the paper's setup was substituted.
pub fn level_under_setup(
    paper: &str,
    claims: &[Claim],
    ratios: &[(String, f64)],
    papers: &Papers,
) -> String {
    let level = level(claims, ratios);
    match assumed_setup(paper, papers) {
        Some(_) => format!("{level}, under an assumed setup"),
        None => level.to_string(),
    }
}

/// Our run of the paper's solver for each mapped column of `paper`, with its mapping.
fn mapped_runs<'a>(
    paper: &'a str,
    runs: &'a Runs,
    papers: &'a Papers,
) -> impl Iterator<Item = (&'a Mapping, &'a RunRow)> + 'a {
    papers.mappings_of(paper).filter_map(move |m| {
        let k = &m.run;
        runs.find(&k.experiment, &k.variant, &k.solver)
            .map(|r| (m, r))
    })
}

/// Our drift norm (the paper's solver, primary variant) over the paper's, per mapped column,
/// labelled "experiment, published column".
pub fn drift_ratios(paper: &str, runs: &Runs, papers: &Papers) -> Vec<(String, f64)> {
    mapped_runs(paper, runs, papers)
        .filter_map(|(m, r)| {
            let (p, _) = papers.published(m, "drift_norm")?;
            Some((
                format!("{}, {}", r.experiment, m.published_column),
                r.drift_norm? / p,
            ))
        })
        .collect()
}

/// How many published per-joint drifts have the sign of ours, out of how many compared.
fn sign_agreement(paper: &str, runs: &Runs, papers: &Papers) -> (usize, usize) {
    let mut same = 0;
    let mut compared = 0;
    for (m, r) in mapped_runs(paper, runs, papers) {
        for joint in [
            "drift_1", "drift_2", "drift_3", "drift_4", "drift_5", "drift_6",
        ] {
            if let (Some((p, _)), Some(o)) = (papers.published(m, joint), metric(r, joint)) {
                compared += 1;
                same += usize::from(p.signum() == o.signum());
            }
        }
    }
    (same, compared)
}

/// The largest |solver − exact| / exact drift norm over the paper's mapped runs, and the run.
fn solver_effect<'a>(
    paper: &'a str,
    runs: &'a Runs,
    papers: &'a Papers,
) -> Option<(f64, &'a RunRow)> {
    mapped_runs(paper, runs, papers)
        .filter_map(|(m, r)| {
            let ex = runs
                .find(&m.run.experiment, &m.run.variant, EXACT)?
                .drift_norm?;
            Some(((r.drift_norm? - ex).abs() / ex, r))
        })
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

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
    if ratios.is_empty() {
        out.push_str(" The paper prints no drift table: the verdict rests on the qualitative claims of its figures.");
    } else {
        let by = |a: &&(String, f64), b: &&(String, f64)| a.1.total_cmp(&b.1);
        let (lo, hi) = (
            ratios.iter().min_by(by).expect("nonempty"),
            ratios.iter().max_by(by).expect("nonempty"),
        );
        out.push_str(&format!(
            " Magnitudes: over {} published columns our drift norm (the paper's solver) is {} (`{}`) to {} (`{}`) times the paper's: {}.",
            ratios.len(),
            sci(lo.1),
            lo.0,
            sci(hi.1),
            hi.0,
            if lo.1 >= 1.0 / CLOSE && hi.1 <= CLOSE { format!("within a factor {CLOSE}") } else { format!("beyond a factor {CLOSE}") }
        ));
        let (same, compared) = sign_agreement(paper, runs, papers);
        out.push_str(&format!(
            " The per-joint drifts have the paper's sign in {same} of {compared} entries."
        ));
    }
    if let Some((e, r)) = solver_effect(paper, runs, papers) {
        if e <= SOLVER_MATTERS {
            out.push_str(&format!(
                " The exact column (the QP solved to optimality in the loop) gives the same drift norm within {:.1} %, so what differs from the paper comes from the scheme, model and paths as implemented (see Deviations), not from the solver.",
                100.0 * e
            ));
        } else {
            out.push_str(&format!(
                " The paper's solver changes the drift norm by up to {:.0} % against the exact column (`{} {}`): that part of the drift is the solver's, not the scheme's.",
                100.0 * e,
                r.experiment,
                r.solver
            ));
        }
    }
    out.push('\n');
    out
}
