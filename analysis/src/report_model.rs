//! One typed model of what the report's pages show that a verdict or a ranking decides, built
//! once per render ([`ReportModel::build`]) so that the report (crate `presentation`) formats it
//! without calling a verdict function or computing a ranking while it writes a page.
//!
//! What it holds so far: each paper's claims evaluated from the stored runs
//! ([`crate::claim_verdict::evaluate`]), the leaderboard (the standard task set and its rows,
//! [`crate::leaderboard::leaderboard`], computed once for the leaderboard page and the front
//! page's top), and zhong2021's efficiency claim over the control experiments' tasks
//! ([`crate::control_claim::overall`]). The other pages still call analysis while they format
//! (docs/reference/layout.md lists them).

use crate::claim_verdict::{evaluate, Claim};
use crate::control_claim::overall;
use crate::leaderboard::{leaderboard, standard_tasks, LeaderboardRow, Task};
use crate::papers::Papers;
use records::control::{ClaimRow, Verdict};
use records::index::Runs;
use records::timing::Timings;

/// The report's decided content (module docs).
#[derive(Clone, Debug)]
pub struct ReportModel {
    /// Every paper of `papers/`, in its order, with its claims evaluated.
    pub papers: Vec<PaperClaims>,
    /// The leaderboard.
    pub leaderboard: Leaderboard,
    /// zhong2021's efficiency claim over every task of `results/control-claim.csv`: PASS or
    /// FAIL when the tasks agree, UNDECIDED otherwise or without tasks.
    pub control_claim: Verdict,
}

/// A paper and its claims' verdicts.
#[derive(Clone, Debug)]
pub struct PaperClaims {
    /// The paper id.
    pub id: String,
    /// Its title.
    pub title: String,
    /// Its claims, in the order `paper.toml` gives them.
    pub claims: Vec<Claim>,
}

/// The leaderboard: the standard task set and the rows of every task set.
#[derive(Clone, Debug)]
pub struct Leaderboard {
    /// The standard task set (the cross experiment's tasks whose exact column completed).
    pub tasks: Vec<Task>,
    /// The rows, as `results/leaderboard.csv` holds them.
    pub rows: Vec<LeaderboardRow>,
}

impl ReportModel {
    /// The model of the report on the stored `runs`, the `papers` (as the report shows them),
    /// the leaderboard's `timings` and the efficiency claim's rows `control_claims`.
    pub fn build(
        runs: &Runs,
        papers: &Papers,
        timings: &Timings,
        control_claims: &[ClaimRow],
    ) -> Self {
        let verdicts: Vec<Verdict> = control_claims.iter().map(|c| c.verdict).collect();
        ReportModel {
            papers: papers
                .papers
                .iter()
                .map(|p| PaperClaims {
                    id: p.id.to_string(),
                    title: p.title.to_string(),
                    claims: evaluate(&p.id, runs, papers),
                })
                .collect(),
            leaderboard: Leaderboard {
                tasks: standard_tasks(runs.all()),
                rows: leaderboard(runs.all(), timings),
            },
            control_claim: overall(&verdicts),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control_claim::judge;
    use crate::control_claim::tests::check;
    use records::control::ClaimCheck;

    #[test]
    fn the_control_claim_is_decided_over_the_tasks() {
        let (runs, papers, timings) =
            (Runs::new(Vec::new()), Papers::default(), Timings::default());
        let build = |claims: &[ClaimRow]| ReportModel::build(&runs, &papers, &timings, claims);
        // Nothing stored: no paper, no leaderboard, no decision.
        let empty = build(&[]);
        assert!(empty.papers.is_empty() && empty.leaderboard.rows.is_empty());
        assert!(empty.leaderboard.tasks.is_empty());
        assert_eq!(empty.control_claim, Verdict::Undecided);
        // Two tasks that pass (lower bound 40 <= 50, accurate), then one that fails.
        let pass = judge(check(4, 1e-8));
        let fail = judge(ClaimCheck {
            steps_needed: 6,
            ..check(12, 1e-9)
        });
        assert_eq!(
            build(&[pass.clone(), pass.clone()]).control_claim,
            Verdict::Pass
        );
        assert_eq!(
            build(&[pass, fail.clone()]).control_claim,
            Verdict::Undecided
        );
        assert_eq!(build(&[fail]).control_claim, Verdict::Fail);
    }
}
