//! Why the published numbers differ: controlled re-runs around every run of a paper's solver.
//!
//! - the ladder ([`ladder_jobs`]): each run re-integrated from RelTol 1e-3 to 1e-10 (BDF and Dormand-Prince; the
//!   exact column to 1e-12; a numerical method's loop stopped at 1e-3 to 1e-10): which digits
//!   are integration (or stopping-rule) noise, and the converged drifts.
//! - the attribution: each run's drift split into scheme + network lag + integration error
//!   (a numerical method's: scheme + sampling gap + stopping rule; exact, telescoping), with
//!   the effect of each switched ingredient ([`Switch`]) beside it.
//! - [`inference`]: the setup the papers leave open (path pose and plane tilt, size, direction,
//!   RMP reading; robot variant and MATLAB-default tolerances as discrete hypotheses) fitted to
//!   a published table, jointly and column by column, always shown beside the declared setup,
//!   never instead of it.
//!
//! The runs explained ([`targets`]) are the neural and numerical runs a published column maps onto
//! (`papers/<paper>/paper.toml`, [`analysis::papers::Papers`]) and those of the variants an
//! experiment file marks `explain = true` (zhang2018's perturbed runs: the paper prints no
//! table, but the perturbation is an ingredient to attribute; the group-code experiments'
//! "as coded" runs). Results: `results/ladder.csv`, `results/attribution.csv`
//! (written by [`write()`]), `results/inference.csv` (by `reproduce infer`); their rows are
//! [`records::LadderRow`], [`records::AttributionRow`] and [`records::inference`]'s.

mod attribution;
mod error;
pub mod inference;
mod ladder;

use analysis::papers::Papers;
pub use attribution::Switch;
use attribution::{attribution_rows, exact_counterpart, switch_jobs};
pub use error::{ExplainError, InferenceError};
pub use ladder::{jobs as ladder_jobs, NUMERICAL_TOLERANCES};
use records::inference::{EntryRow, InferenceRow};
use records::table::Row;
use records::AttributionRow;
use records::LadderRow;
use records::RunRow;
use simulation::run_jobs;
use simulation::run_row;
use spec::RunKey;
use spec::RunSpec;
use spec::SolverChoice;
use std::path::Path;
use store::table::read_if_present;
use store::write_atomic;
use store::{IoAction, IoError};

/// The runs to explain among `jobs`, in `jobs` order: the neural and numerical runs a
/// published column maps onto and those of variants marked `explain = true`.
pub fn targets(jobs: &[RunSpec], papers: &Papers) -> Vec<RunSpec> {
    let mapped: std::collections::HashSet<_> = papers.mappings.iter().map(|m| &m.run).collect();
    jobs.iter()
        .filter(|j| !matches!(j.solver, SolverChoice::Exact))
        .filter(|j| j.explain || mapped.contains(&j.key()))
        .cloned()
        .collect()
}

/// What [`explain`] computes.
#[derive(Clone, Debug, Default)]
pub struct Explained {
    pub ladder: Vec<LadderRow>,
    pub attribution: Vec<AttributionRow>,
}

/// Runs the ladders (of each target and of its exact column) and the switch runs, in parallel,
/// and derives the ladder and attribution rows.
///
/// `all` is every job of the experiment files: the exact column of a target's variant is
/// laddered with the method its experiment integrates it with.
pub fn explain(targets: &[RunSpec], all: &[RunSpec], progress: bool, git_rev: &str) -> Explained {
    // Every job once: the exact ladders are shared by the solvers of one variant.
    let mut ladders: Vec<RunSpec> = Vec::new();
    for t in targets {
        let mut exact = exact_counterpart(t);
        if let Some(declared) = all.iter().find(|j| j.key() == exact.key()) {
            exact.integrator = declared.integrator;
        }
        for base in [t.clone(), exact] {
            if !ladders.iter().any(|l| l.key() == base.key()) {
                ladders.push(base);
            }
        }
    }
    let mut jobs: Vec<RunSpec> = Vec::new();
    let mut spans = Vec::new();
    for base in &ladders {
        let rungs = ladder::jobs(base);
        spans.push((jobs.len(), rungs.len()));
        jobs.extend(rungs);
    }
    let mut switch_spans = Vec::new();
    for t in targets {
        let s = switch_jobs(t);
        switch_spans.push((
            jobs.len(),
            s.iter().map(|(k, _)| *k).collect::<Vec<Switch>>(),
        ));
        jobs.extend(s.into_iter().map(|(_, j)| j));
    }
    let rows: Vec<RunRow> = run_jobs(&jobs, progress)
        .iter()
        .map(|r| run_row(r, git_rev))
        .collect();
    let mut out = Explained::default();
    let mut per_base: Vec<Vec<LadderRow>> = Vec::new();
    for (base, (start, len)) in ladders.iter().zip(&spans) {
        let span = *start..start + len;
        let l = ladder::ladder_rows(base, &jobs[span.clone()], &rows[span]);
        out.ladder.extend(l.iter().cloned());
        per_base.push(l);
    }
    let ladder_of = |job: &RunSpec| {
        ladders
            .iter()
            .position(|l| l.key() == job.key())
            .map(|i| per_base[i].as_slice())
            .unwrap_or(&[])
    };
    for (t, (start, kinds)) in targets.iter().zip(&switch_spans) {
        let switched: Vec<(Switch, RunRow)> = kinds
            .iter()
            .enumerate()
            .map(|(i, k)| (*k, rows[start + i].clone()))
            .collect();
        out.attribution.extend(attribution_rows(
            ladder_of(t),
            ladder_of(&exact_counterpart(t)),
            &switched,
        ));
    }
    out
}

