//! Whether the experiment files describe a run key, decided from the names without making
//! every run (issue 43 item 2; docs/cluster.md, "What is still per run of the sweep").
//!
//! A run key is `experiment / variant / solver` ids. The experiment id names one experiment of
//! the files (ids are defined once across them), and a variant id one variant of it (ids are
//! distinct within an experiment, checked at load): a written variant's by a map of the
//! experiment's written ids; a swept one's, when the sweep's names are decided from its axes
//! ([`crate::sweep::Sweep::prefixes`]), read back into its index from the id's tokens
//! ([`IdReader`]: each axis's value at fixed places, the id made again from the axes and
//! compared). The solver id is then one of that variant's runs' solvers: the runs of a variant
//! are set by its fields `exact`, `solvers` and `numerical`, which only the base variant and the
//! axes whose paths begin with one of them set ([`crate::sweep::Sweep::run_digits`]), so the
//! solvers' ids are made once per distinct digits on those axes (a variant made: one per
//! sweep when no axis sets them), and whether the run keeps its trace is its sweep's choice at
//! its index (`KeptTraces`, from the axes). A key of a sweep whose names are not decided from
//! its axes (a label template, a value whose slug is not one token, ...; at most
//! [`crate::NAMES_COMPARED`] variants, or [`crate::CHECKED_WHOLE`] for a sweep checked whole)
//! is [`Found::Undecided`]: the caller holds those sweeps' runs ([`RunLookup::undecided_runs`]),
//! as every run was held before.
//!
//! What a lookup costs: a few hash lookups and one id made from the axes, plus one variant
//! made per distinct digits on the run axes (at most [`SOLVER_CACHE`] held); nothing per run of
//! the sweep.

use crate::error::ExperimentFileError;
use crate::experiment::{Entry, PaperFile};
use crate::sweep::{IdReader, Sweep};
use spec::{RunKey, RunSpec};
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// How many variants' solver ids a [`RunLookup`] keeps (by the sweep and the digits of its run
/// axes, [`crate::sweep::Sweep::run_digits`]); past it they are dropped and made again when
/// asked for.
const SOLVER_CACHE: usize = 4096;

/// What the experiment files say of a run key ([`RunLookup::find`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Found {
    /// A run of the files, which keeps its trace or not (its sweep's `traces`).
    Run {
        /// Whether the run keeps its trace.
        keeps_trace: bool,
    },
    /// No run of the files.
    NoRun,
    /// Not decided from the names: the key's experiment has a sweep whose names are not
    /// decided from its axes, and the key's variant is none of its other variants. Its runs
    /// are [`RunLookup::undecided_runs`].
    Undecided,
}

/// The run keys of experiment files, decided from the names (module docs).
pub struct RunLookup<'a> {
    files: &'a [PaperFile],
    /// Per experiment id: where the experiment stands and how its variant ids are found.
    experiments: HashMap<&'a str, ExperimentIds<'a>>,
    /// Solver ids of variants by (file, experiment, the entry's first variant, the digits on
    /// its run axes), at most [`SOLVER_CACHE`].
    solvers: RefCell<HashMap<SolversOf, Rc<[String]>>>,
}

/// Which variants share their runs' solvers: (file, experiment, the entry's first variant, the
/// digits on the entry's run axes; none for a written variant).
type SolversOf = (usize, usize, usize, Vec<usize>);

/// How the variant ids of one experiment are found.
struct ExperimentIds<'a> {
    /// The file's index and the experiment's in it.
    file: usize,
    index: usize,
    /// The written variants' ids and indices.
    written: HashMap<String, usize>,
    /// The sweeps whose names are decided from their axes: each one's first variant's index,
    /// the sweep and its id reader.
    decided: Vec<(usize, &'a Sweep, IdReader<'a>)>,
    /// Whether a sweep's names are not decided from its axes.
    undecided: bool,
}

