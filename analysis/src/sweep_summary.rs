//! The runs the report holds, read from `results/runs.csv` in bounded memory ([`Held::read`]),
//! and a large sweep's summary, aggregated row by row ([`SweepSummary`]).
//!
//! **What is held.** An experiment of at most [`MAX_RUN_FIGURES`] runs is held whole. A larger
//! one (a large sweep) is held as [`MAX_RUN_FIGURES`] of its runs, its sample, and its
//! [`SweepSummary`]: every aggregate below has a size set by constants and by the number of its
//! parameters' values (itself capped at [`MAX_VALUES`]), never by its number of runs. The file
//! is read twice, row by row: the first pass counts each experiment's runs and finds its
//! sample, its parameters and the ranges of its metrics; the second aggregates and keeps the
//! sample. "In key order" below is the file's order, which is key order in every `runs.csv`
//! this program writes (and the reader checks it: `store::sorted::read_key_ordered`).
//!
//! **The sample** (the runs that get a figure of their own and a row in a page's tables),
//! chosen among the runs that keep a trace: every run up to [`MAX_RUN_FIGURES`]; beyond, the
//! failed runs first (at most a quarter of the cap, the first in key order), then the extremes
//! ([`Extreme`]: largest and smallest drift norm ||theta(T) - theta(0)|| and position error
//! max_t |r*(t) - f(theta(t))| over the completed runs with a finite metric, the first in key
//! order winning a tie), then runs evenly spaced in key order (the k-th of the s slots left at
//! index floor(k n / s), the next one not yet chosen), up to the cap.
//!
//! **The aggregates of a large sweep** (drift norm d and position error e of its completed
//! runs, on a log scale: only positive values count):
//!
//! - counts: runs, failed runs, runs of a neural solver; the extremes (each run at an extreme,
//!   as above, over every run) and the first [`LISTED_FAILURES`] failed runs in key order;
//! - its parameters, read back from the labels ([`parameters`]): a parameter is numeric when
//!   every run that names it gives a finite number, and is drawn when it takes two values or
//!   more; the first [`MAX_PARAMETERS`] such, in the order the labels name them ([`Axis`]). A
//!   parameter of at most [`MAX_VALUES`] distinct values is an axis of those values; one of more
//!   is cut into [`MAX_VALUES`] intervals of equal width over [min, max] (the last one closed);
//! - per axis point (a value or an interval), d and e each as a [`Sketch`]: count, minimum and
//!   maximum exact, the median from a histogram of [`SKETCH_BINS`] bins of log10 over the
//!   sweep's range of that metric, so within half a bin (1/64 of the range of log10) of the
//!   exact median;
//! - with two drawn parameters or more, a heat map over the first two: per pair of axis points
//!   the [`Sketch`] of d;
//! - the distribution of log10 d over the completed runs: [`BINS`] bins of equal width over
//!   [min, max] of log10 d (bin k holds lo + k w <= x < lo + (k + 1) w, the last one closed).

use records::index::Runs;
use records::RunRow;
use spec::RunKey;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use store::sorted::read_key_ordered;
use store::RunsError;

/// The most runs of one experiment held, drawn and tabled: an experiment with more is a large
/// sweep, held as its sample and its [`SweepSummary`].
pub const MAX_RUN_FIGURES: usize = 24;

/// The most failures a summary lists (the count gives the rest).
pub const LISTED_FAILURES: usize = 10;

/// The most swept parameters a sweep is aggregated against (in the order of the labels).
pub const MAX_PARAMETERS: usize = 3;

/// The most points of a parameter's axis: its distinct values, or as many intervals.
pub const MAX_VALUES: usize = 40;

/// Bins of the drift norm's distribution.
pub const BINS: usize = 24;

/// Bins of log10 of a [`Sketch`], over the sweep's range of its metric.
pub const SKETCH_BINS: usize = 32;

/// The most parameter names followed per experiment while the first pass reads the labels.
const MAX_NAMES: usize = 16;

/// The most distinct revisions and crate versions a sweep records.
const MAX_REVISIONS: usize = 16;

/// Which extreme a run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extreme {
    /// The largest drift norm.
    LargestDrift,
    /// The smallest drift norm.
    SmallestDrift,
    /// The largest position error.
    LargestError,
    /// The smallest position error.
    SmallestError,
}

