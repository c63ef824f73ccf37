//! Trajectories produced elsewhere (MATLAB, Octave, Python), as files, and their score as a row.
//!
//! **Input** ([`crate::trajectory_file::read`], with the input reader of crate `inputs`: a
//! regular file, at most its kind's cap): a [`Trajectory`], from a MAT-file
//! (`crate::trajectory_mat`: variables `t` and `y`) or ([`parse_csv`]) a CSV file with a header
//! row naming the columns `t`, `theta_1 .. theta_n` and optionally `thetadot_1 .. thetadot_n`
//! (in any order, each once; n the task's joint count; no other column), one row per sample: t
//! in seconds from 0 to the task's duration, joint angles in rad, velocities in rad/s.
//! `simulation::score_trajectory` says what is checked and how it is scored.
//!
//! **Output** ([`score_row`]): the score is a row of the `results/runs.csv` schema
//! ([`RunRow`]): the run's metrics (drift, position error, margins, peaks) and score
//! (`score_*`), with `solver_id` = the trajectory's name (`trajectory` unless named),
//! `solver` = `trajectory <file name>`, `solver_kind` = [`TRAJECTORY_KIND`] and
//! `integrator` = [`TRAJECTORY_KIND`] (nothing was integrated: `rtol` and `atol` are 0, `steps`
//! is the number of samples).

use crate::error::{TrajectoryFileError, TrajectoryProblem};
use crate::runs::RunRow;
use catalog::ids::SolverId;
use std::collections::BTreeMap;
use std::path::Path;

/// Samples of a joint trajectory (module docs): `theta[k]` (rad) and optionally `thetadot[k]`
/// (rad/s) at `t[k]` (s), one entry per joint.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// Sample times (s), from 0 to the task's duration.
    pub t: Vec<f64>,
    /// Joint angles (rad) at each sample, one entry per joint.
    pub theta: Vec<Vec<f64>>,
    /// Joint velocities (rad/s) at each sample, when the file gives them.
    pub thetadot: Option<Vec<Vec<f64>>>,
}

/// The `solver_kind` (and `integrator`) of a scored trajectory's row.
pub const TRAJECTORY_KIND: &str = "trajectory";

/// The default solver id of a scored trajectory: [`TRAJECTORY_KIND`].
pub fn trajectory_id() -> SolverId {
    SolverId::new(TRAJECTORY_KIND).expect("\"trajectory\" is a slug")
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

/// The row of a scored trajectory (module docs) from the row of its score's record (the
/// engine's `simulation::row::run_row`); `source` names the file it came from, `name` (a slug,
/// [`TRAJECTORY_KIND`] by default) is its solver id: the row's key is the task and the name,
/// never the exact column's.
pub fn score_row(mut row: RunRow, source: &str, name: &SolverId) -> RunRow {
    row.solver_id = name.clone();
    row.solver = format!("{TRAJECTORY_KIND} {source}");
    row.solver_kind = catalog::solver_kind::SolverKind::Trajectory;
    row.integrator = TRAJECTORY_KIND.to_string();
    row.rtol = 0.0;
    row.atol = 0.0;
    row.max_step = None;
    row
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
    fn the_default_trajectory_id_is_the_kind() {
        assert_eq!(trajectory_id(), TRAJECTORY_KIND);
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

    #[test]
    fn column_selections_are_parsed_strictly() {
        use crate::trajectory_mat::{Columns, ColumnsError as E};
        let parsed = |s: &str| s.parse::<Columns>();
        assert_eq!(
            parsed("theta=1:6,thetadot=7:12").unwrap(),
            Columns {
                theta: (1, 6),
                thetadot: Some((7, 12))
            }
        );
        assert_eq!(
            parsed("theta=1:6,thetadot=7:12").unwrap().to_string(),
            "theta=1:6,thetadot=7:12"
        );
        assert!(matches!(parsed("theta=1-6"), Err(E::Syntax { .. })));
        assert!(matches!(parsed("theta=0:5"), Err(E::Range { .. })));
        assert!(matches!(parsed("theta=6:1"), Err(E::Range { .. })));
        assert!(matches!(parsed("thetadot=1:6"), Err(E::NoTheta { .. })));
        assert!(matches!(
            parsed("theta=1:6,theta=1:6"),
            Err(E::Twice { .. })
        ));
        assert!(matches!(
            parsed("theta=1:6,omega=7:12"),
            Err(E::Unknown { .. })
        ));
        assert!(matches!(
            parsed("theta=1:6,thetadot=7:11"),
            Err(E::Unequal {
                theta: 6,
                thetadot: 5
            })
        ));
        assert!(matches!(
            parsed("theta=1:99999999999999999999999"),
            Err(E::Syntax { .. })
        ));
    }
}
