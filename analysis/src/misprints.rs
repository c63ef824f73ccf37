//! Printed numbers that contradict each other, and the simple misprints that would reconcile
//! them. Generic over any paper's `values.csv`: nothing here names a paper.
//!
//! A column of a published table that prints per-joint drifts d_1..d_n and their norm N says
//! N = ‖d‖_2. Every printed number is rounded to its printed digits: a number printed with
//! mantissa digits m_0.m_1...m_k and exponent e is within u = 0.5 · 10^(e−k) of the true
//! value (u = 0 for a printed 0). Since |‖a‖ − ‖b‖| ≤ ‖a − b‖ ≤ Σ|a_i − b_i|, the printed
//! numbers are **consistent** when |N − ‖d‖| ≤ u(N) + Σ u(d_i) ([`consistent`]); otherwise they
//! contradict each other, and at least one of them is not what the authors computed.
//!
//! For a contradicted column, [`contradictions`] tries every single misprint of one printed
//! number and keeps those under which the column is consistent:
//! - **one exponent**: x read as x · 10^k, k ∈ {−2, −1, 1, 2};
//! - **one digit**: one mantissa digit of x read as another;
//! - **one sign**: x read as −x (only a norm's sign changes the equation);
//! - **one swapped entry**: d_i of this column exchanged with the same joint's entry of another
//!   column of the same table (kept only when that column stays consistent if it was).
//!
//! These are hypotheses, shown beside the printed numbers, never in their place: every ratio
//! and verdict is still taken from what is printed ([`crate::papers::Papers::published`]), and
//! a ratio that rests on a contradicted column is said to ([`is_contradicted`]).

use crate::papers::{PaperValue, Papers};

/// The metric of a printed norm.
const NORM: &str = "drift_norm";

/// The exponents tried by the one-exponent hypothesis.
const EXPONENT_SHIFTS: [i32; 4] = [-2, -1, 1, 2];

/// Whether `metric` is a per-joint drift (`drift_1`, `drift_2`, ...).
fn is_joint(metric: &str) -> bool {
    metric
        .strip_prefix("drift_")
        .is_some_and(|k| k.parse::<usize>().is_ok())
}

/// A printed number as its decimal digits: the mantissa's digits (the first before the point)
/// and the exponent of the first, so value = ±0.d_0 d_1 ... · 10^(exponent + 1).
#[derive(Clone, Debug, PartialEq)]
struct Printed {
    negative: bool,
    digits: Vec<u8>,
    exponent: i32,
}

impl Printed {
    /// The shortest decimal that reads back as `v` (how values.csv printed it); none for 0 or
    /// a non-finite value.
    fn of(v: f64) -> Option<Printed> {
        if v == 0.0 || !v.is_finite() {
            return None;
        }
        let s = format!("{:e}", v.abs());
        let (mantissa, exponent) = s.split_once('e')?;
        Some(Printed {
            negative: v < 0.0,
            digits: mantissa
                .bytes()
                .filter(u8::is_ascii_digit)
                .map(|b| b - b'0')
                .collect(),
            exponent: exponent.parse().ok()?,
        })
    }

    fn value(&self) -> f64 {
        let text: String = self.digits.iter().map(|d| char::from(b'0' + d)).collect();
        let (first, rest) = text.split_at(1);
        let v: f64 = format!("{first}.{rest}e{}", self.exponent)
            .parse()
            .unwrap_or(f64::NAN);
        if self.negative {
            -v
        } else {
            v
        }
    }
}

/// Half a unit of the last printed digit of `v` (module docs); 0 for a printed 0.
pub fn rounding(v: f64) -> f64 {
    Printed::of(v).map_or(0.0, |p| {
        0.5 * 10f64.powi(p.exponent - (p.digits.len() as i32 - 1))
    })
}

/// Whether a printed norm and printed entries agree within their printed digits (module docs).
pub fn consistent(norm: f64, entries: &[f64]) -> bool {
    let of_entries = entries.iter().map(|d| d * d).sum::<f64>().sqrt();
    let slack = rounding(norm) + entries.iter().map(|d| rounding(*d)).sum::<f64>();
    // A relative 1e-12 for the arithmetic of the check itself.
    norm >= 0.0 && (norm - of_entries).abs() <= slack + 1e-12 * norm.abs().max(of_entries)
}

