//! The figure generator on a small synthetic results directory: file names, well-formed SVG with
//! the titles, a PNG beside every SVG, panels by level, failed runs, determinism, and errors that
//! name the bad file; and the committed figures: a PNG beside every SVG, and the SVGs are those
//! the committed results give.

use analysis::sweep_summary::Held;
use presentation::ReportError;
use records::FailureKind;
use records::{runs_csv, RunRow, Status};
use spec::RunKey;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use store::write_atomic;

/// Every figure of the results under `root`, drawn from the runs the report holds, read as
/// `reproduce` reads them (`Held`, with the runs that keep no trace by choice, `untraced`).
fn render_all(root: &Path, untraced: &HashSet<RunKey>) -> Result<Vec<PathBuf>, ReportError> {
    let traced = |key: &RunKey| !untraced.contains(key);
    let held = Held::read(&root.join("results/runs.csv"), &traced)?;
    presentation::figures::render_all(root, &held, &traced)
}

/// A run row with the identity and outcome given and every metric empty; the ids are the
/// labels' slugs, and a solver labelled `exact ...` is the exact column.
fn row(experiment: &str, variant: &str, solver: &str, failed_at: Option<f64>) -> RunRow {
    RunRow {
        paper: "synthetic".into(),
        variant: variant.into(),
        scheme: variant.into(),
        solver: solver.into(),
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
        failed_at,
        ..RunRow::blank(
            &spec::RunKey::from_ids(experiment, &spec::slug(variant), &spec::slug(solver)).unwrap(),
            if solver.starts_with("exact") {
                spec::SolverKind::Exact
            } else {
                spec::SolverKind::Network(settings::NetworkKind::LviPdnn)
            },
        )
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

/// A fresh directory under the system's temporary directory, removed when dropped.
fn scratch(name: &str) -> inputs::Scratch {
    inputs::Scratch::dir(&format!("figures-{name}"))
}

/// Three runs in two experiments: a velocity-level exact and neural run, and a failed
/// acceleration-level run.
fn synthetic_results(root: &Path) {
    // In key order, as every writer of runs.csv writes it (the report's reader checks it).
    let mut runs = [
        row("exp-vel", "VLTCO", "exact (Clarabel)", None),
        row("exp-vel", "VLTCO", "LVI-PDNN", None),
        row("exp-acc", "MTN (zeta=0)", "FP-CDNN", Some(0.5)),
    ];
    runs.sort_by_key(RunRow::key);
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

/// The width and height in a PNG's header, read from the bytes: the eight-byte PNG signature,
/// then the IHDR chunk (length 13, type, width, height); `None` if `bytes` do not start so.
fn png_size(bytes: &[u8]) -> Option<(u32, u32)> {
    const SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];
    let be = |at: usize| -> Option<u32> {
        Some(u32::from_be_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
    };
    if bytes.get(..8)? != SIGNATURE || be(8)? != 13 || bytes.get(12..16)? != b"IHDR" {
        return None;
    }
    Some((be(16)?, be(20)?))
}

/// Decodes a whole PNG (every chunk, every row) and returns its size and its pixels' distinct
/// byte values (a blank image has one).
fn decode_png(bytes: &[u8]) -> Result<((u32, u32), usize), String> {
    let mut reader = png::Decoder::new(bytes)
        .read_info()
        .map_err(|e| e.to_string())?;
    let mut pixels = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut pixels).map_err(|e| e.to_string())?;
    let distinct: std::collections::BTreeSet<u8> =
        pixels[..frame.buffer_size()].iter().copied().collect();
    Ok(((frame.width, frame.height), distinct.len()))
}

/// The file names in `dir` ending in `.extension`, without it, sorted.
fn stems(dir: &Path, extension: &str) -> Vec<String> {
    let mut stems: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|name| Some(name.strip_suffix(&format!(".{extension}"))?.to_string()))
        .collect();
    stems.sort();
    stems
}

#[test]
fn writes_one_figure_per_run_and_one_overview_per_experiment() {
    let root = scratch("names");
    synthetic_results(&root);
    let written = render_all(&root, &Default::default()).unwrap();
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
        let png = std::fs::read(path.with_extension("png")).unwrap();
        assert_eq!(png_size(&png), Some((1200, 900)), "{}", path.display());
        let (size, distinct) = decode_png(&png).unwrap();
        assert_eq!(size, (1200, 900));
        assert!(distinct > 2, "{} has a blank PNG", path.display());
    }
    assert_eq!(stems(&dir, "svg"), stems(&dir, "png"));
}

