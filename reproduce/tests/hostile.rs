//! Results that trust nothing they read, tried as an attacker or a careless user would: crafted
//! rows, an empty experiments directory, the user's own `*.tmp` files, symbolic links leading
//! out of the project, doctored journals, shards and CSVs, a truncated runs.csv, long ids,
//! huge thread counts and infinite budgets, and the argument checks that must come before
//! anything runs. Each case gives a clear error or a correct result, and nothing outside the
//! project is touched.

use crate::common;

use common::{ok, reproduce};
use records::{runs_csv, RunRow};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use store::read_runs;

/// [`common::CHEAP_EXPERIMENT`] with a second variant.
fn cheap() -> String {
    format!(
        "{}{}",
        common::CHEAP_EXPERIMENT,
        "[[experiment.variant]]\nlabel = \"ZNN mu=2\"\nscheme = { kind = \"kong2019-znn\", mu = 2.0, k_p = 1.0 }\n"
    )
}

/// A scratch project: `experiments/` with [`cheap`], `results/`, `report/`, and an
/// `outside/` directory that stands for the rest of the user's disk; removed when dropped.
struct Project {
    base: inputs::Scratch,
}

impl Project {
    fn new(name: &str) -> Self {
        let base = inputs::Scratch::dir(&format!("hostile-{name}"));
        std::fs::create_dir_all(base.join("experiments")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("experiments/kong2019.toml"), cheap()).unwrap();
        // What the report reads besides results/: the papers and the deviations.
        let repo = catalog::root_from_current_dir().unwrap();
        std::fs::create_dir_all(base.join("report")).unwrap();
        std::fs::copy(
            repo.join("report/deviations.md"),
            base.join("report/deviations.md"),
        )
        .unwrap();
        common::copy_tree(&repo.join("papers"), &base.join("papers"));
        Self { base }
    }
    fn experiments(&self) -> PathBuf {
        self.base.join("experiments")
    }
    fn results(&self) -> PathBuf {
        self.base.join("results")
    }
    fn outside(&self) -> PathBuf {
        self.base.join("outside")
    }
    /// `reproduce` on this project's experiments and results (the report beside them).
    fn run(&self) -> Command {
        let mut c = self.mode("run");
        c.arg("--skip-explain");
        c
    }
    /// The gate (`reproduce check`) on this project's experiments and results.
    fn check(&self) -> Command {
        self.mode("check")
    }
    /// `reproduce <mode>` on this project's experiments and results.
    fn mode(&self, mode: &str) -> Command {
        let mut c = reproduce();
        c.arg(mode)
            .arg("--experiments-dir")
            .arg(self.experiments())
            .arg("--results-dir")
            .arg(self.results());
        c
    }
    /// `reproduce` on other experiments and this project's results.
    fn run_with(&self, experiments: &Path) -> Command {
        let mut c = reproduce();
        c.arg("--skip-explain")
            .arg("--experiments-dir")
            .arg(experiments)
            .arg("--results-dir")
            .arg(self.results());
        c
    }
    /// `reproduce report` on this project's results.
    fn report_only(&self) -> Command {
        let mut c = reproduce();
        c.arg("report").arg("--results-dir").arg(self.results());
        c
    }
    /// A first, clean run: results/ sealed with its manifest.
    fn seeded(name: &str) -> Self {
        let p = Self::new(name);
        ok(p.run().output().unwrap());
        p
    }
    fn rows(&self) -> Vec<RunRow> {
        read_runs(&self.results().join("runs.csv")).unwrap()
    }
}

/// Exit 2 with `needle` in the error.
fn refused(out: Output, needle: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(needle), "expected {needle:?} in:\n{err}");
    err
}

