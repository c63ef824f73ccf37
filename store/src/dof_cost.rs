//! `results/dof-cost.csv` (its rows are [`records::dof_cost`]'s) written and read back.

use crate::error::{DofCostError, IoAction, IoError};
use records::dof_cost::{DofCostRow, FILE};
use std::path::{Path, PathBuf};

/// Writes `results_dir/dof-cost.csv` (atomically, replacing the file) and returns its path.
pub fn write(results_dir: &Path, rows: &[DofCostRow]) -> Result<PathBuf, DofCostError> {
    let path = results_dir.join(FILE);
    let bytes = records::table::to_csv(rows).map_err(|source| DofCostError::Csv {
        path: path.clone(),
        source,
    })?;
    crate::atomic::write_atomic(&path, &bytes)
        .map_err(IoError::at(path.clone(), IoAction::Write))?;
    Ok(path)
}

/// Reads `results_dir/dof-cost.csv` ([`records::dof_cost::from_reader`]: legacy scheme ids
/// read as their kinds'); an absent file is no rows.
pub fn read(results_dir: &Path) -> Result<Vec<DofCostRow>, DofCostError> {
    let path = results_dir.join(FILE);
    if !path.exists() {
        return Ok(Vec::new());
    }
    Ok(crate::table::read_with(&path, |bytes| {
        records::dof_cost::from_reader(bytes)
    })?)
}
