//! A published table set beside a sweep's runs (`[[sweep_check]]` of `paper.toml`).
//!
//! Where a paper's setup is an assumption (a path's size, its direction), an experiment sweeps
//! it, and the report sets the published per-joint numbers of one table beside every swept
//! variant: for each variant, the published column its id matches (an id pattern, `*` any
//! text), the ratio of the drift norms and how many per-joint signs agree. The declaration:
//!
//! ```toml
//! [[sweep_check]]
//! experiment = "<sweep experiment id>"
//! heading = "Path direction and size"
//! text = "What the sweep varies and how to read the table."
//! table = "T2"
//! metrics = ["drift_1", "drift_2"]
//! columns = [{ published_experiment = "<values.csv experiment>", variants = "*-phi-1.0-tau-0.0" }]
//! ```
//!
//! A column may name the `published_column` of `values.csv` it is compared with (needed where
//! the published experiment has several, e.g. one per method); without it, the experiment's
//! first. A check may name the variant of the setup as declared (`declared = "<variant id>"`):
//! the report then states the setup's share of the gap between that run and the paper
//! ([`crate::sweep_comparison::setup_share`]).

use crate::claims::Pattern;
use crate::paper_rules::{PaperProblem, MAX_SWEEP_COLUMNS, SWEEP_METRICS};
use crate::papers::PaperValue;
use crate::report_text::is_one_line;
use serde::Deserialize;
use std::collections::BTreeSet;

/// One published column and the swept variants (by id pattern) compared with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SweepColumn {
    /// The `experiment` of `values.csv`.
    pub published_experiment: String,
    /// The `column` of `values.csv` (`None`: the experiment's first).
    pub published_column: Option<String>,
    /// The variant ids compared with it.
    pub variants: Pattern,
}

/// A paper's table beside a sweep's runs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SweepCheck {
    pub paper: String,
    /// The sweep's experiment id.
    pub experiment: String,
    /// The report's subsection title.
    pub heading: String,
    /// The paragraph above the table.
    pub text: String,
    /// The `table` of `values.csv` (`T2`).
    pub table: String,
    /// The per-joint metrics compared (`values.csv` metric names, `runs.csv` columns).
    pub metrics: Vec<String>,
    pub columns: Vec<SweepColumn>,
    /// The variant id of the setup as the experiment files declare it, if the check names one:
    /// the swept setups are then measured against it
    /// ([`crate::sweep_comparison::setup_share`]).
    pub declared: Option<String>,
}

impl SweepCheck {
    /// The published column a swept variant is compared with, if any.
    pub fn column_of(&self, variant_id: &str) -> Option<&SweepColumn> {
        self.columns.iter().find(|c| c.variants.matches(variant_id))
    }
}

/// The serde form of [`SweepCheck`] (the paper comes from the file).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SweepCheckFile {
    experiment: String,
    heading: String,
    text: String,
    table: String,
    metrics: Vec<String>,
    columns: Vec<SweepColumnFile>,
    #[serde(default)]
    declared: Option<String>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepColumnFile {
    published_experiment: String,
    #[serde(default)]
    published_column: Option<String>,
    variants: String,
}

