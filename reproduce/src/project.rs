//! The project a mode works on, resolved from the global options before the mode runs: the
//! project root (`--root`, else found from the working directory), the experiments and results
//! directories under it (a shard's results directory named after the shard), the store's
//! policy (edited files, pruning), and the bound on `--threads`.

use crate::error::ReproduceError;
use crate::options::{GlobalOptions, ShardSpec};
use std::path::PathBuf;
use store::shard::Shard;
use store::Edits;

/// `--threads` may ask for at most this many worker threads per core: more only adds
/// contention, and a mistyped count (100000) must not stall the machine before it says so.
pub const MAX_THREADS_PER_CORE: usize = 4;

/// The resolved directories and policy of one invocation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Project {
    /// The project root (experiments/, papers/, results/, report/).
    pub root: PathBuf,
    /// The experiment files' directory.
    pub experiments_dir: PathBuf,
    /// The results directory written to.
    pub results_dir: PathBuf,
    /// Whether result files edited by hand are taken as they are.
    pub edits: Edits,
    /// Whether more than a quarter of the stored runs may be pruned.
    pub prune: bool,
}

impl Project {
    /// Resolves `global` (the root found from the working directory unless `--root` says it)
    /// and registers the papers' own robot files (`papers/<paper>/robots/*.toml`); `shard`: the
    /// shard whose own results directory is the default.
    pub fn resolve(global: &GlobalOptions, shard: Option<Shard>) -> Result<Self, ReproduceError> {
        let root = match &global.root {
            Some(r) => r.clone(),
            None => catalog::root_from_current_dir()?,
        };
        catalog::register_paper_robots(&root.join("papers"));
        Ok(Self::under(root, global, shard))
    }

    /// The directories of `global` under `root`.
    fn under(root: PathBuf, global: &GlobalOptions, shard: Option<Shard>) -> Self {
        let results = shard.map_or_else(|| store::results_dir::DIR.to_string(), |s| s.dir_name());
        Project {
            experiments_dir: global
                .experiments_dir
                .clone()
                .unwrap_or_else(|| root.join("experiments")),
            results_dir: global
                .results_dir
                .clone()
                .unwrap_or_else(|| root.join(results)),
            edits: global.edits(),
            prune: global.prune,
            root,
        }
    }
}

/// The shard of `K/N` or `auto` (from the environment `env`: a Slurm job array or a
/// Kubernetes Indexed Job; `shards`: N where the environment does not say it).
pub fn resolve_shard(
    spec: ShardSpec,
    shards: Option<usize>,
    env: impl Fn(&str) -> Option<String>,
) -> Result<Shard, ReproduceError> {
    Ok(match spec {
        ShardSpec::Auto => Shard::from_env(env, shards)?,
        ShardSpec::Given(shard) => shard,
    })
}

/// Checks `--threads` against [`MAX_THREADS_PER_CORE`] and makes it the worker pool's size.
pub fn set_threads(threads: Option<u64>) -> Result<(), ReproduceError> {
    let Some(threads) = threads else {
        return Ok(());
    };
    check_threads(threads)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads as usize)
        .build_global()?;
    Ok(())
}

/// `threads` within [`MAX_THREADS_PER_CORE`] times the cores.
fn check_threads(threads: u64) -> Result<(), ReproduceError> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max = MAX_THREADS_PER_CORE * cores;
    if threads as usize > max {
        return Err(ReproduceError::TooManyThreads {
            threads,
            max,
            per_core: MAX_THREADS_PER_CORE,
            cores,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directories_resolve_under_the_root_and_a_shard_gets_its_own() {
        let plain = Project::under("/p".into(), &GlobalOptions::default(), None);
        assert_eq!(plain.experiments_dir, PathBuf::from("/p/experiments"));
        assert_eq!(plain.results_dir, PathBuf::from("/p/results"));
        assert_eq!((plain.edits, plain.prune), (Edits::Refuse, false));
        let no_env = |_: &str| None;
        let spec = |s: &str| s.parse::<ShardSpec>().unwrap();
        let shard = resolve_shard(spec("2/3"), None, no_env).unwrap();
        assert_eq!(shard, Shard::new(2, 3).unwrap());
        let sharded = Project::under("/p".into(), &GlobalOptions::default(), Some(shard));
        assert_eq!(
            sharded.results_dir,
            PathBuf::from("/p/results-shard-2-of-3")
        );
        let given = GlobalOptions {
            results_dir: Some("/r".into()),
            experiments_dir: Some("/e".into()),
            accept_edited: true,
            ..GlobalOptions::default()
        };
        let given = Project::under("/p".into(), &given, Some(shard));
        assert_eq!(given.results_dir, PathBuf::from("/r"));
        assert_eq!(given.experiments_dir, PathBuf::from("/e"));
        assert_eq!(given.edits, Edits::Accept);
        let k8s = |v: &str| (v == "JOB_COMPLETION_INDEX").then(|| "0".to_string());
        assert_eq!(
            resolve_shard(spec("auto"), Some(4), k8s).unwrap(),
            Shard::new(1, 4).unwrap()
        );
    }

    #[test]
    fn a_bad_shard_or_thread_count_is_a_typed_error() {
        let bad = "4/3".parse::<ShardSpec>().unwrap_err();
        assert!(
            bad.to_string()
                .starts_with("shard 4 of 3: K must be in 1..=3"),
            "{bad}"
        );
        assert!(
            bad.to_string().ends_with(
                "or `auto` (K and N from a Slurm job array or a Kubernetes Indexed Job)"
            ),
            "{bad}"
        );
        let no_array = resolve_shard(ShardSpec::Auto, None, |_| None);
        assert!(
            matches!(no_array, Err(ReproduceError::Shard(_))),
            "{no_array:?}"
        );
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let too_many = (MAX_THREADS_PER_CORE * cores + 1) as u64;
        let err = check_threads(too_many).unwrap_err();
        assert!(
            matches!(err, ReproduceError::TooManyThreads { threads, .. } if threads == too_many),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .starts_with(&format!("--threads {too_many}: at most")),
            "{err}"
        );
        assert!(check_threads((MAX_THREADS_PER_CORE * cores) as u64).is_ok());
    }
}
