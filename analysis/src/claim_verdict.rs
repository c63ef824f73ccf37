//! Each paper's claims (`papers/<paper>/paper.toml`, the grammar of [`crate::claims`])
//! evaluated from the stored runs; the report renders them as its checklist.
//!
//! A claim is PASS or FAIL with the measured numbers as evidence, or N/A when the suite does
//! not measure what it is about (or its runs are missing). A data claim compares a metric of a
//! selection of runs with a threshold or, experiment by experiment, with another selection
//! (`compare`); the exact column's value is given beside each run's. The few claims the
//! grammar cannot say are Rust functions under a named id (`rust_claim`).

use crate::claims::{Check, ClaimSpec, Op, Selection, Test, RUST_CLAIMS};
use crate::cost_ratio::{evaluation_ratio, slowdown};
use crate::number::sci;
use crate::papers::Papers;
use records::index::{completed, failed_at, metric, Runs, EXACT};
use records::RunRow;
use settings::NetworkKind;
use spec::SolverKind;

/// The most pairs of runs one `than` claim compares (each pair is a line of its evidence): a
/// paper has at most [`crate::MAX_CLAIMS`] claims, so claims times runs is
/// bounded.
pub const MAX_PAIRS: usize = 10_000;

/// The outcome of one claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    Pass,
    Fail,
    NotApplicable,
}

impl Verdict {
    /// `PASS`, `FAIL` or `N/A`.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Fail => "FAIL",
            Verdict::NotApplicable => "N/A",
        }
    }
}

/// One evaluated claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// A few words, used in the verdict paragraph.
    pub short: String,
    /// The claim as tested, with its threshold.
    pub statement: String,
    pub verdict: Verdict,
    /// The measured numbers (or why the claim could not be evaluated).
    pub evidence: String,
}

/// Why a claim could not be evaluated (its verdict is N/A): the reason, shown as its evidence.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct NotApplicable(pub String);

impl From<&str> for NotApplicable {
    fn from(why: &str) -> Self {
        NotApplicable(why.to_string())
    }
}

impl From<String> for NotApplicable {
    fn from(why: String) -> Self {
        NotApplicable(why)
    }
}

/// Evaluates a claim: `Ok((holds, evidence))`, or `Err(why)` for N/A.
fn check(
    short: &str,
    statement: &str,
    eval: impl FnOnce() -> Result<(bool, String), NotApplicable>,
) -> Claim {
    let (verdict, evidence) = match eval() {
        Ok((true, e)) => (Verdict::Pass, e),
        Ok((false, e)) => (Verdict::Fail, e),
        Err(NotApplicable(e)) => (Verdict::NotApplicable, e),
    };
    Claim {
        short: short.to_string(),
        statement: statement.to_string(),
        verdict,
        evidence,
    }
}

/// The claims of one paper, in the order `paper.toml` gives them.
pub fn evaluate(paper: &str, runs: &Runs, papers: &Papers) -> Vec<Claim> {
    let Some(p) = papers.papers.iter().find(|p| p.id == paper) else {
        return Vec::new();
    };
    p.claims
        .iter()
        .map(|c| evaluate_one(c, runs, papers))
        .collect()
}

fn evaluate_one(c: &ClaimSpec, runs: &Runs, papers: &Papers) -> Claim {
    check(&c.short, &c.text, || match &c.check {
        Check::Compare {
            metric,
            abs,
            runs: selection,
            test,
        } => compare(runs, metric, *abs, selection, test),
        Check::Rust {
            id,
            runs: sel,
            value,
            ..
        } => rust_claim(id, runs, papers, sel.as_ref(), *value),
    })
}

/// The runs of a selection, in key order.
fn selected<'a>(runs: &'a Runs, s: &Selection) -> Vec<&'a RunRow> {
    runs.all()
        .iter()
        .filter(|r| s.matches(&r.experiment, &r.variant_id, &r.solver_id))
        .collect()
}

/// One run's metric for a claim: `Ok(Some(x))`; `Ok(None)` when the run failed before the
/// metric could be measured (the claim fails); `Err` when a completed run did not measure it
/// (N/A).
fn claim_metric(r: &RunRow, name: &str, abs: bool) -> Result<Option<f64>, NotApplicable> {
    match metric(r, name) {
        Some(x) => Ok(Some(if abs { x.abs() } else { x })),
        None if !completed(r) => Ok(None),
        None => value(r, None, name).map(Some),
    }
}

