//! Task cards: the committed `report/tasks/` is exactly what the experiment files give (rendered
//! in memory, never over the committed files), one card per task, and a card carries the
//! suite's own check values.

use presentation::task_card::INDEX;
use reproduce::{load_experiments, task_cards, TASK_CARDS};

use std::collections::BTreeSet;

const REGENERATE: &str = "regenerate with `cargo run --release -p reproduce -- report`";

#[test]
fn the_committed_cards_are_the_generated_ones() {
    let root = catalog::root_from_current_dir().unwrap();
    let generated = task_cards(&load_experiments(&root.join("experiments")).unwrap()).unwrap();
    let dir = root.join("report").join(TASK_CARDS);
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
    let root = catalog::root_from_current_dir().unwrap();
    let generated = task_cards(&load_experiments(&root.join("experiments")).unwrap()).unwrap();
    let tasks: BTreeSet<String> = load_experiments(&root.join("experiments"))
        .unwrap()
        .iter()
        .flat_map(|f| f.jobs().unwrap())
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

/// A sweep of more variants than a sweep's cards gets that many, evenly spaced, its first and
/// last variants among them; a sweep of fewer gets a card per variant; the index lists the
/// cards written.
#[test]
fn a_large_sweep_gets_capped_cards() {
    use reproduce::MAX_SWEEP_CARDS;
    let dir = inputs::Scratch::dir("sweep-cards");
    for (variants, cards_wanted) in [(10, 10), (101, MAX_SWEEP_CARDS)] {
        let step = 1.0 / (variants - 1) as f64;
        std::fs::write(
            dir.join("kong2019.toml"),
            format!(
                r#"{}[[experiment.variant]]
label = "ZNN"
scheme = {{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }}
sweep = {{ "scheme.mu" = {{ from = 1.0, to = 2.0, step = {step} }} }}
[[experiment.variant]]
label = "alone"
scheme = {{ kind = "znn-rmp", mu = 3.0, k_p = 1.0 }}
"#,
                fixtures::katana_circle("a sweep's cards", "kong2019-cards", 0.05, "")
            ),
        )
        .unwrap();
        let files = load_experiments(&dir).unwrap();
        let variants_of_sweep: Vec<String> = (0..variants)
            .map(|i| {
                format!(
                    "kong2019-cards--{}.md",
                    files[0].variant(0, i).unwrap().id()
                )
            })
            .collect();
        let generated = task_cards(&files).unwrap();
        let of_sweep: Vec<&String> = generated
            .keys()
            .filter(|k| variants_of_sweep.contains(k))
            .collect();
        assert_eq!(of_sweep.len(), cards_wanted, "{variants} variants");
        for end in [&variants_of_sweep[0], &variants_of_sweep[variants - 1]] {
            assert!(generated.contains_key(end), "{end} has no card");
        }
        // The variant outside the sweep has its card; the index lists every card.
        assert!(generated.contains_key("kong2019-cards--alone.md"));
        assert_eq!(generated.len(), cards_wanted + 2);
        for name in generated.keys().filter(|k| *k != INDEX) {
            assert!(
                generated[INDEX].contains(name.as_str()),
                "{name} not in the index"
            );
        }
    }
}
