//! Trajectories produced elsewhere (MATLAB, Octave, Python), as files: a [`Trajectory`] of
//! either format, told by its name ([`read()`]): a MAT-file (`.mat`, any case; [`mat_file`]:
//! variables `t` and `y`) or a CSV file ([`csv_file`]), read with this crate's reader (a regular
//! file, at most its kind's cap). `simulation::score_trajectory` says what is checked and how
//! it is scored; `records::trajectory` makes the score a results row.

pub mod csv_file;
pub mod mat_file;

pub use csv_file::{parse_csv, TrajectoryFileError, TrajectoryProblem};
pub use mat_file::{read_mat, Columns, ColumnsError, MatError};

use std::path::Path;

/// Samples of a joint trajectory: `theta[k]` (rad) and optionally `thetadot[k]` (rad/s) at
/// `t[k]` (s), one entry per joint.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// Sample times (s), from 0 to the task's duration.
    pub t: Vec<f64>,
    /// Joint angles (rad) at each sample, one entry per joint.
    pub theta: Vec<Vec<f64>>,
    /// Joint velocities (rad/s) at each sample, when the file gives them.
    pub thetadot: Option<Vec<Vec<f64>>>,
}

/// Why a trajectory file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file was refused or could not be read (a FIFO, a device, over
    /// [`crate::Kind::TrajectoryCsv`]'s cap).
    #[error(transparent)]
    Input(#[from] crate::InputError),
    /// The CSV file's problem (file, line, column).
    #[error(transparent)]
    Csv(#[from] TrajectoryFileError),
    /// The MAT-file's problem.
    #[error(transparent)]
    Mat(#[from] MatError),
    /// A column selection for a CSV file, whose header names its columns.
    #[error("{}: a column selection ({columns}) applies to MAT-files; a CSV file names its columns in its header", path.display())]
    ColumnsOfCsv {
        /// The CSV file.
        path: std::path::PathBuf,
        /// The selection given.
        columns: Columns,
    },
}

/// Reads the trajectory of a `joints`-joint task from `path`: a MAT-file when the name ends in
/// `.mat` (any case; `columns`: which columns of its `y` to read), a CSV file otherwise.
pub fn read(
    path: &Path,
    joints: usize,
    columns: Option<&Columns>,
) -> Result<Trajectory, ReadError> {
    let is_mat = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mat"));
    if is_mat {
        Ok(read_mat(path, joints, columns)?)
    } else if let Some(columns) = columns {
        Err(ReadError::ColumnsOfCsv {
            path: path.to_path_buf(),
            columns: columns.clone(),
        })
    } else {
        let bytes = crate::read(path, crate::Kind::TrajectoryCsv, crate::Origin::Named)?;
        Ok(parse_csv(&bytes, path)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures")
            .join(name)
    }

    /// Written by Octave 7.3: `t = [0; 0.5; 1]`, `y = [1 2 10 20; 3 4 30 40; 5 6 50 60]` and a
    /// string `s` as `save -v7` (compressed); `t'` and `y(:, 1:2)` as `save -v6`.
    #[test]
    fn mat_files_of_octave_are_read_with_and_without_velocities() {
        let tr = read(&fixture("trajectory-v7.mat"), 2, None).unwrap();
        assert_eq!(tr.t, [0.0, 0.5, 1.0]);
        assert_eq!(tr.theta, [vec![1.0, 2.0], vec![3.0, 4.0], vec![5.0, 6.0]]);
        assert_eq!(
            tr.thetadot,
            Some(vec![vec![10.0, 20.0], vec![30.0, 40.0], vec![50.0, 60.0]])
        );
        let tr = read(&fixture("trajectory-v6.mat"), 2, None).unwrap();
        assert_eq!(tr.t, [0.0, 0.5, 1.0]);
        assert_eq!(tr.theta[2], [5.0, 6.0]);
        assert!(tr.thetadot.is_none());
    }

    #[test]
    fn mat_files_of_the_wrong_shape_are_refused() {
        let e = read(&fixture("trajectory-v7.mat"), 3, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("y is 3 x 4; for 3 instants of a 3-joint task"),
            "{e}"
        );
        let e = read(&fixture("trajectory-v6.mat"), 3, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("y is 3 x 2"), "{e}");
        let e = read(&fixture("missing.mat"), 2, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.mat"), "{e}");
        // A name that does not end in .mat is read as CSV (here, one that is not there).
        let csv = fixture("trajectory-v7.csv");
        let e = read(&csv, 2, None).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::Input(crate::InputError::Open {
                    kind: crate::Kind::TrajectoryCsv,
                    ..
                })
            ),
            "{e}"
        );
    }

    /// Uncompressed (v6) files of t (21 x 1) and y (21 x 5), written byte by byte:
    /// `y-trailing-ones.mat` stores y's size as 21 x 5 x 1 x 1 x 1, `y-3d.mat` the same bytes
    /// with the size 21 x 1 x 5 x 1 x 1, `truncated.mat` a copy of such a file cut 40 bytes
    /// short, inside y.
    #[test]
    fn mat_files_with_more_dimensions_or_cut_short_are_named_so() {
        let tr = read(&fixture("y-trailing-ones.mat"), 5, None).unwrap();
        assert_eq!((tr.t.len(), tr.theta.len(), tr.theta[0].len()), (21, 21, 5));
        let e = read(&fixture("y-3d.mat"), 5, None).unwrap_err();
        assert!(
            matches!(e, ReadError::Mat(MatError::NotMatrix { dims: 3, .. })),
            "{e}"
        );
        let e = read(&fixture("truncated.mat"), 5, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("truncated.mat") && e.contains("the file is truncated"),
            "{e}"
        );
    }

    /// The Octave fixture's y is 3 x 4: a selection reads theta from any of its columns, and
    /// thetadot beside it or not at all.
    #[test]
    fn a_column_selection_reads_the_columns_it_names() {
        let select = |spec: &str| spec.parse::<Columns>().unwrap();
        let v7 = fixture("trajectory-v7.mat");
        let tr = read(&v7, 2, Some(&select("theta=3:4"))).unwrap();
        assert_eq!(
            tr.theta,
            [vec![10.0, 20.0], vec![30.0, 40.0], vec![50.0, 60.0]]
        );
        assert!(tr.thetadot.is_none());
        let tr = read(&v7, 1, Some(&select("thetadot=4:4, theta=2:2"))).unwrap();
        assert_eq!(tr.theta, [vec![2.0], vec![4.0], vec![6.0]]);
        assert_eq!(tr.thetadot, Some(vec![vec![20.0], vec![40.0], vec![60.0]]));
        // Past the last column, or not one theta column per joint.
        for (joints, spec) in [(2, "theta=4:5"), (3, "theta=1:2")] {
            let e = read(&v7, joints, Some(&select(spec))).unwrap_err();
            assert!(
                matches!(&e, ReadError::Mat(MatError::Selected { cols: 4, .. })),
                "{spec}: {e}"
            );
        }
        // A CSV names its columns: a selection for one is refused, not ignored.
        let e = read(Path::new("x.csv"), 2, Some(&select("theta=1:2"))).unwrap_err();
        assert!(matches!(e, ReadError::ColumnsOfCsv { .. }), "{e}");
    }
}