fn write(path: &Path, bytes: &[u8]) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn a_crafted_row_cannot_name_a_file_outside_the_project() {
    let p = Project::seeded("crafted");
    let victim_dir = p.outside().join("somewhere");
    let victim = victim_dir.join("znn-eq-22__exact-clarabel.csv");
    write(&victim, b"precious");
    let honest = runs_csv(&p.rows()).unwrap();
    let mut reader = csv::Reader::from_reader(honest.as_slice());
    let column = reader
        .headers()
        .unwrap()
        .iter()
        .position(|h| h == "experiment")
        .unwrap();
    let first = reader.records().next().unwrap().unwrap();
    for experiment in [
        "../../outside/somewhere".to_string(),
        victim_dir.display().to_string(),
    ] {
        // A copy of the first row with its experiment id replaced (written as CSV text: the
        // row type cannot hold such an id).
        let mut crafted = csv::Writer::from_writer(honest.clone());
        let cells = first
            .iter()
            .enumerate()
            .map(|(i, c)| if i == column { experiment.as_str() } else { c });
        crafted.write_record(cells).unwrap();
        std::fs::write(p.results().join("runs.csv"), crafted.into_inner().unwrap()).unwrap();
        // Even with the edit accepted, the name is refused before it becomes a path.
        let err = refused(
            p.run()
                .arg("--accept-edited")
                .arg("--prune")
                .output()
                .unwrap(),
            "is not a slug",
        );
        assert!(err.contains("line"), "{err}");
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious", "{experiment}");
    }
}

#[test]
fn an_empty_or_wrong_experiments_directory_wipes_nothing() {
    let p = Project::seeded("empty");
    let before = std::fs::read(p.results().join("runs.csv")).unwrap();
    let empty = p.base.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    refused(
        p.run_with(&empty).output().unwrap(),
        "holds no experiment file",
    );
    // A directory with other experiments: every stored run would be pruned.
    let other = p.base.join("other");
    write(
        &other.join("kong2019.toml"),
        cheap()
            .replace("kong2019-cheap", "kong2019-other")
            .as_bytes(),
    );
    let err = refused(p.run_with(&other).output().unwrap(), "--prune");
    assert!(
        err.contains(&other.display().to_string()) && err.contains("2 of the 2"),
        "{err}"
    );
    assert_eq!(std::fs::read(p.results().join("runs.csv")).unwrap(), before);
    assert!(p.results().join("traces/kong2019-cheap").is_dir());
    // Said deliberately, it prunes, run by run.
    let out = ok(p.run_with(&other).arg("--prune").output().unwrap());
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("pruned kong2019-cheap / ").count(), 2, "{err}");
    assert!(p.rows().iter().all(|r| r.experiment == "kong2019-other"));
}

#[test]
fn the_users_tmp_files_are_left_alone() {
    let p = Project::seeded("tmp");
    let mine = [
        p.results().join("notes.tmp"),
        p.results().join("notes.2024.12.tmp"),
        p.results().join("traces/kong2019-cheap/backup.2025.1.tmp"),
        p.results().join("a/b/c/work.tmp"),
        p.base.join("report/draft.tmp"),
    ];
    for f in &mine {
        write(f, b"mine");
    }
    // A temporary file of the program's own, left by a killed write, goes: in results/, and
    // in report/ and its figures (a kill while the report was written, e.g. on a full disk).
    let stale = [
        p.results().join(".driftbench-tmp.99999.0.runs.csv"),
        p.base.join("report/.driftbench-tmp.99999.1.REPORT.md"),
        p.base
            .join("report/figures/.driftbench-tmp.99999.2.kong2019-cheap__znn-eq-22__exact.svg"),
    ];
    for f in &stale {
        write(f, b"half");
    }
    ok(p.run().output().unwrap());
    for f in &mine {
        assert_eq!(std::fs::read(f).unwrap(), b"mine", "{}", f.display());
    }
    for f in &stale {
        assert!(!f.exists(), "{} is left", f.display());
    }
    // `reproduce report` alone cleans report/ too.
    write(&stale[1], b"half");
    ok(p.report_only().output().unwrap());
    assert!(!stale[1].exists(), "left by reproduce report");
}

