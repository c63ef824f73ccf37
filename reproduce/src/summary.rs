//! The run summary printed after a run or a score: one table per experiment (drift, position
//! errors, distance to the exact optimum, peak joint speed, steps, wall time), failed runs with
//! their reason.

use records::RunRow;
use settings::NetworkKind;
use std::fmt::Write as _;
use std::io::Write as _;

/// A value in the summary's scientific notation, `-` when absent.
fn fmt(v: Option<f64>) -> String {
    v.map(|v| format!("{v:.3e}")).unwrap_or_else(|| "-".into())
}

/// The summary of `rows` (in their order; a header whenever the experiment changes).
pub fn summary(rows: &[RunRow]) -> String {
    let mut lines = Summary::default();
    let mut out = String::new();
    for r in rows {
        lines.push(r, &mut out);
    }
    lines.finish(&mut out);
    out
}

/// The summary written as the rows come, one at a time (a shard prints it as it folds its
/// journal, holding no row): [`Summary::push`] each row, then [`Summary::finish`].
#[derive(Default)]
pub struct Summary {
    /// The experiment of the last row.
    current: String,
    /// Whether a VP-RNN-PF run was among the rows (its note ends the summary).
    vp_rnn_pf: bool,
}

impl Summary {
    /// Appends the line of `r` to `out`, after a header if its experiment is not the last
    /// row's.
    pub fn push(&mut self, r: &RunRow, out: &mut String) {
        self.vp_rnn_pf |= is_vp_rnn_pf(r);
        if r.experiment != self.current {
            self.current = r.experiment.to_string();
            let _ = writeln!(
                out,
                "\n== {} ({} on {}, T = {} s)",
                self.current, r.robot, r.path, r.duration
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
            return;
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

    /// Appends what ends the summary to `out`: the note on VP-RNN-PF, if one ran.
    pub fn finish(self, out: &mut String) {
        if self.vp_rnn_pf {
            out.push_str(
                "\n|x-x*|max: largest |x_nn - x*|_inf of the joint command against Clarabel along the run. For \
                 VP-RNN-PF it measures the exponential-penalty approximation (its equilibrium is the penalised \
                 optimum, not x*), not a solver fault.\n",
            );
        }
    }
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
