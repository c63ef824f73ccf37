//! A paper's claims as data: the `[[claim]]` tables of `papers/<paper>/paper.toml`.
//!
//! A claim compares one metric (a `runs.csv` column, e.g. `drift_norm`, `max_pos_err`,
//! `drift_6`) of a *selection* of runs with a threshold or with another selection:
//!
//! ```toml
//! [[claim]]
//! short = "drift(VLTCO) << drift(MVN-INVM)"
//! text = "clover, LVI-PDNN: ‖drift‖ of VLTCO at least 10x smaller than MVN-INVM's"
//! metric = "drift_norm"
//! runs = "jia2019-clover / vltco / lvi-pdnn"
//! than = "jia2019-clover / mvn-invm / lvi-pdnn"
//! factor = 10        # metric(runs) * factor <= metric(than); without it metric(runs) < metric(than)
//!
//! [[claim]]
//! short = "position error < 1e-4 m"
//! text = "max position error below 1e-4 m in every jia2019 run"
//! metric = "max_pos_err"
//! runs = "jia2019-* / * / *"
//! below = 1e-4       # or at_most, at_least, above
//! ```
//!
//! A selection is `"<experiment> / <variant> / <solver>"` of id patterns, `*` standing for any
//! text (`jia2019-*`, `vp-rnn-pf-*`, `*`). `abs = true` compares |metric|. `than` pairs each
//! selected run with the runs of the other selection *in the same experiment*. The verdict:
//! PASS when every comparison holds; FAIL when one does not or a selected run did not complete;
//! N/A when nothing is selected or a metric was not measured.
//!
//! What the grammar cannot say (a disjunction, a derived quantity such as a ratio of evaluation
//! counts) is a Rust claim: `rust = "<id>"` with `why` (the reason it is not data), and
//! optionally `runs` and `value` as its arguments; the report's claims module implements it.

use serde::Deserialize;

/// An id pattern: `*` matches any text (possibly empty).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pattern(String);

impl Pattern {
    /// The pattern written as `text`.
    pub fn new(text: &str) -> Pattern {
        Pattern(text.to_string())
    }

    /// The pattern as written.
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// Whether it has a `*` (else it matches one id only).
    pub fn is_pattern(&self) -> bool {
        self.0.contains('*')
    }

    /// Whether `id` matches.
    pub fn matches(&self, id: &str) -> bool {
        let parts: Vec<&str> = self.0.split('*').collect();
        if parts.len() == 1 {
            return self.0 == id;
        }
        let (first, last) = (parts[0], parts[parts.len() - 1]);
        if !id.starts_with(first) || id.len() < first.len() + last.len() || !id.ends_with(last) {
            return false;
        }
        let mut rest = &id[first.len()..id.len() - last.len()];
        for p in &parts[1..parts.len() - 1] {
            match rest.find(p) {
                Some(i) => rest = &rest[i + p.len()..],
                None => return false,
            }
        }
        true
    }
}

/// `"<experiment> / <variant> / <solver>"` of patterns.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Selection {
    pub experiment: Pattern,
    pub variant: Pattern,
    pub solver: Pattern,
}

impl Selection {
    pub fn parse(text: &str) -> Option<Selection> {
        let parts: Vec<&str> = text.split('/').map(str::trim).collect();
        match parts[..] {
            [e, v, s] if !e.is_empty() && !v.is_empty() && !s.is_empty() => Some(Selection {
                experiment: Pattern(e.into()),
                variant: Pattern(v.into()),
                solver: Pattern(s.into()),
            }),
            _ => None,
        }
    }

    /// Whether the run with these ids is selected.
    pub fn matches(&self, experiment: &str, variant: &str, solver: &str) -> bool {
        self.experiment.matches(experiment)
            && self.variant.matches(variant)
            && self.solver.matches(solver)
    }
}

impl std::fmt::Display for Selection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} / {} / {}",
            self.experiment.0, self.variant.0, self.solver.0
        )
    }
}

