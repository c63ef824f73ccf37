//! Every reader of outside input, given what a hostile pull request or a careless user puts in
//! its place: a symbolic link to a secret outside the project (and to `/proc/self/environ`),
//! `/dev/zero`, a FIFO and a file over its cap, as an experiment file, a `paper.toml` or
//! `values.csv`, a trajectory to score (CSV and MAT-file), a `--baseline` and a shard's
//! `shard.toml`. Each is refused with exit code 2, the path and the rule, before anything
//! runs; no process hangs (each is killed after [`TIMEOUT`] and the test fails), and no error
//! shows the secret.

#![cfg(unix)]

use crate::common;

use common::reproduce;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

const CANARY: &str = "CANARY_SECRET_5d1c9a";
/// A hang guard, not a speed target: a process that blocks on its input never ends, while a
/// loaded machine (CI with other jobs, eight test binaries at once) only slows the bounded
/// runs. Boundedness itself is checked by the budgets the messages name.
const TIMEOUT: Duration = Duration::from_secs(900);
const TASK: &str = "kong2019-cheap / znn";

/// A scratch project (`experiments/` with [`common::CHEAP_EXPERIMENT`], its variant given the
/// id `znn`; `papers/` copied from the workspace; `report/`) beside `outside/secret`, which
/// stands for a secret elsewhere on the disk; removed when dropped.
struct Project {
    base: inputs::Scratch,
}

impl Project {
    fn new(name: &str) -> Self {
        let p = Project {
            base: inputs::Scratch::dir(&format!("hostile-inputs-{name}")),
        };
        std::fs::create_dir_all(p.root().join("experiments")).unwrap();
        std::fs::create_dir_all(p.root().join("report")).unwrap();
        std::fs::create_dir_all(p.base.join("outside")).unwrap();
        std::fs::write(p.secret(), format!("TOKEN={CANARY}\nmore = \"{CANARY}\"\n")).unwrap();
        let experiment = common::CHEAP_EXPERIMENT.replace(
            "label = \"ZNN (eq. 22)\"",
            "label = \"ZNN (eq. 22)\"\nid = \"znn\"",
        );
        std::fs::write(p.experiments().join("kong2019.toml"), experiment).unwrap();
        common::copy_tree(
            &common::repo_root().join("papers"),
            &p.root().join("papers"),
        );
        p
    }
    fn root(&self) -> PathBuf {
        self.base.join("project")
    }
    fn experiments(&self) -> PathBuf {
        self.root().join("experiments")
    }
    fn results(&self) -> PathBuf {
        self.root().join("results")
    }
    fn secret(&self) -> PathBuf {
        self.base.join("outside/secret")
    }
    /// `reproduce` on this project.
    fn cmd(&self) -> Command {
        let mut c = reproduce();
        c.arg("--root")
            .arg(self.root())
            .arg("--results-dir")
            .arg(self.results())
            .env("DRIFTBENCH_TEST_CANARY", CANARY);
        c
    }
}

/// What each hostile file is, made at a path.
#[derive(Clone, Copy, Debug)]
enum Hostile {
    /// A link to the secret outside the project.
    LinkOutside,
    /// A link to `/proc/self/environ` (the process's environment holds the canary).
    Environ,
    /// A link to `/dev/zero`.
    DevZero,
    Fifo,
    /// A sparse file one byte over the cap.
    Oversize(u64),
}