impl Extreme {
    /// Every extreme, in the order a page lists them.
    pub const ALL: [Extreme; 4] = [
        Extreme::LargestDrift,
        Extreme::SmallestDrift,
        Extreme::LargestError,
        Extreme::SmallestError,
    ];

    /// The extreme in words.
    pub fn name(self) -> &'static str {
        match self {
            Extreme::LargestDrift => "largest drift norm",
            Extreme::SmallestDrift => "smallest drift norm",
            Extreme::LargestError => "largest position error",
            Extreme::SmallestError => "smallest position error",
        }
    }

    /// The finite metric of a completed run it ranks by.
    fn value(self, r: &RunRow) -> Option<f64> {
        let v = match self {
            Extreme::LargestDrift | Extreme::SmallestDrift => r.drift_norm,
            Extreme::LargestError | Extreme::SmallestError => r.max_pos_err,
        };
        v.filter(|v| v.is_finite() && r.completed())
    }

    /// Whether `v` beats the best so far (strictly: the first wins a tie).
    fn beats(self, v: f64, best: Option<f64>) -> bool {
        match (self, best) {
            (_, None) => true,
            (Extreme::LargestDrift | Extreme::LargestError, Some(b)) => v > b,
            (Extreme::SmallestDrift | Extreme::SmallestError, Some(b)) => v < b,
        }
    }
}

/// The swept parameters of a run, as (name, value text), read back from its label: the sweep
/// grammar (`catalog::sweep`) writes a swept variant's label as `label [k=v, k2=v2]`, k the last
/// segment of each swept path. A part without `=` (a labelled value's text) is left out, and a
/// label without the bracket names none.
pub fn parameters(label: &str) -> Vec<(&str, &str)> {
    let Some((_, inside)) = label.strip_suffix(']').and_then(|l| l.rsplit_once(" [")) else {
        return Vec::new();
    };
    inside
        .split(", ")
        .filter_map(|part| part.split_once('='))
        .map(|(k, v)| (k.trim(), v.trim()))
        .collect()
}

/// The sample's indices among `n` runs (module docs), given the first failures' and the
/// extremes' indices; ascending.
fn sample(n: usize, failures: &[usize], extremes: &[Option<usize>]) -> Vec<usize> {
    if n <= MAX_RUN_FIGURES {
        return (0..n).collect();
    }
    let mut chosen: Vec<usize> = failures.iter().copied().take(MAX_RUN_FIGURES / 4).collect();
    for &i in extremes.iter().flatten() {
        if !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    let slots = MAX_RUN_FIGURES - chosen.len();
    for k in 0..slots {
        let mut i = k * n / slots;
        while chosen.contains(&i) && i + 1 < n {
            i += 1;
        }
        if !chosen.contains(&i) {
            chosen.push(i);
        }
    }
    chosen.sort_unstable();
    chosen.truncate(MAX_RUN_FIGURES);
    chosen
}

/// The first pass's picker of a sample: the runs seen, the first failures and the extremes.
#[derive(Debug, Default)]
struct Picker {
    n: usize,
    failures: Vec<usize>,
    extremes: [Option<(usize, f64)>; 4],
}

impl Picker {
    fn push(&mut self, r: &RunRow) {
        let i = self.n;
        self.n += 1;
        if !r.completed() {
            if self.failures.len() < MAX_RUN_FIGURES / 4 {
                self.failures.push(i);
            }
            return;
        }
        for (e, best) in Extreme::ALL.into_iter().zip(&mut self.extremes) {
            if let Some(v) = e.value(r) {
                if e.beats(v, best.map(|b| b.1)) {
                    *best = Some((i, v));
                }
            }
        }
    }

    fn sample(&self) -> Vec<usize> {
        sample(
            self.n,
            &self.failures,
            &self.extremes.map(|b| b.map(|b| b.0)),
        )
    }
}

/// What the first pass learns of a parameter name.
#[derive(Debug)]
struct NameCensus {
    name: String,
    /// Every run naming it gave a finite number.
    numeric: bool,
    lo: f64,
    hi: f64,
    /// Its distinct values, sorted, up to [`MAX_VALUES`] + 1.
    distinct: Vec<f64>,
}

/// The smallest and largest of some values.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Range {
    lo: f64,
    hi: f64,
}

impl Default for Range {
    fn default() -> Self {
        Range {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
        }
    }
}