#[test]
fn panels_follow_the_level_and_the_overview_scores_neural_runs() {
    let root = scratch("panels");
    synthetic_results(&root);
    render_all(&root, &Default::default()).unwrap();
    let figure = |name: &str| read(&root.join("report/figures").join(name));

    // A scored run's figure has the distance to the optimum as its third panel; the exact
    // column's has none.
    let exact = figure("exp-vel__vltco__exact-clarabel.svg");
    assert!(exact.contains("(c) joint angles") && !exact.contains("|x - x*|"));
    let velocity = figure("exp-vel__vltco__lvi-pdnn.svg");
    for label in [
        "(a) end-effector path",
        "(b) position error",
        "(c) distance to the exact QP optimum |x - x*|",
        "(d) joint angles",
        "(e) joint velocities",
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
        2 + 1 + 1 + 6 + 6,
        "path x2, error, |x - x*|, angles x6, velocities x6"
    );
    assert!(
        series.iter().all(|&points| points <= 400),
        "a 900-sample trace was not thinned: {series:?}"
    );

    let acceleration = figure("exp-acc__mtn-zeta-0__fp-cdnn.svg");
    for label in [
        "(f) joint accelerations",
        "(g) joint torques",
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
    for label in [
        "(a) exact column: position error",
        "(b) solvers: position error",
        "(c) solvers: |x - x*|",
        "|x - x*| (rad/s)",
        "VLTCO / LVI-PDNN",
    ] {
        assert!(overview.contains(label), "overview lacks {label:?}");
    }
    // The exact run is listed by its variant under its heading, not with its solver's label.
    assert!(overview.contains("exact column") && !overview.contains("VLTCO / exact"));
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
    render_all(&root, &Default::default()).unwrap();
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
    unknown.robot = "no-such-arm".into();
    let mut runs = [
        row("exp-vel", "VLTCO", "exact (Clarabel)", None),
        unknown,
        katana,
    ];
    runs.sort_by_key(RunRow::key);
    write_atomic(&root.join("results/runs.csv"), &runs_csv(&runs).unwrap()).unwrap();
    render_all(&root, &Default::default()).unwrap();
    let katana = figure("exp-acc__mtn-zeta-0__fp-cdnn.svg");
    assert_eq!(polylines_of(&katana, 5), 12, "twelve Katana poses");
    let unknown = figure("exp-vel__vltco__lvi-pdnn.svg");
    assert!(!unknown.contains("arm at t = 0"));
    assert_eq!(polylines_of(&unknown, 8), 0);
}

#[test]
fn rendering_twice_gives_identical_bytes_and_removes_stale_figures() {
    let root = scratch("determinism");
    synthetic_results(&root);
    // Figures of a run that is gone, as an earlier rendering wrote them (recorded in
    // report/manifest.toml).
    let report = store::TrackedDir::open_within(&root, "report").unwrap();
    report
        .write(
            Path::new("figures/exp-old__gone__solver.svg"),
            b"<svg></svg>",
        )
        .unwrap();
    report
        .write(Path::new("figures/exp-old__gone__solver.png"), b"\x89PNG")
        .unwrap();
    report.save().unwrap();
    drop(report);
    let stale = root.join("report/figures/exp-old__gone__solver.svg");
    let stale_png = stale.with_extension("png");
    let mine = root.join("report/figures/notes.png");
    write_atomic(&mine, b"not a figure").unwrap();
    // Named like a figure, but the user's: the program did not write it, so it stays.
    let users = root.join("report/figures/my__own__plot.svg");
    write_atomic(&users, b"<svg>mine</svg>").unwrap();
    let bytes = |svgs: Vec<PathBuf>| -> Vec<(Vec<u8>, Vec<u8>)> {
        svgs.iter()
            .map(|p| {
                let png = std::fs::read(p.with_extension("png")).unwrap();
                (std::fs::read(p).unwrap(), png)
            })
            .collect()
    };
    let first = bytes(render_all(&root, &Default::default()).unwrap());
    assert!(!stale.exists(), "a figure of a run that is gone was kept");
    assert!(
        !stale_png.exists(),
        "the PNG of a run that is gone was kept"
    );
    assert!(mine.exists(), "a file not named as a figure was deleted");
    assert!(
        users.exists(),
        "a file the program did not write was deleted"
    );
    let second = bytes(render_all(&root, &Default::default()).unwrap());
    assert_eq!(first, second);
}

#[test]
fn a_malformed_trace_is_an_error_naming_the_file() {
    let root = scratch("malformed");
    synthetic_results(&root);
    let bad = root.join("results/traces/exp-vel/vltco__lvi-pdnn.csv");
    let text = read(&bad).replacen("\n0,", "\nnot-a-number,", 1);
    std::fs::write(&bad, text).unwrap();
    let err = render_all(&root, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("vltco__lvi-pdnn.csv") && err.contains("not a number"),
        "{err}"
    );

    std::fs::write(&bad, "t,theta_1\n0,1\n").unwrap();
    let err = render_all(&root, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("vltco__lvi-pdnn.csv") && err.contains("thetadot"),
        "{err}"
    );

    std::fs::remove_file(&bad).unwrap();
    let err = render_all(&root, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("vltco__lvi-pdnn.csv"), "{err}");
}

/// A trace with finite extreme values (theta = 9e307 and -9e307, velocities near f64::MAX, a
/// position error of 1e308) is drawn, its axes clipped to finite spans: plotters loops forever
/// on an axis whose span overflows, so the rendering runs under a timeout.
#[test]
fn extreme_finite_values_in_a_trace_are_drawn_without_hanging() {
    let root = scratch("extreme");
    synthetic_results(&root);
    let path = root.join("results/traces/exp-vel/vltco__lvi-pdnn.csv");
    let text = read(&path);
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for (row, sign) in [(1, ""), (2, "-")] {
        let mut fields: Vec<String> = lines[row].split(',').map(String::from).collect();
        fields[1] = format!("{sign}9e307");
        fields[7] = format!("{sign}1.7976931348623157e308");
        let n = fields.len();
        fields[n - 2] = "1e308".into();
        lines[row] = fields.join(",");
    }
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    let dir = root.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(
            render_all(&dir, &Default::default())
                .map(|_| ())
                .map_err(|e| e.to_string()),
        );
    });
    let rendered = rx
        .recv_timeout(std::time::Duration::from_secs(120))
        .expect("the figures are drawn within 120 s");
    assert_eq!(rendered, Ok(()));
    let svg = read(&root.join("report/figures/exp-vel__vltco__lvi-pdnn.svg"));
    assert!(svg.contains("<svg") && !svg.contains("inf") && !svg.contains("NaN"));
}

