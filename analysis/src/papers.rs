//! The papers as data: `papers/<paper>/paper.toml` (metadata and which run reproduces each
//! published column) and `papers/<paper>/values.csv` (the published numbers).
//!
//! `values.csv` is long: one number per row, named by (paper, table, experiment, column,
//! metric). Each `[[mapping]]` of `paper.toml` says which of our runs reproduces one
//! (experiment, column) of a paper, by its run key (`"<experiment> / <variant> / <solver>"`,
//! ids, see `spec::run_key`), with companion variants shown beside it.
//! `published_metrics::our_metric` names the `runs.csv` column of each published
//! metric. [`Papers::resolve`] combines both; a published number that finds no run is listed
//! in the report under "published numbers without a run", never dropped silently. Its `[[claim]]` tables are the claims checked against the
//! runs ([`crate::claims`]); its `[[sweep_check]]` tables set a published table beside a sweep's
//! runs (`sweep_check`). Adding a paper is adding a folder: no Rust.

use crate::paper_rules::{check_paper_id, PaperProblem};
use crate::published_metrics::{our_metric, METRIC_ALIASES, PUBLISHED_METRICS};
use crate::report_text::is_one_line;
use crate::sweep_check::SweepCheck;
use records::index::Runs;
use records::RunRow;
use serde::Deserialize;
use spec::RunKey;
use std::path::{Path, PathBuf};

/// One published number.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct PaperValue {
    pub paper: String,
    /// `T2`, `T3`, ... for a printed table, `text` for a number quoted in the text.
    pub table: String,
    /// The paper's experiment name (not our id).
    pub experiment: String,
    /// The paper's column header.
    pub column: String,
    pub metric: String,
    pub value: f64,
    pub note: String,
    /// Why the number contradicts the paper's own others, when it does (set at load by
    /// [`inconsistencies`]): the report shows it marked and computes nothing from it.
    #[serde(skip)]
    pub inconsistent: Option<String>,
}

/// A published number that contradicts the paper's own (file, line, what), warned at load.
#[derive(Clone, Debug, PartialEq)]
pub struct ValueWarning {
    pub file: PathBuf,
    /// The line of values.csv (the header is line 1).
    pub line: usize,
    pub message: String,
}

impl std::fmt::Display for ValueWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}: {}", self.file.display(), self.line, self.message)
    }
}

/// Marks the values of one paper (`values[i]` read from line `i + 2`) that contradict the
/// paper's own numbers, and returns one warning per mark (a second entry for the same
/// (table, experiment, column, metric) is refused when the file is read):
/// - a negative `drift_norm` (a norm is >= 0);
/// - a `drift_norm` below the largest |drift_k| of its own (table, experiment, column) (a
///   2-norm is at least every entry);
/// - a `drift_norm` that is not the 2-norm of its column's printed drift_k within their printed
///   digits ([`crate::misprints::consistent`]).
pub fn inconsistencies(file: &Path, values: &mut [PaperValue]) -> Vec<ValueWarning> {
    let mut warnings = Vec::new();
    let mut mark = |values: &mut [PaperValue], i: usize, message: String| {
        warnings.push(ValueWarning {
            file: file.to_path_buf(),
            line: i + 2,
            message: message.clone(),
        });
        values[i].inconsistent = Some(message);
    };
    for i in 0..values.len() {
        let v = &values[i];
        if v.metric != "drift_norm" || v.inconsistent.is_some() {
            continue;
        }
        if v.value < 0.0 {
            let message = format!("the printed norm {:e} is negative", v.value);
            mark(values, i, message);
            continue;
        }
        let largest = values
            .iter()
            .filter(|w| {
                w.table == v.table
                    && w.experiment == v.experiment
                    && w.column == v.column
                    && w.metric.starts_with("drift_")
                    && w.metric != "drift_norm"
                    && w.inconsistent.is_none()
            })
            .map(|w| (w.value.abs(), w.metric.clone()))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((entry, metric)) = largest {
            if v.value < entry {
                let message = format!(
                    "the printed norm {:e} is below its own {metric} entry {:e}",
                    v.value, entry
                );
                mark(values, i, message);
                continue;
            }
        }
        let entries: Vec<f64> = values
            .iter()
            .filter(|w| {
                w.table == v.table
                    && w.experiment == v.experiment
                    && w.column == v.column
                    && w.metric.starts_with("drift_")
                    && w.metric != "drift_norm"
            })
            .map(|w| w.value)
            .collect();
        if !entries.is_empty() && !crate::misprints::consistent(v.value, &entries) {
            let of_entries = entries.iter().map(|d| d * d).sum::<f64>().sqrt();
            let message = format!(
                "the printed norm {:e} is not the norm of its printed entries ({of_entries:.4e}, within their printed digits)",
                v.value
            );
            mark(values, i, message);
        }
    }
    warnings
}

