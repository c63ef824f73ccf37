//! What is resolved from the command line before any mode runs: the project root (`--root`,
//! else found from the working directory), the experiments and results directories under it
//! (a shard's results directory named after it), the shard of `--shard` (from a Slurm job
//! array or a Kubernetes Indexed Job for `auto`) and the bound on `--threads`.

use crate::cli::Cli;
use crate::error::ReproduceError;
use records::shard::Shard;

/// `--threads` may ask for at most this many worker threads per core: more only adds
/// contention, and a mistyped count (100000) must not stall the machine before it says so.
pub const MAX_THREADS_PER_CORE: usize = 4;

impl Cli {
    /// Fills in the project root (`--root`, else found from the working directory) and the
    /// experiments and results directories under it, unless given; resolves `--shard` (from the
    /// environment for `auto`); checks the thread count against [`MAX_THREADS_PER_CORE`].
    pub fn resolve(self) -> Result<Self, ReproduceError> {
        self.resolve_with(|v| std::env::var(v).ok())
    }

    /// [`Cli::resolve`] with the environment `env` (a shard of `--shard auto`).
    fn resolve_with(
        mut self,
        env: impl Fn(&str) -> Option<String>,
    ) -> Result<Self, ReproduceError> {
        if let Some(threads) = self.threads {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            let max = MAX_THREADS_PER_CORE * cores;
            if threads as usize > max {
                return Err(ReproduceError::TooManyThreads {
                    threads,
                    max,
                    cores,
                });
            }
        }
        let root = match &self.root {
            Some(r) => r.clone(),
            None => catalog::root::from_current_dir()?,
        };
        self.experiments_dir = self
            .experiments_dir_arg
            .clone()
            .unwrap_or_else(|| root.join("experiments"));
        self.shard_resolved = match self.shard.as_deref() {
            None => None,
            Some("auto") => Some(Shard::from_env(env, self.shards)?),
            Some(kn) => Some(Shard::parse(kn)?),
        };
        let results = match self.shard_resolved {
            Some(s) => s.dir_name(),
            None => records::results_dir::DIR.to_string(),
        };
        self.results_dir = self
            .results_dir_arg
            .clone()
            .unwrap_or_else(|| root.join(results));
        self.project_root = root;
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn parse(line: &str) -> Result<Cli, clap::Error> {
        Cli::parse_from_args(line.split_whitespace().map(String::from).collect())
    }

    #[test]
    fn directories_resolve_under_the_root_and_a_shard_gets_its_own() {
        let no_env = |_: &str| None;
        let cli = parse("reproduce --root /p")
            .unwrap()
            .resolve_with(no_env)
            .unwrap();
        assert_eq!(cli.project_root, PathBuf::from("/p"));
        assert_eq!(cli.experiments_dir, PathBuf::from("/p/experiments"));
        assert_eq!(cli.results_dir, PathBuf::from("/p/results"));
        let shard = parse("reproduce shard 2/3 --root /p")
            .unwrap()
            .resolve_with(no_env)
            .unwrap();
        assert_eq!(shard.shard_resolved, Some(Shard::new(2, 3).unwrap()));
        assert_eq!(shard.results_dir, PathBuf::from("/p/results-shard-2-of-3"));
        let given = parse("reproduce shard 2/3 --root /p --results-dir /r --experiments-dir /e")
            .unwrap()
            .resolve_with(no_env)
            .unwrap();
        assert_eq!(given.results_dir, PathBuf::from("/r"));
        assert_eq!(given.experiments_dir, PathBuf::from("/e"));
        let k8s = |v: &str| (v == "JOB_COMPLETION_INDEX").then(|| "0".to_string());
        let auto = parse("reproduce shard --shards 4 --root /p")
            .unwrap()
            .resolve_with(k8s)
            .unwrap();
        assert_eq!(auto.shard_resolved, Some(Shard::new(1, 4).unwrap()));
    }

    #[test]
    fn a_bad_shard_or_thread_count_is_a_typed_error() {
        let no_env = |_: &str| None;
        let bad = parse("reproduce shard 4/3 --root /p")
            .unwrap()
            .resolve_with(no_env);
        assert!(matches!(bad, Err(ReproduceError::Shard(_))), "{bad:?}");
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let too_many = MAX_THREADS_PER_CORE * cores + 1;
        let err = parse(&format!("reproduce --threads {too_many} --root /p"))
            .unwrap()
            .resolve_with(no_env)
            .unwrap_err();
        assert!(
            matches!(err, ReproduceError::TooManyThreads { threads, .. } if threads as usize == too_many),
            "{err:?}"
        );
        assert!(
            err.to_string()
                .starts_with(&format!("--threads {too_many}: at most")),
            "{err}"
        );
        let most = MAX_THREADS_PER_CORE * cores;
        assert!(parse(&format!("reproduce --threads {most} --root /p"))
            .unwrap()
            .resolve_with(no_env)
            .is_ok());
    }
}