#[cfg(unix)]
#[test]
fn symbolic_links_leading_out_of_the_project_are_refused() {
    let p = Project::seeded("links");
    let outside_file = p.outside().join("znn-eq-22__exact-clarabel.csv");
    write(&outside_file, b"precious");
    let traces = p.results().join("traces/kong2019-cheap");
    std::fs::remove_dir_all(&traces).unwrap();
    std::os::unix::fs::symlink(p.outside(), &traces).unwrap();
    let err = refused(p.run().output().unwrap(), "leads outside");
    assert!(err.contains("symbolic link"), "{err}");
    assert_eq!(std::fs::read(&outside_file).unwrap(), b"precious");
    std::fs::remove_file(&traces).unwrap();

    let figures = p.base.join("report/figures");
    std::fs::remove_dir_all(&figures).unwrap();
    std::os::unix::fs::symlink(p.outside(), &figures).unwrap();
    let before: Vec<_> = std::fs::read_dir(p.outside()).unwrap().collect();
    refused(p.run().output().unwrap(), "leads outside");
    refused(p.report_only().output().unwrap(), "leads outside");
    let after: Vec<_> = std::fs::read_dir(p.outside()).unwrap().collect();
    assert_eq!(
        before.len(),
        after.len(),
        "nothing was written through the link"
    );
}

#[test]
fn a_truncated_or_edited_runs_csv_is_refused() {
    let p = Project::seeded("truncated");
    let path = p.results().join("runs.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let figures = std::fs::read_dir(p.base.join("report/figures"))
        .unwrap()
        .count();
    let cut = text.lines().take(2).collect::<Vec<_>>().join("\n") + "\n";
    for (what, bytes) in [
        ("cut at a row boundary", cut.into_bytes()),
        ("emptied", Vec::new()),
        (
            "a number changed",
            text.replacen(",0.", ",9.", 1).into_bytes(),
        ),
    ] {
        std::fs::write(&path, &bytes).unwrap();
        let err = refused(p.run().output().unwrap(), "--accept-edited");
        assert!(
            err.contains("runs.csv") && err.contains("manifest.toml"),
            "{what}: {err}"
        );
        assert_eq!(
            std::fs::read_dir(p.base.join("report/figures"))
                .unwrap()
                .count(),
            figures,
            "{what}: no figure deleted"
        );
        assert_eq!(
            std::fs::read(&path).unwrap(),
            bytes,
            "{what}: nothing written"
        );
    }
    // Without a manifest a results directory cannot be checked either.
    std::fs::write(&path, &text).unwrap();
    std::fs::remove_file(p.results().join("manifest.toml")).unwrap();
    refused(p.run().output().unwrap(), "no manifest.toml");
    // Said deliberate, the files are taken as they are and sealed again.
    ok(p.run().arg("--accept-edited").output().unwrap());
    ok(p.run().output().unwrap());
}

/// The journal of an interrupted run, `rows` written as the program writes them.
fn write_journal(p: &Project, rows: &[RunRow]) {
    let joints = rows.iter().map(|r| r.drift.len()).max().unwrap_or(0);
    let mut text = records::table::header::<RunRow>(joints).join(",") + "\n";
    for r in rows {
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        w.write_record(records::table::record(r, joints).unwrap())
            .unwrap();
        text.push_str(&String::from_utf8(w.into_inner().unwrap()).unwrap());
    }
    std::fs::write(store::journal::path(&p.results()), text).unwrap();
}

#[test]
fn a_journal_row_of_another_revision_is_not_folded() {
    let p = Project::seeded("journal");
    let honest = p.rows();
    let mut doctored = honest[0].clone();
    doctored.drift_norm = Some(9.99);
    doctored.git_rev = "0123456789ab".into();
    write_journal(&p, &[doctored]);
    let out = ok(p.run().output().unwrap());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not folded") && err.contains("0123456789ab"),
        "{err}"
    );
    assert!(!err.contains("folded 1 run"), "{err}");
    let after = p.rows();
    assert_eq!(
        after[0].drift_norm, honest[0].drift_norm,
        "the run was run again"
    );

    // A journal with one run twice is not one this program wrote.
    let rev = reproduce::REVISION.to_string();
    let mut twice = honest[0].clone();
    twice.git_rev = rev;
    write_journal(&p, &[twice.clone(), twice]);
    let before = std::fs::read(p.results().join("runs.csv")).unwrap();
    let err = refused(p.run().output().unwrap(), "listed twice");
    assert!(
        err.contains("journal.csv") && err.contains("line 3"),
        "{err}"
    );
    assert_eq!(std::fs::read(p.results().join("runs.csv")).unwrap(), before);
}