/// A problem with the papers' files, naming the file.
#[derive(Debug, thiserror::Error)]
pub enum PapersError {
    #[error("{}: cannot list: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A file refused or unreadable by the input reader (a link leading out of papers/, a
    /// FIFO or device, over its cap).
    #[error(transparent)]
    Input(#[from] inputs::InputError),
    #[error("{}: {source}", path.display())]
    Csv { path: PathBuf, source: csv::Error },
    #[error("{}: {source}", path.display())]
    Toml {
        path: PathBuf,
        source: inputs::TomlError,
    },
    #[error("{}: {problem}", path.display())]
    Invalid {
        path: PathBuf,
        problem: PaperProblem,
    },
}

/// One paper's `paper.toml`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PaperFile {
    paper: String,
    title: String,
    #[serde(default)]
    citation: Option<String>,
    #[serde(default)]
    assumed_setup: Option<String>,
    #[serde(default, rename = "mapping")]
    mappings: Vec<MappingFile>,
    #[serde(default, rename = "claim")]
    claims: Vec<crate::claims::ClaimFile>,
    #[serde(default, rename = "sweep_check")]
    sweep_checks: Vec<crate::sweep_check::SweepCheckFile>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MappingFile {
    published_experiment: String,
    published_column: String,
    run: String,
    #[serde(default)]
    companions: Vec<String>,
}

/// A paper's metadata and claims.
#[derive(Clone, Debug, PartialEq)]
pub struct Paper {
    pub id: String,
    pub title: String,
    /// Authors, title, venue, year, DOI (as the paper is cited).
    pub citation: Option<String>,
    /// What of the setup was substituted because the paper does not print it (an assumed
    /// robot model, path size, ...): the verdict is then given "under an assumed setup".
    pub assumed_setup: Option<String>,
    /// Its claims, in file order ([`crate::claims`]).
    pub claims: Vec<crate::claims::ClaimSpec>,
}

/// Which of our runs reproduces one column of a published table.
#[derive(Clone, Debug, PartialEq)]
pub struct Mapping {
    pub paper: String,
    /// The values' `experiment`.
    pub published_experiment: String,
    /// The values' `column`.
    pub published_column: String,
    /// Our run (its variant is the one the ratios and the verdict use; its solver the paper's).
    pub run: RunKey,
    /// Further runs of the same experiment shown beside it: `"<variant>"` (the same solver)
    /// or `"<variant> / <solver>"` in the file (a solver whose settings, and so id, differ).
    pub companions: Vec<RunKey>,
}

/// A published compute time and the run it is compared with ([`Papers::timed_runs`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedRun<'a> {
    /// Our experiment id.
    pub experiment: &'a str,
    /// Our solver id.
    pub solver: &'a str,
    /// The paper's (MATLAB) seconds.
    pub published_s: f64,
    /// Our run, if the experiment has one of that solver.
    pub run: Option<&'a RunRow>,
}