impl Range {
    fn push(&mut self, v: f64) {
        self.lo = self.lo.min(v);
        self.hi = self.hi.max(v);
    }
}

/// What the first pass learns of one experiment.
#[derive(Debug, Default)]
struct Census {
    runs: usize,
    /// The picker over the runs that keep a trace.
    traced: Picker,
    names: Vec<NameCensus>,
    /// log10 of the positive drift norms and position errors of the completed runs.
    drift: Range,
    error: Range,
}

/// A positive finite metric's log10.
fn log(v: Option<f64>) -> Option<f64> {
    v.filter(|v| v.is_finite() && *v > 0.0).map(f64::log10)
}

/// The drift norm of a completed run.
fn drift(r: &RunRow) -> Option<f64> {
    r.completed().then_some(r.drift_norm).flatten()
}

/// The largest position error of a completed run.
fn error(r: &RunRow) -> Option<f64> {
    r.completed().then_some(r.max_pos_err).flatten()
}

impl Census {
    fn push(&mut self, r: &RunRow, traced: bool) {
        self.runs += 1;
        if traced {
            self.traced.push(r);
        }
        if let Some(d) = log(drift(r)) {
            self.drift.push(d);
        }
        if let Some(e) = log(error(r)) {
            self.error.push(e);
        }
        for (k, v) in parameters(&r.variant) {
            let at = match self.names.iter().position(|c| c.name == k) {
                Some(at) => at,
                None if self.names.len() < MAX_NAMES => {
                    self.names.push(NameCensus {
                        name: k.to_string(),
                        numeric: true,
                        lo: f64::INFINITY,
                        hi: f64::NEG_INFINITY,
                        distinct: Vec::new(),
                    });
                    self.names.len() - 1
                }
                None => continue,
            };
            let c = &mut self.names[at];
            match v.parse::<f64>().ok().filter(|x| x.is_finite()) {
                Some(x) if c.numeric => {
                    c.lo = c.lo.min(x);
                    c.hi = c.hi.max(x);
                    if c.distinct.len() <= MAX_VALUES {
                        if let Err(at) = c.distinct.binary_search_by(|y| y.total_cmp(&x)) {
                            c.distinct.insert(at, x);
                        }
                    }
                }
                Some(_) => {}
                None => {
                    c.numeric = false;
                    c.distinct = Vec::new();
                }
            }
        }
    }
}

/// A swept parameter's axis: its values, or equal intervals of its range (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The parameter's name (the last segment of its swept path).
    pub name: String,
    /// Its distinct values, sorted; empty when it is cut into intervals.
    pub values: Vec<f64>,
    /// The range cut into [`MAX_VALUES`] intervals, when it has more distinct values.
    pub intervals: Option<(f64, f64)>,
}

impl Axis {
    /// The number of points.
    pub fn len(&self) -> usize {
        match self.intervals {
            Some(_) => MAX_VALUES,
            None => self.values.len(),
        }
    }

    /// Whether it has no point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The point `v` belongs to.
    fn index(&self, v: f64) -> Option<usize> {
        match self.intervals {
            Some((lo, hi)) => {
                let f = (v - lo) / (hi - lo) * MAX_VALUES as f64;
                (f.is_finite() && f >= 0.0).then(|| (f as usize).min(MAX_VALUES - 1))
            }
            None => self.values.binary_search_by(|x| x.total_cmp(&v)).ok(),
        }
    }

    /// Point `i`'s position on the axis: its value, or its interval's middle.
    pub fn position(&self, i: usize) -> f64 {
        match self.intervals {
            Some((lo, hi)) => lo + (i as f64 + 0.5) * (hi - lo) / MAX_VALUES as f64,
            None => self.values[i],
        }
    }
}

/// A bounded summary of positive values (module docs): count, exact minimum and maximum, and
/// a histogram of log10 over a fixed range for the median.
#[derive(Clone, Debug, PartialEq)]
pub struct Sketch {
    /// How many values.
    pub count: usize,
    /// The smallest value (infinite when none).
    pub min: f64,
    /// The largest value (negative infinite when none).
    pub max: f64,
    /// Counts of log10 in [`SKETCH_BINS`] bins over `range`.
    bins: [u32; SKETCH_BINS],
    range: Range,
}

impl Sketch {
    fn new(range: Range) -> Self {
        Sketch {
            count: 0,
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            bins: [0; SKETCH_BINS],
            range,
        }
    }

