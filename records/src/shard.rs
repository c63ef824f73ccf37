//! Sharded runs for clusters: `reproduce --shard K/N` runs its share of the selected runs into
//! `results-shard-K-of-N/`, `reproduce --merge DIR...` combines the shards into `results/`.
//!
//! - **Assignment.** A run belongs to shard `fnv1a64(Job::key()) % N + 1` (K is 1-based). The
//!   hash is FNV-1a 64 written out here (std's `DefaultHasher` is not stable across Rust
//!   releases), so a run's shard depends only on its key and N: not on the order of the files,
//!   on the other runs, or on the machine.
//! - **Manifest.** A shard directory holds `runs.csv`, `traces/` and, written last and
//!   atomically, `shard.toml` ([`Manifest`]): K, N, the selection the shard was given, the run
//!   keys assigned to it, the code revision and a hash of the experiment files. A directory
//!   without a manifest is a shard that has not finished. A shard resumes through the ordinary
//!   journal ([`crate::journal`]) of its directory.
//! - **Merge.** [`check_shards`] verifies that the shards agree (N, experiment files, selection)
//!   and that every selected run appears exactly once; otherwise it says which runs are missing
//!   (and which shard should have produced them) or duplicated, and nothing is written.

use crate::error::{IoAction, IoError, ShardError};
use crate::owned_dir::PathError;
use crate::runs::{read_runs, RunRow};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The manifest's file name in a shard directory.
pub const MANIFEST: &str = "shard.toml";

/// FNV-1a, 64 bits (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Shard K of N (K in 1..=N).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub k: usize,
    pub n: usize,
}

impl Shard {
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

    /// K and N from a scheduler's environment (`get` reads a variable): a Slurm job array
    /// (`SLURM_ARRAY_TASK_ID`, offset by `SLURM_ARRAY_TASK_MIN` when set so that the first task
    /// is shard 1; N = `SLURM_ARRAY_TASK_COUNT`, or `shards`) or a Kubernetes Indexed Job
    /// (`JOB_COMPLETION_INDEX`, 0-based; N = `shards`, else `DRIFTBENCH_SHARDS`).
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
        let n_from = |fallback: Option<usize>| -> Result<usize, ShardError> {
            shards
                .or(fallback)
                .or(num("DRIFTBENCH_SHARDS")?)
                .ok_or(ShardError::UnknownCount)
        };
        if let Some(id) = num("SLURM_ARRAY_TASK_ID")? {
            let min = num("SLURM_ARRAY_TASK_MIN")?.unwrap_or(1);
            let k = (id + 1)
                .checked_sub(min)
                .ok_or(ShardError::BelowMin { id, min })?;
            return Self::new(k, n_from(num("SLURM_ARRAY_TASK_COUNT")?)?);
        }
        if let Some(index) = num("JOB_COMPLETION_INDEX")? {
            return Self::new(index + 1, n_from(None)?);
        }
        Err(ShardError::NoScheduler)
    }

    /// The shard (1-based) a run key belongs to among `n`.
    pub fn of(key: &str, n: usize) -> usize {
        (fnv1a64(key.as_bytes()) % n as u64) as usize + 1
    }

    pub fn owns(&self, key: &str) -> bool {
        Self::of(key, self.n) == self.k
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

/// Runs per shard (index 0: shard 1) when `keys` are split `n` ways.
pub fn plan<'a>(keys: impl IntoIterator<Item = &'a str>, n: usize) -> Vec<usize> {
    let mut counts = vec![0; n];
    for k in keys {
        counts[Shard::of(k, n) - 1] += 1;
    }
    counts
}

/// Which runs a shard was given: the selection flags of its command line.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Selection {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paper: Option<String>,
    #[serde(default)]
    pub experiments: Vec<String>,
    #[serde(default)]
    pub exact_only: bool,
}