#[test]
fn a_long_id_is_refused_at_load_time() {
    let p = Project::new("long");
    let long = "L".repeat(309);
    std::fs::write(
        p.experiments().join("kong2019.toml"),
        cheap().replace("ZNN mu=2", &long),
    )
    .unwrap();
    let err = refused(p.run().output().unwrap(), "309 bytes long");
    assert!(err.contains("variant[1]") && err.contains("label"), "{err}");
    assert!(!p.results().join("runs.csv").exists());
}

#[test]
fn budgets_and_thread_counts_are_bounded_before_anything_runs() {
    let p = Project::new("bounds");
    refused(
        p.run().args(["--threads", "100000"]).output().unwrap(),
        "--threads 100000: at most",
    );
    for (from, to, needle) in [
        (
            "rtol = 1e-8, atol = 1e-10 }",
            "rtol = 1e-8, atol = 1e-10, max_wall_s = inf }",
            "max_wall_s must be positive and finite",
        ),
        (
            "exact_integrator =",
            "scoring = { max-instants = 0 }\nexact_integrator =",
            "max-instants must be at least 1",
        ),
    ] {
        std::fs::write(
            p.experiments().join("kong2019.toml"),
            cheap().replace(from, to),
        )
        .unwrap();
        refused(p.run().output().unwrap(), needle);
    }
    assert!(!p.results().join("runs.csv").exists());
}

#[test]
fn arguments_are_checked_before_anything_runs() {
    let p = Project::seeded("args");
    // A baseline that is a directory, or missing: said before any run, naming the right file.
    let err = refused(
        p.check()
            .arg("--baseline")
            .arg(p.results())
            .output()
            .unwrap(),
        "is a directory",
    );
    assert!(
        err.contains(&p.results().join("runs.csv").display().to_string()),
        "{err}"
    );
    refused(
        p.check()
            .arg("--baseline")
            .arg(p.base.join("absent.csv"))
            .output()
            .unwrap(),
        "absent.csv",
    );
    // A merge of a directory that does not exist.
    refused(
        reproduce()
            .arg("merge")
            .arg(p.base.join("no-such-shard"))
            .arg("--experiments-dir")
            .arg(p.experiments())
            .arg("--results-dir")
            .arg(p.results())
            .output()
            .unwrap(),
        "no such directory",
    );
    // Options a mode does not take, and the old mode flags, are refused, not silently ignored.
    for (pair, said) in [
        (
            ["explain", "--skip-explain"],
            "unexpected argument '--skip-explain'",
        ),
        (
            ["report", "--paper=kong2019"],
            "unexpected argument '--paper'",
        ),
        (["list", "--merge=x"], "unexpected argument '--merge'"),
        (["robots", "list"], "unexpected argument 'list'"),
        (["--list", "--robots"], "unexpected argument '--list'"),
    ] {
        let out = reproduce().args(pair).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{pair:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(said), "{pair:?}: {err}");
    }
}

#[test]
fn report_only_takes_the_lock() {
    let p = Project::seeded("report-lock");
    let lock = std::fs::OpenOptions::new()
        .write(true)
        .open(p.results().join(".lock"))
        .unwrap();
    lock.lock().unwrap();
    refused(
        p.report_only().output().unwrap(),
        "another reproduce is writing",
    );
}

mod shards {
    use super::*;

    /// Two shards of the cheap project, run.
    fn two_shards(p: &Project) -> [PathBuf; 2] {
        let dirs = [p.base.join("s1"), p.base.join("s2")];
        for (k, d) in dirs.iter().enumerate() {
            ok(reproduce()
                .arg("shard")
                .arg(format!("{}/2", k + 1))
                .arg("--experiments-dir")
                .arg(p.experiments())
                .arg("--results-dir")
                .arg(d)
                .output()
                .unwrap());
        }
        dirs
    }

