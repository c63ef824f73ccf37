//! The committed `results/leaderboard.csv` is the leaderboard the committed `results/runs.csv`
//! and `results/leaderboard-timing.csv` give (both are rewritten whenever the report is rendered), byte for byte.

#[test]
fn the_committed_leaderboard_is_the_one_the_committed_runs_give() {
    let root = catalog::root_from_current_dir().unwrap();
    let runs = store::read_runs(&root.join("results/runs.csv")).unwrap();
    let path = root.join("results/leaderboard.csv");
    let committed =
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let timings = store::timing::read(&root.join("results")).unwrap();
    let rows = analysis::leaderboard::leaderboard(&runs, &timings);
    let fresh = String::from_utf8(analysis::leaderboard::leaderboard_csv(&rows).unwrap()).unwrap();
    assert!(
        committed == fresh,
        "{} is stale: regenerate with `cargo run --release -p reproduce -- report`",
        path.display()
    );
    // Every standard task and every solver that ran on all of them is on it.
    let tasks = analysis::leaderboard::standard_tasks(&runs);
    assert!(!tasks.is_empty());
    let standard = rows
        .iter()
        .filter(|r| r.task_set == analysis::leaderboard::STANDARD_SET);
    for r in standard {
        assert_eq!((r.tasks, r.standard_runs), (tasks.len(), tasks.len()));
    }
}