/// `shard.toml`: written last, so a shard directory with one holds a finished shard.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub shard: usize,
    pub shards: usize,
    pub git_rev: String,
    /// [`experiments_hash`] of the experiment files the shard ran.
    pub experiments_hash: String,
    /// The run keys (`experiment / variant / solver`) assigned to the shard.
    pub runs: Vec<String>,
    pub selection: Selection,
}

impl Manifest {
    pub fn write(&self, dir: &Path) -> Result<(), ShardError> {
        let path = dir.join(MANIFEST);
        let text = toml::to_string(self).map_err(|source| ShardError::WriteManifest {
            path: path.clone(),
            source,
        })?;
        crate::runs::write_atomic(&path, text.as_bytes())
            .map_err(IoError::at(&path, IoAction::Write))?;
        Ok(())
    }

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
        inputs::toml_error::from_str(&text)
            .map_err(|source| ShardError::ReadManifest { path, source })
    }

    /// Removes a directory's manifest (a shard starting again is unfinished until it ends).
    pub fn remove(dir: &Path) -> Result<(), ShardError> {
        let path = dir.join(MANIFEST);
        match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                Err(IoError::at(&path, IoAction::Remove)(e).into())
            }
            _ => Ok(()),
        }
    }
}

/// FNV-1a 64 of the experiment files of `dir` (every `*.toml`, by file name: name and
/// contents), as 16 hex digits: shards to be merged must have run the same files.
pub fn experiments_hash(dir: &Path) -> Result<String, IoError> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(IoError::at(dir, IoAction::List))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    let mut bytes = Vec::new();
    for p in &paths {
        bytes.extend(p.file_name().unwrap_or_default().as_encoded_bytes());
        bytes.push(0);
        bytes.extend(std::fs::read(p).map_err(IoError::at(p, IoAction::Read))?);
        bytes.push(0);
    }
    Ok(format!("{:016x}", fnv1a64(&bytes)))
}

/// One finished shard directory.
#[derive(Clone, Debug)]
pub struct ShardDir {
    pub dir: PathBuf,
    pub manifest: Manifest,
    /// Its integrity manifest (every file it wrote, traces included).
    pub files: crate::integrity::Manifest,
    pub rows: Vec<RunRow>,
}

/// Reads a finished shard: its `shard.toml`, its integrity manifest, and its `runs.csv`.
/// Every file the integrity manifest lists (the rows and every trace) must still be what the
/// shard wrote, unless `edits` accepts edits; a directory that does not exist, or a shard
/// without an integrity manifest, is an error saying so.
pub fn read_shard(dir: &Path, edits: crate::tracked_dir::Edits) -> Result<ShardDir, ShardError> {
    if !dir.is_dir() {
        return Err(ShardError::NoDirectory {
            dir: dir.to_path_buf(),
        });
    }
    let manifest = Manifest::read(dir)?;
    let files = crate::integrity::Manifest::read(dir)?.ok_or_else(|| ShardError::NoIntegrity {
        dir: dir.to_path_buf(),
    })?;
    if edits == crate::tracked_dir::Edits::Refuse {
        let mismatches = files.mismatches(dir, |_| true);
        if !mismatches.is_empty() {
            return Err(ShardError::Edited {
                dir: dir.to_path_buf(),
                mismatches,
            });
        }
    }
    let rows = read_runs(&dir.join(crate::results_dir::RUNS))?;
    Ok(ShardDir {
        dir: dir.to_path_buf(),
        manifest,
        files,
        rows,
    })
}

/// A row's trace, relative to its results directory.
fn trace_rel(r: &RunRow) -> Result<PathBuf, PathError> {
    crate::results_dir::ResultsDir::trace_rel(&r.key())
}

