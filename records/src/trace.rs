//! A run's trace: its thinned time history for the figures, written to
//! `results/traces/<experiment>/<variant id>__<solver id>.csv` ([`trace_csv`]). One
//! [`TracePoint`] per kept accepted step (the engine, `simulation::simulate`, thins them
//! uniformly in t and keeps the last); one row of the CSV per point, with the columns
//!
//! ```text
//! t, theta_1 .. theta_n, thetadot_1 .. thetadot_n, [thetaddot_1 .. thetaddot_n, tau_1 .. tau_n,]
//! rx_des, ry_des, rz_des, rx, ry, rz, pos_err, score_dx, net_error
//! ```
//!
//! t in s, joint angles in rad, velocities in rad/s, accelerations in rad/s^2 and torques in
//! N m (acceleration-level runs only), the desired and actual end-effector positions in m,
//! pos_err = |r_des - r| in m, score_dx = |x_nn - x*|_inf (neural runs; empty otherwise) and
//! the network's own error norm net_error (where it has one; empty otherwise).

/// One row of a run's trace (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TracePoint {
    /// Time (s).
    pub t: f64,
    /// Joint angles (rad).
    pub theta: Vec<f64>,
    /// Joint velocities (rad/s).
    pub thetadot: Vec<f64>,
    /// Joint accelerations (rad/s^2; acceleration-level runs).
    pub thetaddot: Option<Vec<f64>>,
    /// Joint torques (N m; acceleration-level runs with the arm's dynamics).
    pub torque: Option<Vec<f64>>,
    /// The path's end-effector position r*(t) (m).
    pub desired: [f64; 3],
    /// The arm's end-effector position f(theta) (m).
    pub actual: [f64; 3],
    /// |x_nn - x*|_inf at this instant (neural runs).
    pub score_dx: Option<f64>,
    /// The network's own error norm at this instant (where it has one).
    pub network_error: Option<f64>,
}

/// A run's trace as CSV (module docs); no points, an empty file.
pub fn trace_csv(trace: &[TracePoint]) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let Some(first) = trace.first() else {
        return w.into_inner().map_err(|e| csv::Error::from(e.into_error()));
    };
    let n = first.theta.len();
    let mut header = vec!["t".to_string()];
    header.extend((1..=n).map(|i| format!("theta_{i}")));
    header.extend((1..=n).map(|i| format!("thetadot_{i}")));
    if first.thetaddot.is_some() {
        header.extend((1..=n).map(|i| format!("thetaddot_{i}")));
    }
    if first.torque.is_some() {
        header.extend((1..=n).map(|i| format!("tau_{i}")));
    }
    header.extend(
        [
            "rx_des",
            "ry_des",
            "rz_des",
            "rx",
            "ry",
            "rz",
            "pos_err",
            "score_dx",
            "net_error",
        ]
        .map(String::from),
    );
    w.write_record(&header)?;
    for p in trace {
        let mut rec: Vec<String> = vec![p.t.to_string()];
        rec.extend(p.theta.iter().chain(&p.thetadot).map(f64::to_string));
        if let Some(a) = &p.thetaddot {
            rec.extend(a.iter().map(f64::to_string));
        }
        if let Some(a) = &p.torque {
            rec.extend(a.iter().map(f64::to_string));
        }
        rec.extend(p.desired.iter().chain(&p.actual).map(f64::to_string));
        let err = ((p.desired[0] - p.actual[0]).powi(2)
            + (p.desired[1] - p.actual[1]).powi(2)
            + (p.desired[2] - p.actual[2]).powi(2))
        .sqrt();
        rec.push(err.to_string());
        rec.push(p.score_dx.map(|v| v.to_string()).unwrap_or_default());
        rec.push(p.network_error.map(|v| v.to_string()).unwrap_or_default());
        w.write_record(&rec)?;
    }
    w.into_inner().map_err(|e| csv::Error::from(e.into_error()))
}