impl Hostile {
    fn make(self, p: &Project, at: &Path) {
        let _ = std::fs::remove_file(at);
        std::fs::create_dir_all(at.parent().unwrap()).unwrap();
        match self {
            Hostile::LinkOutside => std::os::unix::fs::symlink(p.secret(), at).unwrap(),
            Hostile::Environ => std::os::unix::fs::symlink("/proc/self/environ", at).unwrap(),
            Hostile::DevZero => std::os::unix::fs::symlink("/dev/zero", at).unwrap(),
            Hostile::Fifo => {
                let c = std::ffi::CString::new(at.as_os_str().as_encoded_bytes()).unwrap();
                assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
            }
            Hostile::Oversize(cap) => std::fs::File::create(at).unwrap().set_len(cap + 1).unwrap(),
        }
    }
    /// What the refusal says.
    fn needle(self) -> &'static str {
        match self {
            Hostile::LinkOutside | Hostile::Environ | Hostile::DevZero => "leads outside",
            Hostile::Fifo => "is a FIFO, not a regular file",
            Hostile::Oversize(_) => "larger than its cap",
        }
    }
}

/// Every hostile file, with `cap` the cap of the kind it stands for.
fn all(cap: inputs::Kind) -> [Hostile; 5] {
    [
        Hostile::LinkOutside,
        Hostile::Environ,
        Hostile::DevZero,
        Hostile::Fifo,
        Hostile::Oversize(cap.cap()),
    ]
}

