//! The row schemas' errors shared across modules: rows that parse but are not usable
//! ([`RowsError`]: a name that cannot name a file, a run listed twice, rows out of key order)
//! and a run an index does not hold ([`MissingRun`]). They wrap the catalog's naming errors
//! ([`spec::NameError`]). A table that does not read as its schema is a
//! [`crate::table::TableError`]; reading and writing the files is crate `store`'s, whose errors
//! wrap these.

use spec::NameError;

/// Why the rows of a results file (`runs.csv`, a journal) are not usable.
#[derive(Debug, thiserror::Error)]
pub enum RowsError {
    /// A row names a run with a name that cannot name a file.
    #[error("line {line}: {error}")]
    Name {
        /// The row's line (the header is line 1).
        line: usize,
        /// Why the name cannot name a file.
        error: NameError,
    },
    /// Two rows have the same run key.
    #[error("line {line}: the run {key} is listed twice (first on line {first})")]
    Twice {
        /// The second row's line (the header is line 1).
        line: usize,
        /// The run key, `experiment / variant / solver`.
        key: String,
        /// The first row's line.
        first: usize,
    },
    /// A row of a file read in key order comes before (or with) the row above it.
    #[error("line {line}: the run {key} comes after {before}: the rows are not in key order, as this program writes them")]
    Unordered {
        /// The row's line (the header is line 1).
        line: usize,
        /// Its run key.
        key: String,
        /// The key of the row above it.
        before: String,
    },
}

/// A run an [`crate::index::Runs`] does not hold.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("no run of {solver} on {experiment} / {variant}")]
pub struct MissingRun {
    /// The experiment asked for.
    pub experiment: String,
    /// The variant asked for.
    pub variant: String,
    /// The solver asked for.
    pub solver: String,
}
