//! Trajectories as MATLAB / Octave MAT-files (format v5, and v7, its compressed form), read with
//! the `matfile` crate. v7.3 files are HDF5 and are not read (save with `-v7`).
//!
//! The file holds two real double matrices: `t`, the m sample times (a row or a column), and
//! `y`, m x n or m x 2n with a row per instant: the joint angles theta_1 .. theta_n, then
//! optionally the velocities thetadot_1 .. thetadot_n (as MATLAB's `[t, y] = ode45(...)` returns
//! them for a state that starts with theta and thetadot); n is the task's joint count. Other
//! variables are ignored. A `y` that carries more (the group's own `ode15s` state holds the
//! network's state after theta and thetadot) is read through a [`Columns`] selection:
//! `theta=1:6,thetadot=7:12` takes those columns (1-based, inclusive, as MATLAB counts them)
//! and ignores the rest.
//!
//! The file is read by the input reader ([`crate::read()`]: a regular file, at most
//! [`crate::Kind::TrajectoryMat`]'s cap). A v7 file's compressed variables are inflated here,
//! before `matfile` sees the file, and never past [`MAX_INFLATED_BYTES`] in all: a small file
//! that inflates to gigabytes is refused after at most that many bytes, not parsed.

use super::Trajectory;
use crate::shown;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The most bytes the compressed variables of one MAT-file may inflate to, together (256 MiB:
/// 10^7 samples of a 3-joint trajectory with velocities).
pub const MAX_INFLATED_BYTES: u64 = 256 << 20;

/// The MAT-file data types of a top-level element: a matrix, or a compressed element that holds
/// one.
const MI_MATRIX: u32 = 14;
const MI_COMPRESSED: u32 = 15;

/// Why a MAT-file cannot be read as a trajectory.
#[derive(Debug, thiserror::Error)]
pub enum MatError {
    /// The file was refused or could not be read by the input reader.
    #[error(transparent)]
    Input(#[from] crate::InputError),
    /// The compressed variables inflate past [`MAX_INFLATED_BYTES`].
    #[error("{}: its compressed variables inflate to more than {max} bytes; it is not read", path.display())]
    Inflated {
        /// The MAT-file.
        path: PathBuf,
        /// The limit (bytes), [`MAX_INFLATED_BYTES`].
        max: u64,
    },
    /// The file is not a MAT-file of format v5 or v7.
    #[error("{}: not a MAT-file of format v5 or v7 ({reason}; a v7.3 file is HDF5: save with -v7)", path.display())]
    Parse {
        /// The MAT-file.
        path: PathBuf,
        /// What the parser found wrong.
        reason: String,
    },
    /// A variable the trajectory needs is absent, or of a class `matfile` skips (char, cell,
    /// struct).
    #[error(
        "{}: no numeric variable \"{name}\" (a trajectory MAT-file holds t and y as real double matrices; a char, cell or struct variable is skipped)",
        path.display()
    )]
    Missing {
        /// The MAT-file.
        path: PathBuf,
        /// The variable: `t` or `y`.
        name: &'static str,
    },
    /// A variable is not a real double matrix.
    #[error("{}: variable \"{name}\" is not a real double matrix", path.display())]
    NotDouble {
        /// The MAT-file.
        path: PathBuf,
        /// The variable: `t` or `y`.
        name: &'static str,
    },
    /// `y` is not a matrix: more than two dimensions besides trailing singleton ones.
    #[error("{}: y has {dims} dimensions; it must be a matrix with one row per instant of t", path.display())]
    NotMatrix {
        /// The MAT-file.
        path: PathBuf,
        /// The number of dimensions of `y`.
        dims: usize,
    },
    /// `t` is not a vector.
    #[error("{}: t has size {t:?}, it must be a vector", path.display())]
    TimeShape {
        /// The MAT-file.
        path: PathBuf,
        /// The size of `t`.
        t: Vec<usize>,
    },
    /// `y` is neither m x n nor m x 2n for m samples of an n-joint task (no selection given).
    #[error(
        "{}: y is {rows} x {cols}; for {samples} instants of a {joints}-joint task it must be {samples} x {joints} (theta) or {samples} x {} (theta, thetadot), or name its columns (`--columns theta=1:{joints},thetadot=...`)",
        path.display(),
        2 * joints
    )]
    Shape {
        /// The MAT-file.
        path: PathBuf,
        /// Rows of `y`.
        rows: usize,
        /// Columns of `y`.
        cols: usize,
        /// Samples m: the length of `t`.
        samples: usize,
        /// The task's joint count n.
        joints: usize,
    },
    /// `y` does not fit the column selection: not one row per sample, too few columns, or a
    /// theta range not one column per joint.
    #[error(
        "{}: y is {rows} x {cols}; the selection {columns} needs {samples} rows (one per instant of t), at least {} columns and {joints} theta columns (the task's joints)",
        path.display(),
        columns.last_column()
    )]
    Selected {
        /// The MAT-file.
        path: PathBuf,
        /// Rows of `y`.
        rows: usize,
        /// Columns of `y`.
        cols: usize,
        /// Samples m: the length of `t`.
        samples: usize,
        /// The task's joint count n.
        joints: usize,
        /// The selection given.
        columns: Columns,
    },
}

