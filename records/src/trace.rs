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
    let mut out = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    // The rows hold numbers (Display's text, as `to_string` writes them, by `decimal::push`)
    // and empty cells only, which CSV never quotes: they are written directly after the header.
    for p in trace {
        decimal::push(&mut out, p.t);
        let joints = [
            Some(&p.theta),
            Some(&p.thetadot),
            p.thetaddot.as_ref(),
            p.torque.as_ref(),
        ];
        let mut fields = 1 + 6 + 3;
        for values in joints.into_iter().flatten() {
            fields += values.len();
            for &v in values {
                out.push(b',');
                decimal::push(&mut out, v);
            }
        }
        if fields != header.len() {
            // As the CSV writer refuses a record whose length differs from the header's.
            return Err(csv::Error::from(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "trace point at t = {}: {fields} fields, the header has {}",
                    p.t,
                    header.len()
                ),
            )));
        }
        let err = ((p.desired[0] - p.actual[0]).powi(2)
            + (p.desired[1] - p.actual[1]).powi(2)
            + (p.desired[2] - p.actual[2]).powi(2))
        .sqrt();
        for &v in p.desired.iter().chain(&p.actual).chain([&err]) {
            out.push(b',');
            decimal::push(&mut out, v);
        }
        for v in [p.score_dx, p.network_error] {
            out.push(b',');
            if let Some(v) = v {
                decimal::push(&mut out, v);
            }
        }
        out.push(b'\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The columns of both levels, numbers as Rust's Display writes them (no exponent, -0 for
    /// a negative zero), empty cells for an absent score and network error.
    #[test]
    fn a_trace_is_written_column_by_column() {
        let velocity = TracePoint {
            t: 0.5,
            theta: vec![1.0, -0.25],
            thetadot: vec![0.0, -0.0],
            thetaddot: None,
            torque: None,
            desired: [1.0, 0.0, 0.0],
            actual: [0.0; 3],
            score_dx: None,
            network_error: Some(1e-7),
        };
        let csv = String::from_utf8(trace_csv(std::slice::from_ref(&velocity)).unwrap()).unwrap();
        assert_eq!(
            csv,
            "t,theta_1,theta_2,thetadot_1,thetadot_2,rx_des,ry_des,rz_des,rx,ry,rz,pos_err,\
             score_dx,net_error\n0.5,1,-0.25,0,-0,1,0,0,0,0,0,1,,0.0000001\n"
        );
        let acceleration = TracePoint {
            theta: vec![2.0],
            thetadot: vec![3.0],
            thetaddot: Some(vec![4.0]),
            torque: Some(vec![5.5]),
            desired: [0.0, 3.0, 0.0],
            actual: [0.0, 0.0, 4.0],
            score_dx: Some(2.5e-3),
            network_error: None,
            ..velocity
        };
        let csv = String::from_utf8(trace_csv(&[acceleration.clone(), acceleration]).unwrap());
        let row = "0.5,2,3,4,5.5,0,3,0,0,0,4,5,0.0025,\n";
        assert_eq!(
            csv.unwrap(),
            format!(
                "t,theta_1,thetadot_1,thetaddot_1,tau_1,rx_des,ry_des,rz_des,rx,ry,rz,pos_err,\
                 score_dx,net_error\n{row}{row}"
            )
        );
        assert!(trace_csv(&[]).unwrap().is_empty());
        // A point with another shape than the first is refused, not written ragged.
        let mut ragged = vec![velocity.clone(), velocity];
        ragged[1].thetaddot = Some(vec![0.0, 0.0]);
        let e = trace_csv(&ragged).unwrap_err().to_string();
        assert!(e.contains("t = 0.5: 16 fields, the header has 14"), "{e}");
    }
}