    fn width(&self) -> f64 {
        let w = (self.range.hi - self.range.lo) / SKETCH_BINS as f64;
        if w > 0.0 {
            w
        } else {
            1.0
        }
    }

    /// Adds the positive value `v`, whose log10 lies in the range.
    fn push(&mut self, v: f64) {
        let x = v.log10();
        let k = ((x - self.range.lo) / self.width()).max(0.0) as usize;
        self.bins[k.min(SKETCH_BINS - 1)] += 1;
        self.count += 1;
        self.min = self.min.min(v);
        self.max = self.max.max(v);
    }

    /// The median, within half a bin of log10 (the middle of the bin holding the value of
    /// rank ceil(count / 2), kept within [min, max]); `None` without values.
    pub fn median(&self) -> Option<f64> {
        let rank = self.count.div_ceil(2);
        let mut seen = 0;
        for (k, &c) in self.bins.iter().enumerate() {
            seen += c as usize;
            if c > 0 && seen >= rank {
                let mid = self.range.lo + (k as f64 + 0.5) * self.width();
                return Some(10f64.powf(mid).clamp(self.min, self.max));
            }
        }
        None
    }
}

/// A large sweep's summary (module docs), aggregated row by row in the second pass.
#[derive(Clone, Debug)]
pub struct SweepSummary {
    /// Its experiment.
    pub experiment: String,
    /// Its paper.
    pub paper: String,
    /// The number of runs.
    pub runs: usize,
    /// The number of failed runs.
    pub failed: usize,
    /// The number of runs of a neural solver (not the exact column).
    pub neural: usize,
    /// The first [`LISTED_FAILURES`] failed runs, in key order.
    pub failures: Vec<RunRow>,
    /// The drawn parameters' axes, at most [`MAX_PARAMETERS`].
    pub axes: Vec<Axis>,
    /// Per axis, per point: the drift norm's and the position error's sketches.
    pub against: Vec<Vec<(Sketch, Sketch)>>,
    /// With two axes or more: the drift norm's sketch per pair of points of the first two
    /// (index i + j * first axis' length).
    pub heat: Vec<Sketch>,
    /// The distribution of log10 of the drift norm: (bin start, bin end, count); empty when
    /// no completed run has a positive drift norm.
    pub histogram: Vec<(f64, f64, usize)>,
    /// The distinct `git_rev` of its rows (at most 16).
    pub revisions: BTreeSet<String>,
    /// The distinct `crate_version` of its rows (at most 16).
    pub versions: BTreeSet<String>,
    /// How many of its runs the report holds (its sample).
    pub sampled: usize,
    /// How many of them are runs of a neural solver.
    pub sampled_neural: usize,
    /// Per extreme of [`Extreme::ALL`], its value and run so far.
    best: [Option<(f64, RunRow)>; 4],
    drift_range: Range,
}

impl SweepSummary {
    fn new(experiment: &str, c: &Census) -> Self {
        let axes: Vec<Axis> = c
            .names
            .iter()
            .filter(|n| n.numeric && n.distinct.len() >= 2)
            .take(MAX_PARAMETERS)
            .map(|n| Axis {
                name: n.name.clone(),
                intervals: (n.distinct.len() > MAX_VALUES).then_some((n.lo, n.hi)),
                values: if n.distinct.len() > MAX_VALUES {
                    Vec::new()
                } else {
                    n.distinct.clone()
                },
            })
            .collect();
        let against = axes
            .iter()
            .map(|a| vec![(Sketch::new(c.drift), Sketch::new(c.error)); a.len()])
            .collect();
        let heat = match &axes[..] {
            [x, y, ..] => vec![Sketch::new(c.drift); x.len() * y.len()],
            _ => Vec::new(),
        };
        let histogram = if c.drift.lo <= c.drift.hi {
            let width = histogram_width(c.drift);
            (0..BINS)
                .map(|k| {
                    (
                        c.drift.lo + k as f64 * width,
                        c.drift.lo + (k + 1) as f64 * width,
                        0,
                    )
                })
                .collect()
        } else {
            Vec::new()
        };
        SweepSummary {
            experiment: experiment.to_string(),
            paper: String::new(),
            runs: 0,
            failed: 0,
            neural: 0,
            failures: Vec::new(),
            axes,
            against,
            heat,
            histogram,
            revisions: BTreeSet::new(),
            versions: BTreeSet::new(),
            sampled: 0,
            sampled_neural: 0,
            best: [None, None, None, None],
            drift_range: c.drift,
        }
    }

