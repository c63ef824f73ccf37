//! What the papers name must exist among the runs of the experiment files, checked before
//! anything runs ([`check_runs`]).
//!
//! - A mapping's `run` or `companions` entry in an experiment the files define must be one of
//!   its runs; a claim's selection (`runs`, `than`) whose experiment is an id (no `*`) the
//!   files define must select at least one run. Otherwise it is a typo: an error naming the
//!   file, the field and the valid choices (the experiment's variants, or the variant's
//!   solvers).
//! - A `[[sweep_check]]`'s columns must each match a variant of its sweep, and its `declared`
//!   variant be one, where the files define the sweep.
//! - What names an experiment the files do not define (a sweep check's among them), and a selection by an experiment
//!   pattern (`kong2019-*`) that selects nothing, is a note, not an error: a project may hold a
//!   subset of a paper's experiments (the report then shows the run as missing, the claim as
//!   N/A). The note names the file, the field and the run, so a misspelt id is seen.

use crate::claims::{Check, Selection, Test};
use crate::paper_rules::PaperProblem;
use crate::papers::{Papers, PapersError};
use spec::RunKey;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// How many valid choices an error lists before "...".
const SHOWN_CHOICES: usize = 12;

/// A paper file that names an experiment the experiment files do not define (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Absent {
    /// The `paper.toml`.
    pub file: PathBuf,
    /// Where in it: `mapping[2] field `run``, `claim[0] field `than``.
    pub place: String,
    /// The run or selection, as written.
    pub names: String,
}

impl std::fmt::Display for Absent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {}: \"{}\" names no experiment of the experiment files (shown as missing)",
            self.file.display(),
            self.place,
            self.names
        )
    }
}

/// Checks the mappings and claims of `papers` (read from `dir`, whose `<paper>/paper.toml` the
/// error names) against `runs`, every run of the experiment files (module docs); what names an
/// experiment the files do not define is returned, to be said.
pub fn check_runs(
    papers: &Papers,
    dir: &Path,
    runs: &[RunKey],
) -> Result<Vec<Absent>, PapersError> {
    let file = |paper: &str| dir.join(paper).join("paper.toml");
    let mut absent = Vec::new();
    let mut index_of_paper = std::collections::HashMap::<&str, usize>::new();
    for m in &papers.mappings {
        let index = index_of_paper.entry(m.paper.as_str()).or_insert(0);
        let named =
            std::iter::once(("run", &m.run)).chain(m.companions.iter().map(|c| ("companions", c)));
        for (field, key) in named {
            match missing(key, runs) {
                Missing::No => {}
                Missing::Experiment => absent.push(Absent {
                    file: file(&m.paper),
                    place: format!("mapping[{index}] field `{field}`"),
                    names: key.to_string(),
                }),
                Missing::Id(valid) => {
                    return Err(PapersError::Invalid {
                        path: file(&m.paper),
                        problem: PaperProblem::NoSuchRun {
                            index: *index,
                            field,
                            run: key.to_string(),
                            valid,
                        },
                    })
                }
            }
        }
        *index += 1;
    }
    check_sweeps(papers, &file, runs, &mut absent)?;
    for paper in &papers.papers {
        for (index, claim) in paper.claims.iter().enumerate() {
            let selections: Vec<(&'static str, &Selection)> = match &claim.check {
                Check::Compare { runs, test, .. } => {
                    let mut s = vec![("runs", runs)];
                    if let Test::Than { other, .. } = test {
                        s.push(("than", other));
                    }
                    s
                }
                Check::Rust { runs, .. } => runs.iter().map(|r| ("runs", r)).collect(),
            };
            for (field, selection) in selections {
                if runs
                    .iter()
                    .any(|k| selection.matches(&k.experiment, &k.variant, &k.solver))
                {
                    continue;
                }
                // A literal experiment id the files define: the rest is a typo. A pattern
                // (`kong2019-*`) may match only experiments a subset project holds.
                let literal = !selection.experiment.is_pattern();
                if literal
                    && runs
                        .iter()
                        .any(|k| selection.experiment.matches(&k.experiment))
                {
                    return Err(PapersError::Invalid {
                        path: file(&paper.id),
                        problem: PaperProblem::SelectsNothing { index, field },
                    });
                }
                absent.push(Absent {
                    file: file(&paper.id),
                    place: format!("claim[{index}] field `{field}`"),
                    names: selection.to_string(),
                });
            }
        }
    }
    Ok(absent)
}

