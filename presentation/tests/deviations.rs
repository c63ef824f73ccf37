//! report/deviations.md is written by hand; the numbers of results it states must be the
//! results'. Every number in scientific notation followed by a unit of a measured quantity
//! (rad, rad/s, m) is either inside a statement checked here against `results/runs.csv`
//! ([`STATED`]: each number at its printed digits) or inside a passage that says why it is not
//! a number of results ([`NOT_RESULTS`]: a setting, a paper's number, a change between two
//! revisions). A new such number in deviations.md fails the test until it is one or the other.

use analysis::misprints::rounding;
use records::index::{metric, Runs};
use store::read_runs;

/// Which of a selection's values a number states.
#[derive(Clone, Copy, Debug)]
enum Of {
    Min,
    Max,
}

/// One number of a statement: `printed` (as the text writes it) is the `of` of `metric` over
/// `runs` (run keys `experiment / variant / solver`, ids).
struct Number {
    printed: &'static str,
    runs: &'static [&'static str],
    metric: &'static str,
    of: Of,
}

/// robio2018's twelve runs of its methods (the mapped runs of papers/robio2018/paper.toml).
const ROBIO_METHODS: &[&str] = &[
    "robio2018-four-petals / rmp / 94lvi",
    "robio2018-four-petals / rmp / e47",
    "robio2018-four-petals / rmp / m3",
    "robio2018-four-petals / rmp / m4",
    "robio2018-four-petals / rmp / m5",
    "robio2018-four-petals / rmp / m6",
    "robio2018-five-pointed-star / rmp / 94lvi",
    "robio2018-five-pointed-star / rmp / e47",
    "robio2018-five-pointed-star / rmp / m3",
    "robio2018-five-pointed-star / rmp / m4",
    "robio2018-five-pointed-star / rmp / m5",
    "robio2018-five-pointed-star / rmp / m6",
];

