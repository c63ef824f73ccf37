//! One exit code per kind of outcome (docs/reference/exit-codes.md), each checked on the
//! binary where a run can bring it about: success (0), an unexpected failure (1), an input
//! error (2; an argument that is not UTF-8 or an old mode flag is one too, never a panic), the
//! gate's difference (3), an I/O failure (4); the internal kind (70) by the error that carries
//! it, since no input may cause one. The page cites only files that exist.

use crate::common;

use common::reproduce;
use records::runs_csv;
use reproduce::{Exit, ReproduceError};
use std::os::unix::ffi::OsStrExt;
use store::read_runs;

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn each_kind_has_its_own_code() {
    let codes = [
        Exit::Success,
        Exit::UnexpectedFailure,
        Exit::Input,
        Exit::GateDifference,
        Exit::Io,
        Exit::Internal,
    ]
    .map(Exit::code);
    assert_eq!(codes, [0, 1, 2, 3, 4, 70]);
}

#[test]
fn an_unknown_paper_is_an_input_error() {
    let out = reproduce()
        .args(["run", "--dry-run", "--paper", "nosuchpaper"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("nosuchpaper") && err.contains("kong2019"),
        "{err}"
    );
}

#[test]
fn an_argument_that_is_not_utf8_is_an_input_error_not_a_panic() {
    let odd = std::ffi::OsStr::from_bytes(b"kong\xff2019");
    let out = reproduce()
        .args(["list", "--paper"])
        .arg(odd)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.to_lowercase().contains("utf-8"), "{err}");
}

#[test]
fn a_results_directory_the_system_will_not_create_is_an_io_failure() {
    let dir = inputs::Scratch::dir("exit-io");
    std::fs::write(dir.join("kong2019.toml"), common::CHEAP_EXPERIMENT).unwrap();
    // sysfs refuses new entries to every user, root included.
    let out = reproduce()
        .args(["run", "--skip-explain", "--experiments-dir"])
        .arg(&dir)
        .args(["--results-dir", "/sys/driftbench-exit-codes/results"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(4), "{err}");
    assert!(err.contains("/sys/driftbench-exit-codes"), "{err}");
}

#[test]
fn a_poisoned_lock_is_an_internal_error() {
    let e = ReproduceError::Journal(store::journal::JournalError::Poisoned);
    assert_eq!(e.exit(), Exit::Internal);
    assert_eq!(e.exit().code(), 70);
}

/// The mode flags of earlier versions are gone: clap refuses one as any unknown argument
/// (exit 2), and `--help` says the subcommands replaced them; the subcommand succeeds (exit 0).
#[test]
fn an_old_mode_flag_is_a_usage_error_and_its_subcommand_succeeds() {
    let out = reproduce()
        .args(["--list", "--paper", "kong2019"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("unexpected argument '--list'"), "{err}");
    let out = reproduce()
        .args(["list", "--paper", "kong2019"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let help = reproduce().arg("--help").output().unwrap();
    assert_eq!(help.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&help.stdout)
        .contains("The subcommands replaced the mode flags of earlier versions"));
}

#[test]
fn the_gate_compares_with_the_stated_baseline() {
    let root = catalog::root_from_current_dir().unwrap();
    let committed = read_runs(&root.join("results/runs.csv")).unwrap();
    let dir = inputs::Scratch::dir("cli-gate");
    let exp = "kong2019-circle-mu-sweep";

    let same = dir.join("same.csv");
    std::fs::write(&same, runs_csv(&committed).unwrap()).unwrap();
    let ok = reproduce()
        .args(["check", "--experiment", exp, "--baseline"])
        .arg(&same)
        .output()
        .unwrap();
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stdout)
    );

    let mut doctored = committed.clone();
    let row = doctored
        .iter_mut()
        .find(|r| r.experiment == exp && r.drift_norm.is_some())
        .unwrap();
    row.drift_norm = row.drift_norm.map(|d| d * 1.01);
    let bad = dir.join("doctored.csv");
    std::fs::write(&bad, runs_csv(&doctored).unwrap()).unwrap();
    let fail = reproduce()
        .args(["check", "--experiment", exp, "--baseline"])
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(fail.status.code(), Some(3), "a gate difference exits 3");
    assert!(String::from_utf8_lossy(&fail.stdout).contains("drift_norm"));
}

#[test]
fn an_unexpected_failure_exits_non_zero() {
    let dir = inputs::Scratch::dir("cli-exit");
    // The clover in 0.5 s asks for ten times the joint-speed limit: the exact QP is infeasible.
    std::fs::write(
        dir.join("jia2019.toml"),
        r#"paper = "jia2019"
title = "too fast"
[[experiment]]
id = "jia2019-too-fast"
paper_output = "none"
robot = "jaco2-pen"
path = { name = "four-leaf-clover", duration = 0.5 }
theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]
[[experiment.variant]]
label = "VLTCO"
scheme = { kind = "jia2019", phi = 0.2, tau = 0.4, kappa = 20.0, lambda = 20.0 }
"#,
    )
    .unwrap();
    let out = reproduce()
        .args(["--dry-run", "--experiments-dir"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("unexpected failures"));

    // The same files' expected failures (MTN diverges) exit 0.
    let out = reproduce()
        .args([
            "--dry-run",
            "--skip-explain",
            "--experiment",
            "zhang2018-cardioid-scheme",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// docs/reference/exit-codes.md cites only what exists: every backticked path of the
/// repository (a glob's prefix matching at least one file), and every `crate::module` of a
/// workspace crate as that crate's `src/module.rs` or `src/module/mod.rs`.
#[test]
fn the_exit_code_page_cites_only_what_exists() {
    let root = catalog::root_from_current_dir().unwrap();
    let page = std::fs::read_to_string(root.join("docs/reference/exit-codes.md")).unwrap();
    let cited: Vec<&str> = page.split('`').skip(1).step_by(2).collect();
    let mut checked = 0;
    for c in cited {
        let first = c.split(['/', ':']).next().unwrap_or("");
        if first.is_empty() || !root.join(first).join("Cargo.toml").is_file() {
            continue;
        }
        let exists = if let Some((krate, rest)) = c.split_once("::") {
            let module = rest.split("::").next().unwrap();
            let src = root.join(krate).join("src");
            src.join(format!("{module}.rs")).is_file() || src.join(module).join("mod.rs").is_file()
        } else if let Some((dir, prefix)) = c.split_once('*').and_then(|(p, _)| p.rsplit_once('/'))
        {
            std::fs::read_dir(root.join(dir))
                .unwrap()
                .any(|e| e.unwrap().file_name().to_string_lossy().starts_with(prefix))
        } else {
            root.join(c).exists()
        };
        assert!(
            exists,
            "docs/reference/exit-codes.md cites `{c}`, which does not exist"
        );
        checked += 1;
    }
    assert!(checked >= 6, "only {checked} citations checked");
}

/// A run refused before anything runs leaves nothing behind: a project whose papers/ is
/// missing gets no empty report/ (the report's directory is checked, and so created, only
/// after the papers load).
#[test]
fn a_run_refused_for_its_papers_leaves_no_report_directory() {
    let root = inputs::Scratch::dir("exit-no-papers");
    std::fs::create_dir(root.join("experiments")).unwrap();
    std::fs::copy(
        common::repo_root().join("experiments/kong2019.toml"),
        root.join("experiments/kong2019.toml"),
    )
    .unwrap();
    let out = reproduce()
        .args(["run", "--skip-explain", "--root"])
        .arg(&root)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("papers"), "{err}");
    assert!(!root.join("report").exists(), "report/ was created: {err}");
}
