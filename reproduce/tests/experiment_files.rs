//! The experiment files: every committed file loads, every experiment of experiments.md is
//! there, and a malformed file is rejected with an error naming the file and the field.

use reproduce::experiment::{load_dir, PaperFile};
use std::path::PathBuf;

fn experiments_dir() -> PathBuf {
    reproduce::workspace_root().join("experiments")
}

#[test]
fn every_experiment_of_the_spec_is_in_the_files() {
    let files = load_dir(&experiments_dir()).expect("committed experiment files load");
    let ids: Vec<String> = files
        .iter()
        .flat_map(|f| f.experiments.iter().map(|e| e.id.clone()))
        .collect();
    for id in [
        "jia2019-clover",
        "jia2019-star",
        "jia2019-ping",
        "zhang2018-butterfly-scheme",
        "zhang2018-cardioid-scheme",
        "zhang2018-butterfly-robust",
        "zhang2018-cardioid-robust",
        "zhong2021-clover-a",
        "zhong2021-clover-b",
        "zhong2021-dai",
        "kong2019-triangle",
        "kong2019-circle",
    ] {
        assert!(
            ids.iter().any(|i| i == id),
            "experiment {id} missing from experiments/"
        );
    }
    let papers: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
    for p in ["jia2019", "zhang2018", "zhong2021", "kong2019"] {
        assert!(papers.contains(&p), "no experiment file for {p}");
    }
}

/// Writes `text` to a fresh file and loads it.
fn load_text(name: &str, text: &str) -> Result<PaperFile, String> {
    let dir = std::env::temp_dir().join(format!("driftbench-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    PaperFile::load(&path).map_err(|e| e.to_string())
}

const GOOD: &str = r#"
paper = "jia2019"
title = "t"
[[experiment]]
id = "jia2019-x"
paper_output = "-"
robot = "jaco2-pen"
path = { name = "four-leaf-clover", duration = 5.0 }
theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]
[[experiment.variant]]
label = "VLTCO"
scheme = { kind = "jia2019", phi = 0.2, tau = 0.4, kappa = 20.0, lambda = 20.0 }
solvers = [{ kind = "lvi-pdnn", gamma = 1e7 }]
"#;

fn assert_rejected(name: &str, text: &str, must_mention: &[&str]) {
    let err = load_text(name, text).expect_err("malformed file must be rejected");
    assert!(
        err.contains(&format!("{name}.toml")),
        "error does not name the file: {err}"
    );
    for m in must_mention {
        assert!(err.contains(m), "error does not mention `{m}`: {err}");
    }
}

#[test]
fn a_good_file_loads_and_expands_into_runs() {
    let f = load_text("good", GOOD).unwrap();
    let jobs = f.jobs();
    assert_eq!(jobs.len(), 2, "exact column + one neural solver");
    assert_eq!(
        jobs[0].theta_ref, jobs[0].theta0,
        "theta_ref defaults to theta0"
    );
}

#[test]
fn malformed_files_name_the_file_and_the_field() {
    assert_rejected(
        "missing_theta0",
        &GOOD.replace("theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]\n", ""),
        &["theta0"],
    );
    assert_rejected(
        "short_theta0",
        &GOOD.replace("-1.71, -2.95]", "-1.71]"),
        &["theta0", "5 entries"],
    );
    assert_rejected(
        "unknown_robot",
        &GOOD.replace("jaco2-pen", "jaco3"),
        &["robot", "jaco3"],
    );
    assert_rejected(
        "unknown_field",
        &GOOD.replace("paper_output", "paper_outptu"),
        &["paper_outptu"],
    );
    assert_rejected(
        "bad_scheme_kind",
        &GOOD.replace("kind = \"jia2019\"", "kind = \"jia2020\""),
        &["jia2020"],
    );
    assert_rejected(
        "bad_solver_field",
        &GOOD.replace("gamma = 1e7", "gama = 1e7"),
        &["gama"],
    );
    assert_rejected("bad_id", &GOOD.replace("jia2019-x", "zhong2021-x"), &["id"]);
    assert_rejected(
        "bad_tolerance",
        &GOOD
            .replace("solvers = [", "exact = true\nsolvers = [")
            .replace(
                "theta0 = [",
                "integrator = { method = \"bdf\", rtol = -1.0, atol = 1e-8 }\ntheta0 = [",
            ),
        &["integrator"],
    );
}
