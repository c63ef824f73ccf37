//! `results/leaderboard-timing.csv` (its rows are [`records::Timings`]'s) written and read back.

use crate::error::{IoAction, IoError, RunsError};
use records::{TimingRow, Timings, TIMING_FILE};
use std::path::{Path, PathBuf};

/// Writes `results_dir/leaderboard-timing.csv` (atomically, replacing it), rows sorted by key.
pub fn write(results_dir: &Path, timings: &Timings) -> Result<PathBuf, RunsError> {
    let path = results_dir.join(TIMING_FILE);
    let rows: Vec<TimingRow> = timings.rows().cloned().collect();
    let bytes = records::table::to_csv(&rows).map_err(|source| RunsError::Write {
        path: path.clone(),
        source,
    })?;
    crate::atomic::write_atomic(&path, &bytes).map_err(IoError::at(&path, IoAction::Write))?;
    Ok(path)
}

/// Reads `results_dir/leaderboard-timing.csv`; an absent file is no timings.
pub fn read(results_dir: &Path) -> Result<Timings, RunsError> {
    let path = results_dir.join(TIMING_FILE);
    if !path.exists() {
        return Ok(Timings::default());
    }
    let rows = crate::table::read(&path).map_err(|error| RunsError::Table {
        path: path.clone(),
        error,
    })?;
    Ok(Timings::new(rows))
}

#[cfg(test)]
mod tests {
    use super::*;
    use spec::RunKey;

    #[test]
    fn written_and_read_back() {
        let dir = inputs::Scratch::dir("timing");
        let rows = vec![
            TimingRow::from_samples(
                &RunKey::from_ids("b", "v", "s").unwrap(),
                &[(0.5, 0.6)],
                "cpu",
                2,
                "r",
            ),
            TimingRow::from_samples(
                &RunKey::from_ids("a", "v", "s").unwrap(),
                &[(0.1, 0.2)],
                "cpu",
                2,
                "r",
            ),
        ];
        let timings = Timings::new(rows);
        write(&dir, &timings).unwrap();
        let back = read(&dir).unwrap();
        drop(dir);
        assert_eq!(back, timings);
        assert_eq!(
            back.sim_s(&RunKey::from_ids("b", "v", "s").unwrap()),
            Some(0.5)
        );
        assert_eq!(back.rows().next().unwrap().experiment, "a");
        assert!(read(Path::new("/nonexistent-driftbench"))
            .unwrap()
            .is_empty());
    }
}
