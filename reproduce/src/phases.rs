//! The phase clock of `reproduce run`: the wall time of each phase ([`records::phases::Phase`]),
//! printed at the end of the run and written to `results/phases.csv` ([`records::phases`]).

use records::phases::{Measured, Phase, PhaseRow, PhaseStatus, RunContext};
use std::path::Path;
use std::time::Instant;

/// The phases measured so far, each from the end of the one before (the first from `started`).
#[derive(Debug)]
pub struct PhaseClock {
    last: Instant,
    phases: Vec<Measured>,
}

impl PhaseClock {
    /// A clock whose first phase began at `started`.
    pub fn since(started: Instant) -> Self {
        PhaseClock {
            last: started,
            phases: Vec::new(),
        }
    }

    /// Ends `phase` now: it took the time since the previous one ended, and went through
    /// `items` ([`Phase::items_are`]).
    pub fn lap(&mut self, phase: Phase, items: Option<usize>) {
        self.lap_noted(phase, items, String::new());
    }

    /// [`PhaseClock::lap`] with a note.
    pub fn lap_noted(&mut self, phase: Phase, items: Option<usize>, note: String) {
        let now = Instant::now();
        self.phases.push(Measured {
            phase,
            seconds: Some(now.duration_since(self.last).as_secs_f64()),
            items,
            note,
        });
        self.last = now;
    }

    /// Records that `phase` did not run, and `why`; the clock runs on into the next phase.
    pub fn skip(&mut self, phase: Phase, why: String) {
        self.phases.push(Measured {
            phase,
            seconds: None,
            items: None,
            note: why,
        });
    }

    /// The rows of `results/phases.csv`.
    pub fn rows(&self, context: &RunContext) -> Vec<PhaseRow> {
        records::phases::rows(&self.phases, context)
    }
}

/// The per-phase table printed at the end of a run (stderr), with the total, whether the run
/// was complete, and where it was written (`written`).
pub fn table(rows: &[PhaseRow], written: &Path) -> String {
    let total: f64 = rows.iter().filter_map(|r| r.seconds).sum();
    let scope = match rows.first() {
        Some(_) if records::phases::complete(rows) => "a whole reproduction".to_string(),
        Some(r) => format!("partial: {}", r.selection),
        None => String::new(),
    };
    let mut out = format!("phases of this run ({scope}), in {}:\n", written.display());
    for r in rows {
        let line = match r.status {
            PhaseStatus::Ran => format!(
                "  {:<8} {:>8.1} s {:>5.1} %{}",
                r.phase.id(),
                r.seconds.unwrap_or_default(),
                r.share_pct.unwrap_or_default(),
                r.items
                    .map(|n| format!("  {n} {}", r.phase.items_are()))
                    .unwrap_or_default()
            ),
            PhaseStatus::Skipped => format!("  {:<8} skipped: {}", r.phase.id(), r.note),
        };
        out.push_str(line.trim_end());
        if r.status == PhaseStatus::Ran && !r.note.is_empty() {
            out.push_str(&format!(" ({})", r.note));
        }
        out.push('\n');
    }
    out.push_str(&format!("  {:<8} {total:>8.1} s\n", "total"));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laps_follow_one_another_and_the_table_says_what_was_skipped() {
        let mut clock = PhaseClock::since(Instant::now());
        std::thread::sleep(std::time::Duration::from_millis(20));
        clock.lap(Phase::Setup, None);
        clock.skip(Phase::Explain, "--skip-explain".to_string());
        clock.lap_noted(Phase::Runs, Some(3), "1 resumed".to_string());
        let context = RunContext {
            selection: "--paper demo".to_string(),
            whole: false,
            machine: "cpu".to_string(),
            cores: 2,
            git_rev: "r".to_string(),
        };
        let rows = clock.rows(&context);
        assert!(rows[0].seconds.unwrap() >= 0.02, "{rows:?}");
        assert_eq!(rows[1].status, PhaseStatus::Skipped);
        let printed = table(&rows, Path::new("results/phases.csv"));
        assert!(
            printed.starts_with(
                "phases of this run (partial: --paper demo), in results/phases.csv:\n"
            ),
            "{printed}"
        );
        assert!(
            printed.contains("  explain  skipped: --skip-explain\n"),
            "{printed}"
        );
        assert!(
            printed.contains("3 selected runs (1 resumed)\n"),
            "{printed}"
        );
        assert!(printed.contains("  total "), "{printed}");
    }
}