/// Runs `cmd` to its end, killing it (and failing) after [`TIMEOUT`].
fn bounded(mut cmd: Command) -> Output {
    let mut child = cmd
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > TIMEOUT {
            child.kill().unwrap();
            let _ = child.wait();
            panic!("the process did not end within {TIMEOUT:?}: it blocks on its input");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Exit 2 naming `path` and the rule of `hostile`, without the canary.
fn refused(out: Output, hostile: Hostile, path: &Path) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{hostile:?}: {err}");
    assert!(err.contains(hostile.needle()), "{hostile:?}: {err}");
    let name = path.file_name().unwrap().to_string_lossy();
    assert!(err.contains(name.as_ref()), "{hostile:?}: {err}");
    assert!(!err.contains(CANARY), "{hostile:?} shows the secret: {err}");
    assert!(!String::from_utf8_lossy(&out.stdout).contains(CANARY));
}

#[test]
fn experiment_files_are_read_as_inputs() {
    let p = Project::new("experiments");
    let at = p.experiments().join("evil.toml");
    for h in all(inputs::Kind::Experiment) {
        h.make(&p, &at);
        let mut list = p.cmd();
        list.arg("list");
        refused(bounded(list), h, &at);
    }
}

#[test]
fn papers_are_read_as_inputs_before_anything_runs() {
    let p = Project::new("papers");
    let folder = p.root().join("papers/kong2019");
    for (file, kind) in [
        ("paper.toml", inputs::Kind::PaperToml),
        ("values.csv", inputs::Kind::PaperValues),
    ] {
        let at = folder.join(file);
        let original = std::fs::read(&at).unwrap();
        for h in all(kind) {
            h.make(&p, &at);
            let mut run = p.cmd();
            run.arg("--skip-explain");
            refused(bounded(run), h, &at);
            assert!(!p.results().join("runs.csv").exists(), "{h:?}: it ran");
        }
        std::fs::remove_file(&at).unwrap();
        std::fs::write(&at, original).unwrap();
    }
}

#[test]
fn a_malformed_paper_is_refused_before_anything_runs() {
    let p = Project::new("malformed");
    let at = p.root().join("papers/kong2019/paper.toml");
    let original = std::fs::read_to_string(&at).unwrap();
    for (edit, needle) in [
        (
            original.replacen("metric = \"", "metric = \"x", 1),
            "unknown metric \"x",
        ),
        (
            original.replacen("title = \"", "title = \"a\\n## Summary\\n<script>", 1),
            "field `title`: must be one line",
        ),
        (
            format!("{original}\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"c\"\nrun = \"a / b / c\"\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"c\"\nrun = \"a / b / d\"\n"),
            "is already mapped by mapping[",
        ),
        // A typo in a run of an experiment the files define: the valid choices are named.
        (
            format!("{original}\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"typo\"\nrun = \"kong2019-cheap / zn / exact\"\n"),
            "field `run`: no run \"kong2019-cheap / zn / exact\" in the experiment files (valid variants of kong2019-cheap: znn)",
        ),
        (
            format!("{original}\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"typo\"\nrun = \"kong2019-cheap / znn / exact\"\ncompanions = [\"znn / exakt\"]\n"),
            "field `companions`: no run \"kong2019-cheap / znn / exakt\" in the experiment files (valid solvers of kong2019-cheap / znn: exact",
        ),
        (
            format!("{original}\n[[claim]]\nshort = \"s\"\ntext = \"t\"\nmetric = \"drift_norm\"\nruns = \"kong2019-cheap / zzz-* / *\"\nbelow = 1.0\n"),
            "field `runs`: selects no run of the experiment files",
        ),
        (
            format!("{original}{}", "\n[[claim]]\nshort = \"s\"\ntext = \"t\"\nrust = \"diverges\"\nwhy = \"w\"\n".repeat(201)),
            "claims: at most 200 per paper",
        ),
        // Every list a file can grow is capped.
        (
            format!("{original}\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"c\"\nrun = \"kong2019-cheap / znn / exact\"\ncompanions = [{}]\n", vec!["\"znn\""; 51].join(", ")),
            "mapping[3] field `companions`: 51 entries, at most 50",
        ),
        (
            format!("{original}{}", (0..501).map(|i| format!("\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"c{i}\"\nrun = \"kong2019-cheap / znn / exact\"\n")).collect::<String>()),
            "504 mappings: at most 500 per paper",
        ),
        // A sweep check is checked against values.csv and the runs: a metric typo, a table
        // or published experiment values.csv lacks, variants that match none of the sweep's
        // (each used to render a norm of 0 and a ratio of -inf, or nothing, with exit 0).
        (
            format!("{original}{}", sweep_check("drift_l", "T3", "circle-rmp", "*")),
            "sweep_check[0] field `metrics`: unknown metric \"drift_l\"",
        ),
        (
            format!("{original}{}", sweep_check("drift_1", "T9", "circle-rmp", "*")),
            "sweep_check[0] field `table`: values.csv has no table \"T9\" (valid: T3, text)",
        ),
        (
            format!("{original}{}", sweep_check("drift_1", "T3", "circle", "*")),
            "sweep_check[0] columns[0] field `published_experiment`: table T3 of values.csv has no \"circle\" with every metric of the check (valid: circle-rmp",
        ),
        (
            format!("{original}{}", sweep_check("drift_1", "T3", "circle-rmp", "zzz-*")),
            "sweep_check[0] columns[0] field `variants`: \"zzz-*\" matches no variant of kong2019-cheap (valid: znn)",
        ),
    ] {
        std::fs::write(&at, edit).unwrap();
        let mut run = p.cmd();
        run.arg("--skip-explain");
        let out = bounded(run);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(needle) && err.contains("paper.toml"), "{needle}: {err}");
        assert!(!p.results().join("runs.csv").exists(), "{needle}: it ran");
    }
    std::fs::write(&at, &original).unwrap();
    // The same published number twice in values.csv.
    let values = p.root().join("papers/kong2019/values.csv");
    let text = std::fs::read_to_string(&values).unwrap();
    let again = text.lines().nth(1).unwrap();
    std::fs::write(&values, format!("{text}{again}\n")).unwrap();
    let mut run = p.cmd();
    run.arg("--skip-explain");
    let out = bounded(run);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("values.csv") && err.contains("is given already on line 2"),
        "{err}"
    );
    assert!(
        !p.results().join("runs.csv").exists(),
        "a duplicate value: it ran"
    );
}

