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

use crate::claims::Pattern;
use serde::Deserialize;

/// One published column and the swept variants (by id pattern) compared with it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SweepColumn {
    /// The `experiment` of `values.csv`.
    pub published_experiment: String,
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
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SweepColumnFile {
    published_experiment: String,
    variants: String,
}

impl SweepCheckFile {
    pub(crate) fn into_check(self, paper: &str) -> SweepCheck {
        SweepCheck {
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
                    variants: Pattern::new(&c.variants),
                })
                .collect(),
        }
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
        let check = file.into_check("p");
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
