//! One typed model of what the report's pages show that a verdict or a ranking decides, built
//! once per render ([`ReportModel::build`]) so that the report (crate `presentation`) formats it
//! without calling a verdict function or computing a ranking while it writes a page.
//!
//! What it holds: per paper, its claims evaluated from the stored runs
//! ([`crate::claim_verdict::evaluate`]), its verdict ([`crate::paper_verdict`]: the decision,
//! decided once for the front page's summary and the paper's page), its published tables
//! beside ours ([`crate::published_table::side_by_side`]), its printed contradictions
//! ([`crate::misprints`]) and its sweep checks ([`crate::sweep_comparison`]); the leaderboard
//! (the standard task set, its rows, computed once for the leaderboard page and the front
//! page's top, each row's timing alone, and its reading, [`crate::leaderboard_reading`]);
//! zhong2021's efficiency claim over the control experiments' tasks
//! ([`crate::control_claim::overall`]) and the control-rate track
//! ([`crate::control_track`]); the compute times against the papers' MATLAB times
//! ([`crate::cost_ratio`]); the cross experiment's best per column ([`crate::cross_best`]);
//! every large sweep's summary ([`crate::sweep_summary`], aggregated as the rows were
//! read); and the setup inference's
//! verdicts ([`crate::inference_verdict`]); every paper's "why" (its drift attribution and
//! tolerance ladder, [`why`]); and the Performance page's costs, fits and targets
//! ([`performance`]).

pub mod performance;
pub mod why;

use crate::claim_verdict::{evaluate, Claim};
use crate::control_claim::overall;
use crate::control_track::{
    fits_period, main_h_ms, products_per_ms, steps_per_main_tick, success, track, TrackRow,
};
use crate::cost_ratio::{matlab_times, TimeRow};
use crate::cross_best::{bests, ColumnBest};
use crate::inference_verdict::{profile_verdict, spread, table_verdict};
use crate::leaderboard::{
    alone_timing, leaderboard, standard_tasks, LeaderboardRow, Task, STANDARD_PAPER,
};
use crate::leaderboard_reading::{
    standard_reading, timing_reading, StandardReading, TimingReading,
};
use crate::misprints::{contradictions, Contradiction};
use crate::paper_rules::GROUP;
use crate::paper_verdict::{
    assumed_setup, decide, level_under_setup, ratio_span, solver_effect, Decision, Labelled,
};
use crate::papers::Papers;
use crate::published_table::{published_tables, side_by_side, SideBySide};
use crate::sweep_check::SweepCheck;
use crate::sweep_comparison::{setup_share, swept_runs, SetupShare, SweptRun};
use crate::sweep_summary::SweepSummary;
use records::control::{ClaimRow, ControlRow, NoiseRow, StabilityRow, TrendRow, Verdict};
use records::index::completed;
use records::index::Runs;
use records::inference::InferenceRow;
use records::AttributionRow;
use records::LadderRow;
use records::RunRow;
use records::Timings;

/// The report's decided content (module docs), borrowing the runs and papers it was built on.
#[derive(Clone, Debug)]
pub struct ReportModel<'a> {
    /// Every paper of `papers/`, in its order, with its claims evaluated.
    pub papers: Vec<PaperModel<'a>>,
    /// The leaderboard.
    pub leaderboard: Leaderboard,
    /// The published compute times with ours beside them ([`crate::cost_ratio`]).
    pub matlab_times: Vec<TimeRow>,
    /// The best of every column of the cross experiment's matrices ([`crate::cross_best`]).
    pub cross: Vec<ColumnBest<'a>>,
    /// zhong2021's efficiency claim over every task of `results/control-claim.csv`: PASS or
    /// FAIL when the tasks agree, UNDECIDED otherwise or without tasks.
    pub control_claim: Verdict,
    /// The control-rate track ([`crate::control_track`]).
    pub control: Control<'a>,
    /// Every large sweep's summary, by experiment ([`crate::sweep_summary::Held`]: aggregated
    /// as `runs.csv` was read; the runs hold a large sweep's sample only).
    pub sweep_summaries: &'a [SweepSummary],
    /// Every inferred published table, decided ([`crate::inference_verdict`]), by paper in
    /// the order of `results/inference.csv`.
    pub inference: Vec<Inference<'a>>,
    /// Every paper's "why", in the papers' order, then the group's
    /// ([`crate::paper_rules::GROUP`]).
    pub why: Vec<why::Why<'a>>,
    /// The Performance page's content.
    pub performance: performance::Performance<'a>,
}

