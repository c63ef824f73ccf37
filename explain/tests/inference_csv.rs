//! The committed `results/inference.csv` keeps the inference's promise: per table, the
//! reported best of the whole table and of each column alone is no worse than any setup the
//! file holds (every row carries the table residual and every column's residual at its
//! setup), each table has its declared setup, and every profile says whether it re-fits.

use records::inference::{InferenceRow, BEST, DECLARED, HYPOTHESIS, LOCAL, TABLE};
use std::path::Path;

fn committed() -> Vec<InferenceRow> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/inference.csv");
    store::table::read_if_present(&path).unwrap()
}

#[test]
fn the_reported_best_is_no_worse_than_any_evaluated_row() {
    let rows = committed();
    assert!(!rows.is_empty(), "results/inference.csv holds no rows");
    let mut tables: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r.paper.as_str(), r.table.as_str()))
        .collect();
    tables.dedup();
    for (paper, table) in tables {
        let of: Vec<&InferenceRow> = rows
            .iter()
            .filter(|r| r.paper == paper && r.table == table)
            .collect();
        let best = |objective: &str| {
            of.iter()
                .find(|r| r.kind == BEST && r.objective == objective)
                .unwrap_or_else(|| panic!("{paper} {table}: no best fit of {objective}"))
        };
        let joint = best(TABLE);
        assert!(
            of.iter()
                .any(|r| r.kind == DECLARED && r.objective == TABLE),
            "{paper} {table}: no declared row"
        );
        let columns: Vec<&str> = of
            .iter()
            .filter(|r| r.kind == DECLARED && r.objective != TABLE)
            .map(|r| r.objective.as_str())
            .collect();
        assert_eq!(joint.columns().len(), columns.len(), "{paper} {table}");
        for r in &of {
            assert!(
                joint.rel_residual <= r.table_residual,
                "{paper} {table}: best fit {} worse than the {} row at {}",
                joint.rel_residual,
                r.kind,
                r.table_residual
            );
            assert!(
                [DECLARED, BEST, HYPOTHESIS, LOCAL].contains(&r.kind.as_str())
                    || r.profile().is_some(),
                "{paper} {table}: unknown kind {}",
                r.kind
            );
            for (c, name) in columns.iter().enumerate() {
                let own = best(name);
                assert_eq!(own.rel_residual, own.columns()[c]);
                assert!(
                    own.rel_residual <= r.columns()[c],
                    "{paper} {table}: the best fit of {name} alone ({}) is worse than the {} row at {}",
                    own.rel_residual,
                    r.kind,
                    r.columns()[c]
                );
            }
        }
    }
}