/// Every committed SVG figure has its PNG (same stem) and every PNG its SVG; every PNG starts
/// with the PNG signature and a header of non-zero size, and decodes.
#[test]
fn every_committed_figure_has_its_png() {
    let dir = catalog::root_from_current_dir()
        .unwrap()
        .join("report/figures");
    let (svgs, pngs) = (stems(&dir, "svg"), stems(&dir, "png"));
    assert!(!svgs.is_empty(), "no figure in {}", dir.display());
    let lacking = |of: &[String], in_: &[String]| -> Vec<String> {
        of.iter().filter(|s| !in_.contains(s)).cloned().collect()
    };
    let regenerate = "regenerate with `cargo run --release -p reproduce -- report`";
    assert_eq!(
        lacking(&svgs, &pngs),
        Vec::<String>::new(),
        "SVGs without a PNG: {regenerate}"
    );
    assert_eq!(
        lacking(&pngs, &svgs),
        Vec::<String>::new(),
        "PNGs without an SVG: {regenerate}"
    );
    for stem in &pngs {
        let bytes = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
        let size = png_size(&bytes).unwrap_or_else(|| panic!("{stem}.png is not a PNG"));
        assert!(size.0 > 0 && size.1 > 0, "{stem}.png is {size:?}");
        assert_eq!(decode_png(&bytes).map(|d| d.0), Ok(size), "{stem}.png");
    }
}