/// Every paper of `papers/`: metadata, published values and mappings.
#[derive(Clone, Debug, Default)]
pub struct Papers {
    pub papers: Vec<Paper>,
    pub values: Vec<PaperValue>,
    pub mappings: Vec<Mapping>,
    /// Published tables set beside a sweep's runs (`sweep_check`).
    pub sweep_checks: Vec<SweepCheck>,
    /// Published numbers that contradict the paper's own ([`inconsistencies`]).
    pub warnings: Vec<ValueWarning>,
}

impl Papers {
    /// Reads every `papers/<paper>/` folder (sorted by name), each file with the input reader
    /// (crate `inputs`: regular files inside `dir`, at most their kind's cap): `paper.toml` is
    /// required, `values.csv` optional (a paper may publish only figures). Everything
    /// `paper_rules` states is checked here, before anything runs.
    pub fn load(dir: &Path) -> Result<Papers, PapersError> {
        let mut folders: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|source| PapersError::Io {
                path: dir.to_path_buf(),
                source,
            })?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_dir())
            .collect();
        folders.sort();
        let mut out = Papers::default();
        for folder in folders {
            let read = load_folder(dir, &folder)?;
            out.mappings.extend(read.mappings);
            out.sweep_checks.extend(read.sweep_checks);
            out.warnings.extend(read.warnings);
            out.values.extend(read.values);
            out.papers.push(read.paper);
        }
        Ok(out)
    }

    /// The mapping of a published number's (paper, experiment, column), if any.
    pub fn mapping_of(&self, v: &PaperValue) -> Option<&Mapping> {
        self.mappings.iter().find(|m| {
            m.paper == v.paper
                && m.published_experiment == v.experiment
                && m.published_column == v.column
        })
    }

    /// The published compute times (values whose metric is ours `sim_s`) with their mappings,
    /// in the published values' order.
    pub fn timed_values(&self) -> impl Iterator<Item = (&PaperValue, &Mapping)> {
        self.values
            .iter()
            .filter(|v| our_metric(&v.metric) == Some("sim_s"))
            .filter_map(|v| self.mapping_of(v).map(|m| (v, m)))
    }

    /// Our experiments that a published compute time maps onto, in the published values'
    /// order.
    pub fn timed_experiments(&self) -> Vec<&str> {
        let mut experiments: Vec<&str> = self
            .timed_values()
            .map(|(_, m)| m.run.experiment.as_str())
            .collect();
        experiments.dedup();
        experiments
    }

    /// The ids of the papers that publish compute times, in file order.
    pub fn timed_papers(&self) -> Vec<&str> {
        let mut ids: Vec<&str> = self.timed_values().map(|(v, _)| v.paper.as_str()).collect();
        ids.dedup();
        ids
    }

    /// The published compute times of one of our experiments, as (our solver id, seconds).
    pub fn times_of<'a>(
        &'a self,
        experiment: &'a str,
    ) -> impl Iterator<Item = (&'a str, f64)> + 'a {
        self.timed_values()
            .filter(move |(_, m)| m.run.experiment == experiment)
            .map(|(v, m)| (m.run.solver.as_str(), v.value))
    }

    /// The published compute times beside the runs they are compared with (the report's
    /// MATLAB comparison, and what the timing pass times alone): per experiment a time maps
    /// onto ([`Papers::timed_experiments`]) and per published solver, the experiment's first
    /// run of that solver among `runs` (sorted by key), or none.
    pub fn timed_runs<'a>(&'a self, runs: &'a Runs) -> impl Iterator<Item = TimedRun<'a>> + 'a {
        self.timed_experiments()
            .into_iter()
            .flat_map(move |experiment| {
                self.times_of(experiment)
                    .map(move |(solver, published_s)| TimedRun {
                        experiment,
                        solver,
                        published_s,
                        run: runs
                            .of_experiment(experiment)
                            .find(|r| r.solver_id == solver),
                    })
            })
    }

    /// The mappings of one paper, in file order.
    pub fn mappings_of<'a>(&'a self, paper: &'a str) -> impl Iterator<Item = &'a Mapping> + 'a {
        self.mappings.iter().filter(move |m| m.paper == paper)
    }

    /// Finds the run (and column) that reproduces a published number.
    pub fn resolve<'a>(&'a self, v: &PaperValue, runs: &'a Runs) -> Resolution<'a> {
        let Some(mapping) = self.mapping_of(v) else {
            return Resolution::Unmapped(
                "no single run corresponds (see the claims checklist)".to_string(),
            );
        };
        let Some(metric) = our_metric(&v.metric) else {
            return Resolution::Unmapped(format!("the suite does not record `{}`", v.metric));
        };
        let k = &mapping.run;
        match runs.find(&k.experiment, &k.variant, &k.solver) {
            Some(run) => Resolution::Found {
                mapping,
                run,
                metric,
            },
            None => Resolution::Unmapped(format!(
                "mapped to {k}, but that run is missing from results/runs.csv"
            )),
        }
    }

    /// The published numbers that find no run, with the reason.
    pub fn unmapped<'a>(&'a self, runs: &Runs) -> Vec<(&'a PaperValue, String)> {
        self.values
            .iter()
            .filter_map(|v| match self.resolve(v, runs) {
                Resolution::Unmapped(why) => Some((v, why)),
                Resolution::Found { .. } => None,
            })
            .collect()
    }

    /// The published value of `metric` (a `runs.csv` column name) for one mapped column, and
    /// whether it was derived: a drift norm the paper does not print is computed from its
    /// per-joint entries (flagged `true`).
    pub fn published(&self, mapping: &Mapping, metric: &str) -> Option<(f64, bool)> {
        let of_column = || {
            self.values
                .iter()
                .filter(move |v| self.mapping_of(v) == Some(mapping))
        };
        if let Some(v) = of_column()
            .filter(|v| v.inconsistent.is_none())
            .find(|v| our_metric(&v.metric) == Some(metric))
        {
            return Some((v.value, false));
        }
        if metric != "drift_norm" {
            return None;
        }
        let joints: Vec<f64> = of_column()
            .filter(|v| v.inconsistent.is_none())
            .filter(|v| v.metric.starts_with("drift_") && v.metric != "drift_norm")
            .map(|v| v.value)
            .collect();
        (!joints.is_empty()).then(|| (joints.iter().map(|d| d * d).sum::<f64>().sqrt(), true))
    }
}

