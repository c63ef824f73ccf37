//! The regression gate guards the tables the pages show: a ladder, attribution or control
//! number doctored in results/ and re-sealed (so the store's integrity check accepts it) makes
//! `reproduce check` fail, naming the table, the row and the column.

use crate::common;
use common::{copy_tree, ok, reproduce};
use records::control::ControlRow;
use records::AttributionRow;
use records::LadderRow;
use std::path::Path;
use store::results_dir::ResultsDir;
use store::Edits;

/// Rewrites the results table `file` of `results` by `edit` and re-seals the manifest, as a
/// deliberate edit (`--accept-edited`) would.
fn doctor<T: records::table::Row>(results: &Path, file: &str, edit: impl Fn(&mut Vec<T>)) {
    let path = results.join(file);
    let mut rows: Vec<T> = store::table::read(&path).unwrap();
    edit(&mut rows);
    std::fs::write(&path, records::table::to_csv(&rows).unwrap()).unwrap();
    let (dir, _) = ResultsDir::open(results, "test", Edits::Accept).unwrap();
    dir.save().unwrap();
}

fn check(root: &Path) -> std::process::Output {
    reproduce()
        .arg("--root")
        .arg(root)
        .args(["--threads", "2", "check"])
        .output()
        .unwrap()
}

#[test]
fn a_doctored_and_resealed_ladder_or_attribution_number_fails_the_gate() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fifth-paper");
    let root = inputs::Scratch::unmade("gate-x");
    copy_tree(&fixture, &root);
    ok(reproduce()
        .arg("--root")
        .arg(&root)
        .args(["--threads", "2"])
        .output()
        .unwrap());
    let results = root.join("results");
    let agree = ok(check(&root));
    let stdout = String::from_utf8_lossy(&agree.stdout);
    assert!(stdout.contains("agree"), "{stdout}");

    doctor::<LadderRow>(&results, "ladder.csv", |rows| {
        let r = rows.iter_mut().find(|r| r.drift_norm.is_some()).unwrap();
        r.drift_norm = r.drift_norm.map(|d| d * 1.5 + 1e-9);
    });
    let failed = check(&root);
    let stdout = String::from_utf8_lossy(&failed.stdout);
    assert_eq!(failed.status.code(), Some(3), "{stdout}");
    assert!(stdout.contains(": drift_norm "), "{stdout}");
    assert!(
        !stdout.contains("RunKey {") && !stdout.contains("Some("),
        "{stdout}"
    );

    ok(reproduce()
        .arg("--root")
        .arg(&root)
        .args(["--threads", "2"])
        .output()
        .unwrap());
    doctor::<AttributionRow>(&results, "attribution.csv", |rows| {
        let r = rows.iter_mut().find(|r| r.share.is_some()).unwrap();
        r.share = r.share.map(|s| s + 0.25);
    });
    let failed = check(&root);
    let stdout = String::from_utf8_lossy(&failed.stdout);
    assert_eq!(failed.status.code(), Some(3), "{stdout}");
    assert!(stdout.contains(": share "), "{stdout}");
}

/// The gate guards the control experiments' runs the control page shows: a control number
/// doctored in results/ and re-sealed makes a whole `reproduce check` (which re-runs the control
/// experiments) fail with exit 3, naming the table, the row and the column. The fixture's
/// task set is one task of its own paper, with a small budget of its own.
#[test]
fn a_doctored_and_resealed_control_number_fails_the_gate() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fifth-paper");
    let root = inputs::Scratch::unmade("gate-c");
    copy_tree(&fixture, &root);
    std::fs::create_dir_all(root.join("experiments/control")).unwrap();
    std::fs::write(
        root.join("experiments/control/tasks.toml"),
        "[[task]]\nexperiment = \"demo2026-circle\"\nvariant = \"znn-mu1\"\n\n\
         [budget]\nsweep_ms = [5.0]\ncycles = 2\ncheck_ticks = 20\ncheck_steps_factor = 2\n",
    )
    .unwrap();
    ok(reproduce()
        .arg("--root")
        .arg(&root)
        .args(["--threads", "2", "run", "--skip-explain"])
        .output()
        .unwrap());
    let results = root.join("results");
    let rows: Vec<ControlRow> = store::table::read(&results.join("control.csv")).unwrap();
    assert!(!rows.is_empty(), "the fixture's control task ran");
    let agree = ok(check(&root));
    let stdout = String::from_utf8_lossy(&agree.stdout);
    assert!(stdout.contains("agree"), "{stdout}");

    doctor::<ControlRow>(&results, "control.csv", |rows| {
        let r = rows.iter_mut().find(|r| r.max_dx > 0.0).unwrap();
        r.max_dx = r.max_dx * 1.5 + 1e-9;
    });
    let failed = check(&root);
    let stdout = String::from_utf8_lossy(&failed.stdout);
    assert_eq!(failed.status.code(), Some(3), "{stdout}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("control.csv demo2026-circle / "))
        .unwrap_or_else(|| panic!("no control.csv row named: {stdout}"));
    assert!(line.contains(": max_dx "), "{line}");
    assert!(
        !stdout.contains("Some(") && !stdout.contains("RunKey {"),
        "{stdout}"
    );
}