impl<'a> RunLookup<'a> {
    /// The lookup of `files`' run keys: per experiment its written ids and its sweeps' id
    /// readers (the axes' values, no variant made).
    pub fn new(files: &'a [PaperFile]) -> Self {
        let mut experiments = HashMap::new();
        for (f, file) in files.iter().enumerate() {
            for (index, e) in file.experiments.iter().enumerate() {
                let mut v = ExperimentIds {
                    file: f,
                    index,
                    written: HashMap::new(),
                    decided: Vec::new(),
                    undecided: false,
                };
                for (range, entry) in e.variants.groups().zip(&e.variants.0) {
                    match entry {
                        Entry::Written(w) => {
                            v.written.insert(w.id(), range.start);
                        }
                        Entry::Swept(s) => match s.id_reader() {
                            Some(r) => v.decided.push((range.start, s, r)),
                            None => v.undecided = true,
                        },
                    }
                }
                experiments.insert(e.id.as_str(), v);
            }
        }
        RunLookup {
            files,
            experiments,
            solvers: RefCell::new(HashMap::new()),
        }
    }

    /// What the files say of `key` ([`Found`]), or the error of the variant made to learn its
    /// solvers (a swept variant that does not make: the error names its file, variant and
    /// field, as making every run did).
    pub fn find(&self, key: &RunKey) -> Result<Found, ExperimentFileError> {
        let Some(e) = self.experiments.get(key.experiment.as_str()) else {
            return Ok(Found::NoRun);
        };
        let id = key.variant.as_str();
        let (start, local, sweep) = if let Some(&i) = e.written.get(id) {
            (i, 0, None)
        } else if let Some((start, s, v)) = e
            .decided
            .iter()
            .find_map(|(start, s, r)| r.variant(id).map(|v| (*start, *s, v)))
        {
            (start, v, Some(s))
        } else if e.undecided {
            return Ok(Found::Undecided);
        } else {
            return Ok(Found::NoRun);
        };
        let digits = sweep.map_or_else(Vec::new, |s| s.run_digits(local));
        let solvers = self.solvers(e, start, local, digits)?;
        let Some(run) = solvers.iter().position(|s| key.solver == s.as_str()) else {
            return Ok(Found::NoRun);
        };
        let keeps_trace = sweep.is_none_or(|s| s.traces(local).keeps(run));
        Ok(Found::Run { keeps_trace })
    }

    /// The solver ids of the runs of variant `start + local` of experiment `e`, in run order,
    /// made once per (entry, `digits`) ([`SOLVER_CACHE`]).
    fn solvers(
        &self,
        e: &ExperimentIds<'_>,
        start: usize,
        local: usize,
        digits: Vec<usize>,
    ) -> Result<Rc<[String]>, ExperimentFileError> {
        let at = (e.file, e.index, start, digits);
        if let Some(ids) = self.solvers.borrow().get(&at) {
            return Ok(ids.clone());
        }
        let file = &self.files[e.file];
        let v = file
            .variant(e.index, start + local)
            .map_err(|error| file.in_file(error))?;
        let ids: Rc<[String]> = file
            .variant_jobs(&file.experiments[e.index], &v)
            .iter()
            .map(|j| j.solver.id())
            .collect();
        let mut cache = self.solvers.borrow_mut();
        if cache.len() >= SOLVER_CACHE {
            cache.clear();
        }
        cache.insert(at, ids.clone());
        Ok(ids)
    }