/// How a metric is compared.
#[derive(Clone, Debug, PartialEq)]
pub enum Test {
    /// Every selected run's metric `op` the threshold.
    Threshold(Op, f64),
    /// Every selected run's metric (times `factor`) against each run of `other` in its
    /// experiment: `m * factor <= o` with a factor, `m < o` without.
    Than {
        other: Selection,
        factor: Option<f64>,
    },
}

/// A threshold's comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Below,
    AtMost,
    AtLeast,
    Above,
}

impl Op {
    pub fn holds(self, x: f64, t: f64) -> bool {
        match self {
            Op::Below => x < t,
            Op::AtMost => x <= t,
            Op::AtLeast => x >= t,
            Op::Above => x > t,
        }
    }

    pub fn symbol(self) -> &'static str {
        match self {
            Op::Below => "<",
            Op::AtMost => "<=",
            Op::AtLeast => ">=",
            Op::Above => ">",
        }
    }
}

/// One claim of a paper.
#[derive(Clone, Debug, PartialEq)]
pub struct ClaimSpec {
    pub short: String,
    pub text: String,
    pub check: Check,
}

/// What decides a claim.
#[derive(Clone, Debug, PartialEq)]
pub enum Check {
    /// A metric of a selection against a threshold or another selection.
    Compare {
        metric: String,
        abs: bool,
        runs: Selection,
        test: Test,
    },
    /// A claim the grammar cannot say, implemented in Rust under `id`.
    Rust {
        id: String,
        why: String,
        runs: Option<Selection>,
        value: Option<f64>,
    },
}

/// A `[[claim]]` table as written.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClaimFile {
    short: String,
    text: String,
    #[serde(default)]
    metric: Option<String>,
    #[serde(default)]
    abs: bool,
    #[serde(default)]
    runs: Option<String>,
    #[serde(default)]
    below: Option<f64>,
    #[serde(default)]
    at_most: Option<f64>,
    #[serde(default)]
    at_least: Option<f64>,
    #[serde(default)]
    above: Option<f64>,
    #[serde(default)]
    than: Option<String>,
    #[serde(default)]
    factor: Option<f64>,
    #[serde(default)]
    rust: Option<String>,
    #[serde(default)]
    why: Option<String>,
    #[serde(default)]
    value: Option<f64>,
}

/// The ids of the claims implemented in Rust (the report's claims module implements each).
pub const RUST_CLAIMS: &[&str] = &[
    "diverges",
    "fails-or-much-worse-than-vp-cdnn",
    "evaluation-ratio",
];

