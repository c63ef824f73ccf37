//! The report generator: renders from the committed results a front page and a page per paper
//! and topic; the committed pages are the ones they give (rendered into a scratch directory,
//! never over the committed files), are byte-stable,
//! evaluates claims from the numbers (a changed number flips a verdict), and maps every
//! published number that has a mapping onto an existing run.

use analysis::claim_verdict::{self as claims, Verdict};
use analysis::papers::Resolution;
use analysis::sweep_summary::Held;
use presentation::report::{pages, paper_page, render, Inputs, Page, FRONT};
use records::index::Runs;
use records::RunRow;
use std::path::Path;
use store::read_runs;

/// How to bring a stale committed report or figure up to date.
const REGENERATE: &str = "regenerate with `cargo run --release -p reproduce -- report`";

fn committed() -> Inputs {
    let root = catalog::root_from_current_dir().unwrap();
    let held = Held::read(&root.join("results/runs.csv"), &|_| true).unwrap();
    Inputs::load(&root, &root.join("papers"), held).expect("committed inputs load")
}

/// The page `file` of `pages`.
fn page<'a>(pages: &'a [Page], file: &str) -> &'a str {
    &pages
        .iter()
        .find(|p| p.file == file)
        .unwrap_or_else(|| panic!("no page {file}"))
        .markdown
}

/// Every page, one after the other.
fn whole(pages: &[Page]) -> String {
    pages.iter().map(|p| p.markdown.as_str()).collect()
}

#[test]
fn renders_every_paper_and_experiment_from_the_committed_results() {
    let root = catalog::root_from_current_dir().unwrap();
    let inputs = committed();
    let pages = pages(&inputs);
    let md = whole(&pages);
    assert!(inputs.papers.papers.len() >= 4);
    let front = page(&pages, FRONT);
    for paper in inputs.papers.papers.iter().map(|p| &p.id) {
        assert!(
            page(&pages, &paper_page(paper)).contains(&format!("\n# {paper}\n")),
            "no page for {paper}"
        );
        assert!(
            front.contains(&format!("[{paper}]({})", paper_page(paper))),
            "the front page does not link {paper}"
        );
    }
    // Every page is linked from the front page, and links back.
    for p in pages.iter().filter(|p| p.file != FRONT) {
        assert!(
            front.contains(&format!("]({})", p.file)),
            "{} not linked",
            p.file
        );
        assert!(
            p.markdown.starts_with("[← the report](REPORT.md)"),
            "{}",
            p.file
        );
    }
    let rows = read_runs(&root.join("results/runs.csv")).unwrap();
    for r in &rows {
        assert!(
            md.contains(r.experiment.as_str()),
            "experiment {} missing from the report",
            r.experiment
        );
    }
    for (file, heading) in [
        ("score.md", "# Score against the exact optimum"),
        ("leaderboard.md", "# Leaderboard"),
        ("cost.md", "# Cost"),
        ("cross.md", "# Cross experiment"),
        ("published.md", "# Published numbers without a run"),
        ("control.md", "# At a robot's control rate"),
        ("control.md", "### The efficiency claim: "),
        ("control.md", "### Leaderboard: control rate"),
        ("control.md", "## Many cycles"),
        ("group.md", "# The group's own code (reference experiment)"),
        (FRONT, "## Leaderboard, top 5"),
    ] {
        assert!(
            page(&pages, file).contains(heading),
            "{file}: missing {heading}"
        );
    }
    assert!(front.contains("[Deviations and decisions](deviations.md)"));
    assert!(root.join("report/deviations.md").is_file());
}

/// A scratch project root holding copies of what the report is rendered from: the files directly
/// in `results/` and in `report/` (but `REPORT.md`), and in `report/figures/` an empty file of
/// each SVG's name (the report lists the names only).
fn scratch_copy_of_the_inputs(committed: &Path) -> inputs::Scratch {
    let root = inputs::Scratch::dir("report");
    for dir in ["results", "report"] {
        std::fs::create_dir_all(root.join(dir)).unwrap();
        for entry in std::fs::read_dir(committed.join(dir)).unwrap() {
            let entry = entry.unwrap();
            if entry.file_type().unwrap().is_file() && entry.file_name() != "REPORT.md" {
                std::fs::copy(entry.path(), root.join(dir).join(entry.file_name())).unwrap();
            }
        }
    }
    std::fs::create_dir_all(root.join("report/figures")).unwrap();
    for entry in std::fs::read_dir(committed.join("report/figures")).unwrap() {
        let name = entry.unwrap().file_name();
        if name.to_string_lossy().ends_with(".svg") {
            std::fs::write(root.join("report/figures").join(name), "").unwrap();
        }
    }
    root
}