/// Serialises rows as CSV (per-joint columns as [`records::table`] writes them).
pub fn to_csv<T: Row>(rows: &[T]) -> Result<Vec<u8>, ExplainError> {
    Ok(records::table::to_csv(rows)?)
}

/// Writes `results/ladder.csv` and `results/attribution.csv`: fresh rows replace the stored
/// rows of the same runs (experiment, variant, solver); other stored rows are kept if their run
/// still exists among `all` (every job of the experiment files), pruned otherwise.
pub fn write(results_dir: &Path, fresh: &Explained, all: &[RunSpec]) -> Result<(), ExplainError> {
    let ladder_path = results_dir.join(store::results_dir::LADDER);
    let attribution_path = results_dir.join(store::results_dir::ATTRIBUTION);
    let keys: std::collections::HashSet<RunKey> = all.iter().map(RunSpec::key).collect();
    let mut stored_ladder = read_if_present::<LadderRow>(&ladder_path)?;
    stored_ladder.retain(|r| keys.contains(&r.key()));
    let mut stored_attribution = read_if_present::<AttributionRow>(&attribution_path)?;
    stored_attribution.retain(|r| keys.contains(&r.key()));
    let ladder = merge(stored_ladder, &fresh.ladder, LadderRow::key);
    let attribution = merge(stored_attribution, &fresh.attribution, AttributionRow::key);
    for (path, bytes) in [
        (&ladder_path, to_csv(&ladder)?),
        (&attribution_path, to_csv(&attribution)?),
    ] {
        write_atomic(path, &bytes).map_err(IoError::at(path, IoAction::Write))?;
    }
    Ok(())
}

/// Writes `results/inference.csv` and `results/inference-entries.csv`: fresh rows replace the
/// stored rows of the same tables.
pub fn write_inference(
    results_dir: &Path,
    fresh: &[InferenceRow],
    fresh_entries: &[EntryRow],
) -> Result<(), ExplainError> {
    let path = results_dir.join(store::results_dir::INFERENCE);
    let entries_path = results_dir.join(store::results_dir::INFERENCE_ENTRIES);
    let rows = merge(read_if_present(&path)?, fresh, |r: &InferenceRow| {
        (r.paper.clone(), r.table.clone())
    });
    let entries = merge(
        read_if_present(&entries_path)?,
        fresh_entries,
        |r: &EntryRow| (r.paper.clone(), r.table.clone()),
    );
    for (p, bytes) in [(&path, to_csv(&rows)?), (&entries_path, to_csv(&entries)?)] {
        write_atomic(p, &bytes).map_err(IoError::at(p, IoAction::Write))?;
    }
    Ok(())
}

/// Stored rows whose run is not among `fresh`'s, then `fresh`, sorted by run (stable within a
/// run, so rungs and components keep their order).
fn merge<T: Clone, K: Ord>(stored: Vec<T>, fresh: &[T], key: impl Fn(&T) -> K) -> Vec<T> {
    let mut all: Vec<T> = stored
        .into_iter()
        .filter(|s| !fresh.iter().any(|f| key(f) == key(s)))
        .collect();
    all.extend(fresh.iter().cloned());
    all.sort_by_key(|a| key(a));
    all
}
