//! Sharded runs for clusters: `reproduce shard K/N` runs its share of the selected runs into
//! `results-shard-K-of-N/`, `reproduce merge DIR...` combines the shards into `results/`.
//!
//! - **Assignment, by index.** The selection's runs are enumerated in file order (file by
//!   file in name order, experiment by experiment, variant by variant, each variant's runs
//!   exact column first: what `reproduce list` prints); run i (from 0) belongs to shard
//!   `i mod N + 1` (K is 1-based; [`Shard::of_index`]). The shards are strided, not
//!   contiguous, so a sweep whose cost grows along an axis is spread evenly, and every shard
//!   gets floor(T/N) or ceil(T/N) of the T runs ([`plan`]). A shard's runs are found by their
//!   indices (reproduce's `select::Kept`) and only they are made: listing or running shard K of a
//!   sweep does not make the other shards' runs. A run's shard therefore depends on the
//!   selection and the experiment files (both bound below), not on the machine.
//! - **K and N from a scheduler** ([`Shard::from_env`], `shard auto`): a Slurm task id *is*
//!   the shard number K (arrays are `--array=1-N`; one task is resubmitted as `--array=K`); N is
//!   `--shards`, else `DRIFTBENCH_SHARDS`, else the array's size, but only when the array is
//!   exactly 1..N with N >= 2. Any other array (one task, a part of an array, a stepped, sparse
//!   or 0-based one) does not tell N and is refused, naming the variables, unless N is given.
//!   A Kubernetes Indexed Job's `JOB_COMPLETION_INDEX` is K - 1; N must be given.
//! - **Binding.** A shard starts by binding its directory ([`Binding::claim`]):
//!   `shard-binding.toml` records K, N, the selection and the hash of the experiment files the
//!   selection draws its runs from (no other file of the directory), and a
//!   directory bound to anything else (another selection or sweep, other experiment files,
//!   another K or N), or holding results without a binding, is refused before anything runs.
//!   The same shard started again (a requeue) finds its own binding and resumes.
//! - **Manifest.** A shard directory holds `runs.csv`, `traces/` and, written last and
//!   atomically, `shard.toml` ([`Manifest`]): K, N, the selection the shard was given, how many
//!   runs were assigned to it and the sum of their keys' prints ([`crate::keys::KeySum`]: 32
//!   hex digits, whatever the number of runs), the code revision and a hash of the experiment
//!   files. A directory without a manifest is a shard that has not finished. A shard resumes
//!   through the ordinary journal ([`crate::journal`]) of its directory. A manifest is checked
//!   as it is read: K in 1..=N, N >= 1, a key sum of 32 hex digits; otherwise it is an error
//!   naming the file and the field (whether the runs are shard K's needs the selection's
//!   enumeration: the merge checks it).
//! - **Merge.** [`check_shards`] verifies that the shards agree (N, experiment files, selection),
//!   that each shard was assigned and holds exactly the runs whose index in the selection makes
//!   them its own (their counts and key sums), so that every selected run appears exactly once;
//!   otherwise it says which runs are missing (and which shard should have produced them),
//!   duplicated, misplaced or foreign, and nothing is written.

use crate::error::{IoAction, IoError, RunsError};
use crate::integrity::{IntegrityError, Mismatch};
use crate::keys::KeySum;
use crate::owned_dir::PathError;
use crate::sorted::{read_key_ordered, KeyMerge};
use crate::tracked_dir::TrackedError;
use records::RunRow;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The manifest's file name in a shard directory.
pub const MANIFEST: &str = "shard.toml";

use crate::fnv::fnv1a64;