    fn merge(p: &Project, dirs: &[PathBuf], extra: &[&str]) -> Output {
        reproduce()
            .arg("merge")
            .args(dirs)
            .args(extra)
            .arg("--experiments-dir")
            .arg(p.experiments())
            .arg("--results-dir")
            .arg(p.results())
            .output()
            .unwrap()
    }

    /// Shard 1 and 2 hold at least one row each for this project (checked).
    fn nonempty(d: &Path) -> Vec<RunRow> {
        let rows = read_runs(&d.join("runs.csv")).unwrap();
        assert!(!rows.is_empty(), "{} holds no run", d.display());
        rows
    }

    #[test]
    fn a_doctored_shard_is_refused() {
        let p = Project::new("shard-doctored");
        // Enough runs that both shards get some.
        let mut toml = cheap();
        for mu in 3..=6 {
            toml.push_str(&format!(
                "[[experiment.variant]]\nlabel = \"ZNN mu={mu}\"\nscheme = {{ kind = \"kong2019-znn\", mu = {mu}.0, k_p = 1.0 }}\n"
            ));
        }
        std::fs::write(p.experiments().join("kong2019.toml"), toml).unwrap();
        let dirs = two_shards(&p);
        let (r1, r2) = (nonempty(&dirs[0]), nonempty(&dirs[1]));
        let pristine: Vec<Vec<u8>> = dirs
            .iter()
            .map(|d| std::fs::read(d.join("runs.csv")).unwrap())
            .collect();

        // A drift edited by hand.
        let mut edited = r1.clone();
        edited[0].drift_norm = Some(9.99);
        std::fs::write(dirs[0].join("runs.csv"), runs_csv(&edited).unwrap()).unwrap();
        let err = refused(merge(&p, &dirs, &[]), "differ from what the shard wrote");
        assert!(err.contains("runs.csv"), "{err}");
        assert!(!p.results().join("runs.csv").exists(), "nothing written");
        std::fs::write(dirs[0].join("runs.csv"), &pristine[0]).unwrap();

        // A row moved to the shard that does not own it (the edit accepted, ownership is not).
        let mut moved = r2.clone();
        moved.push(r1[0].clone());
        moved.sort_by_key(RunRow::key);
        std::fs::write(dirs[1].join("runs.csv"), runs_csv(&moved).unwrap()).unwrap();
        let err = refused(
            merge(&p, &dirs, &["--accept-edited"]),
            "belongs to shard 1/2",
        );
        assert!(
            !p.results().join("runs.csv").exists(),
            "nothing written: {err}"
        );
        std::fs::write(dirs[1].join("runs.csv"), &pristine[1]).unwrap();

        // Shards of different code revisions.
        let manifest = dirs[1].join("shard.toml");
        let text = std::fs::read_to_string(&manifest).unwrap();
        let other = text
            .lines()
            .map(|l| {
                if l.starts_with("git_rev") {
                    "git_rev = \"another-revision\"".to_string()
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        std::fs::write(&manifest, other).unwrap();
        refused(merge(&p, &dirs, &[]), "different code revisions");
        std::fs::write(&manifest, text).unwrap();

        // A trace missing: refused before anything is written.
        let trace = store::results_dir::ResultsDir::trace_rel(&r1[0].key());
        let saved = std::fs::read(dirs[0].join(&trace)).unwrap();
        std::fs::remove_file(dirs[0].join(&trace)).unwrap();
        refused(merge(&p, &dirs, &[]), "missing");
        assert!(!p.results().join("runs.csv").exists());
        std::fs::write(dirs[0].join(&trace), saved).unwrap();

        // Put back as the shards wrote them, they merge.
        ok(merge(&p, &dirs, &[]));
        assert_eq!(p.rows().len(), r1.len() + r2.len());
    }
}