/// Every committed page of the report is byte for byte the page the committed results give:
/// rendered into a scratch directory, so a stale committed page fails (the test never writes
/// the committed files).
#[test]
fn the_committed_report_is_the_one_the_committed_results_give() {
    let committed_root = catalog::root_from_current_dir().unwrap();
    let scratch = scratch_copy_of_the_inputs(&committed_root);
    let held = Held::read(&scratch.join("results/runs.csv"), &|_| true).unwrap();
    let inputs = Inputs::load(&scratch, &committed_root.join("papers"), held).expect("inputs load");
    let path = render(&scratch, &inputs).expect("report renders");
    assert!(
        path.starts_with(&scratch),
        "rendered outside the scratch root"
    );
    let files = pages(&committed()).into_iter().map(|p| p.file);
    let read = |root: &Path, file: &str| std::fs::read_to_string(root.join("report").join(file));
    let compared: Vec<(String, String, String)> = files
        .map(|file| {
            let committed = read(&committed_root, &file)
                .unwrap_or_else(|_| panic!("report/{file} is not committed; {REGENERATE}"));
            (read(&scratch, &file).unwrap(), committed, file)
        })
        .collect();
    drop(scratch);
    for (rendered, committed, file) in compared {
        check_page(&file, &rendered, &committed);
    }
}

