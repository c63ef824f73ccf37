//! The ReScience-style verdict of one paper, decided by a stated rule ([`RULES`]) from three
//! counts, each printed with the verdict ([`Decision`]'s `Display`):
//!
//! - **numbers**: the published magnitudes of the mapped columns (the run a mapping names,
//!   never a companion): the drift norm (printed, or the norm of the printed joints when the
//!   paper prints none) and the position errors; compute times are not counted (they depend
//!   on the machine and the language; the claims compare work instead). A ratio ours / paper
//!   is *within a factor b* when it lies in [1/b, b]. A column whose printed numbers contradict
//!   each other ([`crate::misprints`]) is not counted: its ratios rest on a contradicted number.
//! - **signs**: the per-joint drifts of the mapped columns whose published and measured values
//!   both exceed the run's round-off floor ([`sign_floor`]): a printed 0 against a run's 1e-20
//!   is not a sign.
//! - **claims**: the evaluated claims ([`crate::claim_verdict`]), PASS against FAIL.
//!
//! The first rule of [`RULES`] whose thresholds all hold gives the level; when none does, the
//! level is "not reproduced" if anything was compared and "not comparable" otherwise. Claims
//! alone never give "reproduced": its rule needs published numbers. The table is documented
//! in docs/reference/verdicts.md (a test keeps the two equal).

use crate::claim_verdict::{Claim, Verdict};
use crate::misprints::{contradictions, is_contradicted};
use crate::papers::{Mapping, Papers};
use records::index::{metric, Runs, EXACT};
use records::RunRow;

/// A verdict level, best first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    Reproduced,
    InMagnitude,
    Qualitatively,
    NotReproduced,
    NotComparable,
}

impl Level {
    /// The level in words.
    pub fn label(self) -> &'static str {
        match self {
            Level::Reproduced => "reproduced",
            Level::InMagnitude => "reproduced in magnitude",
            Level::Qualitatively => "reproduced qualitatively",
            Level::NotReproduced => "not reproduced",
            Level::NotComparable => "not comparable",
        }
    }
}

/// What a rule asks of the evaluated claims.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClaimsRule {
    /// At least one claim evaluated, and none fails.
    AllHold,
    /// No more claims fail than hold.
    NoMoreFailThanHold,
    /// At least one claim holds, and no more fail than hold.
    SomeHoldNoMoreFail,
}

impl ClaimsRule {
    fn holds(self, pass: usize, fail: usize) -> bool {
        match self {
            ClaimsRule::AllHold => pass > 0 && fail == 0,
            ClaimsRule::NoMoreFailThanHold => fail <= pass,
            ClaimsRule::SomeHoldNoMoreFail => pass > 0 && fail <= pass,
        }
    }

    fn text(self) -> &'static str {
        match self {
            ClaimsRule::AllHold => "every evaluated claim holds (at least one)",
            ClaimsRule::NoMoreFailThanHold => "no more claims fail than hold",
            ClaimsRule::SomeHoldNoMoreFail => {
                "at least one claim holds, and no more fail than hold"
            }
        }
    }
}

/// One level's thresholds. `band`: the published numbers must lie within a factor `band` of
/// ours, at least a share `min_within` of them (and at least one number compared); none: the
/// numbers are not asked. `min_signs`: the share of comparable signs that must agree (asked
/// only when some are comparable).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rule {
    pub level: Level,
    pub band: Option<f64>,
    pub min_within: f64,
    pub min_signs: f64,
    pub claims: ClaimsRule,
}

/// The rules, tried in order (module docs).
pub const RULES: [Rule; 3] = [
    Rule {
        level: Level::Reproduced,
        band: Some(3.0),
        min_within: 0.75,
        min_signs: 0.75,
        claims: ClaimsRule::AllHold,
    },
    Rule {
        level: Level::InMagnitude,
        band: Some(10.0),
        min_within: 0.75,
        min_signs: 0.5,
        claims: ClaimsRule::NoMoreFailThanHold,
    },
    Rule {
        level: Level::Qualitatively,
        band: None,
        min_within: 0.0,
        min_signs: 0.5,
        claims: ClaimsRule::SomeHoldNoMoreFail,
    },
];

