//! `results/runs.csv` read from its file (the rows' schema and checks are
//! [`records::RunRow`]'s) and the writability probe of a results directory.

use crate::atomic::TMP_PREFIX;
use crate::error::RunsError;
use records::{check_run_rows, RunRow};
use std::path::Path;

/// Reads `results/runs.csv`. Any problem is an error naming the file, the line and how to
/// recover, never a silently shorter list: an unreadable file, a header that is not this
/// version's columns (an old schema: a missing or an unknown column), a row that does not
/// parse, a name that cannot name a file ([`check_run_rows`]) or a run listed twice. An empty file
/// has no rows.
pub fn read_runs(path: &Path) -> Result<Vec<RunRow>, RunsError> {
    let rows = crate::table::read(path).map_err(|error| RunsError::Table {
        path: path.to_path_buf(),
        error,
    })?;
    check_run_rows(&rows).map_err(|error| RunsError::Rows {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(rows)
}

/// Checks that files can be created in `dir` (created if absent): writes and removes a probe
/// file. The error names the directory.
pub fn check_writable(dir: &Path) -> Result<(), RunsError> {
    let fail = |source| RunsError::NotWritable {
        dir: dir.to_path_buf(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    let probe = dir.join(format!("{TMP_PREFIX}{}.probe", std::process::id()));
    std::fs::write(&probe, b"").map_err(fail)?;
    std::fs::remove_file(&probe).map_err(fail)
}