/// The explanation layer's rows the model reads (absent files: empty).
#[derive(Clone, Copy, Debug, Default)]
pub struct Explained<'a> {
    /// `results/attribution.csv`.
    pub attribution: &'a [AttributionRow],
    /// `results/ladder.csv`.
    pub ladder: &'a [LadderRow],
    /// `results/inference.csv`.
    pub inference: &'a [InferenceRow],
}

/// One published table's setup inference, decided ([`crate::inference_verdict`]).
#[derive(Clone, Debug)]
pub struct Inference<'a> {
    pub paper: &'a str,
    pub table: &'a str,
    /// The table's verdicts in words, the last the overall one (none without the declared
    /// and the inferred setup's rows).
    pub verdicts: Option<Vec<String>>,
    /// Its profiles, in the order of their first row: the parameter, whether the others were
    /// re-fitted, and the verdict on the spread of the profile's residuals.
    pub profiles: Vec<(&'a str, bool, &'static str)>,
}

/// Every inferred table of `rows` (`results/inference.csv`), by paper in first-appearance
/// order, each paper's tables as they run in the file.
fn inferences(rows: &[InferenceRow]) -> Vec<Inference<'_>> {
    let mut papers: Vec<&str> = rows.iter().map(|r| r.paper.as_str()).collect();
    papers.sort_unstable();
    papers.dedup();
    let mut out = Vec::new();
    for paper in papers {
        let of_paper: Vec<&InferenceRow> = rows.iter().filter(|r| r.paper == paper).collect();
        let mut tables: Vec<&str> = of_paper.iter().map(|r| r.table.as_str()).collect();
        tables.dedup();
        for table in tables {
            let of_table: Vec<&InferenceRow> = of_paper
                .iter()
                .copied()
                .filter(|r| r.table == table)
                .collect();
            let mut profiles: Vec<(&str, bool)> = Vec::new();
            for k in of_table.iter().filter_map(|r| r.profile()) {
                if !profiles.contains(&k) {
                    profiles.push(k);
                }
            }
            out.push(Inference {
                paper,
                table,
                verdicts: table_verdict(&of_table),
                profiles: profiles
                    .into_iter()
                    .map(|(name, refitted)| {
                        let along = of_table
                            .iter()
                            .filter(|r| r.profile() == Some((name, refitted)))
                            .map(|r| r.rel_residual);
                        (name, refitted, profile_verdict(spread(along)))
                    })
                    .collect(),
            });
        }
    }
    out
}

/// The control experiments' result rows the model is built on (`results/control*.csv`).
#[derive(Clone, Copy, Debug, Default)]
pub struct ControlInputs<'a> {
    /// `results/control.csv`: every method on every task at every period.
    pub runs: &'a [ControlRow],
    /// `results/control-claim.csv`: zhong2021's efficiency claim per task.
    pub claims: &'a [ClaimRow],
    /// `results/control-stability.csv`: the networks' Euler stability limits.
    pub stability: &'a [StabilityRow],
    /// `results/control-noise.csv`: the noise floor of each of `runs`.
    pub noise: &'a [NoiseRow],
    /// `results/cycles-trend.csv`: the many-cycles runs' trends, as run and under the probe.
    pub trends: &'a [TrendRow],
}

