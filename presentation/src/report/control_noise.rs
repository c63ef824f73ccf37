//! The control page's noise floor (`results/control-noise.csv`, the `class_under_noise` column
//! of `results/cycles-trend.csv`; crate `control`'s rounding-noise probe): which digits of the
//! control table's |x - x*| are reproducible, and which trend classes change under the probe.
//! Every number of the prose is counted or read from those rows by `analysis::control_noise`;
//! this module formats it.

use super::markdown::{sci, sci_opt, text, Table, MISSING};
use analysis::report_model::Control;
use analysis::{NoiseSummary, NOISE_LISTED as LISTED};
use records::control::{TrendClass, TrendRow};

/// The probe's definition, as the page states it.
const PROBE: &str = "Each run of the control table and of the many-cycles table below runs a \
second time as a rounding-noise probe: after every tick each joint angle is moved by one unit \
in the last place (to the next floating-point number up or down, the direction drawn per joint \
and tick from splitmix64 with a fixed seed, the same in every reproduction; a continuous-time \
run moves theta0 once, the same way), a model of what another order of the same floating-point \
operations does to the state. The relative change |m' - m| / |m| of a metric m under the probe \
is its noise floor: a metric with a noise floor of 1e-p is reproducible to about p significant \
digits, and a change of a result below its noise floor is not evidence of anything. \
`results/control-noise.csv` holds it for every deterministic column of every row (0: bit for \
bit; empty: undefined, where one value is missing or m = 0 differs from m').";

/// "Rounding noise": the probe, the summary `s` of max |x - x*|'s noise floor over the rows
/// (the report model's), and the rows where it is at least its listing bound or the probe
/// ended otherwise. Empty without a noise floor.
pub fn section(s: &NoiseSummary) -> String {
    if s.rows == 0 {
        return String::new();
    }
    let mut out = format!("### Rounding noise\n\n{PROBE}\n\n");
    out.push_str(&format!(
        "Of the {} rows, max |x - x*| is the same bit for bit under the probe in {}, moves \
         by less than {} in {}, by {} or more in {}, and has no defined relative change \
         in {}; under the probe, {} runs end with another status.",
        s.rows,
        s.exact,
        sci(LISTED),
        s.below,
        sci(LISTED),
        s.at_least,
        s.undefined,
        s.status_changes,
    ));
    if s.listed.is_empty() {
        out.push_str("\n\n");
        return out;
    }
    out.push_str(" Those rows, largest noise floor first:\n\n");
    let mut t = Table::new([
        "task",
        "method",
        "h (ms)",
        "status (under the probe)",
        "max |x - x*|",
        "its noise floor",
        "drift's noise floor",
        "max tracking error's noise floor",
    ]);
    for (n, r) in &s.listed {
        t.push([
            n.task.clone(),
            n.method.clone(),
            n.h_ms.to_string(),
            match r {
                Some(r) if r.status != n.status_under_noise => {
                    format!("{} ({})", r.status, n.status_under_noise)
                }
                Some(r) => r.status.to_string(),
                None => format!("{MISSING} ({})", n.status_under_noise),
            },
            r.map_or_else(|| MISSING.to_string(), |r| sci(r.max_dx)),
            sci_opt(n.max_dx_noise),
            sci_opt(n.drift_noise),
            sci_opt(n.max_track_err_noise),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out
}

/// A class in words, or [`MISSING`].
fn class(c: Option<TrendClass>) -> &'static str {
    c.map_or(MISSING, |c| c.label())
}

/// The trend column under the probe: its class, or [`MISSING`].
pub fn class_under_noise(r: &TrendRow) -> String {
    class(r.class_under_noise).to_string()
}

/// Which many-cycles runs change class under the probe (the report model's), in a paragraph
/// (none: it says so).
pub fn trend_changes(model: &Control) -> String {
    let classed = model.classed;
    let changed: Vec<String> = model
        .changed_classes
        .iter()
        .map(|r| {
            format!(
                "{}, {} ({}): {} -> {}",
                text(&r.task),
                text(&r.method),
                r.h_ms
                    .map(|h| format!("{h} ms"))
                    .unwrap_or_else(|| "continuous".to_string()),
                class(r.class),
                class(r.class_under_noise)
            )
        })
        .collect();
    if changed.is_empty() {
        format!(
            "Under the rounding-noise probe (\"At a robot's control rate\", *Rounding noise*) \
             every one of the {classed} classes stays as it is (last column).\n\n"
        )
    } else {
        let (verb, those) = if changed.len() == 1 {
            ("changes", "that class is")
        } else {
            ("change", "those classes are")
        };
        format!(
            "Under the rounding-noise probe (\"At a robot's control rate\", *Rounding noise*) \
             {} of the {classed} classes {verb} (last column), so {those} not reproducible: \
             {}.\n\n",
            changed.len(),
            changed.join("; ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixtures::{control_row as row, noise_row};
    use records::control::{ControlRow, ControlStatus, NoiseRow};

    fn noise(r: &ControlRow, max_dx_noise: f64, status: ControlStatus) -> NoiseRow {
        noise_row(r, Some(max_dx_noise), status)
    }

    #[test]
    fn the_section_states_the_summary_and_lists_its_rows() {
        let runs = [row("B", 1e-3), row("D", 0.5)];
        let rows = [
            noise(&runs[0], 0.09, ControlStatus::Ok),
            noise(&runs[1], 3e-5, ControlStatus::Diverged),
        ];
        let s = NoiseSummary {
            rows: 5,
            exact: 1,
            below: 1,
            at_least: 2,
            undefined: 1,
            status_changes: 1,
            listed: vec![(&rows[0], Some(&runs[0])), (&rows[1], Some(&runs[1]))],
        };
        let page = section(&s);
        assert!(
            page.contains(
                "Of the 5 rows, max |x - x*| is the same bit for bit under the probe in 1, \
                 moves by less than 1.00e-3 in 1, by 1.00e-3 or more in 2, and has no defined \
                 relative change in 1; under the probe, 1 runs end with another status."
            ),
            "{page}"
        );
        assert!(
            page.contains("| e / v | B | 1 | ok | 1.00e-3 | 9.00e-2 |"),
            "{page}"
        );
        assert!(
            page.contains("| e / v | D | 1 | ok (diverged) | 5.00e-1 | 3.00e-5 |"),
            "{page}"
        );
        let none = NoiseSummary {
            rows: 0,
            listed: Vec::new(),
            ..s
        };
        assert!(section(&none).is_empty());
    }
}