/// [`RULES`] as a Markdown table, as docs/reference/verdicts.md shows it.
pub fn rules_table() -> String {
    let mut out = String::from(
        "| level | published numbers within a factor | share of them needed | signs agreeing needed | claims |\n|---|---|---|---|---|\n",
    );
    for r in &RULES {
        let (band, within) = match r.band {
            Some(b) => (format!("{b}"), format!("{:.0} %", 100.0 * r.min_within)),
            None => ("not asked".to_string(), "not asked".to_string()),
        };
        out.push_str(&format!(
            "| {} | {band} | {within} | {:.0} % | {} |\n",
            r.level.label(),
            100.0 * r.min_signs,
            r.claims.text()
        ));
    }
    out.push_str(&format!(
        "| {} | none of the above, and something was compared | | | |\n| {} | nothing was compared: no published number, comparable sign or evaluated claim | | | |\n",
        Level::NotReproduced.label(),
        Level::NotComparable.label()
    ));
    out
}

/// Relative difference between the paper's solver and the exact column above which the
/// solver is said to move the drift.
pub const SOLVER_MATTERS: f64 = 0.05;

/// The sign floor of run `r` (rad): one unit of round-off (f64 epsilon) per step of the run at
/// angles of order one radian, eps · max(steps, 1). A drift below it is round-off, not a sign.
pub fn sign_floor(r: &RunRow) -> f64 {
    f64::EPSILON * r.steps.max(1) as f64
}

/// `k` of `n`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Count {
    pub k: usize,
    pub n: usize,
}

impl Count {
    fn share(self) -> Option<f64> {
        (self.n > 0).then(|| self.k as f64 / self.n as f64)
    }
}

impl std::fmt::Display for Count {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} of {}", self.k, self.n)
    }
}

/// The counts a verdict is decided from, and the level they give (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Decision {
    pub level: Level,
    /// Ours / paper of every counted published number, labelled "experiment, column, metric".
    pub ratios: Vec<(String, f64)>,
    /// Published drift norms not counted because their column's printed numbers contradict
    /// each other.
    pub contradicted: usize,
    /// Signs agreeing, of the comparable per-joint entries.
    pub signs: Count,
    /// Entries not comparable in sign (a value at or below the round-off floor).
    pub below_floor: usize,
    pub pass: usize,
    pub fail: usize,
}

impl Decision {
    /// The published numbers within a factor `band` of ours.
    pub fn within(&self, band: f64) -> Count {
        Count {
            k: self
                .ratios
                .iter()
                .filter(|(_, r)| (1.0 / band..=band).contains(r))
                .count(),
            n: self.ratios.len(),
        }
    }

    /// Whether `rule`'s thresholds hold for these counts.
    pub fn meets(&self, rule: &Rule) -> bool {
        let numbers = match rule.band {
            Some(b) => self.within(b).share().is_some_and(|s| s >= rule.min_within),
            None => true,
        };
        let signs = self.signs.share().is_none_or(|s| s >= rule.min_signs);
        numbers && signs && rule.claims.holds(self.pass, self.fail)
    }
}

impl Decision {
    /// The level of the first rule met; else "not reproduced" when anything was compared,
    /// "not comparable" when nothing was.
    fn rule_level(&self) -> Level {
        match RULES.iter().find(|rule| self.meets(rule)) {
            Some(rule) => rule.level,
            None if self.ratios.is_empty() && self.signs.n == 0 && self.pass + self.fail == 0 => {
                Level::NotComparable
            }
            None => Level::NotReproduced,
        }
    }
}