/// The control-rate track, decided ([`crate::control_track`]).
#[derive(Clone, Debug)]
pub struct Control<'a> {
    /// The main control period (ms).
    pub main_h_ms: f64,
    /// Every run at the main period, in file order, with whether its median tick fits the
    /// period and whether it is a success (stable, and accurate once settled).
    pub verdicts: Vec<RunVerdict<'a>>,
    /// The claim's networks as the papers integrate them: each claim row, a completed run of
    /// `results/runs.csv` of its network, and that run's products with M per millisecond.
    pub as_integrated: Vec<(&'a ClaimRow, &'a RunRow, f64)>,
    /// Per stability row (same order): the Euler steps a 1 ms tick needs, where the network
    /// has a stability limit.
    pub steps_per_tick: Vec<Option<u64>>,
    /// The control-rate leaderboard.
    pub track: Vec<TrackRow<'a>>,
    /// The noise floor of max |x - x*| over the runs ([`crate::NoiseSummary`]).
    pub noise: crate::NoiseSummary<'a>,
    /// The many-cycles runs whose class changes under the rounding-noise probe, in file order.
    pub changed_classes: Vec<&'a TrendRow>,
    /// The many-cycles runs with a class, as run or under the probe.
    pub classed: usize,
}

/// A run at the main period with its verdicts.
#[derive(Clone, Copy, Debug)]
pub struct RunVerdict<'a> {
    pub row: &'a ControlRow,
    /// Its median whole tick is within the period.
    pub fits: bool,
    /// It completed within the accuracy of the exact optimum after the first second.
    pub success: bool,
}

impl<'a> Control<'a> {
    /// The track of `control` on the stored `runs`.
    fn build(control: ControlInputs<'a>, runs: &'a Runs) -> Self {
        let h = main_h_ms();
        let (changed_classes, classed) = crate::control_noise::trend_changes(control.trends);
        Control {
            main_h_ms: h,
            verdicts: control
                .runs
                .iter()
                .filter(|r| r.h_ms == h)
                .map(|row| RunVerdict {
                    row,
                    fits: fits_period(row),
                    success: success(row),
                })
                .collect(),
            as_integrated: control
                .claims
                .iter()
                .flat_map(|c| {
                    runs.of_experiment(&c.experiment)
                        .filter(move |r| {
                            r.variant_id == c.variant_id
                                && r.solver_id == c.solver_id
                                && completed(r)
                        })
                        .map(move |r| (c, r, products_per_ms(r, c)))
                })
                .collect(),
            steps_per_tick: control
                .stability
                .iter()
                .map(|s| s.euler_limit_s.map(steps_per_main_tick))
                .collect(),
            track: track(control.runs),
            noise: crate::control_noise::summarise(control.runs, control.noise),
            changed_classes,
            classed,
        }
    }
}

/// A paper: its claims' verdicts, its verdict, its published tables beside ours, its printed
/// contradictions and its sweep checks.
#[derive(Clone, Debug)]
pub struct PaperModel<'a> {
    /// The paper id.
    pub id: String,
    /// Its title.
    pub title: String,
    /// Its claims, in the order `paper.toml` gives them.
    pub claims: Vec<Claim>,
    /// The counts its verdict is decided from, and the level ([`crate::paper_verdict`]).
    pub decision: Decision,
    /// The level in words, with ", under an assumed setup" where the setup was substituted.
    pub level: String,
    /// What of its setup was substituted, if anything.
    pub assumed_setup: Option<&'a str>,
    /// The smallest and the largest counted ratio ours / paper (none when none is counted).
    pub ratio_span: Option<(Labelled, Labelled)>,
    /// The largest |solver − exact| / exact drift norm over its mapped runs, and the run.
    pub solver_effect: Option<(f64, &'a RunRow)>,
    /// Its published tables beside ours (the tables where something maps), in the CSV's order.
    pub tables: Vec<SideBySide<'a>>,
    /// Its columns whose printed numbers contradict each other ([`crate::misprints`]).
    pub contradictions: Vec<Contradiction>,
    /// Its sweep checks, in file order.
    pub sweeps: Vec<Sweep<'a>>,
}

