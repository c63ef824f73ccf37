//! A network of the literature entered as data (issue 39, proof b): kong2019's ZNN scheme
//! (eq. 22) on the circle solved by the power-type varying-parameter network, a point of the
//! zeroing vocabulary (`kind = "zeroing"`, gain law `power`, sign-bi-power activation) written
//! in `experiments/kong2019.toml`, converges to the exact optimum (Clarabel's answer at every
//! accepted step) and keeps the tool on the path; faster than the constant-gain ZNN of the same
//! file.

use simulation::run_job;
use simulation::Outcome;
use simulation::Score;
use spec::RunSpec;
use spec::SolverChoice;

/// The network runs of kong2019's circle.
fn circle_jobs() -> Vec<RunSpec> {
    let root = catalog::root_from_current_dir().unwrap();
    catalog::load_dir(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .filter(|j| {
            j.experiment == "kong2019-circle" && matches!(j.solver, SolverChoice::Neural(_))
        })
        .collect()
}

fn score(job: &RunSpec) -> (Score, f64) {
    let r = run_job(job);
    let Outcome::Completed(m) = &r.run.outcome else {
        panic!("{}: {:?}", job.variant, r.run.outcome)
    };
    (
        m.score.expect("a network run is scored"),
        m.max_position_error,
    )
}

#[test]
fn the_power_type_network_from_the_file_converges_to_the_exact_optimum() {
    let jobs = circle_jobs();
    let find = |label: &str| {
        jobs.iter()
            .find(|j| j.variant == label)
            .unwrap_or_else(|| panic!("{label} in kong2019-circle"))
    };
    let power = find("ZNN scheme (eq. 22) [power-type VP network]");
    let SolverChoice::Neural(spec) = &power.solver else {
        unreachable!()
    };
    let zeroing = spec.zeroing().expect("a point of the zeroing vocabulary");
    assert_eq!(zeroing.gain.law(), "power", "{zeroing:?}");
    let (s, position) = score(power);
    // Started from zero, the network meets the optimum within the settling second and stays
    // on it: its command is the exact QP's to 1e-6 rad/s (RMS) from then on.
    let settled = s.rms_dx_after_settle.unwrap();
    assert!(settled < 1e-6, "rms dx after 1 s {settled}");
    assert!(s.samples > 100, "{} score samples", s.samples);
    assert!(position < 1e-5, "max position error {position}");
    // The constant-gain ZNN (gamma = 1) of the same scheme is still far from it after 1 s.
    let (znn, _) = score(find("ZNN (eq. 22)"));
    assert!(settled < 1e-3 * znn.rms_dx_after_settle.unwrap());
}