/// One paper folder as read: its paper, mappings, sweep checks, published values and their
/// warnings.
struct Folder {
    paper: Paper,
    mappings: Vec<Mapping>,
    values: Vec<PaperValue>,
    sweep_checks: Vec<SweepCheck>,
    warnings: Vec<ValueWarning>,
}

/// Reads and checks one folder `folder` of `dir` (its `paper.toml` and `values.csv`).
fn load_folder(dir: &Path, folder: &Path) -> Result<Folder, PapersError> {
    let path = folder.join("paper.toml");
    let invalid = |problem| PapersError::Invalid {
        path: path.clone(),
        problem,
    };
    let file = read_paper_file(dir, folder, &path)?;
    let mappings = mappings(&file.paper, file.mappings).map_err(invalid)?;
    let values_path = folder.join("values.csv");
    let (values, warnings) = if values_path.symlink_metadata().is_ok() {
        let mut values = read_values(dir, &values_path, &file.paper)?;
        let warnings = inconsistencies(&values_path, &mut values);
        (values, warnings)
    } else {
        (Vec::new(), Vec::new())
    };
    if file.claims.len() > crate::paper_rules::MAX_CLAIMS {
        return Err(invalid(PaperProblem::TooManyClaims {
            count: file.claims.len(),
        }));
    }
    let claims = file
        .claims
        .into_iter()
        .enumerate()
        .map(|(index, c)| {
            c.into_spec()
                .map_err(|error| invalid(PaperProblem::Claim { index, error }))
        })
        .collect::<Result<_, _>>()?;
    if file.sweep_checks.len() > crate::paper_rules::MAX_SWEEP_CHECKS {
        return Err(invalid(PaperProblem::TooManySweepChecks {
            count: file.sweep_checks.len(),
        }));
    }
    let sweep_checks = file
        .sweep_checks
        .into_iter()
        .enumerate()
        .map(|(index, c)| c.into_check(&file.paper, index, &values).map_err(invalid))
        .collect::<Result<_, _>>()?;
    let paper = Paper {
        id: file.paper,
        title: file.title,
        citation: file.citation,
        assumed_setup: file.assumed_setup,
        claims,
    };
    Ok(Folder {
        paper,
        mappings,
        values,
        sweep_checks,
        warnings,
    })
}

