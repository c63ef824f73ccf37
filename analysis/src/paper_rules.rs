//! What a paper folder of `papers/` must satisfy before anything runs, and the typed problem
//! when it does not ([`PaperProblem`]): the paper id is a slug of at most
//! [`spec::MAX_EXPERIMENT_ID`] bytes, the folder's name, and not one of the
//! [`RESERVED_PAPER_IDS`]; texts that reach the report (title, citation, claims) are one line
//! ([`crate::is_one_line`]); each published (experiment, column) has at most one
//! `[[mapping]]`; every values.csv entry is finite, of a known metric, of this paper, and given
//! once; a paper has at most [`MAX_CLAIMS`] claims, [`MAX_MAPPINGS`] mappings of at most
//! [`MAX_COMPANIONS`] companions each, and [`MAX_SWEEP_CHECKS`] sweep checks of at most
//! [`MAX_SWEEP_COLUMNS`] columns; a sweep check compares per-joint drifts
//! ([`SWEEP_METRICS`]) of a table and columns `values.csv` has, its heading and text one line
//! each. [`crate::papers::Papers::load`] applies them; what the files name among the runs is
//! checked by [`crate::check_paper_runs`].

use crate::claims::ClaimError;
use crate::leaderboard::STANDARD_PAPER;
use crate::published_metrics::PUBLISHED_METRICS;
use spec::MAX_EXPERIMENT_ID;

/// Paper id of the group-code reference experiments (`experiments/group.toml`): not a paper of
/// `papers/`, but the id their runs and explanations are filed under.
pub const GROUP: &str = "group";

/// Paper ids the suite files its own runs under (the group-code reference experiments and
/// the cross experiment): no folder of `papers/` may take them.
pub const RESERVED_PAPER_IDS: [&str; 2] = [GROUP, STANDARD_PAPER];

/// The most claims one `paper.toml` may hold: the report evaluates each over every run (and a
/// `than` claim over pairs of runs), so claims times runs stays bounded.
pub const MAX_CLAIMS: usize = 200;

/// The most `[[mapping]]` tables one `paper.toml` may hold (the papers hold at most 12): each
/// is looked up for every published number.
pub const MAX_MAPPINGS: usize = 500;

/// The most `companions` of one mapping (the papers' have at most 3): each is a column of the
/// report's table of the mapped number.
pub const MAX_COMPANIONS: usize = 50;

/// The most `[[sweep_check]]` tables of one `paper.toml` (each is a section of the report).
pub const MAX_SWEEP_CHECKS: usize = 20;

/// The most `columns` of one sweep check (each is compared with every swept run).
pub const MAX_SWEEP_COLUMNS: usize = 100;

/// The metrics a sweep check compares: the per-joint drifts, whose norm and signs the report
/// sets beside the paper's.
pub const SWEEP_METRICS: [&str; 6] = [
    "drift_1", "drift_2", "drift_3", "drift_4", "drift_5", "drift_6",
];