/// One single misprint (module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// The number's exponent off by this many decades: read x as x · 10^k.
    Exponent(i32),
    /// One mantissa digit (0 the first) printed as `from`, read as `to`.
    Digit { position: usize, from: u8, to: u8 },
    /// The sign.
    Sign,
    /// The entry exchanged with the same joint's entry of the named column.
    Swap { column: String },
}

/// A misprint that makes a contradicted column consistent: `metric`, printed `printed`, read
/// as `read_as`.
#[derive(Clone, Debug, PartialEq)]
pub struct Hypothesis {
    pub metric: String,
    pub printed: f64,
    pub read_as: f64,
    pub edit: Edit,
    /// |norm − ‖entries‖| under this reading (the hypotheses are sorted by it, nearest first).
    pub residual: f64,
}

impl std::fmt::Display for Hypothesis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = match &self.edit {
            Edit::Exponent(k) => format!("its exponent off by {k:+}"),
            Edit::Digit { position, from, to } => {
                format!("digit {} printed {from}, read {to}", position + 1)
            }
            Edit::Sign => "its sign".to_string(),
            Edit::Swap { column } => format!("exchanged with {column}'s"),
        };
        write!(
            f,
            "{} printed {:e} read as {:e} ({what})",
            self.metric, self.printed, self.read_as
        )
    }
}

/// A column whose printed norm is not the norm of its printed entries, and the single
/// misprints that would reconcile them (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Contradiction {
    pub paper: String,
    pub table: String,
    /// The paper's experiment and column.
    pub experiment: String,
    pub column: String,
    /// The printed norm, and the norm of the printed entries.
    pub printed_norm: f64,
    pub norm_of_entries: f64,
    pub hypotheses: Vec<Hypothesis>,
}

/// One column's printed joints (metric, value, in file order) and its printed norm.
struct Column<'a> {
    experiment: &'a str,
    column: &'a str,
    joints: Vec<(&'a str, f64)>,
    norm: f64,
}

impl Column<'_> {
    fn entries(&self) -> Vec<f64> {
        self.joints.iter().map(|(_, v)| *v).collect()
    }

    fn consistent(&self) -> bool {
        consistent(self.norm, &self.entries())
    }

    /// |norm − ‖entries‖| with joint `i` (if any) read as `v`, and the norm read as `norm`.
    fn residual(&self, norm: f64, joint: Option<(usize, f64)>) -> f64 {
        let mut e = self.entries();
        if let Some((i, v)) = joint {
            e[i] = v;
        }
        (norm - e.iter().map(|d| d * d).sum::<f64>().sqrt()).abs()
    }

    /// Consistent with joint `i` read as `v`.
    fn consistent_with(&self, i: usize, v: f64) -> bool {
        let mut e = self.entries();
        e[i] = v;
        consistent(self.norm, &e)
    }
}

/// The columns of `values` (one paper's table) that print a norm and at least one joint.
fn columns<'a>(values: &[&'a PaperValue]) -> Vec<Column<'a>> {
    let mut out: Vec<Column> = Vec::new();
    for v in values {
        if out
            .iter()
            .any(|c| c.experiment == v.experiment && c.column == v.column)
        {
            continue;
        }
        let of: Vec<&&PaperValue> = values
            .iter()
            .filter(|w| w.experiment == v.experiment && w.column == v.column)
            .collect();
        let norm = of.iter().find(|w| w.metric == NORM).map(|w| w.value);
        let joints: Vec<(&str, f64)> = of
            .iter()
            .filter(|w| is_joint(&w.metric))
            .map(|w| (w.metric.as_str(), w.value))
            .collect();
        if let (Some(norm), false) = (norm, joints.is_empty()) {
            out.push(Column {
                experiment: &v.experiment,
                column: &v.column,
                joints,
                norm,
            });
        }
    }
    out
}