/// Copies the traces of every shard's rows into `results` (each written atomically and
/// recorded); returns how many. [`check_shards`] has checked that each one is there.
pub fn copy_traces(
    shards: &[ShardDir],
    results: &crate::results_dir::ResultsDir,
) -> Result<usize, ShardError> {
    let mut n = 0;
    for s in shards {
        let owned = crate::owned_dir::OwnedDir::open(&s.dir)?;
        for r in &s.rows {
            let rel = trace_rel(r)?;
            let from = owned.resolve(&rel)?;
            let bytes = std::fs::read(&from).map_err(IoError::at(&from, IoAction::Read))?;
            results.tracked().write(&rel, &bytes)?;
            n += 1;
        }
    }
    Ok(n)
}

/// Checks shards before a merge: the same N, experiment files (`hash`: the current files')
/// and selection; every run of `expected` (the keys the selection describes) in exactly one
/// shard, and no other run. The error lists every problem.
pub fn check_shards(
    shards: &[ShardDir],
    expected: &[String],
    hash: &str,
) -> Result<(), ShardError> {
    let Some(first) = shards.first() else {
        return Err(ShardError::NoShardDirectories);
    };
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
                "{} ran the selection {:?}, {} ran {:?}",
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
    for s in shards {
        let assigned: std::collections::HashSet<&str> =
            s.manifest.runs.iter().map(String::as_str).collect();
        for r in &s.rows {
            let key = r.key().to_string();
            let owner = Shard::of(&key, n);
            if owner != s.manifest.shard || !assigned.contains(key.as_str()) {
                problems.push(format!(
                    "{}: holds {key}, which belongs to shard {owner}/{n}{}",
                    s.dir.display(),
                    if assigned.contains(key.as_str()) {
                        ""
                    } else {
                        " and is not among the runs its shard.toml lists"
                    }
                ));
            }
            match trace_rel(r) {
                Ok(rel) => {
                    let listed = rel.to_string_lossy().replace('\\', "/");
                    if !s.files.files.contains_key(&listed) {
                        problems.push(format!(
                            "{}: the trace of {key} ({}) is not among the files the shard wrote",
                            s.dir.display(),
                            rel.display()
                        ));
                    }
                }
                Err(e) => problems.push(format!("{}: {e}", s.dir.display())),
            }
        }
    }
    if !problems.is_empty() {
        return Err(ShardError::CannotMerge { problems });
    }
    let mut given: Vec<usize> = shards.iter().map(|s| s.manifest.shard).collect();
    given.sort_unstable();
    let absent: Vec<usize> = (1..=n).filter(|k| !given.contains(k)).collect();
    let mut found: std::collections::HashMap<String, Vec<&Path>> = Default::default();
    for s in shards {
        for r in &s.rows {
            found.entry(r.key().to_string()).or_default().push(&s.dir);
        }
    }
    let mut missing = Vec::new();
    for key in expected {
        match found.get(key).map(Vec::len).unwrap_or(0) {
            0 => missing.push(format!(
                "  {key}  (shard {}/{n}{})",
                Shard::of(key, n),
                if absent.contains(&Shard::of(key, n)) {
                    ", not given"
                } else {
                    ""
                }
            )),
            1 => {}
            _ => problems.push(format!(
                "  {key}  duplicated in {}",
                found[key]
                    .iter()
                    .map(|d| d.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }
    let expected_set: std::collections::HashSet<&String> = expected.iter().collect();
    let mut foreign: Vec<&String> = found.keys().filter(|k| !expected_set.contains(k)).collect();
    foreign.sort();
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
    if !missing.is_empty() {
        out.push(format!(
            "{} selected run(s) missing from the shards:\n{}",
            missing.len(),
            missing.join("\n")
        ));
    }
    if !problems.is_empty() {
        out.push(format!(
            "{} run(s) in more than one shard:\n{}",
            problems.len(),
            problems.join("\n")
        ));
    }
    if !foreign.is_empty() {
        out.push(format!(
            "{} run(s) in the shards that the selection does not describe:\n{}",
            foreign.len(),
            foreign
                .iter()
                .map(|k| format!("  {k}"))
                .collect::<Vec<_>>()
                .join("\n")
        ));
    }
    if out.is_empty() {
        Ok(())
    } else {
        Err(ShardError::CannotMerge { problems: out })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_is_the_published_function() {
        // Test vectors of the FNV reference (draft-eastlake-fnv).
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    /// Computed once; a change of the hash (or of the key format) moves runs between shards
    /// and must fail here.
    #[test]
    fn assignment_is_stable() {
        let cases = [
            ("kong2019-circle-mu-sweep / ZNN (eq. 22) [mu=2] / ZNN", 8, 4),
            ("jia2019-clover / VLTCO / exact (Clarabel)", 3, 2),
            ("jia2019-clover / VLTCO / LVI-PDNN", 3, 1),
            (
                "zhang2018-butterfly-gamma-sweep / HL-JDF (zeta=0.6) [gamma=20] / FP-CDNN",
                7,
                4,
            ),
        ];
        let got: Vec<usize> = cases.iter().map(|(k, n, _)| Shard::of(k, *n)).collect();
        let want: Vec<usize> = cases.iter().map(|c| c.2).collect();
        assert_eq!(got, want);
    }

    #[test]
    fn every_key_in_exactly_one_shard() {
        let keys: Vec<String> = (0..200).map(|i| format!("e / v{i} / s")).collect();
        for n in 1..=7 {
            for key in &keys {
                let owners = (1..=n)
                    .filter(|&k| Shard::new(k, n).unwrap().owns(key))
                    .count();
                assert_eq!(owners, 1, "{key} among {n}");
            }
            let counts = plan(keys.iter().map(String::as_str), n);
            assert_eq!(counts.iter().sum::<usize>(), keys.len());
        }
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
        // --array=1-4
        let s = Shard::from_env(
            env(&[
                ("SLURM_ARRAY_TASK_ID", "4"),
                ("SLURM_ARRAY_TASK_MIN", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "4"),
            ]),
            None,
        );
        assert_eq!(s.unwrap(), Shard { k: 4, n: 4 });
        // --array=0-3
        let s = Shard::from_env(
            env(&[
                ("SLURM_ARRAY_TASK_ID", "0"),
                ("SLURM_ARRAY_TASK_MIN", "0"),
                ("SLURM_ARRAY_TASK_COUNT", "4"),
            ]),
            None,
        );
        assert_eq!(s.unwrap(), Shard { k: 1, n: 4 });
        let s = Shard::from_env(env(&[("SLURM_ARRAY_TASK_ID", "2")]), Some(5));
        assert_eq!(s.unwrap(), Shard { k: 2, n: 5 });
        let s = Shard::from_env(
            env(&[("JOB_COMPLETION_INDEX", "0"), ("DRIFTBENCH_SHARDS", "3")]),
            None,
        );
        assert_eq!(s.unwrap(), Shard { k: 1, n: 3 });
        let s = Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "2")]), Some(3));
        assert_eq!(s.unwrap(), Shard { k: 3, n: 3 });
        assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "0")]), None).is_err());
        assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "3")]), Some(3)).is_err());
        assert!(Shard::from_env(env(&[]), Some(3)).is_err());
    }

    #[test]
    fn manifest_round_trips() {
        let m = Manifest {
            shard: 2,
            shards: 3,
            git_rev: "abc".into(),
            experiments_hash: "0123456789abcdef".into(),
            runs: vec!["e / v / s".into()],
            selection: Selection {
                paper: Some("kong2019".into()),
                experiments: vec![],
                exact_only: true,
            },
        };
        let dir = std::env::temp_dir().join(format!("driftbench-manifest-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        m.write(&dir).unwrap();
        assert_eq!(Manifest::read(&dir).unwrap(), m);
        Manifest::remove(&dir).unwrap();
        assert!(Manifest::read(&dir)
            .unwrap_err()
            .to_string()
            .contains("has not finished"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
