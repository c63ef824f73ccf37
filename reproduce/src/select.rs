//! The runs a command line selects: `--paper`, `--experiment` (repeatable) and `--exact-only`
//! narrow the runs the experiment files describe; a paper or experiment no file names is an
//! error that lists the known ones. A shard K/N keeps, of the selected runs in their order,
//! those whose index i (from 0) has i mod N = K - 1 (`store::shard`): [`Kept`] counts each
//! experiment's runs from its plan (`catalog::Variants::run_count`: a sweep's by prefix sums
//! over its axes) and finds each of its indices' variant by bisection, making only the
//! variants that hold one, so a shard of a sweep of 10^7 runs makes its own runs alone.

use crate::error::ReproduceError;
use catalog::{Experiment, PaperFile};
use spec::RunSpec;
use std::collections::HashSet;
use store::shard::{Selection, Shard};

/// The runs of `files` that `selection` keeps, in file order, made as they are taken (a
/// caller collects what it needs), or the first variant that does not make
/// (catalog::PaperFile::variant). [`check_selection`] first.
pub fn selected<'a>(
    files: &'a [PaperFile],
    selection: &'a Selection,
) -> impl Iterator<Item = Result<RunSpec, ReproduceError>> + 'a {
    Kept {
        selection,
        shard: None,
    }
    .runs(files)
}

/// The runs a selection keeps and, with a shard, the shard's share of them (by index in the
/// selection's enumeration: file, experiment, variant, the variant's runs exact column first).
#[derive(Clone, Copy, Debug)]
pub struct Kept<'a> {
    /// The selection flags.
    pub selection: &'a Selection,
    /// The shard, if any (none: every selected run).
    pub shard: Option<Shard>,
}

impl<'a> Kept<'a> {
    /// Whether the selection takes runs from experiment `e` of file `f` (its paper and id).
    fn takes(&self, f: &PaperFile, e: &Experiment) -> bool {
        self.selection.paper.as_ref().is_none_or(|p| &f.paper == p)
            && (self.selection.experiments.is_empty() || self.selection.experiments.contains(&e.id))
    }

    /// How many runs of experiment `e` of `f` the selection keeps (the shard aside), none
    /// made (`--exact-only`: the exact columns alone).
    pub fn selected_in(&self, f: &PaperFile, e: &Experiment) -> usize {
        if !self.takes(f, e) {
            return 0;
        }
        e.variants.run_count(self.selection.exact_only)
    }

    /// How many of the selected runs with indices `start..start + count` are the shard's
    /// (all of them without a shard): those with i mod N = K - 1.
    pub fn owned_in(&self, start: usize, count: usize) -> usize {
        match self.shard {
            None => count,
            // Indices i < x with i mod N = K - 1: ceil((x - K + 1) / N).
            Some(s) => {
                let below = |x: usize| (x + s.n - s.k) / s.n;
                below(start + count) - below(start)
            }
        }
    }

    /// How many selected runs `files` describe (the shard aside), none made.
    pub fn total(&self, files: &[PaperFile]) -> usize {
        files
            .iter()
            .flat_map(|f| f.experiments.iter().map(move |e| self.selected_in(f, e)))
            .sum()
    }

    /// The kept runs of experiment `index` of `f`, whose first selected run has index
    /// `start`, in order: the shard's indices among them, i = K - 1 mod N, each run found
    /// from the experiment's plan (catalog::PaperFile::runs_at), so only the variants holding
    /// a kept run are made.
    pub fn experiment_runs(
        self,
        f: &'a PaperFile,
        index: usize,
        start: usize,
    ) -> impl Iterator<Item = Result<RunSpec, ReproduceError>> + 'a {
        let count = self.selected_in(f, &f.experiments[index]);
        let (first, step) = match self.shard {
            None => (0, 1),
            // The first i >= start with i mod N = K - 1, as an index in the experiment.
            Some(s) => ((s.k - 1 + s.n - start % s.n) % s.n, s.n),
        };
        f.runs_at(
            index,
            self.selection.exact_only,
            (first..count).step_by(step),
        )
        .map(|r| {
            r.map(|d| d.spec)
                .map_err(|e| ReproduceError::from(f.in_file(e)))
        })
    }

    /// The kept runs of `files`, in order, made as they are taken.
    pub fn runs(
        self,
        files: &'a [PaperFile],
    ) -> impl Iterator<Item = Result<RunSpec, ReproduceError>> + 'a {
        let mut start = 0;
        files
            .iter()
            .flat_map(|f| (0..f.experiments.len()).map(move |i| (f, i)))
            .flat_map(move |(f, i)| {
                let first = start;
                start += self.selected_in(f, &f.experiments[i]);
                self.experiment_runs(f, i, first)
            })
    }
}

