//! `benches/clock/build_units.py` (cargo's `--timings` unit table turned into
//! `benches/results/build-profile.csv`) writes rows that [`driftbench_benches::telemetry::build_profile`] reads: every column,
//! kind and the `unblocked_by` edge it derives from cargo's lists, on a fixture shaped as
//! cargo's `cargo-timing.html`. Skipped, saying so, where python3 is missing (CI has it).

use driftbench_benches::telemetry::build_profile::{BuildUnitRow, UnitKind};
use std::path::Path;
use std::process::Command;

#[test]
fn the_script_writes_the_rows_the_schema_reads() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = match Command::new("python3")
        .arg(root.join("benches/clock/build_units.py"))
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/cargo-timing.html"))
        .arg(&root)
        .args([
            "0123456789ab",
            "Test CPU, 2 GHz",
            "2",
            "2026-12-04T00:00:00Z",
            "14.5",
        ])
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            eprintln!("SKIPPED: python3 cannot be run here ({e})");
            return;
        }
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows: Vec<BuildUnitRow> = records::table::from_reader(&out.stdout[..]).unwrap();
    let kinds: Vec<UnitKind> = rows.iter().map(|r| r.kind).collect();
    assert_eq!(
        kinds,
        [
            UnitKind::BuildScript,
            UnitKind::BuildScriptRun,
            UnitKind::Lib,
            UnitKind::Lib,
            UnitKind::Bin
        ]
    );
    let edges: Vec<Option<usize>> = rows.iter().map(|r| r.unblocked_by).collect();
    assert_eq!(edges, [None, Some(0), Some(1), Some(2), Some(3)]);
    // The workspace's crates are known from `cargo metadata` of the checkout.
    let ours: Vec<bool> = rows.iter().map(|r| r.workspace).collect();
    assert_eq!(ours, [false, false, false, true, true]);
    assert_eq!(rows[3].duration_s, 11.7);
    assert_eq!(rows[4].start_s, 13.3);
    assert_eq!(rows[0].machine, "Test CPU, 2 GHz");
    assert_eq!((rows[0].cores, rows[0].build_wall_s), (2, 14.5));
}