/// Which columns of `y` hold theta and, optionally, thetadot (module docs): 1-based, inclusive
/// ranges, each as long as the task has joints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Columns {
    /// theta_1 .. theta_n: columns `theta.0 ..= theta.1`.
    pub theta: (usize, usize),
    /// thetadot_1 .. thetadot_n, when the file has them.
    pub thetadot: Option<(usize, usize)>,
}

/// Why a column selection cannot be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ColumnsError {
    /// The text is not `name=A:B` entries joined by commas, A and B numbers.
    #[error(
        "{}: a column selection is `theta=A:B` or `theta=A:B,thetadot=C:D` (1-based, inclusive)",
        shown(given)
    )]
    Syntax {
        /// The selection as given.
        given: String,
    },
    /// A quantity is given twice.
    #[error("{}: {} is given twice", shown(given), shown(name))]
    Twice {
        /// The selection as given.
        given: String,
        /// The quantity.
        name: String,
    },
    /// A name is neither `theta` nor `thetadot`.
    #[error(
        "{}: {} is not a quantity of a trajectory (theta, thetadot)",
        shown(given),
        shown(name)
    )]
    Unknown {
        /// The selection as given.
        given: String,
        /// The name.
        name: String,
    },
    /// The selection has no `theta` range.
    #[error("{}: no theta range", shown(given))]
    NoTheta {
        /// The selection as given.
        given: String,
    },
    /// A range is not 1 <= A <= B.
    #[error("{}: the range {from}:{to} must satisfy 1 <= A <= B", shown(given))]
    Range {
        /// The selection as given.
        given: String,
        /// Its first column A.
        from: usize,
        /// Its last column B.
        to: usize,
    },
    /// The theta and thetadot ranges have different lengths.
    #[error("theta takes {theta} columns and thetadot {thetadot}: both take one per joint")]
    Unequal {
        /// Columns of the theta range.
        theta: usize,
        /// Columns of the thetadot range.
        thetadot: usize,
    },
}

impl Columns {
    /// The highest column the selection reads (1-based).
    pub fn last_column(&self) -> usize {
        self.theta.1.max(self.thetadot.map_or(0, |d| d.1))
    }

    /// The joints the selection reads (the length of its theta range).
    pub fn joints(&self) -> usize {
        self.theta.1 - self.theta.0 + 1
    }
}

impl std::fmt::Display for Columns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "theta={}:{}", self.theta.0, self.theta.1)?;
        if let Some((a, b)) = self.thetadot {
            write!(f, ",thetadot={a}:{b}")?;
        }
        Ok(())
    }
}

impl std::str::FromStr for Columns {
    type Err = ColumnsError;

    fn from_str(given: &str) -> Result<Self, ColumnsError> {
        let syntax = || ColumnsError::Syntax {
            given: given.to_string(),
        };
        let mut theta = None;
        let mut thetadot = None;
        for part in given.split(',') {
            let (name, range) = part.trim().split_once('=').ok_or_else(syntax)?;
            let (a, b) = range.split_once(':').ok_or_else(syntax)?;
            let number = |s: &str| s.trim().parse::<usize>().map_err(|_| syntax());
            let (from, to) = (number(a)?, number(b)?);
            if from == 0 || to < from {
                return Err(ColumnsError::Range {
                    given: given.to_string(),
                    from,
                    to,
                });
            }
            let slot = match name.trim() {
                "theta" => &mut theta,
                "thetadot" => &mut thetadot,
                other => {
                    return Err(ColumnsError::Unknown {
                        given: given.to_string(),
                        name: other.to_string(),
                    })
                }
            };
            if slot.replace((from, to)).is_some() {
                return Err(ColumnsError::Twice {
                    given: given.to_string(),
                    name: name.trim().to_string(),
                });
            }
        }
        let theta = theta.ok_or_else(|| ColumnsError::NoTheta {
            given: given.to_string(),
        })?;
        let columns = Columns { theta, thetadot };
        if let Some((a, b)) = thetadot {
            if b - a + 1 != columns.joints() {
                return Err(ColumnsError::Unequal {
                    theta: columns.joints(),
                    thetadot: b - a + 1,
                });
            }
        }
        Ok(columns)
    }
}

