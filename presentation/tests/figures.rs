//! The figure generator on a small synthetic results directory: file names, well-formed SVG with
//! the titles, panels by level, failed runs, determinism, and errors that name the bad file.

use presentation::figures::render_all;
use records::runs::{runs_csv, write_atomic, RunRow, Status};
use simulation::error::FailureKind;
use std::path::{Path, PathBuf};

/// A run row with the identity and outcome given and every metric empty.
fn row(experiment: &str, variant: &str, solver: &str, failed_at: Option<f64>) -> RunRow {
    RunRow {
        paper: "synthetic".into(),
        experiment: experiment.into(),
        variant: variant.into(),
        scheme: variant.into(),
        solver: solver.into(),
        solver_kind: "lvi-pdnn".into(),
        robot: "jaco2-pen".into(),
        path: "circle".into(),
        path_scale: None,
        duration: 2.0,
        status: if failed_at.is_some() {
            Status::Failed
        } else {
            Status::Ok
        },
        failure: failed_at
            .map(|t| format!("integrator failed at t = {t}"))
            .unwrap_or_default(),
        failure_kind: failed_at.map(|_| FailureKind::Integrator),
        expected_failure: String::new(),
        failed_at,
        drift: Vec::new(),
        drift_norm: None,
        drift_ref_norm: None,
        max_pos_err: None,
        rms_pos_err: None,
        final_pos_err: None,
        theta_margin: None,
        thetadot_margin: None,
        peak_thetadot: None,
        peak_thetaddot: None,
        peak_torque: None,
        min_sigma_j: None,
        score_samples: None,
        score_max_dx: None,
        score_rms_dx: None,
        score_max_obj_gap: None,
        score_max_violation: None,
        score_failures: 0,
        net_error_final: None,
        net_error_max_after_1s: None,
        integrator: "bdf".into(),
        rtol: 1e-6,
        atol: 1e-8,
        max_step: None,
        steps: 0,
        rejected: 0,
        rhs_evals: 0,
        jac_evals: 0,
        qp_solves: 0,
        qp_fallbacks: 0,
        qp_checks: 0,
        qp_check_max_dx: None,
        wall_s: 0.0,
        sim_s: 0.0,
        observe_s: 0.0,
        crate_version: "0.1.0".into(),
        git_rev: "synthetic".into(),
    }
}

/// A trace CSV of `n` joints over [0, t_end] in `rows` samples, with accelerations and torques
/// if `acceleration`, a score if `scored`; the first position error is exactly 0.
fn trace(n: usize, rows: usize, t_end: f64, acceleration: bool, scored: bool) -> String {
    let blocks: &[&str] = if acceleration {
        &["theta", "thetadot", "thetaddot", "tau"]
    } else {
        &["theta", "thetadot"]
    };
    let mut header = vec!["t".to_string()];
    for block in blocks {
        header.extend((1..=n).map(|i| format!("{block}_{i}")));
    }
    header.extend(
        [
            "rx_des", "ry_des", "rz_des", "rx", "ry", "rz", "pos_err", "score_dx",
        ]
        .map(String::from),
    );
    let mut csv = header.join(",") + "\n";
    for k in 0..rows {
        let t = t_end * k as f64 / (rows - 1) as f64;
        let mut fields = vec![t.to_string()];
        for (b, _) in blocks.iter().enumerate() {
            fields.extend((0..n).map(|i| ((b + 1) as f64 * (t + i as f64).sin()).to_string()));
        }
        let (x, y) = (0.1 * t.cos(), 0.1 * t.sin());
        let err = 1e-6 * t;
        fields.extend([x, y, 0.2, x + err, y, 0.2, err].map(|v| v.to_string()));
        fields.push(if scored {
            (1e-3 * (1.0 + t)).to_string()
        } else {
            String::new()
        });
        csv += &(fields.join(",") + "\n");
    }
    csv
}

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("driftbench-figures-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Three runs in two experiments: a velocity-level exact and neural run, and a failed
/// acceleration-level run.
fn synthetic_results(root: &Path) {
    let runs = [
        row("exp-vel", "VLTCO", "exact (Clarabel)", None),
        row("exp-vel", "VLTCO", "LVI-PDNN", None),
        row("exp-acc", "MTN (zeta=0)", "FP-CDNN", Some(0.5)),
    ];
    write_atomic(&root.join("results/runs.csv"), &runs_csv(&runs).unwrap()).unwrap();
    let traces = root.join("results/traces");
    write_atomic(
        &traces.join("exp-vel/vltco__exact-clarabel.csv"),
        trace(6, 50, 2.0, false, false).as_bytes(),
    )
    .unwrap();
    write_atomic(
        &traces.join("exp-vel/vltco__lvi-pdnn.csv"),
        trace(6, 900, 2.0, false, true).as_bytes(),
    )
    .unwrap();
    write_atomic(
        &traces.join("exp-acc/mtn-zeta-0__fp-cdnn.csv"),
        trace(5, 20, 0.5, true, true).as_bytes(),
    )
    .unwrap();
}

/// The number of points of every polyline with more than ten (data, not axes, ticks or legend).
fn data_lines(svg: &str) -> Vec<usize> {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|element| element.split("points=\"").nth(1)?.split('"').next())
        .map(|points| points.split_whitespace().count())
        .filter(|&count| count > 10)
        .collect()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}