/// A `[[sweep_check]]` of the cheap experiment comparing `metric` of `table`'s
/// `published_experiment` with the variants `variants`.
fn sweep_check(metric: &str, table: &str, published_experiment: &str, variants: &str) -> String {
    format!(
        "\n[[sweep_check]]\nexperiment = \"kong2019-cheap\"\nheading = \"h\"\ntext = \"t\"\ntable = \"{table}\"\nmetrics = [\"{metric}\"]\ncolumns = [{{ published_experiment = \"{published_experiment}\", variants = \"{variants}\" }}]\n"
    )
}

#[test]
fn a_paper_naming_experiments_the_project_lacks_is_noted_and_runs() {
    let p = Project::new("subset");
    let mut run = p.cmd();
    run.arg("--skip-explain");
    let out = bounded(run);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("names no experiment of the experiment files (shown as missing)")
            && err.contains("more such names"),
        "{err}"
    );
    assert!(p.results().join("runs.csv").exists());
}

#[test]
fn a_trajectory_to_score_is_read_as_an_input() {
    let p = Project::new("score");
    for (name, kind) in [
        ("t.csv", inputs::Kind::TrajectoryCsv),
        ("t.mat", inputs::Kind::TrajectoryMat),
    ] {
        let at = p.root().join("contrib").join(name);
        for h in all(kind) {
            h.make(&p, &at);
            let mut score = p.cmd();
            score
                .arg("score")
                .arg(&at)
                .args(["--task", TASK])
                .arg("--score-out")
                .arg(p.root().join("scores"));
            refused(bounded(score), h, &at);
        }
    }
    // /dev/zero named as it is: a character device, refused at once.
    let mut score = p.cmd();
    score
        .args(["score", "/dev/zero", "--task", TASK])
        .arg("--score-out")
        .arg(p.root().join("scores"));
    let out = bounded(score);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("is a character device, not a regular file"),
        "{err}"
    );
    assert!(!p.root().join("scores").exists());
}

#[test]
fn a_baseline_is_read_as_an_input_before_anything_runs() {
    let p = Project::new("baseline");
    let at = p.root().join("contrib/baseline.csv");
    for h in all(inputs::Kind::Baseline) {
        h.make(&p, &at);
        let mut check = p.cmd();
        check.args(["check", "--baseline"]).arg(&at);
        refused(bounded(check), h, &at);
    }
}

#[test]
fn a_shard_manifest_is_read_as_an_input() {
    let p = Project::new("shard");
    let shard = p.root().join("results-shard-1-of-2");
    let at = shard.join(store::shard::MANIFEST);
    for h in all(inputs::Kind::ShardManifest) {
        h.make(&p, &at);
        let mut merge = p.cmd();
        merge.arg("merge").arg(&shard);
        refused(bounded(merge), h, &at);
        assert!(!p.results().join("runs.csv").exists());
    }
}

/// The integrity manifests (`results/manifest.toml`, `report/manifest.toml`, a shard
/// directory's) are read as inputs: a link to a secret or to `/proc/self/environ` is refused
/// without a word of it (a TOML error used to quote the line it failed on).
#[test]
fn integrity_manifests_are_read_as_inputs() {
    let p = Project::new("manifests");
    let shard = p.root().join("results-shard-1-of-2");
    let cases: [(PathBuf, &[&str]); 3] = [
        (p.results().join("manifest.toml"), &["--skip-explain"]),
        (p.root().join("report/manifest.toml"), &["--skip-explain"]),
        (shard.join("manifest.toml"), &["shard", "1/2"]),
    ];
    for (at, args) in cases {
        for h in all(inputs::Kind::Manifest) {
            h.make(&p, &at);
            let mut cmd = reproduce();
            cmd.arg("--root").arg(p.root()).args(args);
            if !args.contains(&"shard") {
                cmd.arg("--results-dir").arg(p.results());
            }
            cmd.env("DRIFTBENCH_TEST_CANARY", CANARY);
            refused(bounded(cmd), h, &at);
            std::fs::remove_file(&at).unwrap();
        }
    }
}

