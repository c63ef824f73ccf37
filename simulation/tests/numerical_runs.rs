//! Numerical QP methods as run solvers, on a paper entered from files only (robio2018: a robot
//! file, a composed scheme, the experiment's own limits, the six methods): every run completes,
//! the methods' error shrinks with their tolerance, joint 6 (which cannot move the tool point on
//! its axis) does not drift, and the experiment's limits are the ones the run respects.

use simulation::run_job;
use simulation::run_row;
use spec::RunSpec;
use spec::SolverChoice;

fn robio_jobs() -> Vec<RunSpec> {
    let root = catalog::root_from_current_dir().unwrap();
    let file = catalog::PaperFile::load(&root.join("experiments/robio2018.toml")).unwrap();
    file.jobs().unwrap()
}

#[test]
fn every_method_runs_and_its_error_follows_its_tolerance() {
    let jobs = robio_jobs();
    let mut methods = Vec::new();
    for job in jobs
        .iter()
        .filter(|j| j.experiment.ends_with("four-petals"))
    {
        let row = run_row(&run_job(job), "test");
        assert!(row.completed(), "{}: {}", row.key(), row.failure);
        // theta_6 turns about the axis the tool point lies on: no drift to rounding.
        assert!(row.drift[5].abs() < 1e-12, "{}: {:?}", row.key(), row.drift);
        let SolverChoice::Numerical(spec) = &job.solver else {
            assert!(row.solver_iterations.is_none() && row.solver_products.is_none());
            continue;
        };
        methods.push(spec.method.id());
        let iterations = row.solver_iterations.unwrap();
        assert!(iterations > 0 && row.solver_iterations_max.unwrap() > 0);
        // Every iteration costs at least 2 products, and every instant one more (its residual).
        let products = row.solver_products.unwrap();
        assert!(
            products > 2 * iterations,
            "{}: {products} products",
            row.key()
        );
        // |x - x*| is bounded by the stopping rule's residual, up to a factor of the QP.
        let dx = row.score_max_dx.unwrap();
        assert!(
            dx < 50.0 * spec.tolerance_in_effect().unwrap(),
            "{}: |x - x*| = {dx:e}",
            row.key()
        );
        // The experiment's |thetadot| <= 1.5 is what the margins are measured against.
        assert!(row.thetadot_margin.unwrap() > 0.0 && row.thetadot_margin.unwrap() < 1.5);
    }
    for m in settings::qp_solver::PLPE_IDS {
        assert!(methods.contains(&m), "{m} is not run");
    }
}

#[test]
fn a_numerical_solver_with_bad_settings_is_refused_naming_the_field() {
    let root = catalog::root_from_current_dir().unwrap();
    let text = std::fs::read_to_string(root.join("experiments/robio2018.toml")).unwrap();
    for (from, to, expect) in [
        (
            "{ method = \"m4\" }",
            "{ method = \"m7\" }",
            "unknown QP solver \"m7\" (known: 94lvi",
        ),
        (
            "{ method = \"m4\" }",
            "{ method = \"m4\", tolerance = nan }",
            "tolerance",
        ),
        (
            "{ method = \"m4\" }",
            "{ method = \"m4\", step = 0.0 }",
            "step",
        ),
        (
            "{ method = \"m4\" }",
            "{ method = \"m4\", tolerence = 1e-3 }",
            "unknown field",
        ),
        (
            "{ method = \"m4\" }",
            "{ method = \"clarabel\", max_iterations = 10 }",
            "field `numerical[3]`: QP solver clarabel takes no setting `max_iterations`",
        ),
        (
            "upper = [1.5, 1.5, 1.5, 1.5, 1.5, 1.5]",
            "upper = [1.5, 1.5]",
            "has 2 entries",
        ),
        (
            "upper = [1.5, 1.5, 1.5, 1.5, 1.5, 1.5]",
            "upper = [1.5, 1.5, 1.5, 1.5, 1.5, -1.5]",
            "lower < 0 < upper",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = text.replacen(from, to, 1);
        let err = catalog::PaperFile::from_toml(&bad).unwrap_err().to_string();
        assert!(err.contains(expect), "{to}: {err}");
    }
    // lambda = 0 is allowed (the paper's baseline has no repetitive term); a negative one not.
    let bad = text.replacen("lambda = 4.0", "lambda = -1.0", 1);
    let err = catalog::PaperFile::from_toml(&bad).unwrap_err().to_string();
    assert!(err.contains("lambda") && err.contains(">= 0"), "{err}");
}
