//! The run summary printed after a run or a score: one table per experiment (drift, position
//! errors, distance to the exact optimum, peak joint speed, steps, wall time), failed runs with
//! their reason.

use records::runs::RunRow;
use settings::network_kind::NetworkKind;
use std::fmt::Write as _;
use std::io::Write as _;

/// A value in the summary's scientific notation, `-` when absent.
fn fmt(v: Option<f64>) -> String {
    v.map(|v| format!("{v:.3e}")).unwrap_or_else(|| "-".into())
}

/// The summary of `rows` (in their order; a header whenever the experiment changes).
pub fn summary(rows: &[RunRow]) -> String {
    let mut out = String::new();
    let mut current = String::new();
    for r in rows {
        if r.experiment != current {
            current = r.experiment.to_string();
            let _ = writeln!(
                out,
                "\n== {current} ({} on {}, T = {} s)",
                r.robot, r.path, r.duration
            );
            let _ = writeln!(
                out,
                "{:<26} {:<28} {:>10} {:>10} {:>10} {:>10} {:>10} {:>7} {:>8}",
                "variant",
                "solver",
                "drift",
                "max err",
                "rms err",
                "|x-x*|max",
                "peak qd",
                "steps",
                "wall s"
            );
        }
        if !r.completed() {
            let _ = writeln!(
                out,
                "{:<26} {:<28} FAILED at t = {} (peak qd {}, max err {}): {}",
                r.variant,
                r.solver,
                fmt(r.failed_at),
                fmt(r.peak_thetadot),
                fmt(r.max_pos_err),
                r.failure
            );
            continue;
        }
        let _ = writeln!(
            out,
            "{:<26} {:<28} {:>10} {:>10} {:>10} {:>10} {:>10} {:>7} {:>8.2}",
            r.variant,
            r.solver,
            fmt(r.drift_norm),
            fmt(r.max_pos_err),
            fmt(r.rms_pos_err),
            fmt(r.score_max_dx),
            fmt(r.peak_thetadot),
            r.steps,
            r.wall_s
        );
    }
    if rows.iter().any(is_vp_rnn_pf) {
        out.push_str(
            "\n|x-x*|max: largest |x_nn - x*|_inf of the joint command against Clarabel along the run. For \
             VP-RNN-PF it measures the exponential-penalty approximation (its equilibrium is the penalised \
             optimum, not x*), not a solver fault.\n",
        );
    }
    out
}

/// Whether the run is of a VP-RNN-PF network (by its `solver_kind`).
fn is_vp_rnn_pf(r: &RunRow) -> bool {
    r.solver_kind.network() == Some(NetworkKind::VpRnnPf)
}

/// Writes to stdout, ending quietly when the reader has gone (e.g. `| head`).
pub fn emit(text: &str) {
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn rows() -> Vec<RunRow> {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/runs.csv");
        records::table::from_reader(std::fs::read(path).unwrap().as_slice()).unwrap()
    }

    #[test]
    fn one_header_per_experiment_and_one_line_per_run() {
        let rows = rows();
        let text = summary(&rows);
        let mut experiments: Vec<&str> = rows.iter().map(|r| r.experiment.as_str()).collect();
        experiments.dedup();
        assert_eq!(text.matches("\n== ").count(), experiments.len());
        let run_lines = text
            .lines()
            .filter(|l| {
                rows.iter()
                    .any(|r| l.starts_with(&format!("{:<26} {:<28} ", r.variant, r.solver)))
            })
            .count();
        assert_eq!(run_lines, rows.len());
        let failed = rows.iter().filter(|r| !r.completed()).count();
        assert_eq!(text.matches(" FAILED at t = ").count(), failed);
    }

    #[test]
    fn a_completed_run_shows_its_numbers_and_a_missing_one_a_dash() {
        let mut row = rows().into_iter().find(|r| r.completed()).unwrap();
        row.score_max_dx = None;
        row.drift_norm = Some(1.5e-3);
        let text = summary(std::slice::from_ref(&row));
        let line = text.lines().last().unwrap();
        assert!(line.contains(" 1.500e-3 "), "{line}");
        assert_eq!(
            line.split_whitespace().filter(|w| *w == "-").count(),
            1,
            "{line}"
        );
        assert_eq!(text.contains("VP-RNN-PF it measures"), is_vp_rnn_pf(&row));
    }
}