/// What is wrong with a `[[claim]]` (the field and the valid choices).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ClaimError {
    #[error("field `metric`: unknown metric {} (valid: drift_k for joint k, {})", settings::shown(metric), records::index::metrics().map(|(n, _)| *n).collect::<Vec<_>>().join(", "))]
    UnknownMetric { metric: String },
    #[error("field `rust`: no Rust claim {} (known: {})", settings::shown(id), RUST_CLAIMS.join(", "))]
    UnknownRust { id: String },
    #[error("field `{field}`: must be a finite number")]
    NotFinite { field: &'static str },
    #[error("field `{field}`: must be one line of text (no line breaks, control or formatting characters)")]
    NotOneLine { field: &'static str },
    #[error("field `{field}`: {} is not \"<experiment> / <variant> / <solver>\" (id patterns, `*` for any text)", settings::shown(text))]
    Selection { field: &'static str, text: String },
    #[error("needs `metric` and `runs` and exactly one of `below`, `at_most`, `at_least`, `above`, `than` (or `rust` and `why` for a claim in Rust)")]
    Shape,
    #[error("field `factor`: only with `than`, and positive and finite")]
    Factor,
}

impl ClaimFile {
    /// The claim, checked: its selections parse, its metric and `rust` id are known, its
    /// numbers are finite and its texts are one line each.
    pub fn into_spec(self) -> Result<ClaimSpec, ClaimError> {
        for (field, text) in [("short", &self.short), ("text", &self.text)] {
            if !crate::report_text::is_one_line(text) {
                return Err(ClaimError::NotOneLine { field });
            }
        }
        let numbers = [
            ("below", self.below),
            ("at_most", self.at_most),
            ("at_least", self.at_least),
            ("above", self.above),
            ("value", self.value),
        ];
        if let Some((field, _)) = numbers
            .iter()
            .find(|(_, x)| x.is_some_and(|x| !x.is_finite()))
        {
            return Err(ClaimError::NotFinite { field });
        }
        if let Some(metric) = self
            .metric
            .as_ref()
            .filter(|m| !records::index::is_metric(m))
        {
            return Err(ClaimError::UnknownMetric {
                metric: metric.clone(),
            });
        }
        if let Some(id) = self
            .rust
            .as_ref()
            .filter(|id| !RUST_CLAIMS.contains(&id.as_str()))
        {
            return Err(ClaimError::UnknownRust { id: id.clone() });
        }
        let selection = |field: &'static str, text: &str| {
            Selection::parse(text).ok_or_else(|| ClaimError::Selection {
                field,
                text: text.into(),
            })
        };
        let runs = self
            .runs
            .as_deref()
            .map(|r| selection("runs", r))
            .transpose()?;
        let check = match (self.rust, self.why) {
            (Some(id), Some(why)) => Check::Rust {
                id,
                why,
                runs,
                value: self.value,
            },
            (None, None) => {
                let thresholds = [
                    (Op::Below, self.below),
                    (Op::AtMost, self.at_most),
                    (Op::AtLeast, self.at_least),
                    (Op::Above, self.above),
                ];
                let given: Vec<(Op, f64)> = thresholds
                    .iter()
                    .filter_map(|(op, t)| t.map(|t| (*op, t)))
                    .collect();
                let test = match (&given[..], self.than) {
                    ([(op, t)], None) if self.factor.is_none() => Test::Threshold(*op, *t),
                    ([], Some(other)) => {
                        if self.factor.is_some_and(|f| !(f > 0.0 && f.is_finite())) {
                            return Err(ClaimError::Factor);
                        }
                        Test::Than {
                            other: selection("than", &other)?,
                            factor: self.factor,
                        }
                    }
                    ([_], None) => return Err(ClaimError::Factor),
                    _ => return Err(ClaimError::Shape),
                };
                Check::Compare {
                    metric: self.metric.ok_or(ClaimError::Shape)?,
                    abs: self.abs,
                    runs: runs.ok_or(ClaimError::Shape)?,
                    test,
                }
            }
            _ => return Err(ClaimError::Shape),
        };
        Ok(ClaimSpec {
            short: self.short,
            text: self.text,
            check,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn claim(toml_text: &str) -> Result<ClaimSpec, ClaimError> {
        toml::from_str::<ClaimFile>(&format!("short = \"s\"\ntext = \"t\"\n{toml_text}"))
            .unwrap()
            .into_spec()
    }

    #[test]
    fn patterns_match_as_globs() {
        let p = |s: &str| Pattern(s.into());
        assert!(p("*").matches("") && p("*").matches("anything"));
        assert!(p("jia2019-*").matches("jia2019-clover") && !p("jia2019-*").matches("kong2019-x"));
        assert!(p("*-scheme").matches("zhang2018-butterfly-scheme"));
        assert!(p("zhang2018-*-scheme").matches("zhang2018-butterfly-scheme"));
        assert!(!p("zhang2018-*-scheme").matches("zhang2018-scheme"));
        assert!(p("a*b*c").matches("abc") && p("a*b*c").matches("axxbyyc"));
        assert!(!p("a*b*c").matches("acb"));
        assert!(p("exact").matches("exact") && !p("exact").matches("exact2"));
    }

    #[test]
    fn claims_parse_and_bad_ones_name_what_is_wrong() {
        let c = claim(
            "metric = \"drift_norm\"\nruns = \"e / v / s\"\nthan = \"e / w / s\"\nfactor = 10.0",
        )
        .unwrap();
        assert!(
            matches!(c.check, Check::Compare { test: Test::Than { factor: Some(f), .. }, .. } if f == 10.0)
        );
        let c = claim("metric = \"max_pos_err\"\nruns = \"e-* / * / *\"\nbelow = 1e-4").unwrap();
        assert!(
            matches!(c.check, Check::Compare { test: Test::Threshold(Op::Below, t), .. } if t == 1e-4)
        );
        assert!(matches!(
            claim("rust = \"diverges\"\nwhy = \"y\"").unwrap().check,
            Check::Rust { .. }
        ));
        assert_eq!(
            claim("metric = \"drift_norm\"\nruns = \"e / v\"\nbelow = 1.0"),
            Err(ClaimError::Selection {
                field: "runs",
                text: "e / v".into()
            })
        );
        assert_eq!(
            claim("metric = \"drift_2\"\nruns = \"e / v / s\"\nbelow = 1.0\nabove = 0.0"),
            Err(ClaimError::Shape)
        );
        assert_eq!(
            claim("metric = \"drift_2\"\nruns = \"e / v / s\""),
            Err(ClaimError::Shape)
        );
        assert_eq!(
            claim("runs = \"e / v / s\"\nbelow = 1.0"),
            Err(ClaimError::Shape)
        );
        assert_eq!(
            claim("metric = \"drift_2\"\nruns = \"e / v / s\"\nbelow = 1.0\nfactor = 2.0"),
            Err(ClaimError::Factor)
        );
        assert_eq!(
            claim(
                "metric = \"drift_2\"\nruns = \"e / v / s\"\nthan = \"e / v / t\"\nfactor = -1.0"
            ),
            Err(ClaimError::Factor)
        );
        assert_eq!(claim("rust = \"diverges\""), Err(ClaimError::Shape));
        assert!(Op::AtMost.holds(1.0, 1.0) && !Op::Below.holds(1.0, 1.0));
    }

    #[test]
    fn typos_non_finite_numbers_and_line_breaks_are_refused_naming_the_field() {
        let e = claim("metric = \"drift_nrom\"\nruns = \"e / v / s\"\nbelow = 1.0").unwrap_err();
        assert_eq!(
            e,
            ClaimError::UnknownMetric {
                metric: "drift_nrom".into()
            }
        );
        let shown = e.to_string();
        assert!(
            shown.contains("drift_norm") && shown.contains("max_pos_err"),
            "{shown}"
        );
        let e = claim("rust = \"divreges\"\nwhy = \"y\"").unwrap_err();
        assert!(e.to_string().contains("known: diverges"), "{e}");
        for (number, field) in [
            ("below = nan", "below"),
            ("above = inf", "above"),
            ("at_least = -inf", "at_least"),
        ] {
            let e = claim(&format!(
                "metric = \"drift_1\"\nruns = \"e / v / s\"\n{number}"
            ));
            assert_eq!(e, Err(ClaimError::NotFinite { field }), "{number}");
        }
        let e = claim("rust = \"evaluation-ratio\"\nwhy = \"y\"\nvalue = nan");
        assert_eq!(e, Err(ClaimError::NotFinite { field: "value" }));
        let two = toml::from_str::<ClaimFile>(
            "short = \"s\"\ntext = \"a\\n## Summary\"\nrust = \"diverges\"\nwhy = \"y\"",
        )
        .unwrap()
        .into_spec();
        assert_eq!(two, Err(ClaimError::NotOneLine { field: "text" }));
        // drift_k names any joint; drift_0 does not.
        assert!(claim("metric = \"drift_7\"\nruns = \"e / v / s\"\nbelow = 1.0").is_ok());
        assert!(claim("metric = \"drift_0\"\nruns = \"e / v / s\"\nbelow = 1.0").is_err());
    }
}
