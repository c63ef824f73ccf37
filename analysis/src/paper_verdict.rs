//! The ReScience-style verdict of one paper: its level, decided from the evaluated claims
//! ([`crate::claim_verdict`]) and the published-vs-ours drift ratios, and the numbers the
//! report's verdict paragraph gives as its reasons (sign agreement, the solver's effect).
//!
//! The level is "reproduced" when every evaluated claim holds and our drift norms are within
//! a factor [`CLOSE`] of the paper's, "reproduced qualitatively" when every claim holds but
//! magnitudes differ more, "partly reproduced" when at least as many claims hold as fail,
//! and "not reproduced" otherwise.

use crate::claim_verdict::{Claim, Verdict};
use crate::papers::{Mapping, Papers};
use records::index::{metric, Runs, EXACT};
use records::runs::RunRow;

/// Magnitudes within this factor of the paper's count as agreeing.
pub const CLOSE: f64 = 3.0;

/// Relative difference between the paper's solver and the exact column above which the
/// solver is said to move the drift.
pub const SOLVER_MATTERS: f64 = 0.05;

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

/// The smallest and the largest drift ratio (with its label: the first smallest, the last
/// largest), and whether every ratio lies within a factor [`CLOSE`] of the paper's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RatioSpan<'a> {
    pub lo: &'a (String, f64),
    pub hi: &'a (String, f64),
    pub within: bool,
}

/// [`RatioSpan`] of `ratios` ([`drift_ratios`]); none when there are none.
pub fn ratio_span(ratios: &[(String, f64)]) -> Option<RatioSpan<'_>> {
    let by = |a: &&(String, f64), b: &&(String, f64)| a.1.total_cmp(&b.1);
    let (lo, hi) = (ratios.iter().min_by(by)?, ratios.iter().max_by(by)?);
    Some(RatioSpan {
        lo,
        hi,
        within: lo.1 >= 1.0 / CLOSE && hi.1 <= CLOSE,
    })
}

/// How many published per-joint drifts have the sign of ours, out of how many compared.
pub fn sign_agreement(paper: &str, runs: &Runs, papers: &Papers) -> (usize, usize) {
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
pub fn solver_effect<'a>(
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_span_names_its_ends_and_says_whether_they_are_close() {
        let ratios = vec![
            ("a".to_string(), 2.0),
            ("b".to_string(), 0.5),
            ("c".to_string(), 2.0),
        ];
        let span = ratio_span(&ratios).unwrap();
        assert_eq!((span.lo.0.as_str(), span.hi.0.as_str()), ("b", "c"));
        assert!(span.within);
        let far = vec![("a".to_string(), 1.0), ("b".to_string(), CLOSE * 1.01)];
        assert!(!ratio_span(&far).unwrap().within);
        assert!(ratio_span(&[]).is_none());
    }
}
