//! The reproduction report, rendered from stored results only, as pages ([`pages`]):
//! `report/REPORT.md`, the front page (provenance, each paper's verdict and why in one line,
//! the leaderboard's top, the contents), `report/paper-<id>.md` per paper, and one page per
//! topic (`group.md`, `score.md`, `leaderboard.md`, `cost.md`, `performance.md`, `control.md`,
//! `cross.md`, `published.md`); the hand-written `report/deviations.md` is linked, not copied.
//!
//! Inputs: `results/runs.csv` (one row per run, read row by row into the runs the report
//! holds: every run of an experiment of at most 24 runs, of a larger one, a large sweep, its
//! sample of 24 and its summary; `analysis::sweep_summary`), `results/dof-cost.csv` (the cost against the
//! number of joints, when measured), `papers/<paper>/` (the papers'
//! published numbers), whether `report/deviations.md` (hand-written) is there, and the SVG
//! names in `report/figures/`. Nothing is re-run and nothing depends on the clock, so
//! identical inputs give a byte-identical report ([`render`] writes it atomically).
//!
//! Every text of `papers/` reaches the report through `shown` (escaped by
//! [`markdown::text`]): an input shows as text, never as Markdown structure or HTML.
//!
//! Layout (one concept per module):
//! - `header`: what this is, provenance (git revision, integrators, tolerances), how to regenerate;
//! - per paper (its page): the `verdict` paragraph, the published `tables` side by side with ours,
//!   the `claims` checklist, the suite's table of every run, and the [`figures`];
//! - the `score` of every neural run against the exact optimum;
//! - the `leaderboard`: every velocity-level solver on the standard task set, qpbenchmark-style;
//! - the `cost` of every run, and zhong2021's MATLAB comparison as ratios;
//! - `control`: every solver at a robot's control rate, zhong2021's efficiency claim, and
//!   many cycles (`results/control*.csv`, `results/cycles*.csv`), with their noise floor under
//!   the rounding-noise probe (`control_noise`);
//! - `performance`: per-instant costs against the exact solvers and the KKT floor, the exact
//!   reference per recorded QP against DAQP, the cost against the number of joints, whole runs
//!   against the MATLAB times, and the machine (the suite's measurements of itself, its build,
//!   clock, phases, profiles and speed-up, are the benches', `benches/REPORT.md`);
//! - [`python`]: the Python package's numpy entry on the leaderboard and the cost of a Python
//!   call (`results/leaderboard-python.csv`, `results/python-call-cost.csv`);
//! - the `cross` experiment matrices;
//! - the published numbers without a run (`records::paper_values`) and those the papers
//!   contradict.

mod claims;
mod control;
mod control_noise;
mod cost;
mod cross;
pub mod figures;
mod header;
mod leaderboard;
pub mod markdown;
mod performance;
pub mod python;
mod score;
mod shown;
mod sweep;
mod tables;
pub use tables::runs_table;
mod verdict;
mod why;

use crate::error::ReportError;
use analysis::cost_ratio::TimeRow;
use analysis::cross_best::ColumnBest;
use analysis::papers::{PaperValue, Papers};
use analysis::report_model::performance::Measured;
use analysis::report_model::why::Why as WhyModel;
use analysis::report_model::{ControlInputs, Explained, Inference, PaperModel, ReportModel};
use analysis::sweep_summary::{Held, SweepSummary};
use analysis::GROUP_PAPER;
use markdown::{sci, Table};
use records::index::Runs;
use std::path::{Path, PathBuf};
use store::table::read_if_present;

/// The figures' names in `report/figures/` and every large sweep's summary (the report
/// model's), what a page's figure links are made from.
type Figures<'a> = (&'a [String], &'a [SweepSummary]);