/// Every reading of `x` under one exponent, one digit or one sign misprint.
fn single_edits(x: f64) -> Vec<(f64, Edit)> {
    let mut out = Vec::new();
    if let Some(p) = Printed::of(x) {
        for k in EXPONENT_SHIFTS {
            let mut q = p.clone();
            q.exponent += k;
            out.push((q.value(), Edit::Exponent(k)));
        }
        out.push((-x, Edit::Sign));
        for position in 0..p.digits.len() {
            for to in 0..=9u8 {
                let from = p.digits[position];
                if to == from || (position == 0 && to == 0) {
                    continue;
                }
                let mut q = p.clone();
                q.digits[position] = to;
                out.push((q.value(), Edit::Digit { position, from, to }));
            }
        }
    }
    out
}

/// The contradicted columns of `paper`'s tables, each with the single misprints that would
/// reconcile it (module docs), in the order values.csv lists them.
pub fn contradictions(paper: &str, papers: &Papers) -> Vec<Contradiction> {
    let mut out = Vec::new();
    for table in crate::published_table::published_tables(paper, papers) {
        let values: Vec<&PaperValue> = papers
            .values
            .iter()
            .filter(|v| v.paper == paper && v.table == table)
            .collect();
        let cols = columns(&values);
        for c in cols.iter().filter(|c| !c.consistent()) {
            let mut hypotheses = Vec::new();
            for (read_as, edit) in single_edits(c.norm) {
                if consistent(read_as, &c.entries()) {
                    hypotheses.push(Hypothesis {
                        metric: NORM.to_string(),
                        printed: c.norm,
                        read_as,
                        edit,
                        residual: c.residual(read_as, None),
                    });
                }
            }
            for (i, (metric, x)) in c.joints.iter().enumerate() {
                for (read_as, edit) in single_edits(*x) {
                    if c.consistent_with(i, read_as) {
                        hypotheses.push(Hypothesis {
                            metric: metric.to_string(),
                            printed: *x,
                            read_as,
                            edit,
                            residual: c.residual(c.norm, Some((i, read_as))),
                        });
                    }
                }
                for other in cols.iter().filter(|o| o.column != c.column) {
                    let Some(j) = other.joints.iter().position(|(m, _)| m == metric) else {
                        continue;
                    };
                    let theirs = other.joints[j].1;
                    let keeps_other = !other.consistent() || other.consistent_with(j, *x);
                    if theirs != *x && keeps_other && c.consistent_with(i, theirs) {
                        hypotheses.push(Hypothesis {
                            metric: metric.to_string(),
                            printed: *x,
                            read_as: theirs,
                            edit: Edit::Swap {
                                column: other.column.to_string(),
                            },
                            residual: c.residual(c.norm, Some((i, theirs))),
                        });
                    }
                }
            }
            hypotheses.sort_by(|a, b| a.residual.total_cmp(&b.residual));
            out.push(Contradiction {
                paper: paper.to_string(),
                table: table.clone(),
                experiment: c.experiment.to_string(),
                column: c.column.to_string(),
                printed_norm: c.norm,
                norm_of_entries: c.entries().iter().map(|d| d * d).sum::<f64>().sqrt(),
                hypotheses,
            });
        }
    }
    out
}