/// Reads the trajectory of a `joints`-joint task from the MAT-file `path` (module docs), its
/// columns those of `columns` when given, else the whole of `y` (n or 2n columns).
pub fn read_mat(
    path: &Path,
    joints: usize,
    columns: Option<&Columns>,
) -> Result<Trajectory, MatError> {
    let bytes = crate::read(path, crate::Kind::TrajectoryMat, crate::Origin::Named)?;
    let bytes = inflate(bytes, path, MAX_INFLATED_BYTES)?;
    let mat = matfile::MatFile::parse(bytes.as_slice()).map_err(|e| MatError::Parse {
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
    // Trailing singleton dimensions (21 x 5 x 1) are a matrix's, as MATLAB reads them.
    let mut y_size = y_size;
    while let [head @ .., 1] = y_size {
        if head.len() < 2 {
            break;
        }
        y_size = head;
    }
    let (rows, cols) = match y_size {
        [rows, cols] => (*rows, *cols),
        _ => {
            return Err(MatError::NotMatrix {
                path: path.to_path_buf(),
                dims: y_size.len(),
            })
        }
    };
    let whole = Columns {
        theta: (1, joints),
        thetadot: (cols == 2 * joints).then_some((joints + 1, 2 * joints)),
    };
    let selection = match columns {
        Some(c) if rows != t.len() || c.last_column() > cols || c.joints() != joints => {
            return Err(MatError::Selected {
                path: path.to_path_buf(),
                rows,
                cols,
                samples: t.len(),
                joints,
                columns: c.clone(),
            })
        }
        Some(c) => c,
        None if rows != t.len() || (cols != joints && cols != 2 * joints) || joints == 0 => {
            return Err(MatError::Shape {
                path: path.to_path_buf(),
                rows,
                cols,
                samples: t.len(),
                joints,
            })
        }
        None => &whole,
    };
    // Column-major: y(k, j) = y[k + j rows] (j 0-based; the selection's ranges are 1-based).
    let row = |k: usize, (from, to): (usize, usize)| -> Vec<f64> {
        (from - 1..to).map(|j| y[k + j * rows]).collect()
    };
    Ok(Trajectory {
        t: t.to_vec(),
        theta: (0..rows).map(|k| row(k, selection.theta)).collect(),
        thetadot: selection
            .thetadot
            .map(|d| (0..rows).map(|k| row(k, d)).collect()),
    })
}

/// The MAT-file `bytes` with every top-level compressed element replaced by the element it
/// inflates to (a v6 file, which `matfile` parses without inflating anything), at most
/// `max` bytes ([`MAX_INFLATED_BYTES`]) inflated in all. A compressed element must hold a matrix (MATLAB
/// never nests them; a nested one would inflate unbounded inside `matfile`), and every
/// top-level element must be a matrix or a compressed one (what MATLAB and Octave write;
/// `matfile` prints a line to standard output for any other and skips it). An element that
/// claims more bytes than the file has left is a truncated file, refused here (`matfile` would
/// drop it and report its variable missing); bytes that do not read as elements are left as
/// they are, for `matfile` to refuse.
fn inflate(bytes: Vec<u8>, path: &Path, max: u64) -> Result<Vec<u8>, MatError> {
    let little = match bytes.get(126..128) {
        Some(b"IM") => true,
        Some(b"MI") => false,
        _ => return Ok(bytes),
    };
    let word = |at: usize| u32_at(&bytes, at, little);
    let parse_error = |reason: &str| MatError::Parse {
        path: path.to_path_buf(),
        reason: reason.to_string(),
    };
    let mut out = bytes[..128].to_vec();
    let mut at = 128;
    let mut budget = max;
    while let (Some(kind), Some(size)) = (word(at), word(at + 4)) {
        let end = (at + 8).saturating_add(size as usize);
        if end > bytes.len() {
            // A variable that claims more bytes than the file has left: a truncated file.
            return Err(parse_error(if kind == MI_COMPRESSED {
                "a compressed variable is cut off"
            } else {
                "a variable is cut off: the file is truncated"
            }));
        }
        if kind != MI_COMPRESSED && kind != MI_MATRIX {
            // Not a variable: `matfile` would print a line of its own to standard output and
            // skip it.
            return Err(parse_error(
                "a top-level element is neither a matrix nor compressed",
            ));
        }
        if kind != MI_COMPRESSED {
            // An uncompressed element with its padding to 8 bytes: as is.
            let next = end.next_multiple_of(8).min(bytes.len());
            out.extend_from_slice(&bytes[at..next]);
            at = next;
            continue;
        }
        let mut inflated = Vec::new();
        libflate::zlib::Decoder::new(&bytes[at + 8..end])
            .map_err(|_| parse_error("a compressed variable is not a zlib stream"))?
            .take(budget + 1)
            .read_to_end(&mut inflated)
            .map_err(|_| parse_error("a compressed variable does not inflate"))?;
        if inflated.len() as u64 > budget {
            return Err(MatError::Inflated {
                path: path.to_path_buf(),
                max,
            });
        }
        budget -= inflated.len() as u64;
        if u32_at(&inflated, 0, little) != Some(MI_MATRIX) {
            return Err(parse_error("a compressed variable does not hold a matrix"));
        }
        out.extend_from_slice(&inflated);
        out.resize(out.len().next_multiple_of(8), 0);
        at = end;
    }
    out.extend_from_slice(&bytes[at.min(bytes.len())..]);
    Ok(out)
}

/// The 32-bit word of `bytes` at `at`, in the file's byte order.
fn u32_at(bytes: &[u8], at: usize, little: bool) -> Option<u32> {
    let b: [u8; 4] = bytes.get(at..at.checked_add(4)?)?.try_into().ok()?;
    Some(if little {
        u32::from_le_bytes(b)
    } else {
        u32::from_be_bytes(b)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A v7 header (little-endian) and one compressed element of `inflated` bytes.
    fn v7(inflated: &[u8]) -> Vec<u8> {
        let mut file = vec![b' '; 128];
        file[124..126].copy_from_slice(&0x0100u16.to_le_bytes());
        file[126..128].copy_from_slice(b"IM");
        let mut z = libflate::zlib::Encoder::new(Vec::new()).unwrap();
        std::io::Write::write_all(&mut z, inflated).unwrap();
        let z = z.finish().into_result().unwrap();
        file.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        file.extend_from_slice(&(z.len() as u32).to_le_bytes());
        file.extend_from_slice(&z);
        file
    }

    #[test]
    fn a_bomb_is_refused_after_the_bound_and_a_nested_element_at_once() {
        let path = Path::new("bomb.mat");
        // A matrix tag claiming the rest, then zeros past a bound of 1 MiB: 4 kB compressed.
        let max = 1 << 20;
        let mut inflated = Vec::new();
        inflated.extend_from_slice(&MI_MATRIX.to_le_bytes());
        inflated.extend_from_slice(&u32::MAX.to_le_bytes());
        inflated.resize(2 * max as usize, 0);
        let file = v7(&inflated);
        assert!(file.len() < 16 << 10, "{}", file.len());
        let e = inflate(file.clone(), path, max).unwrap_err();
        assert!(
            matches!(e, MatError::Inflated { max: m, .. } if m == max),
            "{e}"
        );
        // Within the bound, the element is inflated in place (a v6 file).
        let v6 = inflate(file, path, 4 * max).unwrap();
        assert_eq!(v6.len(), 128 + inflated.len());
        assert_eq!(&v6[128..], &inflated[..]);
        let mut nested = Vec::new();
        nested.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        nested.extend_from_slice(&8u32.to_le_bytes());
        nested.extend_from_slice(&[0; 8]);
        let e = inflate(v7(&nested), path, max).unwrap_err();
        assert!(e.to_string().contains("does not hold a matrix"), "{e}");
        let mut cut = v7(&inflated);
        cut.truncate(cut.len() - 1);
        let e = inflate(cut, path, max).unwrap_err();
        assert!(e.to_string().contains("cut off"), "{e}");
        // A top-level element that is not a variable (miINT8, 8 bytes).
        let mut odd = v7(&inflated)[..128].to_vec();
        odd.extend_from_slice(&1u32.to_le_bytes());
        odd.extend_from_slice(&8u32.to_le_bytes());
        odd.extend_from_slice(&[0; 8]);
        let e = inflate(odd, path, max).unwrap_err();
        assert!(
            e.to_string().contains("neither a matrix nor compressed"),
            "{e}"
        );
        // Not a MAT-file: left for matfile to refuse.
        assert_eq!(
            inflate(b"t,theta_1".to_vec(), path, max).unwrap(),
            b"t,theta_1"
        );
    }

    #[test]
    fn column_selections_are_parsed_strictly() {
        use super::ColumnsError as E;
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