/// A sweep check beside its runs ([`crate::sweep_comparison`]).
#[derive(Clone, Debug)]
pub struct Sweep<'a> {
    /// The check (`[[sweep_check]]` of `paper.toml`).
    pub check: &'a SweepCheck,
    /// Whether any run of its experiment is stored.
    pub ran: bool,
    /// Every swept run whose variant a published column matches, in file order.
    pub swept: Vec<SweptRun<'a>>,
    /// The declared setup's share of the gap, where the check names it.
    pub share: Option<SetupShare<'a>>,
}

/// The leaderboard: the standard task set, the rows of every task set, how each row's runs
/// were timed, and its reading ([`crate::leaderboard_reading`]).
#[derive(Clone, Debug)]
pub struct Leaderboard {
    /// The standard task set (the cross experiment's tasks whose exact column completed).
    pub tasks: Vec<Task>,
    /// The rows, as `results/leaderboard.csv` holds them.
    pub rows: Vec<LeaderboardRow>,
    /// Per row, in the same order: how many of its solver's runs on its set's tasks were timed
    /// alone, and the largest spread of their repetitions
    /// ([`crate::leaderboard::alone_timing`]).
    pub alone: Vec<(usize, f64)>,
    /// The standard set's reading (none without a standard ranking).
    pub reading: Option<StandardReading>,
    /// How the standard set's times were measured (none without timings).
    pub timing: Option<TimingReading>,
}

impl Leaderboard {
    /// The leaderboard of `runs`, timed in `timings`.
    fn build(runs: &Runs, timings: &Timings) -> Self {
        let tasks = standard_tasks(runs.all());
        let rows = leaderboard(runs.all(), timings);
        let alone = rows
            .iter()
            .map(|r| {
                alone_timing(
                    timings,
                    &r.solver_id,
                    &set_tasks(&r.task_set, &rows, &tasks, runs),
                )
            })
            .collect();
        Leaderboard {
            reading: standard_reading(&rows),
            timing: timing_reading(&rows, timings, &tasks),
            alone,
            tasks,
            rows,
        }
    }
}

/// The tasks of the leaderboard's task set `set`: the standard `tasks`, or, for a set of the
/// solvers that did not run on every standard task, the standard tasks its first such solver
/// ran on.
fn set_tasks(set: &str, rows: &[LeaderboardRow], tasks: &[Task], runs: &Runs) -> Vec<Task> {
    let partial = rows
        .iter()
        .filter(|r| r.task_set == set)
        .find(|r| r.standard_runs < tasks.len());
    match partial {
        Some(partial) => tasks
            .iter()
            .filter(|t| {
                runs.all().iter().any(|r| {
                    r.solver_id == partial.solver_id
                        && r.experiment == t.experiment
                        && r.variant_id == t.variant
                })
            })
            .cloned()
            .collect(),
        None => tasks.to_vec(),
    }
}