/// Whether the published column (`experiment`, `column`) has a printed norm that its printed
/// entries contradict, in `table` (any table when none): a ratio taken from this column there
/// rests on a contradicted number.
pub fn is_contradicted(
    contradictions: &[Contradiction],
    table: Option<&str>,
    experiment: &str,
    column: &str,
) -> bool {
    contradictions.iter().any(|c| {
        table.is_none_or(|t| c.table == t) && c.experiment == experiment && c.column == column
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(column: &str, metric: &str, value: f64) -> PaperValue {
        PaperValue {
            paper: "p".into(),
            table: "T1".into(),
            experiment: "E".into(),
            column: column.into(),
            metric: metric.into(),
            value,
            note: String::new(),
            inconsistent: None,
        }
    }

    #[test]
    fn rounding_is_half_the_last_printed_digit() {
        assert_eq!(rounding(0.0), 0.0);
        assert!((rounding(2.5436e-5) - 0.5e-9).abs() < 1e-24);
        assert!((rounding(-3e-4) - 0.5e-4).abs() < 1e-19);
        assert!(consistent(5.0, &[3.0, 4.0]));
        assert!(consistent(5.0, &[3.04, 4.0]), "within the printed digits");
        assert!(consistent(5.001, &[3.001, 4.001]));
        assert!(!consistent(5.001, &[3.201, 4.001]));
        assert!(!consistent(-5.0, &[3.0, 4.0]), "a norm is not negative");
    }

    #[test]
    fn an_exponent_digit_sign_and_swap_are_each_found_and_nothing_else() {
        // Column a: joint 2 printed 4e-6 where 4e-5 was meant (norm 5e-5 of 3e-5, 4e-5).
        // Column b: consistent. Column c: the norm's sign.
        let papers = Papers {
            values: vec![
                value("a", "drift_1", 3e-5),
                value("a", "drift_2", 4e-6),
                value("a", "drift_norm", 5e-5),
                value("b", "drift_1", 6e-5),
                value("b", "drift_2", 8e-5),
                value("b", "drift_norm", 1e-4),
                value("c", "drift_1", 6e-5),
                value("c", "drift_2", 8e-5),
                value("c", "drift_norm", -1e-4),
            ],
            ..Papers::default()
        };
        let found = contradictions("p", &papers);
        let columns: Vec<&str> = found.iter().map(|c| c.column.as_str()).collect();
        assert_eq!(columns, ["a", "c"]);
        let a = &found[0];
        assert!(a
            .hypotheses
            .iter()
            .any(|h| h.metric == "drift_2" && h.edit == Edit::Exponent(1) && h.read_as == 4e-5));
        assert!(a
            .hypotheses
            .iter()
            .all(|h| consistent_reading(&papers, a, h)));
        let c = &found[1];
        assert!(c
            .hypotheses
            .iter()
            .any(|h| h.metric == "drift_norm" && h.edit == Edit::Sign));
        assert!(is_contradicted(&found, None, "E", "c"));
        assert!(is_contradicted(&found, Some("T1"), "E", "c"));
        assert!(!is_contradicted(&found, Some("T2"), "E", "c"));
        assert!(!is_contradicted(&found, None, "E", "b"));
        let residuals: Vec<f64> = a.hypotheses.iter().map(|h| h.residual).collect();
        assert!(residuals.windows(2).all(|w| w[0] <= w[1]), "nearest first");
    }

    /// Whether column `c` is consistent with the hypothesis `h` applied (an independent check
    /// of what [`contradictions`] kept).
    fn consistent_reading(papers: &Papers, c: &Contradiction, h: &Hypothesis) -> bool {
        let of: Vec<&PaperValue> = papers
            .values
            .iter()
            .filter(|v| v.column == c.column)
            .collect();
        let read = |v: &PaperValue| {
            if v.metric == h.metric {
                h.read_as
            } else {
                v.value
            }
        };
        let norm = of.iter().find(|v| v.metric == NORM).map(|v| read(v));
        let entries: Vec<f64> = of
            .iter()
            .filter(|v| is_joint(&v.metric))
            .map(|v| read(v))
            .collect();
        norm.is_some_and(|n| consistent(n, &entries))
    }

    #[test]
    fn a_digit_and_a_swap_with_another_column_are_hypotheses() {
        // a: 3, 4, printed norm 5 but joint 1 printed 8 (a digit); b: 3, 4, 5 (consistent).
        let papers = Papers {
            values: vec![
                value("a", "drift_1", 8.0),
                value("a", "drift_2", 4.0),
                value("a", "drift_norm", 5.0),
                value("b", "drift_1", 3.0),
                value("b", "drift_2", 6.0),
                value("b", "drift_norm", 6.708),
            ],
            ..Papers::default()
        };
        let found = contradictions("p", &papers);
        assert_eq!(found.len(), 1);
        let edits: Vec<&Edit> = found[0].hypotheses.iter().map(|h| &h.edit).collect();
        assert!(edits.contains(&&Edit::Digit {
            position: 0,
            from: 8,
            to: 3
        }));
        // Exchanging joint 1 with b's 3 fixes a but breaks b: not a hypothesis.
        assert!(!edits.iter().any(|e| matches!(e, Edit::Swap { .. })));
    }

    #[test]
    fn the_printed_digits_read_back() {
        let p = Printed::of(-2.5436e-5).unwrap();
        assert_eq!(p.digits, [2, 5, 4, 3, 6]);
        assert_eq!(p.exponent, -5);
        assert_eq!(p.value(), -2.5436e-5);
        assert!(Printed::of(0.0).is_none());
    }
}
