//! Trajectory CSV files: a header row naming the columns `t`, `theta_1 .. theta_n` and
//! optionally `thetadot_1 .. thetadot_n` (in any order, each once; n the task's joint count;
//! no other column), one row per sample: t in seconds from 0 to the task's duration, joint
//! angles in rad, velocities in rad/s.

use super::Trajectory;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Why a trajectory CSV cannot be read (the module docs).
#[derive(Debug, thiserror::Error)]
#[error("{}: {}{problem}", path.display(), line.map(|l| format!("line {l}: ")).unwrap_or_default())]
pub struct TrajectoryFileError {
    /// The file.
    pub path: PathBuf,
    /// The 1-based line (the header is line 1), where the problem is in one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: TrajectoryProblem,
}

/// What is wrong in a trajectory CSV.
#[derive(Debug, thiserror::Error)]
pub enum TrajectoryProblem {
    /// The file is not CSV (or a row has another width).
    #[error(transparent)]
    Csv(#[from] csv::Error),
    /// A header names a column that is none of the trajectory's: its position, 1-based (its
    /// name is the file's content, never quoted).
    #[error("column {0} of the header is none of the trajectory's (t, theta_1 .. theta_n and optionally thetadot_1 .. thetadot_n)")]
    UnknownColumn(usize),
    /// A required column is absent: `t` or `theta_1`.
    #[error("no column \"{0}\"")]
    NoColumn(&'static str),
    /// A column named twice (which would silently win otherwise).
    #[error("column \"{0}\" is given twice (each column once)")]
    ColumnTwice(String),
    /// The theta_i or thetadot_i columns are not numbered 1 .. n.
    #[error("the {stem}_i columns must be numbered 1 .. n without gaps, got {numbers:?}")]
    Gaps {
        /// The columns' stem: `theta` or `thetadot`.
        stem: &'static str,
        /// The numbers given, ascending.
        numbers: Vec<usize>,
    },
    /// The thetadot columns are not one per theta column.
    #[error("{theta} theta_i columns but {thetadot} thetadot_i columns")]
    ColumnCounts {
        /// The theta_i columns.
        theta: usize,
        /// The thetadot_i columns.
        thetadot: usize,
    },
    /// A cell does not parse as a number (its text is the file's content, never quoted).
    #[error("column \"{column}\" is not a number")]
    NotANumber {
        /// The cell's column (a valid trajectory column name).
        column: String,
    },
}

/// Parses a trajectory CSV (module docs) read from `path`. Errors name the file and, where it
/// applies, the line.
pub fn parse_csv(bytes: &[u8], path: &Path) -> Result<Trajectory, TrajectoryFileError> {
    let at_line = |line: Option<usize>| {
        move |problem: TrajectoryProblem| TrajectoryFileError {
            path: path.to_path_buf(),
            line,
            problem,
        }
    };
    let at = |problem: TrajectoryProblem| at_line(None)(problem);
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(bytes);
    let header = reader.headers().map_err(|e| at(e.into()))?.clone();
    // Column index of t, and of each numbered theta_i / thetadot_i.
    let mut t_col = None;
    let mut numbered: BTreeMap<&str, BTreeMap<usize, usize>> = BTreeMap::new();
    for (col, name) in header.iter().enumerate() {
        let (stem, index) = match name.rsplit_once('_') {
            Some((stem @ ("theta" | "thetadot"), i)) => (stem, i.parse::<usize>().ok()),
            _ if name == "t" => {
                if t_col.replace(col).is_some() {
                    return Err(at(TrajectoryProblem::ColumnTwice(name.to_string())));
                }
                continue;
            }
            _ => (name, None),
        };
        match index {
            Some(i) if i >= 1 => {
                if numbered.entry(stem).or_default().insert(i, col).is_some() {
                    return Err(at(TrajectoryProblem::ColumnTwice(name.to_string())));
                }
            }
            _ => return Err(at(TrajectoryProblem::UnknownColumn(col + 1))),
        }
    }
    let t_col = t_col.ok_or_else(|| at(TrajectoryProblem::NoColumn("t")))?;
    let columns = |stem: &'static str| -> Result<Option<Vec<usize>>, TrajectoryFileError> {
        let Some(map) = numbered.get(stem) else {
            return Ok(None);
        };
        if map.keys().copied().ne(1..=map.len()) {
            return Err(at(TrajectoryProblem::Gaps {
                stem,
                numbers: map.keys().copied().collect(),
            }));
        }
        Ok(Some(map.values().copied().collect()))
    };
    let theta_cols = columns("theta")?.ok_or_else(|| at(TrajectoryProblem::NoColumn("theta_1")))?;
    let thetadot_cols = columns("thetadot")?;
    if let Some(v) = &thetadot_cols {
        if v.len() != theta_cols.len() {
            return Err(at(TrajectoryProblem::ColumnCounts {
                theta: theta_cols.len(),
                thetadot: v.len(),
            }));
        }
    }
    let mut trajectory = Trajectory {
        thetadot: thetadot_cols.as_ref().map(|_| Vec::new()),
        ..Trajectory::default()
    };
    for (row, record) in reader.records().enumerate() {
        let line = row + 2;
        let record = record.map_err(|e| at_line(Some(line))(e.into()))?;
        let number = |col: usize| -> Result<f64, TrajectoryFileError> {
            let field = record.get(col).unwrap_or("");
            field.parse::<f64>().map_err(|_| {
                at_line(Some(line))(TrajectoryProblem::NotANumber {
                    column: header[col].to_string(),
                })
            })
        };
        let numbers = |cols: &[usize]| {
            cols.iter()
                .map(|&c| number(c))
                .collect::<Result<Vec<_>, _>>()
        };
        trajectory.t.push(number(t_col)?);
        trajectory.theta.push(numbers(&theta_cols)?);
        if let (Some(cols), Some(v)) = (&thetadot_cols, trajectory.thetadot.as_mut()) {
            v.push(numbers(cols)?);
        }
    }
    Ok(trajectory)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Trajectory, TrajectoryFileError> {
        parse_csv(text.as_bytes(), Path::new("t.csv"))
    }

    #[test]
    fn columns_in_any_order_with_or_without_velocities() {
        let tr = read("theta_2,t,theta_1\n1,0,2\n3,0.5,4\n").unwrap();
        assert_eq!(tr.t, [0.0, 0.5]);
        assert_eq!(tr.theta, [vec![2.0, 1.0], vec![4.0, 3.0]]);
        assert!(tr.thetadot.is_none());
        let tr = read("t, theta_1, thetadot_1\n0, 1, -1\n").unwrap();
        assert_eq!(tr.thetadot, Some(vec![vec![-1.0]]));
    }

    #[test]
    fn bad_files_are_refused_with_the_line_and_column() {
        let e = read("t,theta_1,x\n0,1,2\n").unwrap_err().to_string();
        assert!(
            e.contains("column 3 of the header is none of the trajectory's"),
            "{e}"
        );
        let e = read("t,theta_1,theta_3\n0,1,2\n").unwrap_err().to_string();
        assert!(e.contains("numbered 1 .. n without gaps"), "{e}");
        let e = read("t,theta_1\n0,1\n0.1,abc\n").unwrap_err().to_string();
        assert!(
            e.contains("line 3: column \"theta_1\" is not a number"),
            "{e}"
        );
        let e = read("theta_1\n1\n").unwrap_err().to_string();
        assert!(e.contains("no column \"t\""), "{e}");
        for twice in ["t,theta_1,theta_1\n0,1,2\n", "t,theta_1,t\n0,1,2\n"] {
            let e = read(twice).unwrap_err();
            assert!(
                matches!(e.problem, TrajectoryProblem::ColumnTwice(_)),
                "{e}"
            );
            assert!(e.to_string().contains("is given twice"), "{e}");
        }
        let e = read("t,theta_1, theta_1 \n0,1,2\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("column \"theta_1\" is given twice"), "{e}");
        let e = read("t,theta_1,theta_2,thetadot_1\n0,1,2,3\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("2 theta_i columns but 1 thetadot_i"), "{e}");
    }
}