#[test]
fn writes_one_figure_per_run_and_one_overview_per_experiment() {
    let root = scratch("names");
    synthetic_results(&root);
    let written = render_all(&root).unwrap();
    let dir = root.join("report/figures");
    let expected: Vec<PathBuf> = [
        "exp-acc__mtn-zeta-0__fp-cdnn.svg",
        "exp-acc__overview.svg",
        "exp-vel__overview.svg",
        "exp-vel__vltco__exact-clarabel.svg",
        "exp-vel__vltco__lvi-pdnn.svg",
    ]
    .iter()
    .map(|name| dir.join(name))
    .collect();
    assert_eq!(written, expected);

    let titles = [
        "exp-acc: MTN (zeta=0) / FP-CDNN (failed at t = 0.500 s)",
        "exp-acc: overview of 1 runs",
        "exp-vel: overview of 2 runs",
        "exp-vel: VLTCO / exact (Clarabel)",
        "exp-vel: VLTCO / LVI-PDNN",
    ];
    for (path, title) in written.iter().zip(titles) {
        let svg = read(path);
        assert!(
            svg.starts_with("<svg"),
            "{} does not start with <svg",
            path.display()
        );
        assert!(
            svg.trim_end().ends_with("</svg>"),
            "{} is not closed",
            path.display()
        );
        assert!(
            svg.contains(title),
            "{} lacks its title {title:?}",
            path.display()
        );
        assert!(
            svg.contains("<polyline") || svg.contains("<path"),
            "{} draws no line",
            path.display()
        );
    }
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn panels_follow_the_level_and_the_overview_scores_neural_runs() {
    let root = scratch("panels");
    synthetic_results(&root);
    render_all(&root).unwrap();
    let figure = |name: &str| read(&root.join("report/figures").join(name));

    let velocity = figure("exp-vel__vltco__lvi-pdnn.svg");
    for label in [
        "(a) end-effector path",
        "(b) position error",
        "(c) joint angles",
        "(d) joint velocities",
        "x (m)",
        "y (m)",
        "t (s)",
        "velocity (rad/s)",
        "joint 6",
    ] {
        assert!(
            velocity.contains(label),
            "velocity-level figure lacks {label:?}"
        );
    }
    assert!(
        !velocity.contains("torque"),
        "velocity-level figure has a torque panel"
    );
    let series = data_lines(&velocity);
    assert_eq!(
        series.len(),
        2 + 1 + 6 + 6,
        "path x2, error, angles x6, velocities x6"
    );
    assert!(
        series.iter().all(|&points| points <= 400),
        "a 900-sample trace was not thinned: {series:?}"
    );

    let acceleration = figure("exp-acc__mtn-zeta-0__fp-cdnn.svg");
    for label in [
        "(e) joint accelerations",
        "(f) joint torques",
        "acceleration (rad/s^2)",
        "torque (N m)",
        "joint 5",
    ] {
        assert!(
            acceleration.contains(label),
            "acceleration-level figure lacks {label:?}"
        );
    }
    assert!(!acceleration.contains("joint 6"));

    let overview = figure("exp-vel__overview.svg");
    assert!(
        overview.contains("|x_nn - x*| (rad/s)"),
        "overview lacks the score panel"
    );
    assert!(
        overview.contains("VLTCO / LVI-PDNN") && overview.contains("VLTCO / exact (Clarabel)"),
        "overview legend lacks a run"
    );
    std::fs::remove_dir_all(&root).unwrap();
}

/// The number of polylines of exactly `points` points.
fn polylines_of(svg: &str, points: usize) -> usize {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|element| element.split("points=\"").nth(1)?.split('"').next())
        .filter(|p| p.split_whitespace().count() == points)
        .count()
}