/// Fails naming the first line where `rendered` and `committed` of `file` differ.
fn check_page(file: &str, rendered: &str, committed: &str) {
    if rendered != committed {
        let line = rendered
            .lines()
            .zip(committed.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(rendered.lines().count().min(committed.lines().count()));
        panic!(
            "report/{file} is stale: it differs from the page the committed results give \
             from line {} on\n  committed: {:?}\n  rendered:  {:?}\n{REGENERATE}",
            line + 1,
            committed.lines().nth(line).unwrap_or("(end of file)"),
            rendered.lines().nth(line).unwrap_or("(end of file)"),
        );
    }
}

#[test]
fn rendering_twice_gives_identical_bytes() {
    let first = pages(&committed());
    let second = pages(&committed());
    assert_eq!(first, second);
}

#[test]
fn every_mapped_published_number_finds_its_run() {
    let inputs = committed();
    let papers = &inputs.papers;
    let mut mapped = 0;
    for v in &papers.values {
        if papers.mapping_of(v).is_some() {
            match papers.resolve(v, &inputs.runs) {
                Resolution::Found { .. } => mapped += 1,
                Resolution::Unmapped(why) if why.contains("does not record") => {}
                Resolution::Unmapped(why) => panic!(
                    "{} {} {} {}: {why}",
                    v.paper, v.table, v.experiment, v.column
                ),
            }
        }
    }
    assert!(mapped > 100, "only {mapped} published numbers mapped");
    let pages = pages(&inputs);
    let section = page(&pages, "published.md");
    assert!(
        section.contains("all-vltco") && section.contains("error_norm_settle_s"),
        "unmapped numbers not listed"
    );
}

/// A completed run with the given drift norm (everything else neutral); variant and solver are
/// ids.
fn row(experiment: &str, variant: &str, solver: &str, drift: f64) -> RunRow {
    let kind = if solver == records::index::EXACT {
        spec::SolverKind::Exact
    } else {
        spec::SolverKind::Network(settings::NetworkKind::LviPdnn)
    };
    RunRow {
        paper: "jia2019".into(),
        path: "four-leaf-clover".into(),
        drift: vec![drift, 0.0, 0.0, 0.0, 0.0, drift],
        drift_norm: Some(drift),
        drift_ref_norm: Some(drift),
        max_pos_err: Some(1e-6),
        rms_pos_err: Some(1e-6),
        final_pos_err: Some(1e-6),
        theta_margin: Some(0.5),
        thetadot_margin: Some(0.1),
        peak_thetadot: Some(1.4),
        min_sigma_j: Some(0.2),
        steps: 1,
        rhs_evals: 1,
        qp_solves: 1,
        wall_s: 0.1,
        sim_s: 0.1,
        ..RunRow::blank(
            &spec::RunKey::from_ids(experiment, variant, solver).unwrap(),
            kind,
        )
    }
}

fn synthetic() -> Vec<RunRow> {
    vec![
        row("jia2019-clover", "mvn", "lvi-pdnn", 0.3),
        row("jia2019-clover", "mvn", "exact", 0.3),
        row("jia2019-clover", "mvn-invm", "lvi-pdnn", 0.1),
        row("jia2019-clover", "vltco", "lvi-pdnn", 1e-3),
        row("jia2019-clover", "mvn-jaco2-hand", "exact", 0.0),
    ]
}

/// jia2019's claims (`papers/jia2019/paper.toml`) on `rows`.
fn verdicts(rows: Vec<RunRow>) -> Vec<(String, Verdict)> {
    let root = catalog::root_from_current_dir().unwrap();
    let papers = analysis::papers::Papers::load(&root.join("papers")).unwrap();
    claims::evaluate("jia2019", &Runs::new(rows), &papers)
        .into_iter()
        .map(|c| (c.short, c.verdict))
        .collect()
}

#[test]
fn claims_pass_on_synthetic_rows_and_fail_when_a_number_changes() {
    let all_pass = verdicts(synthetic());
    assert!(
        all_pass.iter().all(|(_, v)| *v == Verdict::Pass),
        "{all_pass:?}"
    );

    // VLTCO's drift no longer 10x below MVN-INVM's: exactly the ordering claim fails.
    let mut rows = synthetic();
    rows[3].drift_norm = Some(0.02);
    let changed = verdicts(rows);
    for ((short, before), (_, after)) in all_pass.iter().zip(&changed) {
        let expected = if short == "drift(VLTCO) << drift(MVN-INVM)" {
            Verdict::Fail
        } else {
            *before
        };
        assert_eq!(*after, expected, "{short}");
    }

    // A velocity bound crossed by 1e-6 rad/s fails the limits claims.
    let mut rows = synthetic();
    rows[0].thetadot_margin = Some(-1e-6);
    let changed = verdicts(rows);
    assert!(
        changed
            .iter()
            .any(|(s, v)| s == "joint velocities inside their limits" && *v == Verdict::Fail),
        "{changed:?}"
    );

    // A missing run makes a claim N/A, never PASS.
    let mut rows = synthetic();
    rows.retain(|r| r.variant_id != "mvn-jaco2-hand");
    let changed = verdicts(rows);
    assert!(
        changed
            .iter()
            .any(|(s, v)| s == "jaco2-hand leaves joint 6 still" && *v == Verdict::NotApplicable),
        "{changed:?}"
    );
}

/// A `than` claim over every pair of runs is cut at `claims::MAX_PAIRS` pairs: N/A, saying
/// so, in bounded time and memory (a paper holds at most `MAX_CLAIMS` such claims).
#[test]
fn a_claim_over_too_many_pairs_of_runs_is_not_applicable() {
    use analysis::claims::{Check, Selection, Test};
    let root = catalog::root_from_current_dir().unwrap();
    let mut papers = analysis::papers::Papers::load(&root.join("papers")).unwrap();
    let every = Selection::parse("* / * / *").unwrap();
    let jia = papers
        .papers
        .iter_mut()
        .find(|p| p.id == "jia2019")
        .unwrap();
    jia.claims.truncate(1);
    jia.claims[0].check = Check::Compare {
        metric: "drift_norm".into(),
        abs: false,
        runs: every.clone(),
        test: Test::Than {
            other: every,
            factor: None,
        },
    };
    let n = 150; // 150^2 pairs in one experiment, above MAX_PAIRS
    assert!(n * n > claims::MAX_PAIRS);
    let rows = (0..n)
        .map(|i| row("jia2019-clover", &format!("v{i}"), "lvi-pdnn", 0.1))
        .collect();
    let out = claims::evaluate("jia2019", &Runs::new(rows), &papers);
    assert_eq!(out[0].verdict, Verdict::NotApplicable, "{:?}", out[0]);
    assert!(
        out[0].evidence.contains("pairs of runs"),
        "{}",
        out[0].evidence
    );
    let rows = (0..10)
        .map(|i| row("jia2019-clover", &format!("v{i}"), "lvi-pdnn", 0.1))
        .collect();
    let out = claims::evaluate("jia2019", &Runs::new(rows), &papers);
    assert_ne!(out[0].verdict, Verdict::NotApplicable, "{:?}", out[0]);
}

/// Verdicts do not depend on machine load: scaling every run's timing columns by its own factor
/// (0.3x to 3.3x) leaves every claim's verdict as it was.
#[test]
fn verdicts_do_not_depend_on_timing() {
    let inputs = committed();
    let verdicts = |rows: Vec<RunRow>| -> Vec<(String, Verdict)> {
        let runs = Runs::new(rows);
        inputs
            .papers
            .papers
            .iter()
            .flat_map(|p| claims::evaluate(&p.id, &runs, &inputs.papers))
            .map(|c| (c.short, c.verdict))
            .collect()
    };
    let before = verdicts(inputs.runs.all().to_vec());
    let mut noisy = inputs.runs.all().to_vec();
    for (i, r) in noisy.iter_mut().enumerate() {
        let f = 0.3 + (i % 7) as f64 * 0.5;
        r.wall_s *= f;
        r.sim_s *= f;
        r.observe_s *= f;
    }
    assert_eq!(before, verdicts(noisy));
}

/// The committed report explains every paper with a published table and has the group-code
/// section, from the committed ladder, attribution and inference results.
#[test]
fn the_report_explains_every_paper_with_a_table() {
    let pages = pages(&committed());
    for paper in ["jia2019", "zhong2021", "kong2019", "zhang2018"] {
        let section = page(&pages, &paper_page(paper));
        assert!(section.contains("### Why the numbers differ"), "{paper}");
        assert!(section.contains("#### Drift attribution"), "{paper}");
        assert!(section.contains("#### Tolerance ladder"), "{paper}");
    }
    for paper in ["jia2019", "zhong2021", "kong2019"] {
        assert!(
            page(&pages, &paper_page(paper)).contains("inferred setup (fitted to the paper)"),
            "{paper}"
        );
    }
    assert!(page(&pages, "group.md").contains("# The group's own code (reference experiment)"));
}

/// Every claim `papers/` leaves to Rust names one that exists, with its reason; every data
/// claim of the committed papers is decided (PASS or FAIL) on the committed results.
#[test]
fn every_claim_of_the_papers_is_implemented_and_decided() {
    let inputs = committed();
    let mut data = 0;
    for p in &inputs.papers.papers {
        for c in &p.claims {
            match &c.check {
                analysis::claims::Check::Rust { id, why, .. } => {
                    assert!(
                        analysis::claims::RUST_CLAIMS.contains(&id.as_str()),
                        "{}: {id}",
                        p.id
                    );
                    assert!(!why.is_empty());
                }
                analysis::claims::Check::Compare { .. } => data += 1,
            }
        }
        for c in claims::evaluate(&p.id, &inputs.runs, &inputs.papers) {
            assert_ne!(
                c.verdict,
                Verdict::NotApplicable,
                "{}: {} — {}",
                p.id,
                c.short,
                c.evidence
            );
        }
    }
    assert!(data >= 20, "only {data} claims are data");
}

/// The control page names the numerical methods the results hold, and no other: OSQP only
/// where its rows are (a build with the `osqp` feature).
#[test]
fn the_control_page_names_the_numerical_methods_of_its_results() {
    let inputs = committed();
    let pages = pages(&inputs);
    let control = page(&pages, "control.md");
    let Some((_, rest)) = control.split_once("these results have ") else {
        assert!(inputs.control.runs.is_empty(), "{control}");
        return;
    };
    let (_, listed) = rest.split_once(": ").expect("a count, then the methods");
    let listed: Vec<&str> = listed
        .split_once(". ")
        .expect("the list ends its sentence")
        .0
        .split(", ")
        .collect();
    let mut held: Vec<&str> = inputs
        .control
        .runs
        .iter()
        .filter(|r| r.family == records::control::Family::Numerical)
        .map(|r| r.method.as_str())
        .collect();
    held.dedup();
    let mut sorted = listed.clone();
    sorted.sort_unstable();
    held.sort_unstable();
    held.dedup();
    assert_eq!(sorted, held, "{control}");
    assert_eq!(
        listed.contains(&"OSQP"),
        held.contains(&"OSQP"),
        "{control}"
    );
}

/// The columns of a Markdown table line (`|`-separated, escaped `\|` inside a cell not
/// counted).
fn columns(line: &str) -> usize {
    line.replace("\\|", "")
        .matches('|')
        .count()
        .saturating_sub(1)
}

/// No page of the report, rendered or hand-written (every `report/*.md`), has a table wider
/// than `MAX_COLUMNS` columns: a person reads it on a screen.
#[test]
fn no_table_of_any_page_is_wider_than_twelve_columns() {
    use presentation::report::markdown::MAX_COLUMNS;
    assert_eq!(MAX_COLUMNS, 12);
    let root = catalog::root_from_current_dir().unwrap();
    let mut pages: Vec<(String, String)> = pages(&committed())
        .into_iter()
        .map(|p| (p.file, p.markdown))
        .collect();
    for entry in std::fs::read_dir(root.join("report")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let file = path.file_name().unwrap().to_string_lossy().into_owned();
            pages.push((file, std::fs::read_to_string(&path).unwrap()));
        }
    }
    let wide: Vec<String> = pages
        .iter()
        .flat_map(|(file, md)| {
            md.lines()
                .enumerate()
                .filter(|(_, l)| l.starts_with('|') && columns(l) > MAX_COLUMNS)
                .map(move |(i, l)| format!("{file}:{}: {} columns", i + 1, columns(l)))
        })
        .collect();
    assert!(
        wide.is_empty(),
        "tables wider than {MAX_COLUMNS} columns: {wide:?}"
    );
    assert_eq!(columns("| a | b \\| c | d |"), 3);
}

