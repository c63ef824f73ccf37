//! A sweep's runs beside the published table of its `[[sweep_check]]`
//! (`sweep_check`): for every swept variant, the published column its id matches, the
//! paper's drift norm there (the 2-norm of the compared per-joint numbers), ours against it, and
//! how many per-joint signs agree where both exceed the run's round-off floor; and, where the check names the declared setup's variant, the
//! setup's share of the gap ([`setup_share`]).

use crate::paper_verdict::sign_floor;
use crate::papers::Papers;
use crate::sweep_check::{SweepCheck, SweepColumn};
use records::index::{completed, metric, Runs};
use records::RunRow;

/// The published value of one column and metric of the check's table (the experiment's
/// `column`, or its first where `column` is `None`).
fn published(
    papers: &Papers,
    check: &SweepCheck,
    column: &SweepColumn,
    metric: &str,
) -> Option<f64> {
    papers
        .values
        .iter()
        .find(|v| {
            v.paper == check.paper
                && v.table == check.table
                && v.experiment == column.published_experiment
                && column
                    .published_column
                    .as_ref()
                    .is_none_or(|c| *c == v.column)
                && v.metric == metric
        })
        .map(|v| v.value)
}

/// What a swept run shows against its published column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Against {
    /// The run failed at `t` (s; 0 when not recorded).
    Failed { t: f64 },
    Completed {
        /// Our drift norm (NaN where not measured).
        norm: f64,
        /// `norm` / the paper's.
        ratio: f64,
        /// Per-joint drifts with the paper's sign, of `compared`: the joints where both ours
        /// and the paper's exceed the run's round-off floor
        /// ([`crate::paper_verdict::sign_floor`]).
        same_sign: usize,
        compared: usize,
        /// Peak |thetadot| (rad/s; NaN where not measured).
        peak_thetadot: f64,
    },
}

/// One swept variant beside its published column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweptRun<'a> {
    pub row: &'a RunRow,
    /// The paper's drift norm: the 2-norm of its per-joint numbers of the column.
    pub paper_norm: f64,
    pub against: Against,
}

/// Every run of the sweep whose variant a published column matches, in file order.
pub fn swept_runs<'a>(check: &'a SweepCheck, runs: &'a Runs, papers: &Papers) -> Vec<SweptRun<'a>> {
    runs.of_experiment(&check.experiment)
        .filter_map(|r| {
            let column = check.column_of(&r.variant_id)?;
            let paper: Vec<f64> = check
                .metrics
                .iter()
                .filter_map(|m| published(papers, check, column, m))
                .collect();
            let paper_norm = paper.iter().map(|v| v * v).sum::<f64>().sqrt();
            let against = if !completed(r) {
                Against::Failed {
                    t: r.failed_at.unwrap_or(0.0),
                }
            } else {
                let ours: Vec<f64> = check.metrics.iter().filter_map(|m| metric(r, m)).collect();
                let norm = r.drift_norm.unwrap_or(f64::NAN);
                // Signs only where both exceed the run's round-off floor (a printed 0 is no sign).
                let floor = sign_floor(r);
                let comparable: Vec<(&f64, &f64)> = ours
                    .iter()
                    .zip(&paper)
                    .filter(|(o, p)| o.abs() > floor && p.abs() > floor)
                    .collect();
                Against::Completed {
                    norm,
                    ratio: norm / paper_norm,
                    same_sign: comparable
                        .iter()
                        .filter(|(o, p)| o.signum() == p.signum())
                        .count(),
                    compared: comparable.len(),
                    peak_thetadot: r.peak_thetadot.unwrap_or(f64::NAN),
                }
            };
            Some(SweptRun {
                row: r,
                paper_norm,
                against,
            })
        })
        .collect()
}

