//! The best solver of a column of the cross experiment (every velocity-level solver on every
//! velocity-level scheme and path): among the completed neural runs of one (experiment,
//! variant), by a rule: the value closest to the exact column's (for the drift, the scheme's
//! property, which a solver should not change) or the smallest. Values within a relative 1e-6
//! of the best tie.

use records::index::{completed, is_neural, metric, Runs, EXACT};
use records::RunRow;

/// How a column's best solver is picked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BestRule {
    /// Closest to the exact column's value.
    ClosestToExact,
    /// Smallest value.
    Smallest,
}

/// The best of one column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Best<'a> {
    /// No completed neural run has the value.
    Nothing,
    /// One run is best.
    Run(&'a RunRow),
    /// `runs` runs share the best value (to a relative 1e-6), `first` among them; `all`: every
    /// ranked run does.
    Tie {
        runs: usize,
        all: bool,
        first: &'a RunRow,
    },
}

/// The measures of the cross experiment's matrices (`runs.csv` columns), each with how its
/// columns' best is picked: the drift against the reference by closeness to the exact column,
/// the position error and the scores by the smallest.
pub const MEASURES: [(&str, BestRule); 4] = [
    ("drift_ref_norm", BestRule::ClosestToExact),
    ("max_pos_err", BestRule::Smallest),
    ("score_max_dx", BestRule::Smallest),
    ("score_rms_dx", BestRule::Smallest),
];

/// The best of one column (experiment, variant) of one measure's matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColumnBest<'a> {
    /// The measure (a `runs.csv` column of [`MEASURES`]).
    pub measure: &'static str,
    pub experiment: &'a str,
    pub variant: &'a str,
    pub best: Best<'a>,
}

/// The best of every column of `paper`'s runs (experiment, variant, in file order) in every
/// measure of [`MEASURES`].
pub fn bests<'a>(runs: &'a Runs, paper: &'a str) -> Vec<ColumnBest<'a>> {
    let mut columns: Vec<(&str, &str)> = runs
        .of_paper(paper)
        .map(|r| (r.experiment.as_str(), r.variant_id.as_str()))
        .collect();
    columns.dedup();
    MEASURES
        .iter()
        .flat_map(|&(measure, rule)| {
            columns
                .iter()
                .map(move |&(experiment, variant)| ColumnBest {
                    measure,
                    experiment,
                    variant,
                    best: best_in(runs, experiment, variant, measure, rule),
                })
        })
        .collect()
}

/// Whether `a` and `b` are equal to a relative 1e-6.
fn tied(a: f64, b: f64) -> bool {
    (b - a).abs() <= 1e-6 * a.abs().max(b.abs())
}

/// The best completed neural run of column `column` (a `runs.csv` metric) of (experiment,
/// variant) under `rule`.
fn best_in<'a>(
    runs: &'a Runs,
    experiment: &'a str,
    variant: &str,
    column: &str,
    rule: BestRule,
) -> Best<'a> {
    let exact = runs
        .find(experiment, variant, EXACT)
        .and_then(|r| metric(r, column));
    let key = |x: f64| match rule {
        BestRule::Smallest => Some(x),
        BestRule::ClosestToExact => exact.map(|e| (x - e).abs()),
    };
    let mut ranked: Vec<(&RunRow, f64)> = runs
        .of_experiment(experiment)
        .filter(|r| r.variant_id == variant && is_neural(r) && completed(r))
        .filter_map(|r| metric(r, column).and_then(key).map(|k| (r, k)))
        .collect();
    ranked.sort_by(|a, b| a.1.total_cmp(&b.1));
    match ranked.as_slice() {
        [] => Best::Nothing,
        [(first, a), (_, b), ..] if tied(*a, *b) => {
            let n = ranked.iter().filter(|(_, k)| tied(*a, *k)).count();
            Best::Tie {
                runs: n,
                all: n == ranked.len(),
                first,
            }
        }
        [(first, _), ..] => Best::Run(first),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use settings::NetworkKind;
    use spec::SolverKind;

    fn run(solver: &str, drift: f64) -> RunRow {
        let kind = if solver == EXACT {
            SolverKind::Exact
        } else {
            SolverKind::Network(NetworkKind::LviPdnn)
        };
        let mut r = RunRow::blank(&spec::RunKey::from_ids("e", "v", solver).unwrap(), kind);
        r.drift_ref_norm = Some(drift);
        r
    }

    #[test]
    fn the_closest_to_exact_wins_and_equal_values_tie() {
        let runs = Runs::new(vec![run(EXACT, 1.0), run("a", 1.5), run("b", 0.9)]);
        let best = best_in(&runs, "e", "v", "drift_ref_norm", BestRule::ClosestToExact);
        assert!(matches!(best, Best::Run(r) if r.solver_id == "b"));
        let best = best_in(&runs, "e", "v", "drift_ref_norm", BestRule::Smallest);
        assert!(matches!(best, Best::Run(r) if r.solver_id == "b"));
        let tied = Runs::new(vec![run("a", 1.0), run("b", 1.0 + 1e-9), run("c", 2.0)]);
        let best = best_in(&tied, "e", "v", "drift_ref_norm", BestRule::Smallest);
        assert!(matches!(
            best,
            Best::Tie {
                runs: 2,
                all: false,
                ..
            }
        ));
        assert_eq!(
            best_in(&tied, "e", "w", "drift_ref_norm", BestRule::Smallest),
            Best::Nothing
        );
    }
}