/// Every sweep check that names its declared setup (robio2018's star: the setup sweep of
/// experiments/robio2018.toml) states on its paper's page the setup's share of the gap, and
/// the share printed is the one crate analysis computes from the committed runs.
#[test]
fn a_sweep_with_its_declared_setup_states_the_share_of_the_gap_from_the_runs() {
    use analysis::sweep_comparison::{setup_share, swept_runs};
    let inputs = committed();
    let pages = pages(&inputs);
    let mut stated = 0;
    for check in inputs
        .papers
        .sweep_checks
        .iter()
        .filter(|c| c.declared.is_some())
    {
        let swept = swept_runs(check, &inputs.runs, &inputs.papers);
        let share = setup_share(check, &swept).unwrap_or_else(|| {
            panic!(
                "{}: the declared setup and another swept setup have completed runs in results/runs.csv",
                check.experiment
            )
        });
        let text = page(&pages, &paper_page(&check.paper));
        let line = format!(
            "carries {:.0} % of the gap on a log scale",
            100.0 * share.share
        );
        assert!(
            text.contains(&line) && text.contains("**The setup's share of the gap.**"),
            "{}: no \"{line}\"",
            check.experiment
        );
        stated += 1;
    }
    assert!(stated >= 1, "no sweep check names its declared setup");
}