#[test]
fn panel_a_draws_the_arm_where_the_robot_is_known_and_fits_the_trace() {
    let root = scratch("arm");
    synthetic_results(&root);
    render_all(&root).unwrap();
    let figure = |name: &str| read(&root.join("report/figures").join(name));

    // jaco2-pen, 6 joints: twelve poses of base, frame origins 1..=6 and pen tip.
    let velocity = figure("exp-vel__vltco__lvi-pdnn.svg");
    assert_eq!(polylines_of(&velocity, 8), 12, "twelve Jaco2 poses");
    assert!(velocity.contains("arm at t = 0") && velocity.contains("arm over time"));

    // A 5-joint trace for a 6-joint robot: no arm, no error.
    let acceleration = figure("exp-acc__mtn-zeta-0__fp-cdnn.svg");
    assert_eq!(polylines_of(&acceleration, 8), 0);
    assert!(!acceleration.contains("arm at t = 0"));

    // The Katana (5 points a pose), and a robot the suite does not know (no arm).
    let mut katana = row("exp-acc", "MTN (zeta=0)", "FP-CDNN", Some(0.5));
    katana.robot = "katana6m180".into();
    let mut unknown = row("exp-vel", "VLTCO", "LVI-PDNN", None);
    unknown.robot = "puma560".into();
    let runs = [
        row("exp-vel", "VLTCO", "exact (Clarabel)", None),
        unknown,
        katana,
    ];
    write_atomic(&root.join("results/runs.csv"), &runs_csv(&runs).unwrap()).unwrap();
    render_all(&root).unwrap();
    let katana = figure("exp-acc__mtn-zeta-0__fp-cdnn.svg");
    assert_eq!(polylines_of(&katana, 5), 12, "twelve Katana poses");
    let unknown = figure("exp-vel__vltco__lvi-pdnn.svg");
    assert!(!unknown.contains("arm at t = 0"));
    assert_eq!(polylines_of(&unknown, 8), 0);
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn rendering_twice_gives_identical_bytes_and_removes_stale_figures() {
    let root = scratch("determinism");
    synthetic_results(&root);
    let stale = root.join("report/figures/exp-old__gone__solver.svg");
    write_atomic(&stale, b"<svg></svg>").unwrap();
    let first: Vec<Vec<u8>> = render_all(&root)
        .unwrap()
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert!(!stale.exists(), "a figure of a run that is gone was kept");
    let second: Vec<Vec<u8>> = render_all(&root)
        .unwrap()
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert_eq!(first, second);
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_malformed_trace_is_an_error_naming_the_file() {
    let root = scratch("malformed");
    synthetic_results(&root);
    let bad = root.join("results/traces/exp-vel/vltco__lvi-pdnn.csv");
    let text = read(&bad).replacen("\n0,", "\nnot-a-number,", 1);
    std::fs::write(&bad, text).unwrap();
    let err = render_all(&root).unwrap_err();
    assert!(
        err.contains("vltco__lvi-pdnn.csv") && err.contains("not a number"),
        "{err}"
    );

    std::fs::write(&bad, "t,theta_1\n0,1\n").unwrap();
    let err = render_all(&root).unwrap_err();
    assert!(
        err.contains("vltco__lvi-pdnn.csv") && err.contains("thetadot"),
        "{err}"
    );

    std::fs::remove_file(&bad).unwrap();
    let err = render_all(&root).unwrap_err();
    assert!(err.contains("vltco__lvi-pdnn.csv"), "{err}");
    std::fs::remove_dir_all(&root).unwrap();
}

/// Regenerates `report/figures/` from the committed results (run with `--ignored`).
#[test]
#[ignore = "rewrites report/figures/ from the committed results"]
fn render_the_committed_results() {
    let root = simulation::root::from_current_dir().unwrap();
    let runs = records::runs::read_runs(&root.join("results/runs.csv")).unwrap();
    let experiments: std::collections::BTreeSet<&str> =
        runs.iter().map(|r| r.experiment.as_str()).collect();
    let written = render_all(&root).unwrap();
    assert_eq!(written.len(), runs.len() + experiments.len());
}