impl SweepCheckFile {
    /// The check of `paper` (its `index`-th in the file), validated against the paper's
    /// published `values` (`crate::paper_rules`): one-line heading and text, metrics among
    /// [`SWEEP_METRICS`] each once, a table of `values.csv`, and every column a published
    /// experiment of that table with a value of every metric. Whether the experiment and the
    /// variants exist among the runs is checked by `crate::check_paper_runs`.
    pub(crate) fn into_check(
        self,
        paper: &str,
        index: usize,
        values: &[PaperValue],
    ) -> Result<SweepCheck, PaperProblem> {
        for (field, text) in [("heading", &self.heading), ("text", &self.text)] {
            if !is_one_line(text) {
                return Err(PaperProblem::SweepNotOneLine { index, field });
            }
        }
        let metric_problem = |found: String| PaperProblem::SweepMetric { index, found };
        if self.metrics.is_empty() {
            return Err(metric_problem("none given".to_string()));
        }
        let mut seen = BTreeSet::new();
        for m in &self.metrics {
            if !SWEEP_METRICS.contains(&m.as_str()) {
                return Err(metric_problem(format!(
                    "unknown metric {}",
                    settings::shown(m)
                )));
            }
            if !seen.insert(m.as_str()) {
                return Err(metric_problem(format!(
                    "{} is given twice",
                    settings::shown(m)
                )));
            }
        }
        if self.columns.len() > MAX_SWEEP_COLUMNS {
            return Err(PaperProblem::TooManySweepColumns {
                index,
                count: self.columns.len(),
            });
        }
        let choices = |set: BTreeSet<&str>| {
            let mut shown: Vec<&str> = set.into_iter().take(12).collect();
            if shown.is_empty() {
                shown.push("none");
            }
            shown.join(", ")
        };
        let of_paper = || values.iter().filter(|v| v.paper == paper);
        if !of_paper().any(|v| v.table == self.table) {
            return Err(PaperProblem::SweepTable {
                index,
                table: self.table,
                valid: choices(of_paper().map(|v| v.table.as_str()).collect()),
            });
        }
        let of_table = || of_paper().filter(|v| v.table == self.table);
        // The published (experiment, column) pairs of the table that give every compared metric.
        let gives_all = |e: &str, c: &str| {
            self.metrics
                .iter()
                .all(|m| of_table().any(|v| v.experiment == e && v.column == c && v.metric == *m))
        };
        let complete: BTreeSet<&str> = of_table()
            .filter(|v| gives_all(&v.experiment, &v.column))
            .map(|v| v.experiment.as_str())
            .collect();
        for (column, c) in self.columns.iter().enumerate() {
            if !complete.contains(c.published_experiment.as_str()) {
                return Err(PaperProblem::SweepColumn {
                    index,
                    column,
                    table: self.table.clone(),
                    experiment: c.published_experiment.clone(),
                    valid: choices(complete),
                });
            }
            if let Some(name) = &c.published_column {
                if !gives_all(&c.published_experiment, name) {
                    return Err(PaperProblem::SweepPublishedColumn {
                        index,
                        column,
                        experiment: c.published_experiment.clone(),
                        valid: choices(
                            of_table()
                                .filter(|v| v.experiment == c.published_experiment)
                                .filter(|v| gives_all(&v.experiment, &v.column))
                                .map(|v| v.column.as_str())
                                .collect(),
                        ),
                    });
                }
            }
        }
        Ok(SweepCheck {
            paper: paper.to_string(),
            experiment: self.experiment,
            heading: self.heading,
            text: self.text,
            table: self.table,
            metrics: self.metrics,
            columns: self
                .columns
                .into_iter()
                .map(|c| SweepColumn {
                    published_experiment: c.published_experiment,
                    published_column: c.published_column,
                    variants: Pattern::new(&c.variants),
                })
                .collect(),
            declared: self.declared,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_variant_finds_the_column_its_id_matches() {
        let file: SweepCheckFile = toml::from_str(
            r#"
experiment = "e-sweep"
heading = "H"
text = "T"
table = "T2"
metrics = ["drift_1"]
columns = [
  { published_experiment = "a", variants = "*-phi-1.0-tau-0.0" },
  { published_experiment = "b", variants = "*-phi-0.2-tau-0.4" },
]
"#,
        )
        .expect("parses");
        let value = |experiment: &str| PaperValue {
            paper: "p".into(),
            table: "T2".into(),
            experiment: experiment.into(),
            column: "c".into(),
            metric: "drift_1".into(),
            value: 1.0,
            note: String::new(),
            inconsistent: None,
        };
        let values = [value("a"), value("b")];
        // A metric typo, an unknown table or published experiment: errors naming the field
        // and the valid choices (they used to render as a norm of 0 and a ratio of -inf).
        let mut typo = file.clone();
        typo.metrics = vec!["drift_l".into()];
        let e = typo.into_check("p", 0, &values).unwrap_err().to_string();
        assert!(e.contains("sweep_check[0] field `metrics`: unknown metric \"drift_l\" (valid: each of drift_1, drift_2"), "{e}");
        let mut table = file.clone();
        table.table = "T9".into();
        let e = table.into_check("p", 1, &values).unwrap_err().to_string();
        assert!(
            e.contains("sweep_check[1] field `table`: values.csv has no table \"T9\" (valid: T2)"),
            "{e}"
        );
        let e = file
            .clone()
            .into_check("p", 0, &values[..1])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("columns[1] field `published_experiment`") && e.contains("(valid: a)"),
            "{e}"
        );
        let mut named = file.clone();
        named.columns[0].published_column = Some("d".into());
        let e = named.into_check("p", 0, &values).unwrap_err().to_string();
        assert_eq!(
            e,
            "sweep_check[0] columns[0] field `published_column`: a has no such column with every metric of the check (valid: c)"
        );
        let mut named = file.clone();
        named.columns[0].published_column = Some("c".into());
        let check = named.into_check("p", 0, &values).unwrap();
        assert_eq!(check.columns[0].published_column.as_deref(), Some("c"));
        let mut heading = file.clone();
        heading.heading = "H\n## injected".into();
        assert!(heading.into_check("p", 0, &values).is_err());
        let check = file.into_check("p", 0, &values).unwrap();
        let col = |v: &str| check.column_of(v).map(|c| c.published_experiment.as_str());
        assert_eq!(
            col("clover-reverse-false-scale-0.1-phi-1.0-tau-0.0"),
            Some("a")
        );
        assert_eq!(
            col("clover-reverse-true-scale-0.2-phi-0.2-tau-0.4"),
            Some("b")
        );
        assert_eq!(col("clover-reverse-true-scale-0.2-phi-0.2-tau-0.0"), None);
        assert_eq!(check.paper, "p");
    }
}
