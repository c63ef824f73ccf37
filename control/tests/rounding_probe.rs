//! The rounding-noise probe (`Rounding::OneUlp`) on kong2019's ZNN task at h = 10 ms: the
//! default path (`Rounding::AsComputed`) gives the committed rows of `results/control.csv` bit
//! for bit; the probe gives the same outcome on every run, and one that differs from the
//! default's (it moves the state).

use control::{load_tasks, run_loop, with_task, Discretisation, LoopOutcome, LoopSettings};
use control::{Method, Numerical, Rounding, Task};
use records::control::ControlRow;
use std::path::Path;
use store::results_dir;

/// The control period of the runs (s): one of the committed period sweep's.
const H: f64 = 1e-2;

/// The standard task `kong2019-circle / znn-eq22`.
fn task() -> Task {
    let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments");
    let set = catalog::load_task_set(&experiments).unwrap();
    let jobs: Vec<_> = catalog::load_dir(&experiments)
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .collect();
    let refs: Vec<_> = set
        .tasks
        .iter()
        .filter(|t| t.experiment.as_str() == "kong2019-circle" && t.variant.as_str() == "znn-eq22")
        .cloned()
        .collect();
    load_tasks(&jobs, &refs).unwrap().remove(0)
}

/// The active set and the ZNN's Euler form, as the reproduction runs them.
fn methods(task: &Task) -> [Method; 2] {
    [
        Method::Numerical(Numerical::active_set()),
        Method::Network {
            spec: task.networks[0].clone(),
            form: Discretisation::Euler,
            substeps: 1,
        },
    ]
}

/// One cycle of `method` on `task` at [`H`] with `rounding`, its durations cleared.
fn run(task: &Task, method: &Method, rounding: Rounding) -> LoopOutcome {
    let mut out = with_task(task, 1, |arm| {
        let mut solver = method.build(arm.scheme.dims()).unwrap();
        let settings = LoopSettings {
            h: H,
            period: arm.period,
            cycles: 1,
            max_ticks: None,
            rounding,
        };
        run_loop(
            arm.robot,
            arm.path,
            arm.scheme,
            solver.as_mut(),
            arm.theta0,
            &settings,
            None,
        )
    })
    .unwrap();
    out.solve_us.clear();
    out.tick_us.clear();
    out
}

#[test]
fn the_default_path_gives_the_committed_rows_bit_for_bit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let rows: Vec<ControlRow> =
        store::control::read(&root.join("results"), results_dir::CONTROL).unwrap();
    let task = task();
    for method in methods(&task) {
        let row = rows
            .iter()
            .find(|r| r.task == task.id() && r.method == method.label() && r.h_ms == H * 1e3)
            .unwrap_or_else(|| panic!("no committed row of {}", method.label()));
        let out = run(&task, &method, Rounding::AsComputed);
        let bits = |v: f64| v.to_bits();
        assert_eq!(out.status.column(), row.status);
        assert_eq!(out.ticks, row.ticks);
        for (name, a, b) in [
            ("max_track_err", out.max_track_err, row.max_track_err),
            ("rms_track_err", out.rms_track_err, row.rms_track_err),
            ("max_dx", out.max_dx, row.max_dx),
            ("rms_dx", out.rms_dx, row.rms_dx),
            ("max_dx_settled", out.max_dx_settled, row.max_dx_settled),
            ("iterations_mean", out.iterations_mean, row.iterations_mean),
        ] {
            assert_eq!(bits(a), bits(b), "{} {name}: {a} against {b}", row.method);
        }
        assert_eq!(out.drift.first().map(|d| bits(*d)), row.drift.map(bits));
        assert_eq!(out.iterations_max, row.iterations_max);
    }
}

#[test]
fn the_probe_is_deterministic_and_moves_the_run() {
    let task = task();
    let [_, network] = methods(&task);
    let (a, b) = (
        run(&task, &network, Rounding::OneUlp),
        run(&task, &network, Rounding::OneUlp),
    );
    // Bit for bit: f64's == would take 0.0 for -0.0 and miss nothing else here (no NaN).
    let bits = |o: &LoopOutcome| {
        [
            o.max_track_err,
            o.rms_track_err,
            o.max_dx,
            o.rms_dx,
            o.max_dx_settled,
        ]
        .into_iter()
        .chain(o.drift.iter().copied())
        .map(f64::to_bits)
        .collect::<Vec<u64>>()
    };
    assert_eq!(a, b);
    assert_eq!(bits(&a), bits(&b));
    let computed = run(&task, &network, Rounding::AsComputed);
    assert_eq!(a.ticks, computed.ticks);
    assert_ne!(a.drift, computed.drift, "the probe moved nothing");
}
