//! Reading one run's trace CSV (`results/traces/<experiment>/<variant>__<solver>.csv`, written by
//! [`records::trace_csv`]) into columns the panels can plot.

use crate::error::{TraceError, TraceProblem};
use std::path::Path;

/// Most samples a figure plots per series; longer traces are thinned evenly (the last sample is
/// always kept, so the drift at t = T stays visible).
pub const MAX_SAMPLES: usize = 400;

/// One run's time history, column by column.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trace {
    /// Time (s).
    pub t: Vec<f64>,
    /// `theta[i][k]`: joint i's angle at sample k (rad).
    pub theta: Vec<Vec<f64>>,
    /// Joint velocities, as `theta` (rad/s).
    pub thetadot: Vec<Vec<f64>>,
    /// Joint accelerations (rad/s^2); acceleration-level runs only.
    pub thetaddot: Option<Vec<Vec<f64>>>,
    /// Joint torques (N m); acceleration-level runs only.
    pub tau: Option<Vec<Vec<f64>>>,
    /// Desired end-effector position, x and y (m).
    pub desired: [Vec<f64>; 2],
    /// Actual end-effector position f(theta), x and y (m).
    pub actual: [Vec<f64>; 2],
    /// Position error |r* - f(theta)| (m).
    pub pos_err: Vec<f64>,
    /// |x_nn - x*| against the exact optimum; `None` where not scored (exact runs).
    pub score_dx: Vec<Option<f64>>,
}

impl Trace {
    /// Reads a trace CSV. An empty file (a run that produced no sample) is an empty trace; any
    /// other malformation (missing column, short row, non-numeric field) is an error naming the file.
    pub fn read(path: &Path) -> Result<Trace, TraceError> {
        let fail = |problem: TraceProblem| TraceError {
            path: path.to_path_buf(),
            problem,
        };
        let bytes = store::read_owned_file(path).map_err(|e| fail(e.into()))?;
        if bytes.is_empty() {
            return Ok(Trace::default());
        }
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        let header = reader.headers().map_err(|e| fail(e.into()))?.clone();
        let column = |name: &str| header.iter().position(|h| h == name);
        let required =
            |name: &'static str| column(name).ok_or_else(|| fail(TraceProblem::NoColumn(name)));
        let joints = |prefix: &str| -> Vec<usize> {
            (1..)
                .map_while(|i| column(&format!("{prefix}_{i}")))
                .collect()
        };
        let theta = joints("theta");
        let thetadot = joints("thetadot");
        if theta.is_empty() || thetadot.len() != theta.len() {
            return Err(fail(TraceProblem::Joints {
                theta: theta.len(),
                thetadot: thetadot.len(),
            }));
        }
        let thetaddot = joints("thetaddot");
        let tau = joints("tau");
        let [t, rx_des, ry_des, rx, ry, pos_err, score_dx] =
            ["t", "rx_des", "ry_des", "rx", "ry", "pos_err", "score_dx"].map(required);
        let (t, rx_des, ry_des, rx, ry, pos_err, score_dx) =
            (t?, rx_des?, ry_des?, rx?, ry?, pos_err?, score_dx?);

        let mut trace = Trace {
            theta: vec![Vec::new(); theta.len()],
            thetadot: vec![Vec::new(); theta.len()],
            thetaddot: (!thetaddot.is_empty()).then(|| vec![Vec::new(); thetaddot.len()]),
            tau: (!tau.is_empty()).then(|| vec![Vec::new(); tau.len()]),
            ..Trace::default()
        };
        for (row, record) in reader.records().enumerate() {
            let record = record.map_err(|e| fail(e.into()))?;
            let field = |c: usize| -> Result<Option<f64>, TraceError> {
                let text = record.get(c).unwrap_or("").trim();
                if text.is_empty() {
                    return Ok(None);
                }
                text.parse().map(Some).map_err(|_| {
                    fail(TraceProblem::NotANumber {
                        row: row + 2,
                        column: header[c].to_string(),
                        text: text.to_string(),
                    })
                })
            };
            let number = |c: usize| {
                field(c)?.ok_or_else(|| {
                    fail(TraceProblem::Empty {
                        row: row + 2,
                        column: header[c].to_string(),
                    })
                })
            };
            let push_joints =
                |into: &mut Vec<Vec<f64>>, columns: &[usize]| -> Result<(), TraceError> {
                    for (series, &c) in into.iter_mut().zip(columns) {
                        series.push(number(c)?);
                    }
                    Ok(())
                };
            trace.t.push(number(t)?);
            push_joints(&mut trace.theta, &theta)?;
            push_joints(&mut trace.thetadot, &thetadot)?;
            if let Some(a) = trace.thetaddot.as_mut() {
                push_joints(a, &thetaddot)?;
            }
            if let Some(a) = trace.tau.as_mut() {
                push_joints(a, &tau)?;
            }
            trace.desired[0].push(number(rx_des)?);
            trace.desired[1].push(number(ry_des)?);
            trace.actual[0].push(number(rx)?);
            trace.actual[1].push(number(ry)?);
            trace.pos_err.push(number(pos_err)?);
            trace.score_dx.push(field(score_dx)?);
        }
        Ok(trace)
    }

    /// Number of joints.
    pub fn joints(&self) -> usize {
        self.theta.len()
    }

    /// Whether any sample carries a score against the exact optimum (a neural run).
    pub fn is_scored(&self) -> bool {
        self.score_dx.iter().any(Option::is_some)
    }

    /// Indices of at most `count` samples evenly spread over the rows, first and last included
    /// (just the first if `count` is 1).
    pub fn spread(&self, count: usize) -> Vec<usize> {
        let n = self.t.len();
        if n <= count {
            return (0..n).collect();
        }
        if count <= 1 {
            return (0..count).collect();
        }
        (0..count).map(|k| k * (n - 1) / (count - 1)).collect()
    }

    /// Indices of at most [`MAX_SAMPLES`] evenly spread samples, first and last included.
    pub fn thinned(&self) -> Vec<usize> {
        self.spread(MAX_SAMPLES)
    }

    /// The joint angles at sample `k` (rad).
    pub fn theta_at(&self, k: usize) -> Vec<f64> {
        self.theta.iter().map(|joint| joint[k]).collect()
    }

    /// `(t, |x - x*|)` at the thinned samples that were scored (none for an unscored run).
    pub fn score_over_time(&self) -> Vec<(f64, f64)> {
        self.thinned()
            .into_iter()
            .filter_map(|k| self.score_dx[k].map(|dx| (self.t[k], dx)))
            .collect()
    }

    /// `(t, value)` pairs of one column at the thinned samples.
    pub fn over_time(&self, values: &[f64]) -> Vec<(f64, f64)> {
        self.thinned()
            .into_iter()
            .map(|k| (self.t[k], values[k]))
            .collect()
    }
}
