//! Trajectories as MATLAB / Octave MAT-files (format v5, and v7, its compressed form), read with
//! the `matfile` crate. v7.3 files are HDF5 and are not read (save with `-v7`).
//!
//! The file holds two real double matrices: `t`, the m sample times (a row or a column), and
//! `y`, m x n or m x 2n with a row per instant: the joint angles theta_1 .. theta_n, then
//! optionally the velocities thetadot_1 .. thetadot_n (as MATLAB's `[t, y] = ode45(...)` returns
//! them for a state that starts with theta and thetadot); n is the task's joint count. Other
//! variables are ignored.

use crate::trajectory::Trajectory;
use std::path::{Path, PathBuf};

/// Why a MAT-file cannot be read as a trajectory.
#[derive(Debug, thiserror::Error)]
pub enum MatError {
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: not a MAT-file of format v5 or v7 ({reason}; a v7.3 file is HDF5: save with -v7)", path.display())]
    Parse { path: PathBuf, reason: String },
    #[error("{}: no variable \"{name}\" (a trajectory MAT-file holds t and y)", path.display())]
    Missing { path: PathBuf, name: &'static str },
    #[error("{}: variable \"{name}\" is not a real double matrix", path.display())]
    NotDouble { path: PathBuf, name: &'static str },
    #[error("{}: t has size {t:?}, it must be a vector", path.display())]
    TimeShape { path: PathBuf, t: Vec<usize> },
    #[error(
        "{}: y is {rows} x {cols}; for {samples} instants of a {joints}-joint task it must be {samples} x {joints} (theta) or {samples} x {} (theta, thetadot)",
        path.display(),
        2 * joints
    )]
    Shape {
        path: PathBuf,
        rows: usize,
        cols: usize,
        samples: usize,
        joints: usize,
    },
}

/// Reads the trajectory of a `joints`-joint task from the MAT-file `path` (module docs).
pub fn read_mat(path: &Path, joints: usize) -> Result<Trajectory, MatError> {
    let file = std::fs::File::open(path).map_err(|source| MatError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mat =
        matfile::MatFile::parse(std::io::BufReader::new(file)).map_err(|e| MatError::Parse {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
    let matrix = |name: &'static str| -> Result<(&[usize], &[f64]), MatError> {
        let array = mat.find_by_name(name).ok_or(MatError::Missing {
            path: path.to_path_buf(),
            name,
        })?;
        match array.data() {
            matfile::NumericData::Double { real, imag: None } => Ok((array.size(), real)),
            _ => Err(MatError::NotDouble {
                path: path.to_path_buf(),
                name,
            }),
        }
    };
    let (t_size, t) = matrix("t")?;
    if t_size.iter().filter(|&&d| d != 1).count() > 1 {
        return Err(MatError::TimeShape {
            path: path.to_path_buf(),
            t: t_size.to_vec(),
        });
    }
    let (y_size, y) = matrix("y")?;
    let (rows, cols) = match y_size {
        [rows, cols] => (*rows, *cols),
        _ => (0, 0),
    };
    if rows != t.len() || (cols != joints && cols != 2 * joints) || joints == 0 {
        return Err(MatError::Shape {
            path: path.to_path_buf(),
            rows,
            cols,
            samples: t.len(),
            joints,
        });
    }
    // Column-major: y(k, j) = y[k + j rows].
    let row = |k: usize, columns: std::ops::Range<usize>| -> Vec<f64> {
        columns.map(|j| y[k + j * rows]).collect()
    };
    Ok(Trajectory {
        t: t.to_vec(),
        theta: (0..rows).map(|k| row(k, 0..joints)).collect(),
        thetadot: (cols == 2 * joints)
            .then(|| (0..rows).map(|k| row(k, joints..2 * joints)).collect()),
    })
}