    fn push(&mut self, r: &RunRow) {
        if self.runs == 0 {
            self.paper = r.paper.clone();
        }
        self.runs += 1;
        self.neural += usize::from(!r.is_exact());
        for (set, v) in [
            (&mut self.revisions, &r.git_rev),
            (&mut self.versions, &r.crate_version),
        ] {
            if set.len() < MAX_REVISIONS && !set.contains(v) {
                set.insert(v.clone());
            }
        }
        if !r.completed() {
            self.failed += 1;
            if self.failures.len() < LISTED_FAILURES {
                self.failures.push(r.clone());
            }
            return;
        }
        for (e, best) in Extreme::ALL.into_iter().zip(&mut self.best) {
            if let Some(v) = e
                .value(r)
                .filter(|&v| e.beats(v, best.as_ref().map(|b| b.0)))
            {
                *best = Some((v, r.clone()));
            }
        }
        let (d, e) = (
            drift(r).filter(|v| *v > 0.0 && v.is_finite()),
            error(r).filter(|v| *v > 0.0 && v.is_finite()),
        );
        if let Some(d) = d {
            let width = histogram_width(self.drift_range);
            let k = ((d.log10() - self.drift_range.lo) / width).max(0.0) as usize;
            if let Some(bin) = self.histogram.get_mut(k.min(BINS - 1)) {
                bin.2 += 1;
            }
        }
        let labelled = parameters(&r.variant);
        let point = |a: &Axis| {
            labelled
                .iter()
                .find(|(k, _)| *k == a.name)
                .and_then(|(_, v)| v.parse::<f64>().ok())
                .and_then(|v| a.index(v))
        };
        let points: Vec<Option<usize>> = self.axes.iter().map(point).collect();
        for (sketches, p) in self.against.iter_mut().zip(&points) {
            if let Some(s) = p.and_then(|p| sketches.get_mut(p)) {
                if let Some(d) = d {
                    s.0.push(d);
                }
                if let Some(e) = e {
                    s.1.push(e);
                }
            }
        }
        if let ([Some(i), Some(j), ..], Some(x), Some(d)) = (&points[..], self.axes.first(), d) {
            if let Some(cell) = self.heat.get_mut(i + j * x.len()) {
                cell.push(d);
            }
        }
    }

    /// Each extreme with its run, in the order of [`Extreme::ALL`] (an extreme no completed
    /// run has a finite metric for is left out); the first run in key order wins a tie.
    pub fn extremes(&self) -> impl Iterator<Item = (Extreme, &RunRow)> {
        Extreme::ALL
            .into_iter()
            .zip(&self.best)
            .filter_map(|(e, b)| Some((e, &b.as_ref()?.1)))
    }

    /// How many of its runs the report does not hold (beyond its sample).
    pub fn left_out(&self) -> usize {
        self.runs - self.sampled
    }

    /// How many of its neural runs the report does not hold.
    pub fn neural_left_out(&self) -> usize {
        self.neural - self.sampled_neural
    }

    /// The number of completed runs with a positive drift norm (the histogram's).
    pub fn drawn_drift(&self) -> usize {
        self.histogram.iter().map(|b| b.2).sum()
    }
}

/// The width of a histogram bin over `r` (1 for a single value).
fn histogram_width(r: Range) -> f64 {
    if r.hi > r.lo {
        (r.hi - r.lo) / BINS as f64
    } else {
        1.0
    }
}

/// The runs the report holds and every large sweep's summary (module docs).
#[derive(Clone, Debug)]
pub struct Held {
    /// Every run of an experiment of at most [`MAX_RUN_FIGURES`] runs; of a large sweep, its
    /// sample.
    pub runs: Runs,
    /// Every large sweep's summary, by experiment.
    pub sweeps: Vec<SweepSummary>,
}