/// A data claim ([`crate::claims`]): `Ok((holds, evidence))`, or `Err(why)` for N/A.
fn compare(
    runs: &Runs,
    name_of_metric: &str,
    abs: bool,
    selection: &Selection,
    test: &Test,
) -> Result<(bool, String), NotApplicable> {
    let rows = nonempty(selected(runs, selection))?;
    let mut holds = true;
    let mut evidence = Vec::new();
    // Threshold tests: the run nearest the bound stands for the others.
    let mut nearest: Option<(&RunRow, f64)> = None;
    let total = rows.len();
    let mut pairs = 0usize;
    for r in rows {
        let Some(x) = claim_metric(r, name_of_metric, abs)? else {
            holds = false;
            evidence.push(format!("{}: {}", name(r), failed_at(r)));
            continue;
        };
        match test {
            Test::Threshold(op, t) => {
                holds &= op.holds(x, *t);
                let upper = matches!(op, Op::Below | Op::AtMost);
                if nearest.is_none_or(|(_, n)| if upper { x > n } else { x < n }) {
                    nearest = Some((r, x));
                }
            }
            Test::Than { other, factor } => {
                let counterparts: Vec<&RunRow> = runs
                    .of_experiment(&r.experiment)
                    .filter(|o| other.matches(&o.experiment, &o.variant_id, &o.solver_id))
                    .collect();
                if counterparts.is_empty() {
                    return Err(format!("no run to compare {} with", name(r)).into());
                }
                pairs += counterparts.len();
                if pairs > MAX_PAIRS {
                    return Err(format!(
                        "the claim compares more than {MAX_PAIRS} pairs of runs; select fewer"
                    )
                    .into());
                }
                for o in counterparts {
                    let Some(y) = claim_metric(o, name_of_metric, abs)? else {
                        return Err(format!("{}: {}", name(o), failed_at(o)).into());
                    };
                    holds &= match factor {
                        Some(f) => x * f <= y,
                        None => x < y,
                    };
                    evidence.push(format!(
                        "{} {} vs {} {} (ratio {})",
                        name(r),
                        shown(x, abs),
                        name(o),
                        shown(y, abs),
                        sci(y / x)
                    ));
                }
            }
        }
    }
    if let Some((r, x)) = nearest {
        let of = if total > 1 {
            format!(" (nearest the bound of {total} runs)")
        } else {
            String::new()
        };
        evidence.insert(
            0,
            format!(
                "{}: {}{of}",
                name(r),
                with_exact(runs, r, x, name_of_metric, abs)
            ),
        );
    }
    Ok((holds, evidence.join("; ")))
}

/// "value (exact value)" of one run's metric, the exact column's beside it when it has one.
fn with_exact(runs: &Runs, r: &RunRow, x: f64, name_of_metric: &str, abs: bool) -> String {
    let exact = (r.solver_id != EXACT)
        .then(|| runs.find(&r.experiment, &r.variant_id, EXACT))
        .flatten()
        .and_then(|e| claim_metric(e, name_of_metric, abs).ok().flatten())
        .map(|e| format!(" (exact {})", shown(e, abs)))
        .unwrap_or_default();
    format!("{}{exact}", shown(x, abs))
}

/// A metric's value as a claim shows it: `|x|` when the claim compares absolute values.
fn shown(x: f64, abs: bool) -> String {
    if abs {
        format!("|{}|", sci(x))
    } else {
        sci(x)
    }
}

/// A metric that must exist (a completed run's drift, a measured error).
fn value(r: &RunRow, v: Option<f64>, what: &str) -> Result<f64, NotApplicable> {
    v.ok_or_else(|| {
        format!(
            "{} / {} / {}: no {what} ({})",
            r.experiment,
            r.variant,
            r.solver,
            if completed(r) {
                "not measured".to_string()
            } else {
                failed_at(r)
            }
        )
        .into()
    })
}

/// `rows`, or an error when there are none (the claim is then N/A).
fn nonempty(rows: Vec<&RunRow>) -> Result<Vec<&RunRow>, NotApplicable> {
    if rows.is_empty() {
        Err("no such runs".into())
    } else {
        Ok(rows)
    }
}

