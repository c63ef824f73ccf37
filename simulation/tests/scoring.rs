//! The scoring grid: a network run scored at every accepted step, at a bounded number of
//! instants, or not at all, as the experiment file's `scoring` says.

use simulation::run_job;
use simulation::Outcome;
use spec::RunSpec;
use spec::Scoring;
use spec::SolverChoice;

fn znn_job() -> RunSpec {
    let root = catalog::root_from_current_dir().unwrap();
    catalog::load_dir(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
        .find(|j| {
            j.experiment == "kong2019-circle"
                && j.variant == "ZNN (eq. 22)"
                && matches!(j.solver, SolverChoice::Neural(_))
        })
        .expect("kong2019's ZNN run")
}

fn samples_and_max_dx(job: &RunSpec) -> (usize, usize, Option<f64>) {
    let r = run_job(job);
    let Outcome::Completed(m) = &r.run.outcome else {
        panic!("{:?}", r.run.outcome)
    };
    let score = m.score.map(|s| (s.samples, s.max_dx));
    (
        r.run.stats.steps,
        score.map_or(0, |s| s.0),
        score.map(|s| s.1),
    )
}

#[test]
fn a_grid_bounds_the_exact_solves_and_every_step_sees_them_all() {
    let every = znn_job();
    assert_eq!(every.scoring, Scoring::EveryStep);
    let (steps, n_every, max_every) = samples_and_max_dx(&every);
    // Every accepted step, and the initial state.
    assert_eq!(n_every, steps + 1);
    let grid = RunSpec {
        scoring: Scoring::MaxInstants(20),
        ..every.clone()
    };
    let (_, n_grid, max_grid) = samples_and_max_dx(&grid);
    assert!((2..=22).contains(&n_grid), "{n_grid} instants");
    // The grid's instants are a subset of the accepted steps: its max cannot exceed theirs.
    assert!(max_grid.unwrap() <= max_every.unwrap());
    let off = RunSpec {
        scoring: Scoring::Off,
        ..every
    };
    assert_eq!(samples_and_max_dx(&off).1, 0);
}

#[test]
fn the_scoring_setting_is_read_from_the_experiment_file() {
    let file = |scoring: &str| {
        format!(
            r#"{}[[experiment.variant]]
label = "ZNN"
scheme = {{ kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }}
solvers = [{{ kind = "znn", gamma = 1.0 }}]
"#,
            fixtures::katana_circle("t", "kong2019-e", 9.0, scoring)
        )
    };
    let scoring_of = |text: &str| {
        catalog::PaperFile::from_toml(text)
            .map(|f| f.jobs().unwrap()[1].scoring)
            .map_err(|e| e.to_string())
    };
    assert_eq!(scoring_of(&file("")), Ok(Scoring::EveryStep));
    assert_eq!(
        scoring_of(&file("scoring = { max-instants = 500 }")),
        Ok(Scoring::MaxInstants(500))
    );
    assert_eq!(scoring_of(&file("scoring = \"off\"")), Ok(Scoring::Off));
    let err = scoring_of(&file("scoring = \"sometimes\"")).unwrap_err();
    assert!(
        err.contains("every-step") && err.contains("max-instants"),
        "{err}"
    );
}