/// A paper's "why" (the report model's, none for a paper outside it), the stored explanations
/// and every inferred table, decided (the report model's): what the "why" sections are made
/// from.
type Why<'a, 'm> = (
    Option<&'a WhyModel<'m>>,
    (&'a why::Explanations, &'a [Inference<'m>]),
);

/// The `paper` value of the suite's own cross experiment.
pub const CROSS: &str = "cross";

/// Everything the report is rendered from.
#[derive(Clone, Debug)]
pub struct Inputs {
    /// The runs held of `results/runs.csv`: every run of an experiment of at most 24 runs, a
    /// large sweep's sample ([`Held`]).
    pub runs: Runs,
    /// Every large sweep's summary, aggregated as `results/runs.csv` was read.
    pub sweeps: Vec<SweepSummary>,
    /// `papers/`: each paper's metadata, published values and mappings.
    pub papers: Papers,
    /// Whether `report/deviations.md` (hand-written) is there: the front page links it.
    pub deviations: bool,
    /// SVG file names in `report/figures/`, sorted.
    pub figures: Vec<String>,
    /// Ladders, attribution and inference (`results/*.csv` beside runs.csv; absent = empty).
    pub explanations: why::Explanations,
    /// `results/leaderboard-timing.csv`: the compared runs timed alone (absent = empty).
    pub timings: records::Timings,
    /// `results/dof-cost.csv` (absent = empty).
    pub dof_cost: Vec<records::dof_cost::DofCostRow>,
    /// `results/qp-replay.csv` (absent = empty).
    pub qp_replay: Vec<records::QpReplayRow>,
    /// The control experiments' result files (absent = empty).
    pub control: control::ControlResults,
    /// The Python package's result files (absent = empty).
    pub python: python::PythonResults,
}

impl Inputs {
    /// Reads the inputs under the workspace root `root` (results/, report/) beside the runs
    /// the report holds, `held` (`analysis::sweep_summary::Held`, the figures' too), and the
    /// papers of `papers` (the project's `papers/`).
    pub fn load(root: &Path, papers: &Path, held: Held) -> Result<Self, ReportError> {
        let report = root.join("report");
        let results = root.join(store::results_dir::DIR);
        Ok(Inputs {
            runs: held.runs,
            sweeps: held.sweeps,
            papers: Papers::load(papers)?,
            deviations: report.join(DEVIATIONS).is_file(),
            figures: figures::list(&report.join("figures"))?,
            explanations: why::Explanations {
                ladder: read_if_present(&results.join(store::results_dir::LADDER))?,
                attribution: read_if_present(&results.join(store::results_dir::ATTRIBUTION))?,
                inference: read_if_present(&results.join(store::results_dir::INFERENCE))?,
                entries: read_if_present(&results.join(store::results_dir::INFERENCE_ENTRIES))?,
            },
            timings: store::timing::read(&results)?,
            dof_cost: store::dof_cost::read(&results)?,
            qp_replay: read_if_present(&results.join(records::QP_REPLAY_FILE))?,
            control: control::ControlResults::load(&results)?,
            python: python::PythonResults::load(&results)?,
        })
    }
}

/// One page of the report: its file under `report/` and its Markdown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Page {
    /// The file name (`REPORT.md`, `paper-<id>.md`, `leaderboard.md`, ...).
    pub file: String,
    /// The page.
    pub markdown: String,
}

/// The front page.
pub const FRONT: &str = "REPORT.md";

/// The prefix of a paper's page (`paper-jia2019.md`).
pub const PAPER_PAGE: &str = "paper-";

/// The file of `paper`'s page.
pub fn paper_page(paper: &str) -> String {
    format!("{PAPER_PAGE}{paper}.md")
}

/// Renders the report's pages under `root/report/` from `inputs`, the stored results loaded
/// ([`Inputs::load`]; a paper's page that no paper has any more is removed, if this program
/// wrote it and nobody edited it) and returns the front page's path.
pub fn render(root: &Path, inputs: &Inputs) -> Result<PathBuf, ReportError> {
    let report = store::TrackedDir::open_within(root, "report")?;
    let pages = pages(inputs);
    for listed in report.listed(PAPER_PAGE)? {
        if !pages.iter().any(|p| p.file == listed) {
            if let store::Removal::Kept(why) = report.remove(Path::new(&listed))? {
                eprintln!("note: {why}");
            }
        }
    }
    for page in &pages {
        report.write(Path::new(&page.file), page.markdown.as_bytes())?;
    }
    report.save()?;
    Ok(report.path().join(FRONT))
}

/// A topic page: `markdown`'s first `## ` heading made the page's title, a link back to the
/// front page above it.
fn topic(file: &str, markdown: String) -> Page {
    let markdown = match markdown.strip_prefix("## ") {
        Some(rest) => format!("# {rest}"),
        None => markdown,
    };
    Page {
        file: file.to_string(),
        markdown: format!("[← the report](REPORT.md)\n\n{markdown}"),
    }
}

/// The report's pages: the front page (verdicts, why in one line, the leaderboard's top,
/// links), one page per paper, and one per topic (the group's code, scores, leaderboard, cost,
/// performance, control, cross experiment, published numbers without a run or contradicted).
pub fn pages(inputs: &Inputs) -> Vec<Page> {
    let Inputs {
        runs,
        sweeps,
        papers,
        deviations,
        figures,
        explanations,
        timings,
        dof_cost,
        qp_replay,
        control,
        python,
    } = inputs;
    // Every text of papers/ escaped once, before any section shows it.
    let papers = &shown::papers(papers);
    // What the pages show that analysis decides, decided once.
    let measured = Measured {
        dof: dof_cost,
        qp_replay,
    };
    let model = ReportModel::build(
        runs,
        papers,
        timings,
        ControlInputs {
            runs: &control.runs,
            claims: &control.claims,
            stability: &control.stability,
            noise: &control.noise,
            trends: &control.trends,
        },
        Explained {
            attribution: &explanations.attribution,
            ladder: &explanations.ladder,
            inference: &explanations.inference,
        },
        measured,
        sweeps,
    );
    let inferred = &model.inference;
    let evaluated = &model.papers;
    let summaries = model.sweep_summaries;
    let mut head = header::header(runs, sweeps, papers, figures.len());
    head.push_str(&summary_section(evaluated, &model));
    let mut pages: Vec<Page> = evaluated
        .iter()
        .map(|e| {
            paper_page_of(
                e,
                runs,
                papers,
                (model.why_of(&e.id), (explanations, inferred)),
                (figures, summaries),
            )
        })
        .collect();
    let group = group_section(
        runs,
        (model.why_of(GROUP_PAPER), (explanations, inferred)),
        papers,
        (figures, summaries),
    );
    if !group.is_empty() {
        pages.push(topic("group.md", group));
    }
    pages.push(topic("score.md", score_page(runs, sweeps, papers)));
    let top = leaderboard::top(&model.leaderboard, FRONT_TOP);
    let board = leaderboard::section(&model.leaderboard, timings);
    if !board.is_empty() {
        pages.push(topic(
            "leaderboard.md",
            board + &python::leaderboard(&python.leaderboard),
        ));
    }
    pages.push(topic(
        "cost.md",
        cost_page(runs, sweeps, papers, &model.matlab_times),
    ));
    let mut out = performance::section(&model.performance, measured, runs, papers, figures);
    out.push_str(&python::call_cost(&python.call_cost));
    pages.push(topic("performance.md", out));
    let mut out = control::section(control, model.control_claim, &model.control, figures);
    out.push_str(&control::cycles_section(control, &model.control, figures));
    pages.push(topic("control.md", out));
    pages.push(topic(
        "cross.md",
        cross_page(runs, &model.cross, (figures, summaries)),
    ));
    pages.push(topic("published.md", published_page(runs, papers)));
    let front = front_page(head, &top, &pages, *deviations);
    std::iter::once(front).chain(pages).collect()
}

/// `## Summary` of the front page: per paper, its verdict, its claims by verdict, the range of
/// our magnitudes over the paper's (the model's `ratio_span`) and why in one line.
fn summary_section(evaluated: &[PaperModel], model: &ReportModel) -> String {
    use analysis::claim_verdict::Verdict;
    let mut summary = Table::new([
        "paper",
        "verdict",
        "claims PASS / FAIL / N/A",
        "ours ÷ paper's (counted)",
        "why, in one line",
    ]);
    for e in evaluated {
        let paper = e.id.as_str();
        let n = |v: Verdict| e.claims.iter().filter(|x| x.verdict == v).count();
        let decision = &e.decision;
        let range = match &e.ratio_span {
            Some((lo, hi)) => format!(
                "{} to {} ({} numbers)",
                sci(lo.1),
                sci(hi.1),
                decision.ratios.len()
            ),
            None => "no published magnitude counted".to_string(),
        };
        summary.push([
            format!("[{paper}]({})", paper_page(paper)),
            match decision.signs.n {
                0 => e.level.clone(),
                _ => format!("{} (signs agree in {})", e.level, decision.signs),
            },
            format!(
                "{} / {} / {}",
                n(Verdict::Pass),
                n(Verdict::Fail),
                n(Verdict::NotApplicable)
            ),
            range,
            model
                .why_of(paper)
                .map(why::one_line)
                .filter(|w| !w.is_empty())
                .unwrap_or_else(|| "no drift attribution of its solvers".to_string()),
        ]);
    }
    format!("## Summary\n\n{}\n", summary.render())
}

/// A paper's page: its title and citation, the verdict and why, the published tables side by
/// side with ours, the sweep checks, why the numbers differ, the claims, and every run with
/// its figures.
fn paper_page_of(
    e: &PaperModel,
    runs: &Runs,
    papers: &Papers,
    (model, explained): Why,
    (figures, summaries): Figures,
) -> Page {
    let (paper, title, c) = (e.id.as_str(), e.title.as_str(), &e.claims);
    let mut out = format!("[← the report](REPORT.md)\n\n# {paper}\n\n*{title}.*\n\n");
    let citation = papers.papers.iter().find(|p| p.id == *paper);
    if let Some(c) = citation.and_then(|p| p.citation.as_ref()) {
        out.push_str(&format!("Paper: {c}.\n\n"));
    }
    out.push_str(&verdict::paragraph(e));
    if let Some(model) = model {
        out.push_str(&why::summary(model, explained.1));
    }
    let tables: Vec<String> = e
        .tables
        .iter()
        .map(|t| tables::side_by_side(t, papers, runs))
        .collect();
    if !tables.is_empty() {
        out.push_str("\n### Published tables side by side\n\n");
        out.push_str(&tables.join("\n"));
    }
    out.push_str(&verdict::contradictions(&e.contradictions));
    for check in &e.sweeps {
        out.push_str(&sweep::section(check));
    }
    if let Some(model) = model {
        out.push_str(&why::section(model, explained, papers));
    }
    out.push_str("\n### Claims\n\n");
    out.push_str(&claims::checklist(c));
    out.push_str(if tables.is_empty() {
        "\n### Every run (the paper prints no table: this is the suite's)\n\n"
    } else {
        "\n### Every run\n\n"
    });
    for exp in runs.experiments(paper) {
        out.push_str(&format!(
            "#### `{exp}`\n\n{}",
            tables::runs_table(runs, summaries, &exp)
        ));
        out.push('\n');
        out.push_str(&figures::links(figures, runs, &exp, summaries));
    }
    Page {
        file: paper_page(paper),
        markdown: out,
    }
}

/// `## Score against the exact optimum`: per paper (and the cross experiment), every neural
/// run's score.
fn score_page(runs: &Runs, sweeps: &[SweepSummary], papers: &Papers) -> String {
    let mut out = format!("## Score against the exact optimum\n\n{}\n\n", score::NOTE);
    for paper in papers.papers.iter().map(|p| p.id.as_str()).chain([CROSS]) {
        let t = score::score_table(runs, sweeps, paper);
        if !t.is_empty() {
            out.push_str(&format!("### {paper}\n\n{t}\n"));
        }
    }
    out
}

/// `## Cost`: per paper (and the cross experiment), every run's effort, then the compute time
/// against the papers' MATLAB times (`times`).
fn cost_page(runs: &Runs, sweeps: &[SweepSummary], papers: &Papers, times: &[TimeRow]) -> String {
    let mut out = String::from("## Cost\n\nSteps, evaluations and QP solves are counted by the integrator and the scorer (the exact QP is solved at every RHS evaluation of the exact column and at every accepted step of a neural run). Wall times come from runs executed in parallel: compare them within one table, not across machines.\n\n");
    for paper in papers.papers.iter().map(|p| p.id.as_str()).chain([CROSS]) {
        out.push_str(&format!(
            "### {paper}\n\n{}\n",
            cost::cost_table(runs, sweeps, paper)
        ));
    }
    out.push_str(&format!(
        "### {}: compute time against the paper's MATLAB times\n\n",
        cost::timed_papers(papers)
    ));
    out.push_str(
        "Ours is `sim_s`: the wall time of the simulation proper (arm, network, integrator), \
         without the observation at accepted steps (metrics and the Clarabel solves that score \
         the run, which cost more than the networks themselves: ~50 us a solve against 0.3-3 us a \
         network evaluation). Absolute times are not comparable across machines and languages; \
         the ratios are.\n\n",
    );
    out.push_str(&cost::matlab_comparison(runs, times));
    out.push('\n');
    out
}

/// `## Cross experiment`: the matrices of every velocity-level solver on every velocity-level
/// scheme and path (their columns' `bests`), and the figures.
fn cross_page(runs: &Runs, bests: &[ColumnBest], (figures, summaries): Figures) -> String {
    let mut out = String::from("## Cross experiment\n\nEvery velocity-level solver on every velocity-level scheme and path (ids: ");
    out.push_str(
        &runs
            .experiments(CROSS)
            .iter()
            .map(|e| format!("`{e}`"))
            .collect::<Vec<_>>()
            .join(", "),
    );
    out.push_str("). Columns are scheme · path; a failed run shows its failure time.\n\n");
    out.push_str(&cross::section(runs, CROSS, bests));
    for exp in runs.experiments(CROSS) {
        out.push_str(&figures::links(figures, runs, &exp, summaries));
    }
    out
}

/// The published numbers without a run and those the papers contradict, each a table.
fn published_page(runs: &Runs, papers: &Papers) -> String {
    let mut out = String::from("## Published numbers without a run\n\n");
    let missing = papers.unmapped(runs);
    if missing.is_empty() {
        out.push_str("Every published number maps to a run.\n");
    } else {
        out.push_str(&values_table("value", missing).render());
    }
    out.push_str("\n## Published numbers the papers contradict\n\n");
    let contradicted: Vec<_> = papers
        .values
        .iter()
        .filter_map(|v| v.inconsistent.clone().map(|why| (v, why)))
        .collect();
    if contradicted.is_empty() {
        out.push_str("No published number contradicts its paper's own.\n");
    } else {
        out.push_str(
            "Checked at load (`analysis::papers::inconsistencies`): a norm below one of its own \
             entries, a negative norm, a number given twice. These are shown marked † in their \
             tables and no ratio, range or verdict is computed from them (a drift norm falls \
             back to the norm of the printed joints).\n\n",
        );
        out.push_str(&values_table("printed", contradicted).render());
    }
    out
}

/// Published values with a reason each (why they have no run, or why they contradict the
/// paper), as a table whose number column is headed `value_header`.
fn values_table(value_header: &str, values: Vec<(&PaperValue, String)>) -> Table {
    let mut t = Table::new([
        "paper",
        "table",
        "experiment",
        "column",
        "metric",
        value_header,
        "why",
    ]);
    for (v, why) in values {
        t.push([
            v.paper.clone(),
            v.table.clone(),
            v.experiment.clone(),
            v.column.clone(),
            v.metric.clone(),
            sci(v.value),
            why,
        ]);
    }
    t
}

/// How many solvers of the leaderboard the front page shows.
pub const FRONT_TOP: usize = 5;

/// The hand-written page of decisions, beside the report's pages.
pub const DEVIATIONS: &str = "deviations.md";

/// The front page: `head` (provenance and the summary), the leaderboard's `top`, and the
/// contents: every page, and the deviations (`report/deviations.md`, written by hand) where
/// they are.
fn front_page(head: String, top: &str, pages: &[Page], deviations: bool) -> Page {
    let mut out = head;
    if !top.is_empty() {
        out.push_str(&format!(
            "## Leaderboard, top {FRONT_TOP}\n\n{top}\nThe whole table, its definitions and \
             the other task sets: [leaderboard.md](leaderboard.md).\n\n"
        ));
    }
    out.push_str("## Contents\n\n");
    for page in pages {
        let title = page
            .markdown
            .lines()
            .find_map(|l| l.strip_prefix("# "))
            .unwrap_or(&page.file);
        out.push_str(&format!("- [{title}]({})\n", page.file));
    }
    if deviations {
        out.push_str(&format!(
            "- [Deviations and decisions]({DEVIATIONS}): every decision where a paper is silent \
             or contradicts itself (written by hand)\n"
        ));
    }
    Page {
        file: FRONT.to_string(),
        markdown: out,
    }
}

/// The group-code reference experiments (`experiments/group.toml`, docs/group-code.md):
/// every run, its attribution and ladder. Their numbers are the code's own metrics (drift and
/// max end-effector error), not published values.
fn group_section(
    runs: &Runs,
    (model, explained): Why,
    papers: &Papers,
    (figures, summaries): Figures,
) -> String {
    let group = GROUP_PAPER;
    let experiments = runs.experiments(group);
    if experiments.is_empty() {
        return String::new();
    }
    let mut out = String::from(
        "## The group's own code (reference experiment)\n\nThe only public code of this family (docs/group-code.md) computes a star (EXP1) and a butterfly (EXP2) with a zeroing network that has a growing-gain term -nu t E, the group's power-sigmoid and an injected perturbation, on the Jaco2 with the ZNN scheme of kong2019 (22) (k = 6 and 5, no joint limits, no feedback). We compute exactly what it describes, and switch each of its ingredients off in its own variant (nu = 0, no perturbation, linear activation, udot with and without the -k thetadot term, the butterfly closed), so each ingredient's share of the drift is measured, not guessed. These are not published numbers: the group's stored results are not part of the papers.\n\n",
    );
    for exp in &experiments {
        out.push_str(&format!(
            "#### `{exp}`\n\n{}",
            tables::runs_table(runs, summaries, exp)
        ));
        out.push('\n');
        out.push_str(&figures::links(figures, runs, exp, summaries));
    }
    if let Some(model) = model {
        out.push_str(&why::section(model, explained, papers));
    }
    out.push('\n');
    out
}
