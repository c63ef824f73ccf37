//! A fifth paper without writing Rust: the fixture `tests/fixtures/fifth-paper/` (an experiment
//! file, `papers/demo2026/` with its published values, mappings and claims, and the report's
//! deviations) gets its report section: the published table side by side with our runs, the
//! claims checked, a verdict and the drift attribution.

use crate::common;
use common::{copy_tree, ok, reproduce};
use std::path::Path;

#[test]
fn a_paper_added_as_data_gets_its_report_section() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fifth-paper");
    let root = inputs::Scratch::unmade("fifth-paper");
    copy_tree(&fixture, &root);
    ok(reproduce()
        .arg("--root")
        .arg(&root)
        .args(["--threads", "2"])
        .output()
        .unwrap());
    let md = std::fs::read_to_string(root.join("report/REPORT.md")).unwrap();
    let section = std::fs::read_to_string(root.join("report/paper-demo2026.md"))
        .expect("a page for the fifth paper");
    assert!(section.contains("A fixture paper: the ZNN scheme on the Katana circle"));
    // The published table beside ours (the paper's numbers, our runs, ratios).
    assert!(
        section.contains("### Published tables side by side"),
        "{section}"
    );
    assert!(section.contains("**Table 1**"), "{section}");
    assert!(section.contains("paper: ZNN, mu = 1"), "{section}");
    assert!(section.contains("2.00e-5"), "{section}");
    // The claims, decided from the runs: two hold, the third is false by construction.
    assert!(
        section.contains("- **PASS** circle, ZNN: ‖drift‖ with mu = 4"),
        "{section}"
    );
    assert!(
        section.contains("- **PASS** every run: max position error below 1e-6 m"),
        "{section}"
    );
    assert!(
        section.contains("- **FAIL** every run: max position error below 1e-9 m"),
        "{section}"
    );
    // The verdict, with the counts and thresholds of the rule that decided it
    // (docs/reference/verdicts.md).
    assert!(section.contains("**Verdict: "), "{section}");
    assert!(
        section.contains("decided it from: published numbers within a factor 3: "),
        "{section}"
    );
    assert!(
        section.contains("claims: 2 hold, 1 fail. 2 of 3 evaluated claims hold"),
        "{section}"
    );
    // The explanation layer ran on the mapped runs.
    assert!(section.contains("#### Drift attribution"), "{section}");
    assert!(section.contains("#### Tolerance ladder"), "{section}");
    assert!(
        md.lines()
            .any(|l| l.starts_with("| [demo2026](paper-demo2026.md) | ")
                && l.contains(" | 2 / 1 / 0 | ")),
        "{md}"
    );
}
