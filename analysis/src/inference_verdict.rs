//! The verdicts of the setup inference in words, and the thresholds behind them, stated once
//! here, from the rows of `results/inference.csv` alone: a column (or a table) counts as
//! reproduced when its relative residual r_c (or r, see the module doc of [`records::inference`])
//! is at most [`REPRODUCED`]; a profile is flat when its largest
//! residual is below [`FLAT`] times its smallest, weakly determined below [`WEAK`] times,
//! determined otherwise.

use records::inference::{InferenceRow, BEST, DECLARED, FAILED, TABLE};

/// Largest relative residual that counts as reproduced.
pub const REPRODUCED: f64 = 0.25;
/// A profile spread (largest / smallest residual) below this: the table does not determine
/// the parameter.
pub const FLAT: f64 = 1.25;
/// A profile spread below this (and at least [`FLAT`]): weakly determined.
pub const WEAK: f64 = 2.0;

/// Largest over smallest of `residuals`, failed points ([`FAILED`]) left out.
pub fn spread(residuals: impl IntoIterator<Item = f64>) -> f64 {
    let r: Vec<f64> = residuals.into_iter().filter(|r| *r < FAILED).collect();
    let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = r.iter().copied().fold(0.0, f64::max);
    hi / lo.max(f64::MIN_POSITIVE)
}

/// The words for a profile of spread `s`.
pub fn profile_verdict(s: f64) -> &'static str {
    if s < FLAT {
        "flat: the table does not determine it"
    } else if s < WEAK {
        "weakly determined: the residual moves by less than 2x over the range"
    } else {
        "determined"
    }
}

fn percent(r: f64) -> String {
    if r >= FAILED {
        "failed".to_string()
    } else {
        format!("{:.0} %", 100.0 * r)
    }
}

/// A setup in words: its hypothesis (robot, how the drift is computed) and its pose.
pub fn describe_setup(r: &InferenceRow) -> String {
    let mut parts = vec![
        format!("robot {}", r.robot),
        r.integration.describe().to_string(),
        format!("rotation {:.2} rad", r.rotation),
    ];
    if r.tilt_x != 0.0 || r.tilt_y != 0.0 {
        parts.push(format!(
            "plane tilted {:.2} rad about x, {:.2} rad about y",
            r.tilt_x, r.tilt_y
        ));
    }
    if r.phase != 0.0 {
        parts.push(format!("start phase {:.2}", r.phase));
    }
    if r.scale_factor != 1.0 {
        parts.push(format!("size x{:.2}", r.scale_factor));
    }
    if r.reverse {
        parts.push("reversed".to_string());
    }
    // The reading as printed is the declared one (and the only one of schemes without an RMP
    // term): named only when another was inferred.
    if !r.rmp.is_printed() {
        parts.push(format!("RMP read as {}", r.rmp.label()));
    }
    parts.join(", ")
}