/// What is wrong with a paper's `paper.toml` or `values.csv` (the field or line, and the valid
/// choices); [`crate::papers::PapersError::Invalid`] adds the file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PaperProblem {
    #[error("the folder's name is not UTF-8; a paper id is lower-case ASCII letters, digits, `.` and single `-`")]
    FolderNotUtf8,
    #[error("the folder's name {} is not a paper id: use lower-case ASCII letters, digits, `.` and single `-`, at most {MAX_EXPERIMENT_ID} bytes (e.g. {})", settings::shown(id), settings::shown(suggestion))]
    NotAnId { id: String, suggestion: String },
    #[error("the folder's name {} is reserved (the suite's own: {})", settings::shown(id), RESERVED_PAPER_IDS.join(", "))]
    Reserved { id: String },
    #[error(
        "field `paper`: {} must be the folder's name {}",
        settings::shown(paper),
        settings::shown(folder)
    )]
    NotTheFolder { paper: String, folder: String },
    #[error("field `{field}`: must be one line of text (no line breaks, control or formatting characters)")]
    NotOneLine { field: &'static str },
    #[error(
        "mapping[{index}] field `run`: {} is not \"<experiment> / <variant> / <solver>\" (ids)",
        settings::shown(run)
    )]
    Run { index: usize, run: String },
    #[error("mapping[{index}] field `companions`: {} is not \"<variant>\" or \"<variant> / <solver>\" (ids)", settings::shown(companion))]
    Companion { index: usize, companion: String },
    #[error("mapping[{index}]: published experiment {} column {} is already mapped by mapping[{first}] (one run per published column)", settings::shown(experiment), settings::shown(column))]
    MappingTwice {
        index: usize,
        first: usize,
        experiment: String,
        column: String,
    },
    #[error("claim[{index}]: {error}")]
    Claim { index: usize, error: ClaimError },
    #[error("{count} claims: at most {MAX_CLAIMS} per paper (each is evaluated over every run)")]
    TooManyClaims { count: usize },
    #[error("{count} mappings: at most {MAX_MAPPINGS} per paper")]
    TooManyMappings { count: usize },
    #[error("mapping[{index}] field `companions`: {count} entries, at most {MAX_COMPANIONS}")]
    TooManyCompanions { index: usize, count: usize },
    #[error("{count} sweep checks: at most {MAX_SWEEP_CHECKS} per paper")]
    TooManySweepChecks { count: usize },
    #[error("sweep_check[{index}] field `columns`: {count} entries, at most {MAX_SWEEP_COLUMNS}")]
    TooManySweepColumns { index: usize, count: usize },
    #[error("sweep_check[{index}] field `{field}`: must be one line of text (no line breaks, control or formatting characters)")]
    SweepNotOneLine { index: usize, field: &'static str },
    #[error("sweep_check[{index}] field `metrics`: {found} (valid: each of {} at most once, at least one)", SWEEP_METRICS.join(", "))]
    SweepMetric { index: usize, found: String },
    #[error(
        "sweep_check[{index}] field `table`: values.csv has no table {} (valid: {valid})",
        settings::shown(table)
    )]
    SweepTable {
        index: usize,
        table: String,
        valid: String,
    },
    #[error("sweep_check[{index}] columns[{column}] field `published_experiment`: table {table} of values.csv has no {} with every metric of the check (valid: {valid})", settings::shown(experiment))]
    SweepColumn {
        index: usize,
        column: usize,
        table: String,
        experiment: String,
        valid: String,
    },
    #[error("sweep_check[{index}] columns[{column}] field `published_column`: {experiment} has no such column with every metric of the check (valid: {valid})")]
    SweepPublishedColumn {
        index: usize,
        column: usize,
        experiment: String,
        valid: String,
    },
    #[error(
        "sweep_check[{index}] field `declared`: {} is no variant of {experiment} (valid: {valid})",
        settings::shown(variant)
    )]
    SweepDeclared {
        index: usize,
        variant: String,
        experiment: String,
        valid: String,
    },
    #[error("sweep_check[{index}] columns[{column}] field `variants`: {} matches no variant of {experiment} (valid: {valid})", settings::shown(pattern))]
    SweepSelectsNothing {
        index: usize,
        column: usize,
        pattern: String,
        experiment: String,
        valid: String,
    },
    #[error(
        "mapping[{index}] field `{field}`: no run {} in the experiment files (valid {valid})",
        settings::shown(run)
    )]
    NoSuchRun {
        index: usize,
        field: &'static str,
        run: String,
        valid: String,
    },
    #[error("claim[{index}] field `{field}`: selects no run of the experiment files")]
    SelectsNothing { index: usize, field: &'static str },
    #[error("line {line}: value {value} is not a finite number")]
    ValueNotFinite { line: usize, value: f64 },
    #[error("line {line}: unknown metric {} (valid: {})", settings::shown(metric), PUBLISHED_METRICS.join(", "))]
    UnknownMetric { line: usize, metric: String },
    #[error(
        "line {line}: a value of paper {} in the folder of {}",
        settings::shown(paper),
        settings::shown(folder)
    )]
    OtherPaper {
        line: usize,
        paper: String,
        folder: String,
    },
    /// `value`: which published number, `"the <metric> of <experiment> / <column> in table <table>"`.
    #[error("line {line}: {value} is given already on line {first}")]
    ValueTwice {
        line: usize,
        first: usize,
        value: String,
    },
    #[error("line {line}: field `{field}` must be one line of text (no line breaks, control or formatting characters)")]
    ValueNotOneLine { line: usize, field: &'static str },
}

/// Checks a paper folder's name as a paper id (module docs).
pub fn check_paper_id(id: &str) -> Result<(), PaperProblem> {
    if !spec::ids::is_id_form(id) || id.len() > MAX_EXPERIMENT_ID {
        return Err(PaperProblem::NotAnId {
            id: id.to_string(),
            suggestion: settings::slug(id).chars().take(MAX_EXPERIMENT_ID).collect(),
        });
    }
    if RESERVED_PAPER_IDS.contains(&id) {
        return Err(PaperProblem::Reserved { id: id.to_string() });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_ids_are_short_unreserved_slugs() {
        for good in ["jia2019", "kong2019", "a.b-2"] {
            assert_eq!(check_paper_id(good), Ok(()), "{good}");
        }
        for bad in [
            "Jia2019",
            "a b",
            "a](javascript:alert(1))",
            "café",
            "-a",
            "a--b",
            "",
        ] {
            assert!(
                matches!(check_paper_id(bad), Err(PaperProblem::NotAnId { .. })),
                "{bad:?}"
            );
        }
        let long = "p".repeat(MAX_EXPERIMENT_ID + 1);
        assert!(matches!(
            check_paper_id(&long),
            Err(PaperProblem::NotAnId { .. })
        ));
        assert!(check_paper_id(&long[1..]).is_ok());
        for reserved in RESERVED_PAPER_IDS {
            let e = check_paper_id(reserved).unwrap_err();
            assert!(e.to_string().contains("reserved"), "{e}");
        }
    }
}