/// The `paper.toml` at `path` of `folder` (under `dir`), read and checked as a file: the
/// folder's name is a paper id and the file's `paper`, and its texts are one line each.
fn read_paper_file(dir: &Path, folder: &Path, path: &Path) -> Result<PaperFile, PapersError> {
    let invalid = |problem| PapersError::Invalid {
        path: path.to_path_buf(),
        problem,
    };
    let name = folder
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or(PaperProblem::FolderNotUtf8)
        .map_err(invalid)?;
    check_paper_id(name).map_err(invalid)?;
    let text = inputs::read_text(path, inputs::Kind::PaperToml, inputs::Origin::Under(dir))?;
    let file: PaperFile = inputs::parse_toml(&text).map_err(|source| PapersError::Toml {
        path: path.to_path_buf(),
        source,
    })?;
    if file.paper != name {
        return Err(invalid(PaperProblem::NotTheFolder {
            paper: file.paper,
            folder: name.to_string(),
        }));
    }
    let lines = [
        ("title", Some(&file.title)),
        ("citation", file.citation.as_ref()),
        ("assumed_setup", file.assumed_setup.as_ref()),
    ];
    if let Some((field, _)) = lines
        .iter()
        .find(|(_, text)| text.is_some_and(|t| !is_one_line(t)))
    {
        return Err(invalid(PaperProblem::NotOneLine { field }));
    }
    Ok(file)
}

