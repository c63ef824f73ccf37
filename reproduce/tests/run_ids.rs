//! Run ids, not labels, are identities: renaming every display label of an experiment file
//! orphans nothing, moves no result, and the regression gate still passes.

use crate::common;
use common::{ok, reproduce};
use std::path::{Path, PathBuf};
use store::read_runs;

/// kong2019's experiment file with every `label = "..."` (variant labels, sweep templates)
/// rewritten.
fn relabelled(text: &str) -> String {
    text.lines()
        .map(|l| match l.strip_prefix("label = \"") {
            Some(rest) => format!("label = \"renamed: {rest}"),
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if e.path().is_dir() {
            out.extend(files_under(&e.path()));
        } else {
            out.push(e.path().strip_prefix(dir).unwrap().to_path_buf());
        }
    }
    out.sort();
    out
}

#[test]
fn renaming_every_label_orphans_nothing_and_moves_no_result() {
    let root = catalog::root_from_current_dir().unwrap();
    let base = inputs::Scratch::unmade("run-ids");
    let experiments = base.join("experiments");
    let results = base.join("results");
    std::fs::create_dir_all(&experiments).unwrap();
    // What the report reads beside results/ (the papers come from the project root).
    std::fs::create_dir_all(base.join("report")).unwrap();
    std::fs::copy(
        root.join("report/deviations.md"),
        base.join("report/deviations.md"),
    )
    .unwrap();
    let original = std::fs::read_to_string(root.join("experiments/kong2019.toml")).unwrap();
    let file = experiments.join("kong2019.toml");
    std::fs::write(&file, &original).unwrap();
    // `run` (without the explanation layer) or `check`, on these experiments and results.
    let run = |mode: &str, extra: &[&str]| {
        let mut c = reproduce();
        c.arg(mode)
            .args((mode == "run").then_some("--skip-explain"))
            .arg("--experiments-dir")
            .arg(&experiments)
            .arg("--results-dir")
            .arg(&results)
            .args(extra);
        c.output().unwrap()
    };
    ok(run("run", &[]));
    let before = read_runs(&results.join("runs.csv")).unwrap();
    let traces_before = files_under(&results.join("traces"));
    assert!(before.len() > 10 && !traces_before.is_empty());

    let renamed = relabelled(&original);
    assert_ne!(renamed, original);
    std::fs::write(&file, &renamed).unwrap();

    // The gate, against the rows written under the old labels.
    let gate = ok(run(
        "check",
        &["--baseline", results.join("runs.csv").to_str().unwrap()],
    ));
    assert!(
        String::from_utf8_lossy(&gate.stdout).contains(&format!("{} runs agree", before.len())),
        "{}",
        String::from_utf8_lossy(&gate.stdout)
    );

    // Written again: the same runs under the same keys and file names, new labels only.
    let again = ok(run("run", &[]));
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(!stderr.contains("pruned"), "{stderr}");
    let after = read_runs(&results.join("runs.csv")).unwrap();
    assert_eq!(after.len(), before.len());
    for (a, b) in after.iter().zip(&before) {
        assert_eq!(a.key(), b.key());
        assert_eq!(
            (&a.status, &a.drift, a.max_pos_err),
            (&b.status, &b.drift, b.max_pos_err)
        );
        assert_eq!(a.variant, format!("renamed: {}", b.variant));
    }
    assert_eq!(files_under(&results.join("traces")), traces_before);
}