impl<'a> ReportModel<'a> {
    /// The model of the report on the stored `runs`, the `papers` (as the report shows them),
    /// the runs timed alone (`timings`, the leaderboard's and the MATLAB comparison's), the
    /// control experiments' rows `control`, the explanation layer's rows `explained` and the
    /// Performance page's measurements `measured`.
    pub fn build(
        runs: &'a Runs,
        papers: &'a Papers,
        timings: &'a Timings,
        control: ControlInputs<'a>,
        explained: Explained<'a>,
        measured: performance::Measured<'a>,
        sweeps: &'a [SweepSummary],
    ) -> Self {
        let verdicts: Vec<Verdict> = control.claims.iter().map(|c| c.verdict).collect();
        ReportModel {
            papers: papers
                .papers
                .iter()
                .map(|p| PaperModel::build(&p.id, &p.title, runs, papers))
                .collect(),
            leaderboard: Leaderboard::build(runs, timings),
            control_claim: overall(&verdicts),
            control: Control::build(control, runs),
            sweep_summaries: sweeps,
            inference: inferences(explained.inference),
            why: papers
                .papers
                .iter()
                .map(|p| p.id.as_str())
                .chain([GROUP])
                .map(|paper| why::Why::build(paper, explained, papers))
                .collect(),
            performance: performance::Performance::build(measured, runs, timings, papers),
            matlab_times: matlab_times(runs, papers),
            cross: bests(runs, STANDARD_PAPER),
        }
    }

    /// The "why" of `paper` (a paper of the model, or the group).
    pub fn why_of(&self, paper: &str) -> Option<&why::Why<'a>> {
        self.why.iter().find(|w| w.paper == paper)
    }
}

impl<'a> PaperModel<'a> {
    /// The model of paper `id` (titled `title`) on `runs`.
    fn build(id: &'a str, title: &str, runs: &'a Runs, papers: &'a Papers) -> Self {
        let claims = evaluate(id, runs, papers);
        let decision = decide(id, &claims, runs, papers);
        let contradictions = contradictions(id, papers);
        PaperModel {
            id: id.to_string(),
            title: title.to_string(),
            level: level_under_setup(id, &decision, papers),
            assumed_setup: assumed_setup(id, papers),
            ratio_span: ratio_span(&decision.ratios).map(|(lo, hi)| (lo.clone(), hi.clone())),
            solver_effect: solver_effect(id, runs, papers),
            tables: published_tables(id, papers)
                .iter()
                .filter_map(|t| side_by_side(id, t, papers, runs, &contradictions))
                .collect(),
            sweeps: papers
                .sweep_checks
                .iter()
                .filter(|c| c.paper == id)
                .map(|check| {
                    let swept = swept_runs(check, runs, papers);
                    Sweep {
                        check,
                        ran: runs.of_experiment(&check.experiment).next().is_some(),
                        share: setup_share(check, &swept),
                        swept,
                    }
                })
                .collect(),
            contradictions,
            claims,
            decision,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control_claim::judge;
    use crate::control_claim::tests::check;
    use records::control::ClaimCheck;

    #[test]
    fn the_control_claim_is_decided_over_the_tasks() {
        let (runs, papers, timings) =
            (Runs::new(Vec::new()), Papers::default(), Timings::default());
        let build = |claims: &[ClaimRow]| {
            let control = ControlInputs {
                claims,
                ..ControlInputs::default()
            };
            ReportModel::build(
                &runs,
                &papers,
                &timings,
                control,
                Explained::default(),
                performance::Measured::default(),
                &[],
            )
            .control_claim
        };
        // Nothing stored: no paper, no leaderboard, no decision.
        let empty = ReportModel::build(
            &runs,
            &papers,
            &timings,
            ControlInputs::default(),
            Explained::default(),
            performance::Measured::default(),
            &[],
        );
        assert!(empty.papers.is_empty() && empty.leaderboard.rows.is_empty());
        assert!(empty.leaderboard.tasks.is_empty() && empty.control.track.is_empty());
        assert_eq!(empty.control_claim, Verdict::Undecided);
        // Two tasks that pass (lower bound 40 <= 50, accurate), then one that fails.
        let pass = judge(check(4, 1e-8));
        let fail = judge(ClaimCheck {
            steps_needed: 6,
            ..check(12, 1e-9)
        });
        assert_eq!(build(&[pass.clone(), pass.clone()]), Verdict::Pass);
        assert_eq!(build(&[pass, fail.clone()]), Verdict::Undecided);
        assert_eq!(build(&[fail]), Verdict::Fail);
    }
}