    /// The runs of the sweeps whose names are not decided from their axes (the keys
    /// [`RunLookup::find`] leaves [`Found::Undecided`]), in file order, made one variant at a
    /// time, or the first variant that does not make.
    pub fn undecided_runs(
        &self,
    ) -> impl Iterator<Item = Result<RunSpec, ExperimentFileError>> + 'a {
        let files = self.files;
        files.iter().flat_map(|file| {
            file.experiments
                .iter()
                .enumerate()
                .flat_map(move |(index, e)| {
                    let mut first = 0;
                    e.variants
                        .0
                        .iter()
                        .filter_map(move |entry| {
                            let runs = first..first + entry.runs(false);
                            first = runs.end;
                            match entry {
                                Entry::Swept(s) if s.id_reader().is_none() => Some(runs),
                                _ => None,
                            }
                        })
                        .flat_map(move |runs| {
                            file.runs_at(index, false, runs).map(move |r| {
                                r.map(|d| d.spec).map_err(|error| file.in_file(error))
                            })
                        })
                })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::near_misses;
    use proptest::prelude::*;
    use std::collections::HashSet;

    /// An axis of a sweep of valid kong2019 variants: its key and its values. Uneven run
    /// counts (`exact`, `solvers`), a solver's parameter, labelled values (with an empty text:
    /// names not decided from the axes), ranges on either side of zero, a key of two tokens.
    fn axis() -> impl Strategy<Value = (String, String)> {
        let n = 1usize..4;
        prop_oneof![
            n.clone().prop_map(|n| (
                "scheme.mu".to_string(),
                format!(
                    "[{}]",
                    (0..n).map(|k| format!("{k}.5")).collect::<Vec<_>>().join(", ")
                )
            )),
            (1u32..4, 0u32..3).prop_map(|(a, n)| (
                "scheme.mu".to_string(),
                format!("{{ from = {a}.0, to = {}.0, step = 0.5 }}", a + n)
            )),
            (1u32..4, 0u32..3).prop_map(|(a, n)| (
                "theta0.2".to_string(),
                format!("{{ from = -{}.25, to = -{a}.25, step = 1.0 }}", a + n)
            )),
            Just(("scheme.k_p".to_string(), "[1.0, 2.0]".to_string())),
            Just(("path.scale".to_string(), "[0.05, 0.1]".to_string())),
            Just(("path.reverse".to_string(), "[false, true]".to_string())),
            Just(("exact".to_string(), "[true, false]".to_string())),
            Just((
                "solvers".to_string(),
                "[{ value = [{ kind = \"znn\", gamma = 1.0 }], label = \"one\" }, \
                 { value = [{ kind = \"znn\", gamma = 1.0 }, { kind = \"finite-time\", beta = 1.0, alpha = 0.1, smoothing = 1e-6 }], label = \"two\" }]"
                    .to_string()
            )),
            Just(("solvers.0.gamma".to_string(), "[1.0, 2.0, 4.0]".to_string())),
            Just((
                "path.duration".to_string(),
                "[{ value = 0.05, label = \"short\" }, { value = 0.1, label = \"long\" }]"
                    .to_string()
            )),
            Just((
                "network_init".to_string(),
                "[{ value = \"zero\", label = \"\" }, { value = \"exact\", label = \"exact\" }]"
                    .to_string()
            )),
        ]
    }

    /// An experiment file of two experiments: one with a written variant and the sweep of
    /// `axes` (a declared id when `id`, `traces` when given), one with a written variant alone.
    fn file(axes: &[(String, String)], id: bool, traces: &str) -> Option<PaperFile> {
        let entries: Vec<String> = crate::sweep::apart(axes)
            .iter()
            .map(|(k, v)| format!("\"{k}\" = {v}"))
            .collect();
        let written = "[[experiment.variant]]\nlabel = \"Written\"\n\
             scheme = { kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }\n\
             solvers = [{ kind = \"znn\", gamma = 1.0 }]\n";
        let text = format!(
            "{}{written}[[experiment.variant]]\n{}label = \"L\"\n\
             scheme = {{ kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }}\n\
             solvers = [{{ kind = \"znn\", gamma = 1.0 }}]\n\
             path = {{ name = \"circle\", duration = 0.05 }}\ntheta0 = {}\n{traces}\
             sweep = {{ {} }}\n{}{written}",
            fixtures::katana_circle("lookup", "kong2019-lookup", 0.05, ""),
            if id { "id = \"z\"\n" } else { "" },
            fixtures::KATANA_THETA0,
            entries.join(", "),
            fixtures::katana_circle("lookup", "kong2019-other", 0.05, "")
                .split_once("[[experiment]]")
                .map(|(_, e)| format!("[[experiment]]{e}"))
                .expect("an experiment"),
        );
        PaperFile::from_toml(&text).ok()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// The lookup agrees with every run of the files made (what was held before): on
        /// every run's key, and on keys near them (a wrong digit, an extra or a missing token,
        /// a value slug of another axis or place, another variant's token, another solver's
        /// id, another experiment's id), each with whether it keeps its trace; the keys it
        /// leaves undecided answered by the undecided sweeps' runs.
        #[test]
        fn the_lookup_agrees_with_every_run_made(
            axes in proptest::collection::vec(axis(), 1..4),
            id in any::<bool>(),
            traces in prop_oneof![
                Just(""),
                Just("traces = \"none\"\n"),
                Just("traces = { every = 2 }\n"),
                Just("traces = { every = 3 }\n"),
            ],
        ) {
            let Some(f) = file(&axes, id, traces) else { return Ok(()) };
            let files = [f];
            let full: HashMap<String, bool> = files[0]
                .iter_jobs()
                .map(|j| j.map(|j| (j.key().to_string(), j.keep_trace)))
                .collect::<Result<_, _>>()
                .unwrap();
            let lookup = RunLookup::new(&files);
            let undecided: HashMap<String, bool> = lookup
                .undecided_runs()
                .map(|j| j.map(|j| (j.key().to_string(), j.keep_trace)))
                .collect::<Result<_, _>>()
                .unwrap();
            prop_assert!(undecided.iter().all(|(k, t)| full.get(k) == Some(t)));
            let keys: Vec<RunKey> = full.keys().map(|k| RunKey::parse(k).unwrap()).collect();
            let variants: Vec<String> = keys.iter().map(|k| k.variant.to_string()).collect();
            let solvers: HashSet<String> = keys.iter().map(|k| k.solver.to_string()).collect();
            let experiments = ["kong2019-lookup", "kong2019-other", "kong2019-none"];
            let mut asked = 0;
            for key in &keys {
                let mut near: Vec<(String, String, String)> = Vec::new();
                for e in experiments {
                    near.push((e.to_string(), key.variant.to_string(), key.solver.to_string()));
                }
                for s in &solvers {
                    near.push((key.experiment.to_string(), key.variant.to_string(), s.clone()));
                }
                let others: Vec<String> = variants.iter().take(4).cloned().collect();
                for v in near_misses(key.variant.as_str(), &others) {
                    near.push((key.experiment.to_string(), v, key.solver.to_string()));
                }
                for (e, v, s) in near {
                    let Ok(k) = RunKey::from_ids(&e, &v, &s) else { continue };
                    let text = k.to_string();
                    let got = match lookup.find(&k).unwrap() {
                        Found::Run { keeps_trace } => Some(keeps_trace),
                        Found::NoRun => None,
                        Found::Undecided => {
                            prop_assert!(files[0].experiments[0].id == e);
                            undecided.get(&text).copied()
                        }
                    };
                    prop_assert_eq!(got, full.get(&text).copied(), "{}", text);
                    asked += 1;
                }
            }
            prop_assert!(asked > keys.len());
        }
    }

    /// A sweep whose names are decided from its axes leaves nothing undecided, and a key whose
    /// variant is made to learn its solvers (the first asked of its digits on the run axes:
    /// here the first of the sweep) and does not make (a label past 100 bytes, off the lines
    /// the load checks) is that variant's error, naming the field, as making every run was.
    #[test]
    fn a_decided_sweep_holds_no_run_and_an_unmade_variant_is_its_error() {
        let text = format!(
            "{}[[experiment.variant]]\nlabel = \"{}\"\nid = \"z\"\n\
             scheme = {{ kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }}\n\
             sweep = {{ \"scheme.mu\" = {{ from = 1.0, to = 2.0, step = 0.00001 }} }}\n",
            fixtures::katana_circle("lookup", "kong2019-lookup", 0.05, ""),
            "L".repeat(90)
        );
        let files = [PaperFile::from_toml(&text).unwrap()];
        let lookup = RunLookup::new(&files);
        assert_eq!(lookup.undecided_runs().count(), 0);
        let key = |v: &str, s: &str| RunKey::from_ids("kong2019-lookup", v, s).unwrap();
        let err = lookup
            .find(&key("z-mu-1.00001", "exact"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("variant[1] (") && err.contains("field `label`"),
            "{err}"
        );
        assert_eq!(
            lookup.find(&key("z-mu-1.5", "exact")).unwrap(),
            Found::Run { keeps_trace: true }
        );
        assert_eq!(lookup.find(&key("z-mu-1.5", "znn")).unwrap(), Found::NoRun);
        assert_eq!(
            lookup.find(&key("z-mu-2.5", "exact")).unwrap(),
            Found::NoRun
        );
        assert_eq!(
            lookup.find(&key("z-mu-1.50", "exact")).unwrap(),
            Found::NoRun
        );
    }
}