/// The `[[sweep_check]]` tables of `papers` against `runs`: a sweep the files do not define is
/// noted in `absent` (the report shows its section as not run); in one they define, every
/// column's `variants` must match a variant of it, and `declared`, if given, be one.
fn check_sweeps(
    papers: &Papers,
    file: &dyn Fn(&str) -> PathBuf,
    runs: &[RunKey],
    absent: &mut Vec<Absent>,
) -> Result<(), PapersError> {
    let mut index_of_paper = std::collections::HashMap::<&str, usize>::new();
    for check in &papers.sweep_checks {
        let index = index_of_paper.entry(check.paper.as_str()).or_insert(0);
        let variants: BTreeSet<&str> = runs
            .iter()
            .filter(|k| k.experiment == check.experiment)
            .map(|k| k.variant.as_str())
            .collect();
        if variants.is_empty() {
            absent.push(Absent {
                file: file(&check.paper),
                place: format!("sweep_check[{index}] field `experiment`"),
                names: check.experiment.clone(),
            });
        }
        let shown = || {
            let mut shown: Vec<&str> = variants.iter().copied().take(SHOWN_CHOICES).collect();
            if variants.len() > SHOWN_CHOICES {
                shown.push("...");
            }
            shown.join(", ")
        };
        if let Some(declared) = &check.declared {
            if !variants.is_empty() && !variants.contains(declared.as_str()) {
                return Err(PapersError::Invalid {
                    path: file(&check.paper),
                    problem: PaperProblem::SweepDeclared {
                        index: *index,
                        variant: declared.clone(),
                        experiment: check.experiment.clone(),
                        valid: shown(),
                    },
                });
            }
        }
        let unmatched =
            check.columns.iter().enumerate().find(|(_, c)| {
                !variants.is_empty() && !variants.iter().any(|v| c.variants.matches(v))
            });
        if let Some((column, c)) = unmatched {
            return Err(PapersError::Invalid {
                path: file(&check.paper),
                problem: PaperProblem::SweepSelectsNothing {
                    index: *index,
                    column,
                    pattern: c.variants.as_str().to_string(),
                    experiment: check.experiment.clone(),
                    valid: shown(),
                },
            });
        }
        *index += 1;
    }
    Ok(())
}

/// Whether a run is among the runs, and if not, at which id.
#[derive(Debug, PartialEq)]
enum Missing {
    No,
    /// Its experiment is not one of the files'.
    Experiment,
    /// Its variant or solver is not; the valid choices there.
    Id(String),
}

/// Whether `key` is one of `runs` (module docs).
fn missing(key: &RunKey, runs: &[RunKey]) -> Missing {
    if runs.contains(key) {
        return Missing::No;
    }
    let of_experiment: Vec<&RunKey> = runs
        .iter()
        .filter(|k| k.experiment == key.experiment)
        .collect();
    let of_variant: Vec<&RunKey> = of_experiment
        .iter()
        .copied()
        .filter(|k| k.variant == key.variant)
        .collect();
    let (what, ids): (String, BTreeSet<&str>) = if of_experiment.is_empty() {
        return Missing::Experiment;
    } else if of_variant.is_empty() {
        (
            format!("variants of {}", key.experiment),
            of_experiment.iter().map(|k| k.variant.as_str()).collect(),
        )
    } else {
        (
            format!("solvers of {} / {}", key.experiment, key.variant),
            of_variant.iter().map(|k| k.solver.as_str()).collect(),
        )
    };
    let mut shown: Vec<&str> = ids.iter().copied().take(SHOWN_CHOICES).collect();
    if ids.len() > SHOWN_CHOICES {
        shown.push("...");
    }
    Missing::Id(format!("{what}: {}", shown.join(", ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_run_names_the_choices_at_its_first_unknown_id() {
        let runs = [
            RunKey::from_ids("e1", "v1", "s1").unwrap(),
            RunKey::from_ids("e1", "v1", "s2").unwrap(),
            RunKey::from_ids("e1", "v2", "s1").unwrap(),
            RunKey::from_ids("e2", "v1", "s1").unwrap(),
        ];
        let id = |e, v, s| missing(&RunKey::from_ids(e, v, s).unwrap(), &runs);
        assert_eq!(id("e1", "v1", "s2"), Missing::No);
        assert_eq!(id("e3", "v1", "s1"), Missing::Experiment);
        assert_eq!(
            id("e1", "v3", "s1"),
            Missing::Id("variants of e1: v1, v2".into())
        );
        assert_eq!(
            id("e1", "v2", "s2"),
            Missing::Id("solvers of e1 / v2: s1".into())
        );
        let many: Vec<RunKey> = (0..20)
            .map(|i| RunKey::from_ids("e", &format!("v{i:02}"), "s").unwrap())
            .collect();
        let Missing::Id(shown) = missing(&RunKey::from_ids("e", "x", "s").unwrap(), &many) else {
            panic!("a missing variant")
        };
        assert!(shown.ends_with("v11, ..."), "{shown}");
    }
}