/// A per-run table of a large sweep shows the runs its figures draw (the sample the report
/// holds of it), at most MAX_RUN_FIGURES, and says how many it left out; a small
/// experiment's shows every run and says nothing.
#[test]
fn a_large_sweeps_tables_are_bounded() {
    use analysis::sweep_summary::Held;
    use presentation::figures::sweep::MAX_RUN_FIGURES;
    use presentation::report::runs_table;
    let mut rows: Vec<RunRow> = (0..1000)
        .map(|i| row("jia2019-sweep", &format!("v-{i}"), "exact", 1e-3 * i as f64))
        .collect();
    rows.extend((0..5).map(|i| row("jia2019-small", &format!("v-{i}"), "exact", 0.1)));
    rows.sort_by_key(RunRow::key);
    let dir = inputs::Scratch::dir("large-tables");
    let path = dir.join("runs.csv");
    std::fs::write(&path, records::runs_csv(&rows).unwrap()).unwrap();
    let Held { runs, sweeps } = Held::read(&path, &|_| true).unwrap();
    drop(dir);
    assert_eq!(
        runs.all().len(),
        MAX_RUN_FIGURES + 5,
        "the sample and the small one"
    );
    let data_rows = |table: &str| table.lines().filter(|l| l.starts_with("| v-")).count();
    let large = runs_table(&runs, &sweeps, "jia2019-sweep");
    assert_eq!(data_rows(&large), MAX_RUN_FIGURES, "{large}");
    assert!(
        large.contains(&format!("{} more run(s)", 1000 - MAX_RUN_FIGURES)),
        "{large}"
    );
    // Its extremes are among the runs shown.
    assert!(
        large.contains("| v-0 |") && large.contains("| v-999 |"),
        "{large}"
    );
    let small = runs_table(&runs, &sweeps, "jia2019-small");
    assert_eq!(data_rows(&small), 5, "{small}");
    assert!(!small.contains("more run(s)"), "{small}");
}
