//! The verdicts of the setup inference in words, and the thresholds behind them, stated once
//! here: a column (or a table) counts as reproduced when its relative residual r_c (or r, see
//! the module doc of [`super`]) is at most [`REPRODUCED`]; a profile is flat when its largest
//! residual is below [`FLAT`] times its smallest, weakly determined below [`WEAK`] times,
//! determined otherwise.

use super::{InferenceRow, BEST, DECLARED, TABLE};

/// Largest relative residual that counts as reproduced.
pub const REPRODUCED: f64 = 0.25;
/// A profile spread (largest / smallest residual) below this: the table does not determine
/// the parameter.
pub const FLAT: f64 = 1.25;
/// A profile spread below this (and at least [`FLAT`]): weakly determined.
pub const WEAK: f64 = 2.0;

/// Largest over smallest of `residuals`, failed points ([`super::FAILED`]) left out.
pub fn spread(residuals: impl IntoIterator<Item = f64>) -> f64 {
    let r: Vec<f64> = residuals
        .into_iter()
        .filter(|r| *r < super::FAILED)
        .collect();
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
    if r >= super::FAILED {
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
    parts.push(format!("RMP {}", r.rmp));
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
    for r in rows.iter().filter(|r| r.kind == BEST && r.objective != TABLE) {
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
    out.push(if worst <= REPRODUCED {
        format!(
            "One inferred setup explains all {} columns together, each within {} ({}).",
            columns.len(),
            percent(worst),
            describe_setup(joint)
        )
    } else {
        format!(
            "No single setup tried explains all {} columns{}: the best shared setup (table residual {}; {}) leaves {}.",
            columns.len(),
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