/// The names of the experiment files of `files` that `selection` draws its runs from: the
/// files of its paper (all without `--paper`) that define one of its experiments (any without
/// `--experiment`). A shard is bound to these files only (store::shard::experiments_hash):
/// another file added beside them does not make the shard's runs another sweep's.
pub fn selection_files<'a>(
    files: &'a [PaperFile],
    selection: &Selection,
) -> impl Iterator<Item = &'a str> + 'a {
    let paper = selection.paper.clone();
    let experiments = selection.experiments.clone();
    files
        .iter()
        .filter(move |f| {
            paper.as_ref().is_none_or(|p| &f.paper == p)
                && (experiments.is_empty()
                    || f.experiments.iter().any(|e| experiments.contains(&e.id)))
        })
        .map(|f| f.file_name.as_str())
}

/// A paper or experiment of `selection` that no file of `files` names is an error listing the
/// known ones (every experiment of a file has runs: a variant that runs nothing is refused at
/// load).
pub fn check_selection(files: &[PaperFile], selection: &Selection) -> Result<(), ReproduceError> {
    if let Some(p) = &selection.paper {
        if !files.iter().any(|f| &f.paper == p) {
            return Err(ReproduceError::UnknownPaper {
                paper: p.clone(),
                known: files.iter().map(|f| f.paper.clone()).collect(),
            });
        }
    }
    let ids: HashSet<&str> = files
        .iter()
        .flat_map(|f| &f.experiments)
        .map(|e| e.id.as_str())
        .collect();
    for e in &selection.experiments {
        if !ids.contains(e.as_str()) {
            let mut known: Vec<String> = ids.iter().map(|id| id.to_string()).collect();
            known.sort_unstable();
            return Err(ReproduceError::UnknownExperiment {
                experiment: e.clone(),
                known,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::load_dir;
    use spec::SolverChoice;
    use std::path::Path;

    /// The project's experiment files and their runs.
    fn project() -> (Vec<PaperFile>, Vec<RunSpec>) {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments");
        let files = load_dir(&dir).expect("the project's experiment files");
        let all = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
        (files, all)
    }

    fn select(
        paper: Option<&str>,
        experiments: &[&str],
        exact_only: bool,
    ) -> Result<Vec<RunSpec>, ReproduceError> {
        let (files, _) = project();
        let selection = Selection {
            paper: paper.map(String::from),
            experiments: experiments.iter().map(|e| e.to_string()).collect(),
            exact_only,
        };
        check_selection(&files, &selection)?;
        selected(&files, &selection).collect()
    }

    #[test]
    fn no_flag_selects_every_run() {
        let (_, all) = project();
        let keys = |jobs: &[RunSpec]| jobs.iter().map(RunSpec::key).collect::<Vec<_>>();
        assert_eq!(keys(&select(None, &[], false).unwrap()), keys(&all));
    }

    #[test]
    fn a_paper_selects_exactly_its_runs() {
        let (files, all) = project();
        let paper = &files[0].paper;
        let jobs = select(Some(paper), &[], false).unwrap();
        assert!(!jobs.is_empty());
        assert!(jobs.iter().all(|j| &j.paper == paper));
        assert_eq!(jobs.len(), all.iter().filter(|j| &j.paper == paper).count());
        assert!(jobs.len() < all.len(), "one paper of several");
    }

    #[test]
    fn experiments_and_exact_only_narrow_the_selection() {
        let (_, all) = project();
        let (a, b) = (&all[0].experiment, &all.last().unwrap().experiment);
        assert_ne!(a, b);
        let jobs = select(None, &[a, b], false).unwrap();
        let expected = all
            .iter()
            .filter(|j| &j.experiment == a || &j.experiment == b)
            .count();
        assert_eq!(jobs.len(), expected);
        let exact = select(None, &[a, b], true).unwrap();
        assert!(!exact.is_empty() && exact.len() < jobs.len());
        assert!(exact.iter().all(|j| j.solver == SolverChoice::Exact));
    }

    #[test]
    fn a_selection_reads_the_files_of_its_paper_and_experiments_only() {
        let (files, _) = project();
        let names = |paper: Option<&str>, experiments: &[&str]| {
            let selection = Selection {
                paper: paper.map(String::from),
                experiments: experiments.iter().map(|e| e.to_string()).collect(),
                exact_only: false,
            };
            selection_files(&files, &selection).collect::<Vec<_>>()
        };
        let every: Vec<&str> = files.iter().map(|f| f.file_name.as_str()).collect();
        assert!(every.iter().all(|n| n.ends_with(".toml")), "{every:?}");
        assert_eq!(names(None, &[]), every);
        let kong = files.iter().find(|f| f.paper == "kong2019").unwrap();
        assert_eq!(names(Some("kong2019"), &[]), [kong.file_name.as_str()]);
        let one = &kong.experiments[0].id;
        assert_eq!(names(None, &[one]), [kong.file_name.as_str()]);
    }

    #[test]
    fn an_unknown_paper_or_experiment_names_the_known_ones() {
        let (files, _) = project();
        match select(Some("nopaper"), &[], false) {
            Err(ReproduceError::UnknownPaper { paper, known }) => {
                assert_eq!(paper, "nopaper");
                assert_eq!(
                    known,
                    files.iter().map(|f| f.paper.clone()).collect::<Vec<_>>()
                );
            }
            other => panic!("{other:?}"),
        }
        let err = select(None, &["nope"], false).unwrap_err();
        let ReproduceError::UnknownExperiment { experiment, known } = &err else {
            panic!("{err:?}");
        };
        assert_eq!(experiment, "nope");
        assert!(known.windows(2).all(|w| w[0] < w[1]), "sorted and distinct");
        assert!(err
            .to_string()
            .starts_with("unknown experiment \"nope\" (known: "));
    }

    /// A shard's runs, found by index, are exactly the selected runs i with i mod N = K - 1,
    /// in order; the counts made without runs agree; every run is in one shard.
    #[test]
    fn a_shard_is_every_nth_selected_run() {
        let (files, _) = project();
        every_nth(
            &files,
            &[(None, false), (Some("kong2019"), false), (None, true)],
        );
    }

    /// The same of a sweep whose variants make different numbers of runs (it sweeps `exact`
    /// and the list of `solvers`): a shard found by index from the sweep's axes cannot take
    /// the runs per variant for a constant.
    #[test]
    fn a_shard_of_a_sweep_of_uneven_variants_is_every_nth_selected_run() {
        let text = r#"paper = "kong2019"
title = "t"
[[experiment]]
id = "kong2019-uneven"
paper_output = "-"
robot = "katana6m180"
path = { name = "circle", duration = 1.0 }
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
[[experiment.variant]]
label = "S"
scheme = { kind = "znn-rmp", k_p = 1.0 }
solvers = [{ kind = "znn", gamma = 1.0 }]
sweep = { "exact" = [true, false], "solvers" = [{ value = [{ kind = "znn", gamma = 1.0 }], label = "one" }, { value = [{ kind = "znn", gamma = 1.0 }, { kind = "zeroing", gain = { law = "power", gamma = 10.0, p = 2.0 }, activation = "sign-bi-power", exponent = 0.5 }], label = "two" }], "scheme.mu" = [1, 2, 3] }
"#;
        let files = [crate::experiments::from_toml(text).unwrap()];
        let runs: Vec<usize> = (0..files[0].experiments[0].variants.len())
            .map(|i| files[0].variant(0, i).unwrap().run_count())
            .collect();
        assert_eq!(runs, [2, 2, 2, 3, 3, 3, 1, 1, 1, 2, 2, 2]);
        every_nth(&files, &[(None, false), (None, true)]);
    }

    /// [`a_shard_is_every_nth_selected_run`] for `files` and each (paper, exact only) of
    /// `selections`, in 1, 3, 5 and 64 shards.
    fn every_nth(files: &[PaperFile], selections: &[(Option<&str>, bool)]) {
        for &(paper, exact_only) in selections {
            let selection = Selection {
                paper: paper.map(String::from),
                experiments: vec![],
                exact_only,
            };
            let keys: Vec<String> = selected(files, &selection)
                .map(|j| j.unwrap().key().to_string())
                .collect();
            let all = Kept {
                selection: &selection,
                shard: None,
            };
            assert_eq!(all.total(files), keys.len());
            for n in [1, 3, 5, 64] {
                let mut seen = 0;
                for k in 1..=n {
                    let kept = Kept {
                        selection: &selection,
                        shard: Some(Shard::new(k, n).unwrap()),
                    };
                    let got: Vec<String> = kept
                        .runs(files)
                        .map(|j| j.unwrap().key().to_string())
                        .collect();
                    let want: Vec<String> = keys.iter().skip(k - 1).step_by(n).cloned().collect();
                    assert_eq!(
                        got, want,
                        "shard {k}/{n} of {paper:?}, exact only {exact_only}"
                    );
                    assert_eq!(kept.owned_in(0, keys.len()), got.len());
                    assert_eq!(store::shard::plan(keys.len(), n)[k - 1], got.len());
                    seen += got.len();
                }
                assert_eq!(seen, keys.len());
            }
        }
    }
}