impl std::fmt::Display for Decision {
    /// The counts and the thresholds they were held against.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let pct = |x: f64| format!("{:.0} %", 100.0 * x);
        let mut parts = Vec::new();
        for rule in RULES.iter().filter(|r| r.band.is_some()) {
            let b = rule.band.unwrap_or(1.0);
            parts.push(format!(
                "published numbers within a factor {b}: {} ({} needs {})",
                self.within(b),
                rule.level.label(),
                pct(rule.min_within)
            ));
        }
        if self.contradicted > 0 {
            parts.push(format!(
                "{} published drift norm{} not counted ({} column's printed numbers contradict each other)",
                self.contradicted,
                if self.contradicted == 1 { "" } else { "s" },
                if self.contradicted == 1 { "its" } else { "each" }
            ));
        }
        let thresholds: Vec<String> = RULES
            .iter()
            .map(|r| format!("{} {}", r.level.label(), pct(r.min_signs)))
            .collect();
        parts.push(format!(
            "per-joint signs agree in {} entries above the round-off floor ({} below it not compared; needed: {})",
            self.signs,
            self.below_floor,
            thresholds.join(", ")
        ));
        parts.push(format!("claims: {} hold, {} fail", self.pass, self.fail));
        write!(f, "{}", parts.join("; "))
    }
}

/// The decision on `paper` (module docs).
pub fn decide(paper: &str, claims: &[Claim], runs: &Runs, papers: &Papers) -> Decision {
    let count = |v: Verdict| claims.iter().filter(|c| c.verdict == v).count();
    let contradicted = contradictions(paper, papers);
    let mut contradicted_columns: Vec<&Mapping> = Vec::new();
    let mut ratios = Vec::new();
    for (m, r) in mapped_runs(paper, runs, papers) {
        for name in MAGNITUDES {
            // A drift norm from a column that contradicts itself is not counted.
            if name == "drift_norm"
                && is_contradicted(
                    &contradicted,
                    None,
                    &m.published_experiment,
                    &m.published_column,
                )
            {
                contradicted_columns.push(m);
                continue;
            }
            let Some((p, _)) = papers.published(m, name) else {
                continue;
            };
            if let Some(o) = metric(r, name).filter(|_| p != 0.0) {
                ratios.push((
                    format!("{}, {}, {name}", r.experiment, m.published_column),
                    o / p,
                ));
            }
        }
    }
    let (signs, below_floor) = sign_agreement(paper, runs, papers);
    let mut d = Decision {
        level: Level::NotComparable,
        ratios,
        contradicted: contradicted_columns.len(),
        signs,
        below_floor,
        pass: count(Verdict::Pass),
        fail: count(Verdict::Fail),
    };
    d.level = d.rule_level();
    d
}

/// The published magnitudes counted by the verdict (module docs).
const MAGNITUDES: [&str; 3] = ["drift_norm", "max_pos_err", "final_pos_err"];

/// What of `paper`'s setup was substituted (paper.toml's `assumed_setup`), if anything.
pub fn assumed_setup<'a>(paper: &str, papers: &'a Papers) -> Option<&'a str> {
    papers
        .papers
        .iter()
        .find(|p| p.id == paper)
        .and_then(|p| p.assumed_setup.as_deref())
}