const fn one(printed: &'static str, run: &'static [&'static str], metric: &'static str) -> Number {
    Number {
        printed,
        runs: run,
        metric,
        of: Of::Min,
    }
}

/// Statements of deviations.md with the numbers of results they hold.
const STATED: &[(&str, &[Number])] = &[
    (
        "leave |x - x*| of\n  3.10e-3 to 4.19e-3 rad/s at some instant",
        &[
            Number {
                printed: "3.10e-3",
                runs: ROBIO_METHODS,
                metric: "score_max_dx",
                of: Of::Min,
            },
            Number {
                printed: "4.19e-3",
                runs: ROBIO_METHODS,
                metric: "score_max_dx",
                of: Of::Max,
            },
        ],
    ),
    (
        "drift 1.24e-3 to 1.26e-2 rad",
        &[
            Number {
                printed: "1.24e-3",
                runs: ROBIO_METHODS,
                metric: "drift_norm",
                of: Of::Min,
            },
            Number {
                printed: "1.26e-2",
                runs: ROBIO_METHODS,
                metric: "drift_norm",
                of: Of::Max,
            },
        ],
    ),
    (
        "maximum position errors of 8.09e-4 to 4.54e-3 m",
        &[
            Number {
                printed: "8.09e-4",
                runs: ROBIO_METHODS,
                metric: "max_pos_err",
                of: Of::Min,
            },
            Number {
                printed: "4.54e-3",
                runs: ROBIO_METHODS,
                metric: "max_pos_err",
                of: Of::Max,
            },
        ],
    ),
    (
        "drifts 1.01e-5 rad on the four\n  petals and 1.06e-7 rad on the star",
        &[
            one(
                "1.01e-5",
                &["robio2018-four-petals / rmp / exact"],
                "drift_norm",
            ),
            one(
                "1.06e-7",
                &["robio2018-five-pointed-star / rmp / exact"],
                "drift_norm",
            ),
        ],
    ),
    (
        "from 1.21e-2 to\n  1.16e-2 rad",
        &[
            one(
                "1.21e-2",
                &["robio2018-four-petals / rmp / 94lvi"],
                "drift_norm",
            ),
            one(
                "1.16e-2",
                &["robio2018-four-petals / rmp-h-1e-4 / 94lvi-h-0.0001"],
                "drift_norm",
            ),
        ],
    ),
    (
        "brings |x - x*| to 4.14e-6 rad/s and the drift to\n  5.41e-4 rad",
        &[
            one(
                "4.14e-6",
                &["robio2018-four-petals / rmp-tol-1e-6 / 94lvi-tol-1e-6"],
                "score_max_dx",
            ),
            one(
                "5.41e-4",
                &["robio2018-four-petals / rmp-tol-1e-6 / 94lvi-tol-1e-6"],
                "drift_norm",
            ),
        ],
    ),
];

/// Passages whose numbers with a unit are not numbers of results, and why.
const NOT_RESULTS: &[(&str, &str)] = &[
    ("with delta = 1e-6 rad", "a setting of ours"),
    (
        "at most 1.7e-7 rad, at most 1.9e-5 relative on drifts above\n  1e-4 rad",
        "a change between two revisions' results, not a number of results/",
    ),
    ("is at most 1e-3 rad/s", "the leaderboard's tolerance"),
    (
        "~1e-2 rad/s from x* by design",
        "a property of the scheme, said in order of magnitude",
    ),
    ("below 1e-5 m in its figures", "the paper's numbers"),
    (
        "every drift is below\n  1e-5 rad on the four petals",
        "the paper's numbers",
    ),
];

fn deviations() -> String {
    let root = catalog::root_from_current_dir().unwrap();
    std::fs::read_to_string(root.join("report").join("deviations.md")).expect("deviations.md")
}

/// The byte offsets of every number in scientific notation followed by rad, rad/s or m.
fn numbers_with_units(doc: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let words: Vec<(usize, &str)> = doc
        .split_whitespace()
        .map(|w| (w.as_ptr() as usize - doc.as_ptr() as usize, w))
        .collect();
    for pair in words.windows(2) {
        let (at, w) = pair[0];
        let number = w
            .trim_start_matches(['(', '~', '≈'])
            .trim_end_matches([',', ';', '.', ':', ')']);
        let unit = pair[1].1.trim_end_matches([',', ';', '.', ':', ')']);
        let scientific = number.contains('e')
            && number.starts_with(|c: char| c.is_ascii_digit())
            && number.parse::<f64>().is_ok();
        if scientific && ["rad", "rad/s", "m"].contains(&unit) {
            out.push((at, format!("{number} {unit}")));
        }
    }
    out
}

/// The byte ranges where `passage` occurs in `doc`.
fn occurrences(doc: &str, passage: &str) -> Vec<std::ops::Range<usize>> {
    doc.match_indices(passage)
        .map(|(i, p)| i..i + p.len())
        .collect()
}

#[test]
fn every_number_of_results_in_the_deviations_is_the_results() {
    let doc = deviations();
    let root = catalog::root_from_current_dir().unwrap();
    let runs = Runs::new(read_runs(&root.join("results").join("runs.csv")).unwrap());
    for (passage, numbers) in STATED {
        assert!(
            doc.contains(passage),
            "deviations.md no longer says \"{passage}\": update presentation/tests/deviations.rs"
        );
        for n in *numbers {
            assert!(passage.contains(n.printed), "{passage}: {}", n.printed);
            let values: Vec<f64> = n
                .runs
                .iter()
                .map(|k| {
                    let k = spec::RunKey::parse(k).unwrap();
                    let r = runs
                        .find(&k.experiment, &k.variant, &k.solver)
                        .unwrap_or_else(|| panic!("no run {k}"));
                    metric(r, n.metric).unwrap_or_else(|| panic!("{k}: no {}", n.metric))
                })
                .collect();
            let value = match n.of {
                Of::Min => values.iter().copied().fold(f64::INFINITY, f64::min),
                Of::Max => values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            };
            let printed: f64 = n.printed.parse().unwrap();
            assert!(
                (value - printed).abs() <= rounding(printed),
                "deviations.md says {} for the {:?} of {} over {} run(s); results/runs.csv has {value:e}",
                n.printed,
                n.of,
                n.metric,
                n.runs.len()
            );
        }
    }
}

#[test]
fn every_number_with_a_unit_in_the_deviations_is_checked_or_said_not_a_result() {
    let doc = deviations();
    let covered: Vec<std::ops::Range<usize>> = STATED
        .iter()
        .map(|(p, _)| *p)
        .chain(NOT_RESULTS.iter().map(|(p, _)| *p))
        .flat_map(|p| occurrences(&doc, p))
        .collect();
    for (_, why) in NOT_RESULTS {
        assert!(!why.is_empty());
    }
    let unchecked: Vec<String> = numbers_with_units(&doc)
        .into_iter()
        .filter(|(at, _)| !covered.iter().any(|r| r.contains(at)))
        .map(|(at, n)| {
            let line = doc[..at].lines().count();
            format!("line {line}: {n}")
        })
        .collect();
    assert!(
        unchecked.is_empty(),
        "deviations.md states numbers with units that no test checks against results/ (add them \
         to STATED or, when not results, to NOT_RESULTS in presentation/tests/deviations.rs): {unchecked:?}"
    );
}

#[test]
fn the_scanner_finds_numbers_with_units() {
    let found = numbers_with_units("drifts (1.0e-5 rad), 3 m, 4e-3 m; and 2e-1 s.");
    let numbers: Vec<&str> = found.iter().map(|(_, n)| n.as_str()).collect();
    assert_eq!(numbers, ["1.0e-5 rad", "4e-3 m"]);
}