/// The setup's share of the gap between the run of the declared setup and the paper
/// ([`setup_share`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetupShare<'a> {
    /// The run of the setup as declared.
    pub declared: &'a RunRow,
    /// Its drift norm d_0.
    pub declared_norm: f64,
    /// The paper's norm p of the declared run's column.
    pub paper_norm: f64,
    /// g = p / d_0: the factor by which the declared setup misses the paper.
    pub gap: f64,
    /// How many other swept setups completed (the factors below are theirs).
    pub setups: usize,
    /// The smallest and largest factor d_i / d_0 over them.
    pub range: (f64, f64),
    /// The setup whose factor goes furthest toward the paper's norm.
    pub nearest: &'a RunRow,
    /// Its factor f = d_i / d_0.
    pub factor: f64,
    /// ln f / ln g: the share of the gap, on a log scale, that this one part of the setup
    /// carries (1 or more: it alone closes the gap; 0 or less: it moves away from the paper).
    pub share: f64,
    /// Whether that part of the setup alone can carry the whole gap: share >= 1.
    pub closes_gap: bool,
    /// The share toward the paper, max(share, 0): a part that moves away carries none of it.
    pub toward_paper: f64,
}

/// The setup's share of the gap, when `check` names its declared variant and that run and at
/// least one other swept run completed with a drift norm, and the declared norm is not the
/// paper's (g != 1): over the other completed runs i of the sweep, the factors
/// f_i = d_i / d_0 of their drift norms on the declared run's d_0, and the largest
/// ln f_i / ln g, where g = p / d_0 and p is the paper's norm of the declared run's column.
/// A share of s means the part of the setup that run changes moves the drift s of the way
/// (in orders of magnitude) from our declared setup to the paper.
pub fn setup_share<'a>(check: &SweepCheck, swept: &[SweptRun<'a>]) -> Option<SetupShare<'a>> {
    let declared_id = check.declared.as_deref()?;
    let norm = |s: &SweptRun| match s.against {
        Against::Completed { norm, .. } if norm.is_finite() && norm > 0.0 => Some(norm),
        _ => None,
    };
    let base = swept
        .iter()
        .find(|s| s.row.variant_id.as_str() == declared_id)?;
    let d0 = norm(base)?;
    let gap = base.paper_norm / d0;
    if !(gap.is_finite() && gap > 0.0) || gap == 1.0 {
        return None;
    }
    let others: Vec<(&SweptRun<'a>, f64)> = swept
        .iter()
        .filter(|s| s.row.variant_id.as_str() != declared_id)
        .filter_map(|s| norm(s).map(|d| (s, d / d0)))
        .collect();
    let share = |f: f64| f.ln() / gap.ln();
    let (nearest, factor) = others
        .iter()
        .copied()
        .max_by(|a, b| share(a.1).total_cmp(&share(b.1)))?;
    let carried = share(factor);
    let factors = others.iter().map(|(_, f)| *f);
    Some(SetupShare {
        declared: base.row,
        declared_norm: d0,
        paper_norm: base.paper_norm,
        gap,
        setups: others.len(),
        range: (
            factors.clone().fold(f64::INFINITY, f64::min),
            factors.fold(f64::NEG_INFINITY, f64::max),
        ),
        nearest: nearest.row,
        factor,
        share: carried,
        closes_gap: carried >= 1.0,
        toward_paper: carried.max(0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::Pattern;
    use crate::sweep_check::SweepColumn;
    use spec::SolverKind;

    #[test]
    fn a_swept_run_is_set_against_the_norm_of_the_printed_joints() {
        let check = SweepCheck {
            paper: "p".into(),
            experiment: "e".into(),
            heading: "h".into(),
            text: "t".into(),
            table: "T2".into(),
            metrics: vec!["drift_1".into(), "drift_2".into()],
            columns: vec![SweepColumn {
                published_experiment: "E".into(),
                published_column: None,
                variants: Pattern::new("*"),
            }],
            declared: None,
        };
        let value = |metric: &str, value: f64| crate::papers::PaperValue {
            paper: "p".into(),
            table: "T2".into(),
            experiment: "E".into(),
            column: "c".into(),
            metric: metric.into(),
            value,
            note: String::new(),
            inconsistent: None,
        };
        let papers = Papers {
            values: vec![value("drift_1", 3.0), value("drift_2", -4.0)],
            ..Papers::default()
        };
        let mut r = RunRow::blank(
            &spec::RunKey::from_ids("e", "v", "exact").unwrap(),
            SolverKind::Exact,
        );
        r.drift = vec![0.3, 0.4];
        r.drift_norm = Some(0.5);
        let runs = Runs::new(vec![r]);
        let swept = swept_runs(&check, &runs, &papers);
        assert_eq!(swept.len(), 1);
        assert_eq!(swept[0].paper_norm, 5.0);
        assert!(matches!(
            swept[0].against,
            Against::Completed { ratio, same_sign: 1, compared: 2, .. } if ratio == 0.1
        ));
    }

    /// The declared run's gap to the paper's norm of the named column, and the swept setup
    /// that goes furthest toward it: its share ln f / ln g.
    #[test]
    fn the_setup_share_is_the_largest_log_step_toward_the_paper_of_the_named_column() {
        let value = |column: &str, metric: &str, value: f64| crate::papers::PaperValue {
            paper: "p".into(),
            table: "T4".into(),
            experiment: "E".into(),
            column: column.into(),
            metric: metric.into(),
            value,
            note: String::new(),
            inconsistent: None,
        };
        let papers = Papers {
            values: vec![
                value("c", "drift_1", 3.0),
                value("c", "drift_2", -4.0),
                value("k", "drift_1", 30.0),
                value("k", "drift_2", -40.0),
            ],
            ..Papers::default()
        };
        let run = |variant: &str, norm: f64| {
            let mut r = RunRow::blank(
                &spec::RunKey::from_ids("e", variant, "exact").unwrap(),
                SolverKind::Exact,
            );
            r.drift = vec![0.6 * norm, -0.8 * norm];
            r.drift_norm = Some(norm);
            r
        };
        let swept_zero = {
            let mut r = run("declared", 0.5);
            r.drift = vec![0.3, 1e-20];
            let mut zero = papers.clone();
            zero.values[1].value = 0.0;
            let runs = Runs::new(vec![r]);
            let check = SweepCheck {
                columns: vec![SweepColumn {
                    published_experiment: "E".into(),
                    published_column: Some("c".into()),
                    variants: Pattern::new("*"),
                }],
                declared: None,
                paper: "p".into(),
                experiment: "e".into(),
                heading: "h".into(),
                text: "t".into(),
                table: "T4".into(),
                metrics: vec!["drift_1".into(), "drift_2".into()],
            };
            swept_runs(&check, &runs, &zero)[0].against
        };
        assert!(
            matches!(
                swept_zero,
                Against::Completed {
                    same_sign: 1,
                    compared: 1,
                    ..
                }
            ),
            "a printed 0 against round-off is not a sign: {swept_zero:?}"
        );
        let runs = Runs::new(vec![
            run("declared", 0.5),
            run("bigger", 1.0),
            run("smaller", 0.25),
        ]);
        let check = SweepCheck {
            paper: "p".into(),
            experiment: "e".into(),
            heading: "h".into(),
            text: "t".into(),
            table: "T4".into(),
            metrics: vec!["drift_1".into(), "drift_2".into()],
            columns: vec![SweepColumn {
                published_experiment: "E".into(),
                published_column: Some("k".into()),
                variants: Pattern::new("*"),
            }],
            declared: None,
        };
        let swept = swept_runs(&check, &runs, &papers);
        assert!(
            swept.iter().all(|s| s.paper_norm == 50.0),
            "column k's norm"
        );
        assert_eq!(setup_share(&check, &swept), None, "no declared variant");
        let mut check = check.clone();
        check.declared = Some("declared".into());
        let share = setup_share(&check, &swept).unwrap();
        assert_eq!(share.declared.variant_id.as_str(), "declared");
        assert_eq!((share.declared_norm, share.paper_norm), (0.5, 50.0));
        assert!((share.gap - 100.0).abs() < 1e-12);
        assert_eq!(share.setups, 2);
        assert_eq!(share.range, (0.5, 2.0));
        assert_eq!(share.nearest.variant_id.as_str(), "bigger");
        assert_eq!(share.factor, 2.0);
        assert!((share.share - 2f64.ln() / 100f64.ln()).abs() < 1e-12);
        // The paper's norm below ours: the step down is the one toward it.
        check.columns[0].published_column = Some("c".into());
        let runs = Runs::new(vec![
            run("declared", 50.0),
            run("bigger", 100.0),
            run("smaller", 25.0),
        ]);
        let swept = swept_runs(&check, &runs, &papers);
        let share = setup_share(&check, &swept).unwrap();
        assert_eq!(share.nearest.variant_id.as_str(), "smaller");
        assert!((share.share - 0.5f64.ln() / 0.1f64.ln()).abs() < 1e-12);
    }
}