/// The verdict level, with ", under an assumed setup" where the paper's setup was substituted.
pub fn level_under_setup(paper: &str, decision: &Decision, papers: &Papers) -> String {
    let level = decision.level.label();
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

/// A number with its label ("experiment, column, metric").
pub type Labelled = (String, f64);

/// The smallest and the largest of `ratios` (with its label: the first smallest, the last
/// largest); none when there are none.
pub fn ratio_span(ratios: &[Labelled]) -> Option<(&Labelled, &Labelled)> {
    let by = |a: &&Labelled, b: &&Labelled| a.1.total_cmp(&b.1);
    Some((ratios.iter().min_by(by)?, ratios.iter().max_by(by)?))
}

/// How many published per-joint drifts of the mapped columns have the sign of ours, of those
/// where both exceed the run's [`sign_floor`]; and how many were not compared for being at or
/// below it.
pub fn sign_agreement(paper: &str, runs: &Runs, papers: &Papers) -> (Count, usize) {
    let mut signs = Count::default();
    let mut below = 0;
    for (m, r) in mapped_runs(paper, runs, papers) {
        let floor = sign_floor(r);
        for joint in 1..=r.drift.len() {
            let name = format!("drift_{joint}");
            let (Some((p, _)), Some(o)) = (papers.published(m, &name), metric(r, &name)) else {
                continue;
            };
            if p.abs() <= floor || o.abs() <= floor {
                below += 1;
                continue;
            }
            signs.n += 1;
            signs.k += usize::from(p.signum() == o.signum());
        }
    }
    (signs, below)
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

    fn decision(ratios: &[f64], signs: (usize, usize), pass: usize, fail: usize) -> Decision {
        let mut d = Decision {
            level: Level::NotComparable,
            ratios: ratios.iter().map(|r| (String::new(), *r)).collect(),
            contradicted: 0,
            signs: Count {
                k: signs.0,
                n: signs.1,
            },
            below_floor: 0,
            pass,
            fail,
        };
        d.level = d.rule_level();
        d
    }

    #[test]
    fn each_level_is_given_by_its_thresholds() {
        assert_eq!(decision(&[1.0, 2.0], (4, 4), 2, 0).level, Level::Reproduced);
        assert_eq!(
            decision(&[1.0, 2.0], (4, 4), 2, 1).level,
            Level::InMagnitude,
            "a failed claim"
        );
        assert_eq!(
            decision(&[5.0, 0.2], (3, 4), 2, 0).level,
            Level::InMagnitude
        );
        assert_eq!(
            decision(&[1e-2], (1, 6), 3, 0).level,
            Level::NotReproduced,
            "1 of 6 signs"
        );
        assert_eq!(
            decision(&[1e4], (0, 0), 1, 0).level,
            Level::Qualitatively,
            "one number 1e4 off, its claims hold"
        );
        assert_eq!(
            decision(&[1e4], (0, 0), 1, 2).level,
            Level::NotReproduced,
            "more claims fail than hold"
        );
        assert_eq!(decision(&[], (0, 0), 0, 0).level, Level::NotComparable);
        assert_eq!(decision(&[], (0, 0), 0, 1).level, Level::NotReproduced);
    }

    #[test]
    fn claims_alone_never_give_reproduced() {
        assert_eq!(decision(&[], (0, 0), 9, 0).level, Level::Qualitatively);
        assert!(RULES
            .iter()
            .filter(|r| r.level == Level::Reproduced)
            .all(|r| r.band.is_some() && r.min_within > 0.0));
    }

    #[test]
    fn the_verdict_prints_its_counts_and_thresholds() {
        let d = decision(&[1.0, 20.0], (3, 5), 2, 1);
        let text = d.to_string();
        assert!(
            text.contains("within a factor 3: 1 of 2 (reproduced needs 75 %)"),
            "{text}"
        );
        assert!(text.contains("signs agree in 3 of 5 entries"), "{text}");
        assert!(text.contains("claims: 2 hold, 1 fail"), "{text}");
    }

    #[test]
    fn the_documented_rules_are_the_codes() {
        let doc =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/reference/verdicts.md");
        let doc = std::fs::read_to_string(&doc).expect("docs/reference/verdicts.md");
        assert!(
            doc.contains(&rules_table()),
            "docs/reference/verdicts.md must show the rule table as the code has it:\n{}",
            rules_table()
        );
    }

    #[test]
    fn the_span_names_its_ends() {
        let ratios = vec![
            ("a".to_string(), 2.0),
            ("b".to_string(), 0.5),
            ("c".to_string(), 2.0),
        ];
        let (lo, hi) = ratio_span(&ratios).unwrap();
        assert_eq!((lo.0.as_str(), hi.0.as_str()), ("b", "c"));
        assert!(ratio_span(&[]).is_none());
    }
}