/// Copies the files of `from` into `to`, folders included.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// The committed SVG figures are byte for byte those the committed results give: rendered from
/// a copy of `results/` in a scratch directory, so nothing in the repository is written.
#[test]
fn the_committed_figures_are_those_the_committed_results_give() {
    let committed = catalog::root_from_current_dir().unwrap();
    let root = scratch("committed");
    std::fs::create_dir_all(root.join("results")).unwrap();
    for file in ["runs.csv", "inference.csv"] {
        std::fs::copy(
            committed.join("results").join(file),
            root.join("results").join(file),
        )
        .unwrap();
    }
    // Measured by `reproduce cost`, not by every checkout: copied where it exists.
    let dof_cost = committed.join("results").join(records::dof_cost::FILE);
    if dof_cost.exists() {
        std::fs::copy(
            &dof_cost,
            root.join("results").join(records::dof_cost::FILE),
        )
        .unwrap();
    }
    // The control experiments' results (the `control` crate), where they exist.
    for file in [store::results_dir::CONTROL, store::results_dir::CYCLES] {
        let path = committed.join("results").join(file);
        if path.exists() {
            std::fs::copy(&path, root.join("results").join(file)).unwrap();
        }
    }
    copy_tree(
        &committed.join("results/traces"),
        &root.join("results/traces"),
    );
    // The arm figures draw each run's robot, which may be a paper's robot file
    // (papers/<paper>/robots/): registered as `reproduce` registers them.
    catalog::register_paper_robots(&committed.join("papers"));
    render_all(&root, &Default::default()).unwrap();
    let (ours, theirs) = (
        root.join("report/figures"),
        committed.join("report/figures"),
    );
    let regenerate = "regenerate with `cargo run --release -p reproduce -- report`";
    assert_eq!(
        stems(&ours, "svg"),
        stems(&theirs, "svg"),
        "the committed figures are not those of the committed results: {regenerate}"
    );
    for stem in stems(&ours, "svg") {
        let name = format!("{stem}.svg");
        assert!(
            std::fs::read(ours.join(&name)).unwrap() == std::fs::read(theirs.join(&name)).unwrap(),
            "report/figures/{name} is stale: {regenerate}"
        );
    }
}

/// `run --paper X` draws X's figures only: the others are neither redrawn nor removed.
#[test]
fn one_papers_figures_are_drawn_alone_and_the_others_kept() {
    let root = scratch("one-paper");
    synthetic_results(&root);
    let runs_csv_path = root.join("results/runs.csv");
    let mut runs = store::read_runs(&runs_csv_path).unwrap();
    for r in runs.iter_mut().filter(|r| r.experiment == "exp-acc") {
        r.paper = "other".into();
    }
    write_atomic(&runs_csv_path, &runs_csv(&runs).unwrap()).unwrap();
    render_all(&root, &Default::default()).unwrap();
    let dir = root.join("report/figures");
    let kept = std::fs::read(dir.join("exp-vel__overview.png")).unwrap();
    // A figure the other paper's runs no longer give would be removed; exp-vel's are not its.
    let held = Held::read(&runs_csv_path, &|_| true).unwrap();
    let written = presentation::figures::render_paper(&root, "other", &held, &|_| true).unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        ["exp-acc__mtn-zeta-0__fp-cdnn.svg", "exp-acc__overview.svg"]
    );
    assert_eq!(
        std::fs::read(dir.join("exp-vel__overview.png")).unwrap(),
        kept
    );
    assert!(dir.join("exp-vel__vltco__lvi-pdnn.svg").is_file());
}

