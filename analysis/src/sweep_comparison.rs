//! A sweep's runs beside the published table of its `[[sweep_check]]`
//! ([`crate::sweep_check`]): for every swept variant, the published column its id matches, the
//! paper's drift norm there (the 2-norm of the compared per-joint numbers), ours against it, and
//! how many per-joint signs agree.

use crate::papers::Papers;
use crate::sweep_check::SweepCheck;
use records::index::{completed, metric, Runs};
use records::runs::RunRow;

/// The published value of one column and metric of the check's table.
fn published(papers: &Papers, check: &SweepCheck, experiment: &str, metric: &str) -> Option<f64> {
    papers
        .values
        .iter()
        .find(|v| {
            v.paper == check.paper
                && v.table == check.table
                && v.experiment == experiment
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
        /// Per-joint drifts with the paper's sign, of `compared`.
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
                .filter_map(|m| published(papers, check, &column.published_experiment, m))
                .collect();
            let paper_norm = paper.iter().map(|v| v * v).sum::<f64>().sqrt();
            let against = if !completed(r) {
                Against::Failed {
                    t: r.failed_at.unwrap_or(0.0),
                }
            } else {
                let ours: Vec<f64> = check.metrics.iter().filter_map(|m| metric(r, m)).collect();
                let norm = r.drift_norm.unwrap_or(f64::NAN);
                Against::Completed {
                    norm,
                    ratio: norm / paper_norm,
                    same_sign: ours
                        .iter()
                        .zip(&paper)
                        .filter(|(o, p)| o.signum() == p.signum())
                        .count(),
                    compared: paper.len(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::Pattern;
    use crate::sweep_check::SweepColumn;
    use catalog::solver_kind::SolverKind;

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
                variants: Pattern::new("*"),
            }],
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
            &catalog::run_key::RunKey::from_ids("e", "v", "exact").unwrap(),
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
}