/// Why a shard cannot be chosen, written, read or merged.
#[derive(Debug, thiserror::Error)]
pub enum ShardError {
    /// N is 0.
    #[error("the number of shards N must be at least 1")]
    NoShards,
    /// K is not in 1..=N.
    #[error("shard {k} of {n}: K must be in 1..={n} (K is 1-based)")]
    OutOfRange {
        /// The shard number K given.
        k: usize,
        /// The number of shards N.
        n: usize,
    },
    /// `--shard` has no `/` (the text given).
    #[error("--shard {}: expected K/N, e.g. 2/8", settings::shown(.0))]
    Syntax(String),
    /// K or N of `--shard` is not a whole number (the text given).
    #[error("--shard {}: expected K/N with whole numbers, e.g. 2/8", settings::shown(.0))]
    NotWhole(String),
    /// A scheduler's or driftbench's environment variable is not a whole number.
    #[error(
        "environment variable {name}={} is not a whole number",
        settings::shown(value)
    )]
    Environment {
        /// The variable.
        name: String,
        /// Its value.
        value: String,
    },
    /// A Kubernetes Indexed Job's index without the number of shards N.
    #[error("JOB_COMPLETION_INDEX={index} (a Kubernetes Indexed Job) gives K but not the number of shards N: give --shards N or set DRIFTBENCH_SHARDS=N (the Job's completions)")]
    IndexWithoutCount {
        /// `JOB_COMPLETION_INDEX` (from 0).
        index: usize,
    },
    /// A Slurm array task, N not given, whose array is not exactly 1-N with N >= 2.
    #[error("the Slurm array ({said}) does not tell the number of shards N: only an array of exactly 1-N with N >= 2 does, not one task (a resubmitted one), a part of an array, or a stepped, sparse or 0-based array; give --shards N or set DRIFTBENCH_SHARDS=N")]
    ArrayWithoutCount {
        /// The Slurm array variables as set (or unset).
        said: String,
    },
    /// The Slurm task id is not a shard number 1..=N.
    #[error("SLURM_ARRAY_TASK_ID={id}: task ids are shard numbers 1..={n} (submit --array=1-{n}; resubmit one task as --array=K)")]
    TaskId {
        /// `SLURM_ARRAY_TASK_ID`.
        id: usize,
        /// The number of shards N.
        n: usize,
    },
    /// `--shard` without K/N, and no scheduler's variable is set.
    #[error("--shard without K/N reads the scheduler's environment, but neither SLURM_ARRAY_TASK_ID nor JOB_COMPLETION_INDEX is set; give --shard K/N")]
    NoScheduler,
    /// A file operation failed.
    #[error(transparent)]
    Io(#[from] IoError),
    /// `shard.toml` or `shard-binding.toml` could not be serialised.
    #[error("{}: {source}", path.display())]
    WriteManifest {
        /// The file.
        path: PathBuf,
        /// The TOML error.
        source: toml::ser::Error,
    },
    /// `shard.toml` does not read as a shard manifest.
    #[error("{}: {source}", path.display())]
    ReadManifest {
        /// The file.
        path: PathBuf,
        /// The TOML error, with its line.
        source: inputs::TomlError,
    },
    /// `shard.toml` refused or unreadable by the input reader (a link outside the shard
    /// directory, a FIFO, over its cap).
    #[error(transparent)]
    Input(#[from] inputs::InputError),
    /// `shard.toml` names no valid shard.
    #[error("{}: `shard = {shard}`, `shards = {shards}`: {source}", path.display())]
    ManifestShard {
        /// The file.
        path: PathBuf,
        /// Its `shard`.
        shard: usize,
        /// Its `shards`.
        shards: usize,
        /// Why they make no shard.
        source: Box<ShardError>,
    },
    /// `shard.toml`'s `key_sum` is not 32 lower-case hex digits.
    #[error("{}: `key_sum = {}`: expected 32 lower-case hex digits (the sum of the prints of the shard's run keys, store::keys)", path.display(), settings::shown(value))]
    ManifestKeySum {
        /// The file.
        path: PathBuf,
        /// The value as written.
        value: String,
    },
    /// `shard-binding.toml` does not read as a binding.
    #[error("{}: {source}", path.display())]
    ReadBinding {
        /// The file.
        path: PathBuf,
        /// The TOML error, with its line.
        source: inputs::TomlError,
    },
    /// The directory is bound to another shard, selection or set of experiment files.
    #[error("{}: bound to another shard, so nothing was run: {}; one directory serves one shard of one selection: give this shard its own --results-dir, or remove {} if its runs are not wanted", dir.display(), differences.join("; "), dir.display())]
    BoundElsewhere {
        /// The shard directory.
        dir: PathBuf,
        /// What differs, one item each.
        differences: Vec<String>,
    },
    /// The directory holds results but no binding.
    #[error("{}: holds {file} but no {}, so which selection it ran cannot be told (a directory of an older version, or not a shard's); nothing was run: give this shard its own --results-dir, or remove the directory", dir.display(), crate::shard::BINDING)]
    Unbound {
        /// The shard directory.
        dir: PathBuf,
        /// The result file it holds (`runs.csv`, the journal, `shard.toml`).
        file: &'static str,
    },
    /// The shard directory has no `shard.toml`: the shard has not finished.
    #[error("{}: no {}: the shard has not finished (run it again; it resumes where it stopped)", dir.display(), crate::shard::MANIFEST)]
    Unfinished {
        /// The shard directory.
        dir: PathBuf,
    },
    /// A directory given to merge does not exist.
    #[error("{}: no such directory (give the directories that `reproduce shard K/N` wrote)", dir.display())]
    NoDirectory {
        /// The path given.
        dir: PathBuf,
    },
    /// The shard's integrity manifest could not be read.
    #[error(transparent)]
    Integrity(#[from] IntegrityError),
    /// The shard directory has no integrity manifest.
    #[error("{}: no {}: not a shard this version wrote, so its files cannot be checked; run the shard again", dir.display(), crate::integrity::FILE)]
    NoIntegrity {
        /// The shard directory.
        dir: PathBuf,
    },
    /// Files of the shard differ from its integrity manifest.
    #[error("{}: {} file(s) differ from what the shard wrote:\n{}\nrun the shard again, or merge with --accept-edited if the edit is deliberate", dir.display(), mismatches.len(), mismatches.iter().map(|m| format!("  {m}")).collect::<Vec<_>>().join("\n"))]
    Edited {
        /// The shard directory.
        dir: PathBuf,
        /// Every file that differs, and how.
        mismatches: Vec<Mismatch>,
    },
    /// A shard's `runs.csv` could not be read.
    #[error(transparent)]
    Runs(#[from] RunsError),
    /// A path under a directory was refused.
    #[error(transparent)]
    Path(#[from] PathError),
    /// A tracked write failed.
    #[error(transparent)]
    Tracked(#[from] TrackedError),
    /// The results directory merged into failed.
    #[error(transparent)]
    Results(#[from] crate::results_dir::ResultsError),
    /// `merge` was given no shard directory.
    #[error("merge needs at least one shard directory")]
    NoShardDirectories,
    /// The shards do not fit together; every problem, one a line.
    #[error("cannot merge; nothing was written:\n{}", problems.join("\n"))]
    CannotMerge {
        /// The problems, one each.
        problems: Vec<String>,
    },
}

/// Shard K of N (K in 1..=N).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// The shard's number K, from 1.
    pub k: usize,
    /// The number of shards N.
    pub n: usize,
}

impl Shard {
    /// Shard `k` of `n`; an error when `n` is 0 or `k` is not in 1..=n.
    pub fn new(k: usize, n: usize) -> Result<Self, ShardError> {
        if n == 0 {
            return Err(ShardError::NoShards);
        }
        if k == 0 || k > n {
            return Err(ShardError::OutOfRange { k, n });
        }
        Ok(Self { k, n })
    }

    /// `"K/N"`.
    pub fn parse(s: &str) -> Result<Self, ShardError> {
        let (k, n) = s
            .split_once('/')
            .ok_or_else(|| ShardError::Syntax(s.to_string()))?;
        let num = |x: &str| {
            x.trim()
                .parse::<usize>()
                .map_err(|_| ShardError::NotWhole(s.to_string()))
        };
        Self::new(num(k)?, num(n)?)
    }

    /// K and N from a scheduler's environment (`get` reads a variable; `shards`: `--shards`),
    /// by the rules of the module doc: a Slurm job array (`SLURM_ARRAY_TASK_ID`, `_MIN`, `_MAX`,
    /// `_COUNT`) or a Kubernetes Indexed Job (`JOB_COMPLETION_INDEX`).
    pub fn from_env(
        get: impl Fn(&str) -> Option<String>,
        shards: Option<usize>,
    ) -> Result<Self, ShardError> {
        let num = |name: &str| -> Result<Option<usize>, ShardError> {
            match get(name) {
                None => Ok(None),
                Some(v) => {
                    v.trim()
                        .parse::<usize>()
                        .map(Some)
                        .map_err(|_| ShardError::Environment {
                            name: name.to_string(),
                            value: v,
                        })
                }
            }
        };
        let given = match shards {
            Some(n) => Some(n),
            None => num("DRIFTBENCH_SHARDS")?,
        };
        if let Some(id) = num("SLURM_ARRAY_TASK_ID")? {
            let array = [
                "SLURM_ARRAY_TASK_MIN",
                "SLURM_ARRAY_TASK_MAX",
                "SLURM_ARRAY_TASK_COUNT",
            ]
            .map(|name| num(name).map(|v| (name, v)));
            let [min, max, count] = array;
            let (min, max, count) = (min?, max?, count?);
            let n = match (given, min.1, max.1, count.1) {
                (Some(n), ..) => n,
                (None, Some(1), Some(max), Some(count)) if max == count && count >= 2 => count,
                _ => {
                    let said = [("SLURM_ARRAY_TASK_ID", Some(id)), min, max, count]
                        .iter()
                        .map(|(name, v)| match v {
                            Some(v) => format!("{name}={v}"),
                            None => format!("{name} unset"),
                        })
                        .collect::<Vec<_>>()
                        .join(", ");
                    return Err(ShardError::ArrayWithoutCount { said });
                }
            };
            if id == 0 || id > n {
                return Err(ShardError::TaskId { id, n });
            }
            return Self::new(id, n);
        }
        if let Some(index) = num("JOB_COMPLETION_INDEX")? {
            let n = given.ok_or(ShardError::IndexWithoutCount { index })?;
            return Self::new(index + 1, n);
        }
        Err(ShardError::NoScheduler)
    }

    /// The shard (1-based) that run `index` (from 0, in the selection's enumeration) belongs
    /// to among `n` (n >= 1): `index mod n + 1`.
    pub fn of_index(index: usize, n: usize) -> usize {
        index % n + 1
    }

    /// `results-shard-K-of-N`.
    pub fn dir_name(&self) -> String {
        format!("results-shard-{}-of-{}", self.k, self.n)
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

/// Runs per shard (index 0: shard 1) when `total` runs are split `n` ways (n >= 1): shard K
/// gets the indices congruent to K - 1 mod n, so ceil((total - K + 1) / n) of them.
pub fn plan(total: usize, n: usize) -> Vec<usize> {
    (1..=n).map(|k| (total + n - k) / n).collect()
}

/// Which runs a shard was given: the selection flags of its command line.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Selection {
    /// `--paper`: the paper selected, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper: Option<String>,
    /// `--experiment`: the experiments selected (none: no such flag).
    #[serde(default)]
    pub experiments: Vec<String>,
    /// `--exact-only`: only the exact column.
    #[serde(default)]
    pub exact_only: bool,
}

impl std::fmt::Display for Selection {
    /// The selection as its command-line flags (`every run` without any).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut flags = Vec::new();
        if let Some(p) = &self.paper {
            flags.push(format!("--paper {p}"));
        }
        flags.extend(self.experiments.iter().map(|e| format!("--experiment {e}")));
        if self.exact_only {
            flags.push("--exact-only".to_string());
        }
        if flags.is_empty() {
            f.write_str("every run (no selection flags)")
        } else {
            f.write_str(&flags.join(" "))
        }
    }
}

/// The binding file's name in a shard directory.
pub const BINDING: &str = "shard-binding.toml";

/// `shard-binding.toml`: what a shard directory is for, written when the shard first starts.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Binding {
    /// The shard's number K, from 1.
    pub shard: usize,
    /// The number of shards N.
    pub shards: usize,
    /// [`experiments_hash`] of the experiment files the shard runs.
    pub experiments_hash: String,
    /// The selection flags the shard runs.
    pub selection: Selection,
}

impl Binding {
    /// Binds the shard directory `results` to this shard before anything runs: a directory
    /// bound to the same shard is resumed; one bound to another shard, selection or set of
    /// experiment files, or holding results (`runs.csv`, a journal, `shard.toml`) but no
    /// binding, is refused; an empty one is bound (the binding written and recorded in its
    /// integrity manifest, which the opening of `results` checked it against).
    pub fn claim(&self, results: &crate::results_dir::ResultsDir) -> Result<(), ShardError> {
        let dir = results.path();
        let path = dir.join(BINDING);
        match inputs::read_text(
            &path,
            inputs::Kind::ShardBinding,
            inputs::Origin::Under(dir),
        ) {
            Ok(text) => {
                let found: Binding = inputs::parse_toml(&text)
                    .map_err(|source| ShardError::ReadBinding { path, source })?;
                if found == *self {
                    return Ok(());
                }
                return Err(ShardError::BoundElsewhere {
                    dir: dir.to_path_buf(),
                    differences: self.differences(&found),
                });
            }
            Err(e) if e.is_not_found() => {}
            Err(e) => return Err(e.into()),
        }
        let held = [
            crate::results_dir::RUNS,
            crate::results_dir::JOURNAL,
            MANIFEST,
        ];
        if let Some(file) = held.into_iter().find(|f| dir.join(f).exists()) {
            return Err(ShardError::Unbound {
                dir: dir.to_path_buf(),
                file,
            });
        }
        let text = toml::to_string(self).map_err(|source| ShardError::WriteManifest {
            path: path.clone(),
            source,
        })?;
        results
            .tracked()
            .write(Path::new(BINDING), text.as_bytes())?;
        results.save()?;
        Ok(())
    }

    /// How `found` (a directory's binding) differs from this shard, one item each.
    fn differences(&self, found: &Binding) -> Vec<String> {
        let mut out = Vec::new();
        if (found.shard, found.shards) != (self.shard, self.shards) {
            out.push(format!(
                "it is shard {}/{}'s, this is shard {}/{}",
                found.shard, found.shards, self.shard, self.shards
            ));
        }
        if found.selection != self.selection {
            out.push(format!(
                "it ran the selection `{}`, this runs `{}`",
                found.selection, self.selection
            ));
        }
        if found.experiments_hash != self.experiments_hash {
            out.push(format!(
                "it ran other experiment files (hash {}, the current ones hash {}): a sweep edited since, or another checkout",
                found.experiments_hash, self.experiments_hash
            ));
        }
        out
    }

    /// The manifest of the finished shard: this binding, the code revision and the run keys
    /// assigned to it (their count and sum).
    pub fn manifest(&self, git_rev: &str, assigned: KeySum) -> Manifest {
        Manifest {
            shard: self.shard,
            shards: self.shards,
            git_rev: git_rev.to_string(),
            experiments_hash: self.experiments_hash.clone(),
            runs: assigned.count,
            key_sum: assigned.hex(),
            selection: self.selection.clone(),
        }
    }
}

/// `shard.toml`: written last, so a shard directory with one holds a finished shard.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The shard's number K, from 1.
    pub shard: usize,
    /// The number of shards N.
    pub shards: usize,
    /// The code revision that ran the shard (as `runs.csv`'s `git_rev`).
    pub git_rev: String,
    /// [`experiments_hash`] of the experiment files the shard ran.
    pub experiments_hash: String,
    /// How many runs were assigned to the shard.
    pub runs: usize,
    /// The sum of the prints of the run keys (`experiment / variant / solver`) assigned to the
    /// shard ([`KeySum`]), as 32 hex digits: the merge compares it with the selection's.
    pub key_sum: String,
    /// The selection flags the shard ran.
    pub selection: Selection,
}

impl Manifest {
    /// Writes the manifest into the shard directory `dir`, atomically.
    pub fn write(&self, dir: &Path) -> Result<(), ShardError> {
        let path = dir.join(MANIFEST);
        let text = toml::to_string(self).map_err(|source| ShardError::WriteManifest {
            path: path.clone(),
            source,
        })?;
        crate::atomic::write_atomic(&path, text.as_bytes())
            .map_err(IoError::at(&path, IoAction::Write))?;
        Ok(())
    }

    /// Reads the manifest of the shard directory `dir` and checks it (a valid shard, a key sum
    /// of 32 hex digits); an unfinished shard has none.
    pub fn read(dir: &Path) -> Result<Self, ShardError> {
        let path = dir.join(MANIFEST);
        let kind = inputs::Kind::ShardManifest;
        let text = inputs::read_text(&path, kind, inputs::Origin::Under(dir)).map_err(|e| {
            if e.is_not_found() {
                ShardError::Unfinished {
                    dir: dir.to_path_buf(),
                }
            } else {
                e.into()
            }
        })?;
        let manifest: Self =
            inputs::parse_toml(&text).map_err(|source| ShardError::ReadManifest {
                path: path.clone(),
                source,
            })?;
        manifest.check(&path)?;
        Ok(manifest)
    }

    /// Checks a manifest read from `path` (the rules of the module doc).
    fn check(&self, path: &Path) -> Result<(), ShardError> {
        Shard::new(self.shard, self.shards).map_err(|source| ShardError::ManifestShard {
            path: path.to_path_buf(),
            shard: self.shard,
            shards: self.shards,
            source: Box::new(source),
        })?;
        let hex = |c: u8| c.is_ascii_digit() || (b'a'..=b'f').contains(&c);
        if self.key_sum.len() != 32 || !self.key_sum.bytes().all(hex) {
            return Err(ShardError::ManifestKeySum {
                path: path.to_path_buf(),
                value: self.key_sum.clone(),
            });
        }
        Ok(())
    }

    /// Removes a directory's manifest (a shard starting again is unfinished until it ends).
    pub fn remove(dir: &Path) -> Result<(), ShardError> {
        let path = dir.join(MANIFEST);
        match std::fs::remove_file(&path) {
            Ok(()) => {
                crate::kill_point::passed();
                Ok(())
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
            Err(e) => Err(IoError::at(&path, IoAction::Remove)(e).into()),
        }
    }
}

/// FNV-1a 64 of the experiment files `names` of `dir` (in name order: name and contents), as
/// 16 hex digits: shards to be merged must have run the same files. The caller names the files
/// its selection draws runs from, so a file the selection does not read (another sweep added
/// beside it) does not change the hash.
pub fn experiments_hash<'a>(
    dir: &Path,
    names: impl IntoIterator<Item = &'a str>,
) -> Result<String, IoError> {
    let mut names: Vec<&str> = names.into_iter().collect();
    names.sort_unstable();
    names.dedup();
    let mut bytes = Vec::new();
    for name in names {
        let path = dir.join(name);
        bytes.extend(name.as_bytes());
        bytes.push(0);
        let file = inputs::read(&path, inputs::Kind::Experiment, inputs::Origin::Under(dir))
            .map_err(crate::owned_dir::io_error)
            .map_err(IoError::at(&path, IoAction::Read))?;
        bytes.extend(file);
        bytes.push(0);
    }
    Ok(format!("{:016x}", fnv1a64(&bytes)))
}

/// One finished shard directory (its rows are not held: [`runs_files`] streams them; nor is
/// its integrity manifest, one entry per trace: [`read_shard`] reads it by streaming).
#[derive(Debug)]
pub struct ShardDir {
    /// The shard directory.
    pub dir: PathBuf,
    /// Its `shard.toml`.
    pub manifest: Manifest,
    /// Its rows whose trace is not among the files it wrote, one problem each (said by
    /// [`check_shards`] with the runs' placement).
    traceless: Vec<String>,
    /// The directory, every path under it checked.
    owned: crate::owned_dir::OwnedDir,
}

/// Reads a finished shard: its `shard.toml` and its integrity manifest. Every file the
/// integrity manifest lists (the rows and every trace) must still be what the shard wrote,
/// unless `edits` accepts edits (each file is hashed as a stream); a directory that does not
/// exist, or a shard without an integrity manifest, is an error saying so. The rows whose
/// trace is not among those files (unless their run keeps none by choice: `traced` false for
/// its key) are noted for [`check_shards`]. The integrity manifest is read by streaming
/// (`crate::integrity::Manifest`), never held: a merge holds nothing per trace of a shard.
pub fn read_shard(
    dir: &Path,
    edits: crate::tracked_dir::Edits,
    traced: impl Fn(&spec::RunKey) -> bool,
) -> Result<ShardDir, ShardError> {
    if !dir.is_dir() {
        return Err(ShardError::NoDirectory {
            dir: dir.to_path_buf(),
        });
    }
    let manifest = Manifest::read(dir)?;
    let mut files =
        crate::integrity::Manifest::open(dir)?.ok_or_else(|| ShardError::NoIntegrity {
            dir: dir.to_path_buf(),
        })?;
    if edits == crate::tracked_dir::Edits::Refuse {
        let mismatches = files.mismatches(dir, |_| true)?;
        if !mismatches.is_empty() {
            return Err(ShardError::Edited {
                dir: dir.to_path_buf(),
                mismatches,
            });
        }
    }
    // Whether every traced row's trace is listed: the listed traces and the traced rows'
    // traces, each summed as a multiset of paths (crate::keys::KeySum); equal sums are the
    // same set (but with probability ~2^-128), so no row is looked up. Otherwise (a row
    // without its trace, or a trace listed without its row) each row's trace is looked up.
    let trace_name = |key: &spec::RunKey| {
        crate::results_dir::ResultsDir::trace_rel(key)
            .to_string_lossy()
            .replace('\\', "/")
    };
    let traces = format!("{}/", crate::results_dir::TRACES);
    let mut listed = KeySum::default();
    for entry in files.entries()? {
        let (file, _) = entry?;
        if file.starts_with(&traces) {
            listed.add(&file);
        }
    }
    let runs = dir.join(crate::results_dir::RUNS);
    let mut held = KeySum::default();
    for row in read_key_ordered(&runs)? {
        let key = row?.key();
        if traced(&key) {
            held.add(&trace_name(&key));
        }
    }
    let mut traceless = Vec::new();
    if listed != held {
        for row in read_key_ordered(&runs)? {
            let key = row?.key();
            if traced(&key) && files.get(&trace_name(&key))?.is_none() {
                traceless.push(format!(
                    "{}: the trace of {key} ({}) is not among the files the shard wrote",
                    dir.display(),
                    crate::results_dir::ResultsDir::trace_rel(&key).display()
                ));
            }
        }
    }
    Ok(ShardDir {
        dir: dir.to_path_buf(),
        manifest,
        traceless,
        owned: crate::owned_dir::OwnedDir::open(dir)?,
    })
}

/// The shards' `runs.csv`, each opened to be read row by row in key order (index i: the
/// shard `shards[i]`).
pub fn runs_files(shards: &[ShardDir]) -> Result<Vec<crate::sorted::KeyOrdered>, ShardError> {
    Ok(shards
        .iter()
        .map(|s| read_key_ordered(&s.dir.join(crate::results_dir::RUNS)))
        .collect::<Result<Vec<_>, _>>()?)
}

/// A row's trace, relative to its results directory.
fn trace_rel(r: &RunRow) -> PathBuf {
    crate::results_dir::ResultsDir::trace_rel(&r.key())
}

/// Copies the trace of `row`, a row of `shard`, into `results` (written atomically and
/// recorded). [`read_shard`] has checked that it is there.
pub fn copy_trace(
    shard: &ShardDir,
    row: &RunRow,
    results: &crate::results_dir::ResultsDir,
) -> Result<(), ShardError> {
    let rel = trace_rel(row);
    let from = shard.owned.resolve(&rel)?;
    let bytes = crate::owned_dir::read_file(&from).map_err(IoError::at(&from, IoAction::Read))?;
    results.tracked().write(&rel, &bytes)?;
    Ok(())
}

/// Checks shards before a merge (each read by [`read_shard`], which checked its files): the
/// same N, experiment files (`hash`: the current files') and selection
/// (`manifest_problems`); and the runs each shard was assigned and holds: the selection's keys
/// (`expected()`, in its enumeration order: the i-th is shard `i mod N + 1`'s) in exactly one
/// shard each, its own, and no other run.
///
/// In memory independent of the number of runs: the expected keys are summed per shard
/// ([`KeySum`]) in one pass over `expected()`, each shard's rows (streamed in key order,
/// [`runs_files`] merged k-way, so a run in two shards comes as two rows in a row) summed
/// likewise, and both compared with the sum its manifest records. Only when they differ is
/// each run placed (`coverage_problems`: the selection's keys and the shards holding each,
/// O(runs), the error path alone) to say which runs are missing, and which shard should have
/// produced them, duplicated, in the wrong shard or foreign. The rows whose trace the shard did
/// not write ([`read_shard`]) are listed after these. The error lists every problem of the
/// first of these steps that finds any: the manifests, then the coverage and the traces.
pub fn check_shards<I: Iterator<Item = String>>(
    shards: &[ShardDir],
    expected: impl Fn() -> I,
    hash: &str,
) -> Result<(), ShardError> {
    let Some(first) = shards.first() else {
        return Err(ShardError::NoShardDirectories);
    };
    let n = first.manifest.shards;
    let mut problems = manifest_problems(shards, first, hash);
    if !problems.is_empty() {
        return Err(ShardError::CannotMerge { problems });
    }
    // What the selection assigns each shard (index k - 1: shard k).
    let mut assigned = vec![KeySum::default(); n];
    for (i, key) in expected().enumerate() {
        assigned[Shard::of_index(i, n) - 1].add(&key);
    }
    for s in shards {
        let wants = assigned[s.manifest.shard - 1];
        if (s.manifest.runs, s.manifest.key_sum.as_str()) != (wants.count, wants.hex().as_str()) {
            problems.push(format!(
                "{}: its {MANIFEST} records {} run(s) (key sum {}), but the selection assigns shard {}/{n} {} run(s) (key sum {}): it was not written for these experiment files and this selection",
                s.dir.display(),
                s.manifest.runs,
                s.manifest.key_sum,
                s.manifest.shard,
                wants.count,
                wants.hex()
            ));
        }
    }
    if !problems.is_empty() {
        return Err(ShardError::CannotMerge { problems });
    }
    // What each shard holds, and whether a run comes twice.
    let mut held = vec![KeySum::default(); shards.len()];
    let mut twice = false;
    let mut last: Option<spec::RunKey> = None;
    for item in KeyMerge::new(runs_files(shards)?)? {
        let (i, r) = item?;
        let key = r.key();
        held[i].add(&key.to_string());
        twice |= last.as_ref() == Some(&key);
        last = Some(key);
    }
    let all_given = (1..=n).all(|k| shards.iter().any(|s| s.manifest.shard == k));
    let each_holds_its_own = shards
        .iter()
        .zip(&held)
        .all(|(s, h)| *h == assigned[s.manifest.shard - 1]);
    if !(all_given && each_holds_its_own && !twice) {
        problems = coverage_problems(shards, &expected().collect::<Vec<_>>(), n)?;
    }
    problems.extend(shards.iter().flat_map(|s| s.traceless.iter().cloned()));
    if problems.is_empty() {
        Ok(())
    } else {
        Err(ShardError::CannotMerge { problems })
    }
}

/// Where the shards' manifests disagree with `first`'s or with the current experiment files
/// (`hash`): the number of shards, the experiment files, the selection, the code revision.
fn manifest_problems(shards: &[ShardDir], first: &ShardDir, hash: &str) -> Vec<String> {
    let n = first.manifest.shards;
    let mut problems = Vec::new();
    for s in shards {
        let m = &s.manifest;
        if m.shards != n {
            problems.push(format!(
                "{} is shard {}/{}, {} is shard {}/{n}: shards of different splits cannot be merged",
                s.dir.display(),
                m.shard,
                m.shards,
                first.dir.display(),
                first.manifest.shard
            ));
        }
        if m.experiments_hash != hash {
            problems.push(format!(
                "{} ran other experiment files (hash {}, the current ones hash {hash}): run it again, or merge with the files it ran",
                s.dir.display(),
                m.experiments_hash
            ));
        }
        if m.selection != first.manifest.selection {
            problems.push(format!(
                "{} ran the selection `{}`, {} ran `{}`",
                s.dir.display(),
                m.selection,
                first.dir.display(),
                first.manifest.selection
            ));
        }
    }
    let revisions: std::collections::BTreeSet<&str> =
        shards.iter().map(|s| s.manifest.git_rev.as_str()).collect();
    if revisions.len() > 1 {
        problems.push(format!(
            "the shards were run by different code revisions ({}), so their results are not comparable: run them again from one revision",
            shards
                .iter()
                .map(|s| format!("{}: {}", s.dir.display(), s.manifest.git_rev))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    problems
}

/// How the shards' runs cover the `expected` keys of the selection (in its enumeration
/// order), as problems (one entry per kind, listing its runs): shards of the `n` not given,
/// rows in a shard not theirs, selected runs missing, runs in more than one shard, runs the
/// selection does not describe. Every run is placed (the keys and the shards holding each):
/// the error path of [`check_shards`], which calls it only when the sums differ.
fn coverage_problems(
    shards: &[ShardDir],
    expected: &[String],
    n: usize,
) -> Result<Vec<String>, ShardError> {
    use std::collections::HashMap;
    let owners: HashMap<&str, usize> = expected
        .iter()
        .enumerate()
        .map(|(i, key)| (key.as_str(), Shard::of_index(i, n)))
        .collect();
    let mut found: HashMap<&str, Vec<usize>> = HashMap::new();
    let mut misplaced = Vec::new();
    let mut foreign = Vec::new();
    for item in KeyMerge::new(runs_files(shards)?)? {
        let (i, r) = item?;
        let key = r.key().to_string();
        match owners.get_key_value(key.as_str()) {
            Some((&known, &owner)) => {
                if owner != shards[i].manifest.shard {
                    misplaced.push(format!(
                        "  {}: holds {key}, which belongs to shard {owner}/{n}",
                        shards[i].dir.display()
                    ));
                }
                found.entry(known).or_default().push(i);
            }
            None => foreign.push(format!("  {key}  (in {})", shards[i].dir.display())),
        }
    }
    let mut given: Vec<usize> = shards.iter().map(|s| s.manifest.shard).collect();
    given.sort_unstable();
    let absent: Vec<usize> = (1..=n)
        .filter(|k| given.binary_search(k).is_err())
        .collect();
    let mut missing = Vec::new();
    let mut duplicated = Vec::new();
    for (i, key) in expected.iter().enumerate() {
        let owner = Shard::of_index(i, n);
        match found.get(key.as_str()).map_or(&[][..], Vec::as_slice) {
            [] => missing.push(format!(
                "  {key}  (shard {owner}/{n}{})",
                if absent.contains(&owner) {
                    ", not given"
                } else {
                    ""
                }
            )),
            [_] => {}
            holders => duplicated.push(format!(
                "  {key}  duplicated in {}",
                holders
                    .iter()
                    .map(|&i| shards[i].dir.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }
    let mut out = Vec::new();
    if !absent.is_empty() {
        out.push(format!(
            "shard(s) {} of {n} not given",
            absent
                .iter()
                .map(|k| k.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    for (what, list) in [
        ("row(s) in a shard that is not theirs", misplaced),
        ("selected run(s) missing from the shards", missing),
        ("run(s) in more than one shard", duplicated),
        (
            "run(s) in the shards that the selection does not describe",
            foreign,
        ),
    ] {
        if !list.is_empty() {
            out.push(format!("{} {what}:\n{}", list.len(), list.join("\n")));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Strided by index: run i is shard i mod N + 1's; each index in one shard, and the plan
    /// counts each shard's indices, balanced to one.
    #[test]
    fn every_index_in_exactly_one_shard() {
        assert_eq!(Shard::of_index(0, 8), 1);
        assert_eq!(Shard::of_index(7, 8), 8);
        assert_eq!(Shard::of_index(8, 8), 1);
        assert_eq!(Shard::of_index(13, 3), 2);
        for total in [0, 1, 2, 7, 64, 101] {
            for n in 1..=9 {
                let counts = plan(total, n);
                for k in 1..=n {
                    let owned = (0..total).filter(|&i| Shard::of_index(i, n) == k).count();
                    assert_eq!(owned, counts[k - 1], "{k}/{n} of {total}");
                }
                assert_eq!(counts.iter().sum::<usize>(), total);
                assert!(counts.iter().max().unwrap() - counts.iter().min().unwrap() <= 1);
            }
        }
        // More shards than runs: the last shards are empty.
        assert_eq!(plan(3, 8), [1, 1, 1, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn k_and_n_from_the_command_line_and_the_environment() {
        assert_eq!(Shard::parse("2/3").unwrap(), Shard { k: 2, n: 3 });
        assert!(Shard::parse("0/3").is_err());
        assert!(Shard::parse("4/3").is_err());
        assert!(Shard::parse("1/0").is_err());
        assert!(Shard::parse("3").is_err());
        let env = |vars: &'static [(&'static str, &'static str)]| {
            move |name: &str| {
                vars.iter()
                    .find(|(k, _)| *k == name)
                    .map(|(_, v)| v.to_string())
            }
        };
        let slurm =
            |id: &'static str, min: &'static str, max: &'static str, count: &'static str| {
                move |name: &str| {
                    match name {
                        "SLURM_ARRAY_TASK_ID" => Some(id),
                        "SLURM_ARRAY_TASK_MIN" => Some(min),
                        "SLURM_ARRAY_TASK_MAX" => Some(max),
                        "SLURM_ARRAY_TASK_COUNT" => Some(count),
                        _ => None,
                    }
                    .map(String::from)
                }
            };
        // --array=1-4: the array tells N.
        let s = Shard::from_env(slurm("4", "1", "4", "4"), None);
        assert_eq!(s.unwrap(), Shard { k: 4, n: 4 });
        // A resubmitted task (--array=2), part of an array (--array=2-3), a stepped, sparse or
        // 0-based array: N is not told, and the error names the variables.
        for (id, min, max, count) in [
            ("2", "2", "2", "1"),
            ("1", "1", "1", "1"),
            ("3", "2", "3", "2"),
            ("3", "1", "7", "4"),
            ("5", "1", "9", "3"),
            ("0", "0", "3", "4"),
        ] {
            let e = Shard::from_env(slurm(id, min, max, count), None).unwrap_err();
            assert!(matches!(e, ShardError::ArrayWithoutCount { .. }), "{e}");
            let msg = e.to_string();
            for said in [
                format!("SLURM_ARRAY_TASK_ID={id}"),
                format!("SLURM_ARRAY_TASK_COUNT={count}"),
                format!("SLURM_ARRAY_TASK_MIN={min}"),
                "--shards N".to_string(),
                "DRIFTBENCH_SHARDS".to_string(),
            ] {
                assert!(msg.contains(&said), "{said} not in {msg}");
            }
        }
        assert!(Shard::from_env(env(&[("SLURM_ARRAY_TASK_ID", "2")]), None)
            .unwrap_err()
            .to_string()
            .contains("SLURM_ARRAY_TASK_COUNT unset"));
        // ... unless N is given: the task id is the shard number.
        let s = Shard::from_env(slurm("2", "2", "2", "1"), Some(4));
        assert_eq!(s.unwrap(), Shard { k: 2, n: 4 });
        let with_env = |name: &str| match name {
            "DRIFTBENCH_SHARDS" => Some("4".to_string()),
            _ => slurm("3", "3", "3", "1")(name),
        };
        assert_eq!(
            Shard::from_env(with_env, None).unwrap(),
            Shard { k: 3, n: 4 }
        );
        // --shards wins over DRIFTBENCH_SHARDS and over the array.
        assert_eq!(
            Shard::from_env(with_env, Some(8)).unwrap(),
            Shard { k: 3, n: 8 }
        );
        assert_eq!(
            Shard::from_env(slurm("2", "1", "4", "4"), Some(2)).unwrap(),
            Shard { k: 2, n: 2 }
        );
        // A task id outside 1..=N.
        for (id, n) in [("0", 4), ("5", 4)] {
            let e = Shard::from_env(slurm(id, id, id, "1"), Some(n)).unwrap_err();
            assert!(matches!(e, ShardError::TaskId { .. }), "{e}");
            assert!(e.to_string().contains("--array=1-4"), "{e}");
        }
        let s = Shard::from_env(env(&[("SLURM_ARRAY_TASK_ID", "2")]), Some(5));
        assert_eq!(s.unwrap(), Shard { k: 2, n: 5 });
        assert!(matches!(
            Shard::from_env(slurm("x", "1", "4", "4"), None),
            Err(ShardError::Environment { .. })
        ));
        // Kubernetes: the index is K - 1 and N must be given.
        let s = Shard::from_env(
            env(&[("JOB_COMPLETION_INDEX", "0"), ("DRIFTBENCH_SHARDS", "3")]),
            None,
        );
        assert_eq!(s.unwrap(), Shard { k: 1, n: 3 });
        let s = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "2")]), Some(3));
        assert_eq!(s.unwrap(), Shard { k: 3, n: 3 });
        let e = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "0")]), None).unwrap_err();
        assert!(e.to_string().contains("JOB_COMPLETION_INDEX=0"), "{e}");
        assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "3")]), Some(3)).is_err());
        assert!(Shard::from_env(env(&[]), Some(3)).is_err());
    }

    /// A shard whose traced rows each have their trace listed reads with none noted, also
    /// when its manifest lists a trace of no row (the sums differ, and each row is looked up);
    /// a row whose trace is not listed is noted, naming the run; a run that keeps no trace by
    /// choice needs none.
    #[test]
    fn a_row_without_its_listed_trace_is_noted() {
        use crate::results_dir::ResultsDir;
        use crate::tracked_dir::Edits;
        let dir = inputs::Scratch::unmade("traceless");
        let key = |v: &str| spec::RunKey::from_ids("exp", v, "exact").unwrap();
        let rows: Vec<RunRow> = ["a", "b", "c"]
            .iter()
            .map(|v| RunRow::blank(&key(v), spec::SolverKind::Exact))
            .collect();
        let trace: [records::TracePoint; 0] = [];
        {
            let (results, _) = ResultsDir::open(&dir, "r", Edits::Refuse).unwrap();
            results
                .commit_runs::<crate::results_dir::ResultsError>(0, rows.into_iter().map(Ok))
                .unwrap();
            for v in ["a", "b", "c", "orphan"] {
                results.write_trace(&key(v), &trace).unwrap();
            }
            results.save().unwrap();
        }
        Manifest {
            shard: 1,
            shards: 1,
            git_rev: "r".into(),
            experiments_hash: "0".into(),
            runs: 3,
            key_sum: format!("{:032x}", 0),
            selection: Selection::default(),
        }
        .write(&dir)
        .unwrap();
        let traceless = |traced: fn(&spec::RunKey) -> bool| {
            read_shard(&dir, Edits::Refuse, traced).unwrap().traceless
        };
        assert!(traceless(|_| true).is_empty());
        // b's trace removed, as the program removes a file (and its entry).
        {
            let (results, _) = ResultsDir::open(&dir, "r", Edits::Refuse).unwrap();
            let rel = ResultsDir::trace_rel(&key("b"));
            results.tracked().remove(&rel).unwrap();
            results.save().unwrap();
        }
        let noted = traceless(|_| true);
        assert_eq!(noted.len(), 1, "{noted:?}");
        assert!(noted[0].contains("exp / b / exact"), "{noted:?}");
        assert!(traceless(|k| k.variant.as_str() != "b").is_empty());
        // The orphan removed: the listed traces are the traced rows' (equal sums).
        {
            let (results, _) = ResultsDir::open(&dir, "r", Edits::Refuse).unwrap();
            let rel = ResultsDir::trace_rel(&key("orphan"));
            results.tracked().remove(&rel).unwrap();
            results.save().unwrap();
        }
        assert!(traceless(|k| k.variant.as_str() != "b").is_empty());
        assert_eq!(traceless(|_| true).len(), 1);
    }

    #[test]
    fn manifest_round_trips() {
        let m = Manifest {
            shard: 2,
            shards: 3,
            git_rev: "abc".into(),
            experiments_hash: "0123456789abcdef".into(),
            runs: 1,
            key_sum: format!("{:032x}", u128::MAX - 7),
            selection: Selection {
                paper: Some("kong2019".into()),
                experiments: vec![],
                exact_only: true,
            },
        };
        let dir = inputs::Scratch::dir("manifest");
        m.write(&dir).unwrap();
        assert_eq!(Manifest::read(&dir).unwrap(), m);
        Manifest::remove(&dir).unwrap();
        assert!(Manifest::read(&dir)
            .unwrap_err()
            .to_string()
            .contains("has not finished"));
    }

    /// A manifest that no shard could have written is refused as it is read, naming the file
    /// and the field: never a panic.
    #[test]
    fn impossible_manifests_are_refused_naming_the_field() {
        let dir = inputs::Scratch::dir("bad-manifest");
        let good = Manifest {
            shard: 1,
            shards: 2,
            git_rev: "abc".into(),
            experiments_hash: "0123456789abcdef".into(),
            runs: 2,
            key_sum: "0123456789abcdef0123456789abcdef".into(),
            selection: Selection::default(),
        };
        let refused = |m: &Manifest, wants: &[&str]| {
            m.write(&dir).unwrap();
            let e = Manifest::read(&dir).unwrap_err();
            let msg = e.to_string();
            assert!(
                msg.contains(&dir.join(MANIFEST).display().to_string()),
                "{msg}"
            );
            for w in wants {
                assert!(msg.contains(w), "{w} not in {msg}");
            }
            e
        };
        let e = refused(
            &Manifest {
                shards: 0,
                ..good.clone()
            },
            &["`shards = 0`", "at least 1"],
        );
        assert!(matches!(e, ShardError::ManifestShard { .. }), "{e}");
        refused(
            &Manifest {
                shard: 3,
                ..good.clone()
            },
            &["`shard = 3`", "1..=2"],
        );
        refused(
            &Manifest {
                shard: 0,
                ..good.clone()
            },
            &["`shard = 0`"],
        );
        for bad in ["", "0123", "0123456789ABCDEF0123456789abcdef", "../x"] {
            let e = refused(
                &Manifest {
                    key_sum: bad.into(),
                    ..good.clone()
                },
                &["`key_sum = ", "32 lower-case hex digits"],
            );
            assert!(matches!(e, ShardError::ManifestKeySum { .. }), "{e}");
        }
        good.write(&dir).unwrap();
        assert_eq!(Manifest::read(&dir).unwrap(), good);
    }
}