/// The `[[mapping]]` tables of `paper`'s file (at most `paper_rules::MAX_MAPPINGS`, each
/// with at most `paper_rules::MAX_COMPANIONS` companions), checked: each run a run key, each published
/// (experiment, column) mapped once, each companion a variant (or variant / solver) of the
/// run's experiment.
fn mappings(paper: &str, files: Vec<MappingFile>) -> Result<Vec<Mapping>, PaperProblem> {
    use crate::paper_rules::{MAX_COMPANIONS, MAX_MAPPINGS};
    if files.len() > MAX_MAPPINGS {
        return Err(PaperProblem::TooManyMappings { count: files.len() });
    }
    let mut mappings: Vec<Mapping> = Vec::new();
    for (index, m) in files.into_iter().enumerate() {
        if m.companions.len() > MAX_COMPANIONS {
            return Err(PaperProblem::TooManyCompanions {
                index,
                count: m.companions.len(),
            });
        }
        let run = RunKey::parse(&m.run).map_err(|_| PaperProblem::Run {
            index,
            run: m.run.clone(),
        })?;
        if let Some(first) = mappings.iter().position(|o| {
            o.published_experiment == m.published_experiment
                && o.published_column == m.published_column
        }) {
            return Err(PaperProblem::MappingTwice {
                index,
                first,
                experiment: m.published_experiment,
                column: m.published_column,
            });
        }
        let companions = m
            .companions
            .iter()
            .map(|c| {
                let key = if c.contains('/') {
                    RunKey::parse(&format!("{} / {c}", run.experiment))
                } else {
                    RunKey::from_ids(&run.experiment, c.trim(), &run.solver).map_err(Into::into)
                };
                key.map_err(|_| PaperProblem::Companion {
                    index,
                    companion: c.clone(),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        mappings.push(Mapping {
            paper: paper.to_string(),
            published_experiment: m.published_experiment,
            published_column: m.published_column,
            run,
            companions,
        });
    }
    Ok(mappings)
}

/// The published values of `paper` in `path` (a values.csv of `dir`), each checked: finite, of
/// a known metric, of this paper, its texts one line.
fn read_values(dir: &Path, path: &Path, paper: &str) -> Result<Vec<PaperValue>, PapersError> {
    let bytes = inputs::read(path, inputs::Kind::PaperValues, inputs::Origin::Under(dir))?;
    let csv_err = |source| PapersError::Csv {
        path: path.to_path_buf(),
        source,
    };
    let invalid = |problem| PapersError::Invalid {
        path: path.to_path_buf(),
        problem,
    };
    let mut values = Vec::new();
    // Each published number's (table, experiment, column, metric), and the line giving it.
    let mut first_line = std::collections::HashMap::new();
    for (i, row) in csv::Reader::from_reader(bytes.as_slice())
        .deserialize()
        .enumerate()
    {
        let mut v: PaperValue = row.map_err(csv_err)?;
        let line = i + 2;
        if let Some((_, name)) = METRIC_ALIASES.iter().find(|(a, _)| *a == v.metric) {
            v.metric = name.to_string();
        }
        if !v.value.is_finite() {
            return Err(invalid(PaperProblem::ValueNotFinite {
                line,
                value: v.value,
            }));
        }
        if !PUBLISHED_METRICS.contains(&v.metric.as_str()) {
            return Err(invalid(PaperProblem::UnknownMetric {
                line,
                metric: v.metric,
            }));
        }
        if v.paper != paper {
            return Err(invalid(PaperProblem::OtherPaper {
                line,
                paper: v.paper,
                folder: paper.to_string(),
            }));
        }
        let texts = [
            ("table", &v.table),
            ("experiment", &v.experiment),
            ("column", &v.column),
            ("note", &v.note),
        ];
        if let Some((field, _)) = texts.iter().find(|(_, t)| !is_one_line(t)) {
            return Err(invalid(PaperProblem::ValueNotOneLine { line, field }));
        }
        let id = [&v.table, &v.experiment, &v.column, &v.metric].map(String::clone);
        if let Some(first) = first_line.insert(id, line) {
            return Err(invalid(PaperProblem::ValueTwice {
                line,
                first,
                value: format!(
                    "the {} of {} / {} in table {}",
                    v.metric, v.experiment, v.column, v.table
                ),
            }));
        }
        values.push(v);
    }
    Ok(values)
}

impl Papers {
    /// The printed entry of `mapping`'s column for `metric` that contradicts the paper's own
    /// numbers, with the reason ([`inconsistencies`]).
    pub fn inconsistent(&self, mapping: &Mapping, metric: &str) -> Option<(f64, &str)> {
        self.values
            .iter()
            .filter(|v| self.mapping_of(v) == Some(mapping))
            .filter(|v| our_metric(&v.metric) == Some(metric))
            .find_map(|v| v.inconsistent.as_deref().map(|why| (v.value, why)))
    }
}

/// Where a published number lands among our runs.
#[derive(Clone, Debug, PartialEq)]
pub enum Resolution<'a> {
    /// Our run and the `runs.csv` column that measures the number.
    Found {
        mapping: &'a Mapping,
        run: &'a RunRow,
        metric: &'static str,
    },
    /// No run reproduces it (with the reason, for the report).
    Unmapped(String),
}

/// The tables a setup can be fitted to (crate `explain`, `inference::problem`): (paper, table),
/// each published table with per-joint drifts.
pub fn table_ids(values: &[PaperValue]) -> Vec<(String, String)> {
    let mut ids: Vec<(String, String)> = values
        .iter()
        .filter(|v| v.table != "text" && v.metric.starts_with("drift_") && v.metric != "drift_norm")
        .map(|v| (v.paper.clone(), v.table.clone()))
        .collect();
    ids.dedup();
    ids
}
