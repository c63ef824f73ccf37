//! One exit code per kind of outcome (docs/reference/exit-codes.md), each checked on the
//! binary where a run can bring it about: an input error (2), an argument that is not UTF-8
//! (2, not a panic), an I/O failure (4); the internal kind (70) by the error that carries it,
//! since no input may cause one. The gate's difference (3) is `cli.rs`'s
//! `the_gate_compares_with_the_stated_baseline`; an unexpected failure (1) is
//! `an_unexpected_failure_exits_non_zero` there. The deprecated mode flags say so on stderr.

use crate::common;

use common::reproduce;
use reproduce::error::Exit;
use reproduce::ReproduceError;
use std::os::unix::ffi::OsStrExt;

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
    let dir = std::env::temp_dir().join(format!("driftbench-exit-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_poisoned_lock_is_an_internal_error() {
    let e = ReproduceError::Journal(store::journal::JournalError::Poisoned);
    assert_eq!(e.exit(), Exit::Internal);
    assert_eq!(e.exit().code(), 70);
}

#[test]
fn an_old_mode_flag_works_and_says_it_is_deprecated() {
    let out = reproduce()
        .args(["--list", "--paper", "kong2019"])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains(
            "warning: `--list` is deprecated and will be removed: write `reproduce list` instead"
        ),
        "{err}"
    );
    let out = reproduce()
        .args(["list", "--paper", "kong2019"])
        .output()
        .unwrap();
    assert!(!stderr(&out).contains("deprecated"), "{}", stderr(&out));
}
