//! The phase clock of `reproduce run`: the wall time of each phase ([`Phase`]), printed at the
//! end of the run (stderr) and, with `--phases FILE`, written to FILE as CSV ([`PhaseRow`]).
//! The phases are the suite's measurement of itself, not a result of the papers: they never go
//! into `results/` (benches/REPORT.md reads `benches/results/phases.csv`, written so).
//!
//! One [`PhaseRow`] per [`Phase`], in the order the phases run: `setup` (the experiment files,
//! the checks before anything runs, the results directory opened and the journal resumed),
//! `runs` (the selected runs, their summary and `runs.csv` with the traces), `explain` (the
//! explanation layer), `control` (the control experiments), `timing` (the timing pass,
//! module `timing`), `figures` and `report` (the report's pages, its task cards and the
//! leaderboard table). The phases follow one another without gaps: each one's time runs from
//! the end of the one before, so the shares (`share_pct`, of the sum) add up to 100.
//!
//! A phase that did not run is a row with `status` `skipped`, no time and the reason in
//! `note` (`--skip-explain`; a run of a selection gets no control experiments and no timing
//! pass). `selection` is the run's selection flags and `whole` whether it was every run; the
//! file is rewritten whole by each run, so it never mixes the phases of two runs.
//!
//! `items` counts what the phase went through ([`Phase::items_are`]). `seconds` and
//! `share_pct` are the only columns that change between two runs of the same code on the same
//! machine.

use records::table::Row;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;
use store::{IoAction, IoError, RunsError};

/// The file name the benches keep it under (`benches/results/phases.csv`).
pub const FILE: &str = "phases.csv";

/// A phase of `reproduce run`, in the order they run (the module docs say what each covers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// The experiment files read, the checks before anything runs, the results directory
    /// opened, the journal resumed.
    Setup,
    /// The selected runs in parallel, their summary, `runs.csv` and the traces written.
    Runs,
    /// The explanation layer: tolerance ladders and drift attribution.
    Explain,
    /// The control experiments (a whole reproduction only).
    Control,
    /// The timing pass: the compared runs again, one at a time (a whole reproduction only).
    Timing,
    /// The report's figures.
    Figures,
    /// The report's pages, its task cards and `results/leaderboard.csv`.
    Report,
}

impl Phase {
    /// Every phase, in the order they run.
    pub const ALL: [Phase; 7] = [
        Phase::Setup,
        Phase::Runs,
        Phase::Explain,
        Phase::Control,
        Phase::Timing,
        Phase::Figures,
        Phase::Report,
    ];

    /// The id in the phases file.
    pub fn id(self) -> &'static str {
        match self {
            Phase::Setup => "setup",
            Phase::Runs => "runs",
            Phase::Explain => "explain",
            Phase::Control => "control",
            Phase::Timing => "timing",
            Phase::Figures => "figures",
            Phase::Report => "report",
        }
    }

    /// What the phase's `items` count (empty: it has no count).
    pub fn items_are(self) -> &'static str {
        match self {
            Phase::Setup | Phase::Report => "",
            Phase::Runs => "selected runs",
            Phase::Explain => "runs explained",
            Phase::Control => "control and many-cycles runs",
            Phase::Timing => "runs timed alone",
            Phase::Figures => "figures",
        }
    }
}

/// Whether a phase ran.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PhaseStatus {
    /// Ran; `seconds` holds its wall time.
    Ran,
    /// Not run; the row's `note` says why.
    Skipped,
}

/// One row of the phases file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhaseRow {
    /// The phase.
    pub phase: Phase,
    /// Whether it ran (`ran`) or was skipped (`skipped`).
    pub status: PhaseStatus,
    /// Wall time (s, to the millisecond); empty when skipped.
    pub seconds: Option<f64>,
    /// `seconds` over the sum of the file's seconds, in per cent (to 0.1); empty when skipped.
    pub share_pct: Option<f64>,
    /// How many of [`Phase::items_are`] the phase went through; empty where it counts nothing.
    pub items: Option<usize>,
    /// Why a phase was skipped, or what else to know about it (runs resumed from the journal).
    pub note: String,
    /// The run's selection flags (`store::shard::Selection` as text).
    pub selection: String,
    /// Whether the selection was every run (a whole reproduction).
    pub whole: bool,
    /// CPU model and logical cores (`reproduce::cost::machine`).
    pub machine: String,
    /// Logical cores available.
    pub cores: usize,
    /// The code revision of the run (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
}

impl Row for PhaseRow {}

/// A phase as measured, before the shares are known.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The phase.
    pub phase: Phase,
    /// Wall time (s); `None`: skipped.
    pub seconds: Option<f64>,
    /// How many of [`Phase::items_are`] it went through; `None` where it counts nothing.
    pub items: Option<usize>,
    /// Why it was skipped, or what else to know about it.
    pub note: String,
}

/// What every row of one run shares.
#[derive(Clone, Debug, PartialEq)]
pub struct RunContext {
    /// The run's selection flags, as text.
    pub selection: String,
    /// Whether the selection was every run.
    pub whole: bool,
    /// CPU model.
    pub machine: String,
    /// Logical cores available.
    pub cores: usize,
    /// The code revision of the run.
    pub git_rev: String,
}