/// An experiment file of `variants` (TOML `[[experiment.variant]]` tables) on the PUMA560's
/// four-leaf clover over `duration` seconds.
fn puma_experiment(duration: f64, variants: &str) -> String {
    format!(
        "paper = \"robio2018\"\ntitle = \"t\"\n[[experiment]]\nid = \"robio2018-bounded\"\npaper_output = \"none\"\nrobot = \"puma560\"\npath = {{ name = \"four-leaf-clover\", duration = {duration:?} }}\ntheta0 = [0.0, -0.7853981633974483, 0.0, 1.5707963267948966, -0.7853981633974483, 0.0]\n{variants}"
    )
}

/// Runs that would take minutes end as failed rows, with their reason, within seconds: a
/// scheme weight of 1e-300 (the optimum chatters between the bounds' vertices and the exact
/// column's integrator stalls, each evaluation a Clarabel solve) meets the evaluation budget
/// scaled from the path's duration, and a numerical method held to 1e-12 with 10^6 iterations
/// per instant meets the run's iteration budget or its cap at an instant, whichever first. Settings outside their documented ranges are
/// refused at load, naming their field (a tolerance of 1e-300 was refused as about `solvers`,
/// its label "314 bytes long").
#[test]
fn every_run_is_bounded_and_ranges_are_checked_at_load() {
    let p = Project::new("bounded");
    std::fs::remove_file(p.experiments().join("kong2019.toml")).unwrap();
    let file = p.experiments().join("robio2018.toml");
    std::fs::write(
        &file,
        puma_experiment(
            0.5,
            "[[experiment.variant]]\nid = \"w\"\nlabel = \"w\"\nscheme = { kind = \"velocity-rmp\", weight = 1e-300, lambda = 4.0, upsilon = 2.0, k_p = 1.0 }\n\
             [[experiment.variant]]\nid = \"n\"\nlabel = \"n\"\nexact = false\nscheme = { kind = \"velocity-rmp\", lambda = 4.0, upsilon = 2.0 }\nnumerical = [{ method = \"m5\", tolerance = 1e-12, max_iterations = 1000000 }]\n",
        ),
    )
    .unwrap();
    let mut run = p.cmd();
    run.args(["--skip-explain", "--dry-run"]);
    let out = bounded(run);
    let err = String::from_utf8_lossy(&out.stderr);
    let all = format!("{}{err}", String::from_utf8_lossy(&out.stdout));
    assert_eq!(out.status.code(), Some(1), "{all}");
    assert!(
        all.contains("robio2018-bounded / w / exact: stopped at")
            && all.contains("right-hand-side evaluations used up"),
        "{all}"
    );
    assert!(
        all.contains("robio2018-bounded / n / m5-tol-1e-12-iter-1000000: numerical method at t =")
            && (all.contains("iteration budget of 2000000 iterations")
                || all.contains("in 1000000 iterations")),
        "{all}"
    );
    for (setting, needle) in [
        (
            "{ method = \"m5\", tolerance = 1e-300 }",
            "variant[0] (\"n\") field `numerical[0]`",
        ),
        (
            "{ method = \"m5\", tolerance = 1e-300 }",
            "tolerance = 1e-300 must be within [1e-12, 1e0]",
        ),
        (
            "{ method = \"m5\", max_iterations = 4000000000 }",
            "max_iterations = 4000000000 must be within [1, 1000000]",
        ),
    ] {
        std::fs::write(
            &file,
            puma_experiment(
                2.0,
                &format!("[[experiment.variant]]\nid = \"n\"\nlabel = \"n\"\nexact = false\nscheme = {{ kind = \"velocity-rmp\", lambda = 4.0, upsilon = 2.0 }}\nnumerical = [{setting}]\n"),
            ),
        )
        .unwrap();
        let mut list = p.cmd();
        list.arg("list");
        let out = bounded(list);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(needle) && !err.contains("`solvers`"),
            "{needle}: {err}"
        );
    }
}