impl Held {
    /// Reads `path` (a `runs.csv`; absent: no rows) twice, row by row (module docs); the runs
    /// whose key `traced` says no to keep no trace by choice and are left out of the samples (a sweep's
    /// summary still counts them). Any problem is the reader's error naming the file and the
    /// line (`store::sorted::read_key_ordered`: the schema, the names, a run listed twice or
    /// out of key order).
    pub fn read(path: &Path, traced: &dyn Fn(&RunKey) -> bool) -> Result<Held, RunsError> {
        let traced = |r: &RunRow| traced(&r.key());
        let mut census: BTreeMap<String, Census> = BTreeMap::new();
        for row in read_key_ordered(path)? {
            let row = row?;
            let traced = traced(&row);
            match census.get_mut(row.experiment.as_str()) {
                Some(c) => c.push(&row, traced),
                None => {
                    let mut c = Census::default();
                    c.push(&row, traced);
                    census.insert(row.experiment.to_string(), c);
                }
            }
        }
        // Per large sweep: its summary, its sample among its traced runs, and the index of its
        // next traced run.
        let mut large: BTreeMap<String, (SweepSummary, Vec<usize>, usize)> = census
            .iter()
            .filter(|(_, c)| c.runs > MAX_RUN_FIGURES)
            .map(|(e, c)| (e.clone(), (SweepSummary::new(e, c), c.traced.sample(), 0)))
            .collect();
        drop(census);
        let mut held = Vec::new();
        for row in read_key_ordered(path)? {
            let row = row?;
            let Some((sweep, sample, next)) = large.get_mut(row.experiment.as_str()) else {
                held.push(row);
                continue;
            };
            sweep.push(&row);
            if traced(&row) {
                if sample.binary_search(next).is_ok() {
                    sweep.sampled += 1;
                    sweep.sampled_neural += usize::from(!row.is_exact());
                    held.push(row);
                }
                *next += 1;
            }
        }
        Ok(Held {
            runs: Runs::new(held),
            sweeps: large.into_values().map(|(s, _, _)| s).collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::Status;
    use spec::SolverKind;

    fn run(i: usize, label: &str, drift: Option<f64>, error: Option<f64>, failed: bool) -> RunRow {
        let key = RunKey::parse(&format!("s / v{i:05} / exact")).unwrap();
        let mut r = RunRow::blank(&key, SolverKind::Exact);
        r.variant = label.to_string();
        r.drift_norm = drift;
        r.max_pos_err = error;
        if failed {
            r.status = Status::Failed;
        }
        r
    }

    /// `rows` as the runs.csv of a scratch directory (removed when dropped), and its path.
    fn scratch(name: &str, rows: &[RunRow]) -> (inputs::Scratch, std::path::PathBuf) {
        let dir = inputs::Scratch::dir(&format!("sweep-summary-{name}"));
        let path = dir.join("runs.csv");
        std::fs::write(&path, records::runs_csv(rows).unwrap()).unwrap();
        (dir, path)
    }

    #[test]
    fn parameters_are_read_back_from_generated_labels() {
        assert_eq!(
            parameters("ZNN (eq. 22) [mu=0.25, reverse=false]"),
            [("mu", "0.25"), ("reverse", "false")]
        );
        assert_eq!(parameters("MVN [reversed, a=0.1]").len(), 1);
        assert!(parameters("finite-time (kong2019 eq. 14)").is_empty());
        assert!(parameters("{phi} template").is_empty());
    }

    /// The sample picked in one pass is the rule of the module docs, checked against a
    /// direct reading of it on every run at once.
    #[test]
    fn the_sample_takes_failures_extremes_then_evenly_spaced_runs() {
        let rows: Vec<RunRow> = (0..1000)
            .map(|i| {
                let d = 1.0 + ((i * 7919) % 1000) as f64;
                run(i, "x", Some(d), Some(1.0 / d), i % 97 == 5)
            })
            .collect();
        let mut p = Picker::default();
        rows.iter().for_each(|r| p.push(r));
        let s = p.sample();
        assert_eq!(s.len(), MAX_RUN_FIGURES);
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        let failed: Vec<usize> = (0..1000).filter(|i| i % 97 == 5).take(6).collect();
        assert!(failed.iter().all(|i| s.contains(i)), "{s:?}");
        // Largest drift: d = 1000 at the completed i with (7919 i) mod 1000 = 999.
        let largest = (0..1000)
            .filter(|i| i % 97 != 5)
            .max_by(|&a, &b| {
                let d = |i: usize| (i * 7919) % 1000;
                d(a).cmp(&d(b)).then(b.cmp(&a))
            })
            .unwrap();
        assert!(s.contains(&largest));
        assert_eq!(sample(10, &[], &[]), (0..10).collect::<Vec<_>>());
        // Evenly spaced only: the k-th of 24 at floor(k n / 24).
        let even = sample(240, &[], &[]);
        assert_eq!(even, (0..24).map(|k| k * 10).collect::<Vec<_>>());
    }

    /// A sketch's median is within half a bin of log10 of the exact one, and its count,
    /// minimum and maximum are exact.
    #[test]
    fn a_sketch_holds_the_median_within_half_a_bin() {
        let values: Vec<f64> = (1..=1001).map(|i| 1e-6 * f64::from(i).powi(2)).collect();
        let range = Range {
            lo: values[0].log10(),
            hi: values[1000].log10(),
        };
        let mut s = Sketch::new(range);
        values.iter().for_each(|&v| s.push(v));
        assert_eq!((s.count, s.min, s.max), (1001, values[0], values[1000]));
        let exact = values[500].log10();
        let half_bin = 0.5 * (range.hi - range.lo) / SKETCH_BINS as f64;
        let median = s.median().unwrap().log10();
        assert!(
            (median - exact).abs() <= half_bin + 1e-12,
            "{median} {exact}"
        );
        assert_eq!(Sketch::new(range).median(), None);
    }

    /// A large sweep is held as its sample and summarised; a small experiment is held whole;
    /// the summary's counts, extremes, failures, axes, heat map and histogram are those of
    /// every row.
    #[test]
    fn a_large_sweep_is_held_as_its_sample_and_its_summary() {
        let mut rows: Vec<RunRow> = (0..5000)
            .map(|i| {
                let (mu, scale) = (i / 100, i % 100);
                let d = 1e-6 * (1.0 + mu as f64) * (1.0 + (scale as f64).sqrt());
                let label = format!("ZNN [mu={mu}, scale={scale}, mode=fast]");
                run(
                    i,
                    &label,
                    Some(d),
                    Some(1e-5 / (1.0 + i as f64)),
                    i % 331 == 7,
                )
            })
            .collect();
        let small_key = RunKey::parse("t / only / exact").unwrap();
        rows.push(RunRow::blank(&small_key, SolverKind::Exact));
        let (_dir, path) = scratch("large", &rows);
        let held = Held::read(&path, &|_| true).unwrap();
        assert_eq!(held.runs.all().len(), MAX_RUN_FIGURES + 1);
        assert_eq!(held.runs.of_experiment("t").count(), 1);
        let [s] = &held.sweeps[..] else {
            panic!("{:?}", held.sweeps.len())
        };
        assert_eq!((s.runs, s.failed, s.neural, s.sampled), (5000, 16, 0, 24));
        assert_eq!((s.left_out(), s.neural_left_out()), (5000 - 24, 0));
        assert_eq!(s.failures.len(), LISTED_FAILURES);
        assert_eq!(s.failures[0].variant_id.as_str(), "v00007");
        let at = |e: Extreme| s.extremes().find(|(x, _)| *x == e).unwrap().1;
        assert_eq!(at(Extreme::LargestDrift).variant_id.as_str(), "v04999");
        assert_eq!(at(Extreme::SmallestDrift).variant_id.as_str(), "v00000");
        // mu: 50 values, more than MAX_VALUES: intervals; scale: 100 values too; mode is not
        // numeric.
        assert_eq!(s.axes.len(), 2);
        assert_eq!(s.axes[0].intervals, Some((0.0, 49.0)));
        assert_eq!(s.heat.len(), MAX_VALUES * MAX_VALUES);
        let completed = 5000 - 16;
        assert_eq!(s.drawn_drift(), completed);
        let per_axis: usize = s.against[0].iter().map(|p| p.0.count).sum();
        assert_eq!(per_axis, completed);
        let cells: usize = s.heat.iter().map(|c| c.count).sum();
        assert_eq!(cells, completed);
        // The first interval of mu (width 49 / 40) holds mu = 0 and 1: its smallest drift is
        // the sweep's.
        assert_eq!(s.against[0][0].0.min, 1e-6);
    }

    /// Out of key order, the file is refused naming its line, as every reader of runs does.
    #[test]
    fn rows_out_of_key_order_are_refused() {
        let rows = vec![
            run(2, "x", None, None, false),
            run(1, "x", None, None, false),
        ];
        let (_dir, path) = scratch("unordered", &rows);
        let err = Held::read(&path, &|_| true).unwrap_err().to_string();
        assert!(err.contains("line 3"), "{err}");
    }
}
