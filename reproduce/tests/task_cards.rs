//! Task cards: the committed `report/tasks/` is exactly what the experiment files give (rendered
//! in memory, never over the committed files), one card per task, and a card carries the
//! suite's own check values.

use catalog::experiment::{load_dir, PaperFile};
use reproduce::task_card::{cards, INDEX, TASKS};
use simulation::check_job;
use std::collections::BTreeSet;

const REGENERATE: &str = "regenerate with `cargo run --release -p reproduce -- --report-only`";

#[test]
fn the_committed_cards_are_the_generated_ones() {
    let root = catalog::root::from_current_dir().unwrap();
    let generated = cards(&root.join("experiments")).unwrap();
    let dir = root.join("report").join(TASKS);
    let committed: BTreeSet<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let expected: BTreeSet<String> = generated.keys().cloned().collect();
    assert_eq!(committed, expected, "report/tasks/ differs; {REGENERATE}");
    for (name, text) in &generated {
        let stored = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(
            stored == *text,
            "report/tasks/{name} is stale; {REGENERATE}"
        );
    }
}

#[test]
fn every_task_has_a_card_with_its_check_values() {
    let root = catalog::root::from_current_dir().unwrap();
    let generated = cards(&root.join("experiments")).unwrap();
    let tasks: BTreeSet<String> = load_dir(&root.join("experiments"), check_job)
        .unwrap()
        .iter()
        .flat_map(PaperFile::jobs)
        .map(|j| j.task().to_string())
        .collect();
    assert_eq!(generated.len(), tasks.len() + 1);
    let index = &generated[INDEX];
    for task in &tasks {
        assert!(index.contains(&format!("| {task} |")), "{task} not indexed");
    }
    let card = &generated["kong2019-circle--znn-eq22.md"];
    // docs/robots.md's check value: the Katana's task point at theta*0 is
    // (0.081034, 0.249398, 0.379100) m, where the circle starts.
    assert!(card.contains("r_start = f(theta_ref) = [0.08103"), "{card}");
    for part in [
        "q = mu (theta - theta*0)",
        "`{ kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }`",
        "l1 = 0.2015, l2 = 0.19, l3 = 0.139",
        "- theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.5471975511965976] rad",
    ] {
        assert!(card.contains(part), "{part} not in\n{card}");
    }
}