/// The rows of one run: its `phases` in the order given, seconds to the millisecond, each
/// share of the sum (to 0.1 %).
pub fn rows(phases: &[Measured], context: &RunContext) -> Vec<PhaseRow> {
    let total: f64 = phases.iter().filter_map(|p| p.seconds).sum();
    let round = |v: f64, digits: i32| {
        let f = 10f64.powi(digits);
        (v * f).round() / f
    };
    phases
        .iter()
        .map(|p| PhaseRow {
            phase: p.phase,
            status: if p.seconds.is_some() {
                PhaseStatus::Ran
            } else {
                PhaseStatus::Skipped
            },
            seconds: p.seconds.map(|s| round(s, 3)),
            share_pct: p
                .seconds
                .map(|s| round(if total > 0.0 { 100.0 * s / total } else { 0.0 }, 1)),
            items: p.items,
            note: p.note.clone(),
            selection: context.selection.clone(),
            whole: context.whole,
            machine: context.machine.clone(),
            cores: context.cores,
            git_rev: context.git_rev.clone(),
        })
        .collect()
}

/// Whether `rows` are of a complete reproduction: every run selected and every phase run.
pub fn complete(rows: &[PhaseRow]) -> bool {
    rows.iter().all(|r| r.whole && r.status == PhaseStatus::Ran)
}

/// Writes the phase table to `path` (atomically, replacing it).
pub fn write(path: &Path, rows: &[PhaseRow]) -> Result<(), RunsError> {
    let bytes = records::table::to_csv(rows).map_err(|source| RunsError::Write {
        path: path.to_path_buf(),
        source,
    })?;
    store::write_atomic(path, &bytes).map_err(IoError::at(path, IoAction::Write))?;
    Ok(())
}

/// Reads the phase table at `path`; an absent file is no rows.
pub fn read(path: &Path) -> Result<Vec<PhaseRow>, RunsError> {
    store::table::read_if_present(path).map_err(|error| RunsError::Table {
        path: path.to_path_buf(),
        error,
    })
}

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

    /// The rows of the phase table.
    pub fn rows(&self, context: &RunContext) -> Vec<PhaseRow> {
        rows(&self.phases, context)
    }
}

/// The per-phase table printed at the end of a run (stderr), with the total and whether the
/// run was complete.
pub fn table(rows: &[PhaseRow]) -> String {
    let total: f64 = rows.iter().filter_map(|r| r.seconds).sum();
    let scope = match rows.first() {
        Some(_) if complete(rows) => "a whole reproduction".to_string(),
        Some(r) => format!("partial: {}", r.selection),
        None => String::new(),
    };
    let mut out = format!("phases of this run ({scope}):\n");
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

    fn context(whole: bool) -> RunContext {
        RunContext {
            selection: "every run (no selection flags)".to_string(),
            whole,
            machine: "cpu".to_string(),
            cores: 2,
            git_rev: "r".to_string(),
        }
    }

    fn measured(phase: Phase, seconds: Option<f64>) -> Measured {
        Measured {
            phase,
            seconds,
            items: None,
            note: String::new(),
        }
    }

    #[test]
    fn shares_of_the_sum_and_skipped_phases_without_time() {
        let phases = [
            measured(Phase::Runs, Some(3.00049)),
            measured(Phase::Explain, None),
            measured(Phase::Report, Some(1.0)),
        ];
        let rows = rows(&phases, &context(true));
        assert_eq!(rows[0].seconds, Some(3.0));
        assert_eq!(rows[0].share_pct, Some(75.0));
        assert_eq!(rows[2].share_pct, Some(25.0));
        assert_eq!(rows[1].status, PhaseStatus::Skipped);
        assert_eq!((rows[1].seconds, rows[1].share_pct), (None, None));
        assert!(!complete(&rows), "a skipped phase is not a complete run");
        let ran = rows
            .iter()
            .filter(|r| r.status == PhaseStatus::Ran)
            .cloned()
            .collect::<Vec<_>>();
        assert!(complete(&ran));
        let partial = super::rows(&phases[..1], &context(false));
        assert!(!complete(&partial), "a selection is not a complete run");
    }

    #[test]
    fn written_and_read_back_with_ids() {
        let dir = inputs::Scratch::dir("phases");
        let phases: Vec<Measured> = Phase::ALL
            .iter()
            .map(|&p| Measured {
                items: Some(4),
                note: "a, \"quoted\" note".to_string(),
                ..measured(p, Some(1.0))
            })
            .collect();
        let rows = rows(&phases, &context(true));
        let path = dir.join(FILE);
        write(&path, &rows).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let back = read(&path).unwrap();
        drop(dir);
        assert_eq!(back, rows);
        assert!(
            text.starts_with("phase,status,seconds,share_pct,items,note,"),
            "{text}"
        );
        for p in Phase::ALL {
            assert!(text.contains(&format!("\n{},ran,1.0,", p.id())), "{text}");
        }
        assert!(read(Path::new("/nonexistent-driftbench/phases.csv"))
            .unwrap()
            .is_empty());
    }

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
        let printed = table(&rows);
        assert!(
            printed.starts_with("phases of this run (partial: --paper demo):\n"),
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