/// "experiment / variant / solver".
fn name(r: &RunRow) -> String {
    format!("{} / {} / {}", r.experiment, r.variant, r.solver)
}

/// The claims the grammar cannot say, by the id `paper.toml` names them with (its `why` says
/// why each is not data). `selection` and `value` are the claim's `runs` and `value`.
fn rust_claim(
    id: &str,
    runs: &Runs,
    papers: &Papers,
    selection: Option<&Selection>,
    value_arg: Option<f64>,
) -> Result<(bool, String), NotApplicable> {
    let rows = || -> Result<Vec<&RunRow>, NotApplicable> {
        nonempty(selected(runs, selection.ok_or("the claim needs `runs`")?))
    };
    match id {
        // A disjunction: the run fails, or a joint leaves its velocity bound.
        "diverges" => {
            let rows = rows()?;
            let ok = rows
                .iter()
                .all(|r| !completed(r) || r.thetadot_margin.is_some_and(|m| m < 0.0));
            let ev = rows.iter().map(|r| format!("{} ({})", peaks(r), r.solver));
            Ok((ok, ev.collect::<Vec<_>>().join("; ")))
        }
        // A disjunction against the variable-gain network beside each run: fails, or its
        // position error or drift is at least `value` times the VP-CDNN's.
        "fails-or-much-worse-than-vp-cdnn" => {
            let much = value_arg.ok_or("the claim needs `value`")?;
            let mut ok = true;
            let mut ev = Vec::new();
            for f in rows()? {
                let vp = runs
                    .of_experiment(&f.experiment)
                    .find(|r| r.solver_kind == SolverKind::Network(NetworkKind::VpCdnn))
                    .ok_or("no VP-CDNN run beside it")?;
                let worse =
                    |a: Option<f64>, b: Option<f64>| a.zip(b).is_some_and(|(a, b)| a >= much * b);
                ok &= !completed(f)
                    || worse(f.max_pos_err, vp.max_pos_err)
                    || worse(f.drift_norm, vp.drift_norm);
                ev.push(format!(
                    "{}, max position error {} m (VP-CDNN {} m)",
                    peaks(f),
                    f.max_pos_err.map(sci).unwrap_or_default(),
                    vp.max_pos_err.map(sci).unwrap_or_default()
                ));
            }
            Ok((ok, ev.join("; ")))
        }
        // A derived quantity: S-LVI-PDNN's RHS evaluations over the mean VP-RNN-PF's, within a
        // factor 2 of the paper's ratio `value` (its MATLAB seconds shown beside).
        "evaluation-ratio" => {
            let target = value_arg.ok_or("the claim needs `value`")?;
            let rows = rows()?;
            let exp = rows[0].experiment.as_str();
            let ours = evaluation_ratio(runs, exp).ok_or("evaluation counts missing")?;
            let s = slowdown(runs, papers, exp);
            let paper = s
                .paper
                .map(|p| format!("; paper, MATLAB seconds: {}", sci(p)))
                .unwrap_or_default();
            let timing = s
                .ours
                .map(|t| {
                    format!(
                        "; ours in simulation seconds {} (timing, varies by machine)",
                        sci(t)
                    )
                })
                .unwrap_or_default();
            Ok((
                ours >= target / 2.0 && ours <= target * 2.0,
                format!("ours, evaluations: {}{paper}{timing}", sci(ours)),
            ))
        }
        other => Err(format!(
            "no Rust claim \"{other}\" (known: {})",
            RUST_CLAIMS.join(", ")
        )
        .into()),
    }
}

/// "experiment: drift or failure, peak |θ̇|, |θ̈|, |τ|" of a zhang2018-style run.
fn peaks(r: &RunRow) -> String {
    format!(
        "{}: {}, peak |θ̇| {}, |θ̈| {}, |τ| {}",
        r.experiment,
        if completed(r) {
            format!("drift {}", r.drift_norm.map(sci).unwrap_or_default())
        } else {
            failed_at(r)
        },
        r.peak_thetadot.map(sci).unwrap_or_default(),
        r.peak_thetaddot.map(sci).unwrap_or_default(),
        r.peak_torque.map(sci).unwrap_or_default()
    )
}