/// A merged 10^4-run sweep renders a bounded number of figures: a run figure for
/// `MAX_RUN_FIGURES` runs only (their traces alone are written: the others' are not read), the
/// overview and the sweep figure over its parameters; its page shows the sweep figure, its
/// extremes and failures, and links only the drawn runs (the sample the report holds).
#[test]
fn a_large_sweep_renders_a_bounded_number_of_figures() {
    use analysis::sweep_summary::Held;
    use presentation::figures::sweep::MAX_RUN_FIGURES;
    let root = scratch("large-sweep");
    let mut runs: Vec<RunRow> = (0..10_000)
        .map(|i| {
            let (mu, scale) = (i / 100, i % 100);
            let variant = format!("ZNN [mu={mu}, scale={scale}]");
            let failed = (i % 331 == 7).then_some(0.5);
            let mut r = row("big-sweep", &variant, "exact (Clarabel)", failed);
            if failed.is_none() {
                r.drift_norm = Some(1e-6 * (1.0 + mu as f64) * (1.0 + (scale as f64).sqrt()));
                r.max_pos_err = Some(1e-5 / (1.0 + i as f64));
            }
            r
        })
        .collect();
    runs.sort_by_key(RunRow::key);
    write_atomic(&root.join("results/runs.csv"), &runs_csv(&runs).unwrap()).unwrap();
    let held = Held::read(&root.join("results/runs.csv"), &|_| true).unwrap();
    assert_eq!(held.runs.all().len(), MAX_RUN_FIGURES);
    for r in held.runs.all() {
        let key = r.key();
        write_atomic(
            &root.join(format!("results/traces/big-sweep/{}.csv", key.stem())),
            trace(5, 20, 2.0, false, false).as_bytes(),
        )
        .unwrap();
    }
    let written = render_all(&root, &Default::default()).unwrap();
    assert_eq!(written.len(), MAX_RUN_FIGURES + 2, "{written:?}");
    let dir = root.join("report/figures");
    let sweep = read(&dir.join("big-sweep__sweep.svg"));
    assert!(sweep.contains("big-sweep: 10000 runs over mu, scale (31 failed)"));
    assert!(sweep.contains("drift norm against mu: min, median, max"));
    assert!(sweep.contains("median log10 drift norm over mu and scale"));
    assert!(sweep.contains("mu (40 intervals)"), "100 values of mu, cut");
    assert!(read(&dir.join("big-sweep__overview.svg")).contains("overview of 24 runs"));
    assert_eq!(stems(&dir, "svg").len(), MAX_RUN_FIGURES + 2);

    let figures = presentation::report::figures::list(&dir).unwrap();
    let page =
        presentation::report::figures::links(&figures, &held.runs, "big-sweep", &held.sweeps);
    assert!(page.contains("(figures/big-sweep__sweep.svg)"), "{page}");
    assert!(
        page.contains("10000 runs, 31 failed (the first 10 listed)"),
        "{page}"
    );
    assert!(
        page.contains("| largest drift norm | ZNN \\[mu=99, scale=99\\] / exact (Clarabel)"),
        "{page}"
    );
    assert_eq!(page.matches("| failed |").count(), 10, "{page}");
    assert_eq!(
        page.matches("](figures/big-sweep__znn-").count(),
        MAX_RUN_FIGURES,
        "{page}"
    );
}

/// A sweep whose runs keep no trace by choice (`traces` of the experiment file): those runs get
/// no figure of their own and their traces are not read (none is written here); the sweep
/// figure still counts every row. Runs 0, 3, 6, ... keep theirs (`{ every = 3 }`): 20 of 60,
/// all drawn; with `"none"` only the overview and the sweep figure. Without saying which runs
/// keep none, the first missing trace is an error.
#[test]
fn runs_without_a_trace_by_choice_get_no_figure_of_their_own() {
    let root = scratch("untraced-sweep");
    let mut runs: Vec<RunRow> = (0..60)
        .map(|i| {
            let mut r = row(
                "part-sweep",
                &format!("ZNN [mu={i:02}]"),
                "exact (Clarabel)",
                None,
            );
            r.drift_norm = Some(1e-6 * (1.0 + i as f64));
            r.max_pos_err = Some(1e-5);
            r
        })
        .collect();
    runs.sort_by_key(RunRow::key);
    write_atomic(&root.join("results/runs.csv"), &runs_csv(&runs).unwrap()).unwrap();
    let untraced = |keep: fn(usize) -> bool| -> std::collections::HashSet<_> {
        runs.iter()
            .enumerate()
            .filter(|(i, _)| !keep(*i))
            .map(|(_, r)| r.key())
            .collect()
    };
    let dir = root.join("report/figures");
    // "none": no trace at all, the overview (of no run) and the sweep figure over 60 rows.
    assert_eq!(render_all(&root, &untraced(|_| false)).unwrap().len(), 2);
    assert!(read(&dir.join("part-sweep__sweep.svg")).contains("part-sweep: 60 runs"));
    // { every = 3 }: runs 0, 3, ... keep theirs and get a figure each.
    for r in runs.iter().step_by(3) {
        write_atomic(
            &root.join(format!("results/traces/part-sweep/{}.csv", r.key().stem())),
            trace(5, 20, 2.0, false, false).as_bytes(),
        )
        .unwrap();
    }
    let written = render_all(&root, &untraced(|i| i % 3 == 0)).unwrap();
    assert_eq!(written.len(), 20 + 2, "{written:?}");
    assert!(read(&dir.join("part-sweep__overview.svg")).contains("overview of 20 runs"));
    assert_eq!(stems(&dir, "svg").len(), 20 + 2);
    // A trace missing where no choice left it out is an error.
    let err = render_all(&root, &Default::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("part-sweep"), "{err}");
}