/// The verdicts of one table's rows: one sentence per column (its own fit), then one for the
/// table (one setup shared by all columns); `None` without a declared and a best-fit row.
pub fn table_verdict(rows: &[&InferenceRow]) -> Option<Vec<String>> {
    let find = |kind: &str, objective: &str| {
        rows.iter()
            .find(|r| r.kind == kind && r.objective == objective)
    };
    let joint = find(BEST, TABLE)?;
    let mut columns: Vec<&str> = Vec::new();
    for r in rows
        .iter()
        .filter(|r| r.kind == BEST && r.objective != TABLE)
    {
        columns.push(&r.objective);
    }
    let mut out = Vec::new();
    let mut alone = 0;
    for c in &columns {
        let (Some(best), Some(declared)) = (find(BEST, c), find(DECLARED, c)) else {
            continue;
        };
        if best.rel_residual <= REPRODUCED {
            alone += 1;
            out.push(format!(
                "{c}: reproduced within {} under an inferred setup ({}); the declared setup is {} off.",
                percent(best.rel_residual),
                describe_setup(best),
                percent(declared.rel_residual)
            ));
        } else {
            out.push(format!(
                "{c}: not reproduced under any setup tried (best {} off, declared {}).",
                percent(best.rel_residual),
                percent(declared.rel_residual)
            ));
        }
    }
    let at_joint = joint.columns();
    let worst = at_joint.iter().copied().fold(0.0, f64::max);
    let listed: Vec<String> = columns
        .iter()
        .zip(&at_joint)
        .map(|(c, r)| format!("{c} {}", percent(*r)))
        .collect();
    let all = match columns.len() {
        1 => "the column".to_string(),
        2 => "both columns".to_string(),
        n => format!("all {n} columns"),
    };
    out.push(if worst <= REPRODUCED {
        format!(
            "One inferred setup explains {all} together, each within {} ({}).",
            percent(worst),
            describe_setup(joint)
        )
    } else {
        format!(
            "No single setup tried explains {all}{}: the best shared setup (table residual {}; {}) leaves {}.",
            if alone == columns.len() {
                ", though each is reproduced alone"
            } else {
                ""
            },
            percent(joint.rel_residual),
            describe_setup(joint),
            listed.join(", ")
        )
    });
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::inference::Integration;

    fn row(kind: &str, objective: &str, r: f64, columns: &str) -> InferenceRow {
        InferenceRow {
            paper: "p".into(),
            table: "T".into(),
            kind: kind.into(),
            objective: objective.into(),
            robot: "jaco2-pen".into(),
            integration: Integration::Exact,
            rotation: 0.5,
            phase: 0.0,
            scale_factor: 1.0,
            tilt_x: 0.0,
            tilt_y: 0.0,
            reverse: false,
            rmp: spec::RmpReading::Printed,
            rel_residual: r,
            table_residual: r,
            column_residuals: columns.into(),
            max_entry_error: None,
            signs_matched: None,
            entries: None,
            evaluations: 0,
            wall_s: 0.0,
        }
    }

    fn table(joint: f64, at_joint: &str, a: f64, b: f64) -> Vec<InferenceRow> {
        vec![
            row(DECLARED, TABLE, 1.0, "1;1"),
            row(DECLARED, "A", 1.0, "1;1"),
            row(DECLARED, "B", 1.0, "1;1"),
            row(BEST, TABLE, joint, at_joint),
            row(BEST, "A", a, "0.1;0.9"),
            row(BEST, "B", b, "0.9;0.6"),
        ]
    }

    #[test]
    fn columns_and_tables_get_their_verdicts() {
        let rows = table(0.45, "0.3;0.57", 0.1, 0.6);
        let refs: Vec<&InferenceRow> = rows.iter().collect();
        let v = table_verdict(&refs).unwrap();
        assert_eq!(v.len(), 3);
        assert!(v[0].starts_with("A: reproduced within 10 %"), "{}", v[0]);
        assert!(
            !v[0].contains("RMP"),
            "the declared reading goes unnamed: {}",
            v[0]
        );
        let other = InferenceRow {
            rmp: spec::RmpReading::Expansion,
            ..rows[4].clone()
        };
        assert!(describe_setup(&other).ends_with("RMP read as expansion"));
        assert!(v[1].starts_with("B: not reproduced under any setup tried (best 60 %"));
        assert!(v[2].starts_with("No single setup tried explains both columns:"));
        assert!(v[2].ends_with("leaves A 30 %, B 57 %."), "{}", v[2]);

        let rows = table(0.2, "0.15;0.24", 0.1, 0.2);
        let refs: Vec<&InferenceRow> = rows.iter().collect();
        let v = table_verdict(&refs).unwrap();
        assert!(
            v[2].starts_with("One inferred setup explains both columns together, each within 24 %")
        );

        assert!(table_verdict(&refs[..2]).is_none());
    }

    #[test]
    fn profile_spreads_leave_failed_points_out() {
        assert_eq!(spread([0.5, 0.6, super::FAILED]), 1.2);
        assert!(profile_verdict(1.2).starts_with("flat"));
        assert!(profile_verdict(1.5).starts_with("weakly"));
        assert_eq!(profile_verdict(2.5), "determined");
    }
}
