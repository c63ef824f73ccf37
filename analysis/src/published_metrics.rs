//! The metrics a paper's `values.csv` may name, and the `runs.csv` column each is measured by.
//! Read by the papers' loader ([`crate::papers`]), which renames the [`METRIC_ALIASES`] of
//! older files and refuses any other name, and by the folder rules
//! ([`crate::paper_rules::PaperProblem::UnknownMetric`], which lists them).

/// The metrics a values.csv row may name: the `runs.csv` column that measures the published
/// number (one name per metric, as claims and runs.csv write it), and `error_norm_settle_s`
/// (a settling time no run measures: listed under "published numbers without a run").
pub const PUBLISHED_METRICS: [&str; 11] = [
    "drift_1",
    "drift_2",
    "drift_3",
    "drift_4",
    "drift_5",
    "drift_6",
    "drift_norm",
    "sim_s",
    "max_pos_err",
    "final_pos_err",
    ERROR_NORM_SETTLE,
];

/// The published metric no run measures.
const ERROR_NORM_SETTLE: &str = "error_norm_settle_s";

/// Metric names of earlier values.csv files, read as the `runs.csv` name they stand for.
pub const METRIC_ALIASES: [(&str, &str); 3] = [
    ("compute_time_s", "sim_s"),
    ("max_position_error_m", "max_pos_err"),
    ("final_position_error_m", "final_pos_err"),
];

/// The `runs.csv` column that measures a published metric, if we measure it (the metric's own
/// name: values.csv uses runs.csv's names).
pub fn our_metric(published_metric: &str) -> Option<&'static str> {
    PUBLISHED_METRICS
        .into_iter()
        .find(|&m| m == published_metric && m != ERROR_NORM_SETTLE)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_published_metric_is_measured_by_its_own_column_but_the_settling_time() {
        assert_eq!(our_metric("drift_norm"), Some("drift_norm"));
        assert_eq!(our_metric("sim_s"), Some("sim_s"));
        assert_eq!(our_metric(ERROR_NORM_SETTLE), None);
        assert_eq!(
            our_metric("compute_time_s"),
            None,
            "an alias is renamed at load"
        );
    }
}
