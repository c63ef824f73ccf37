//! driftbench's store: where the rows of crate `records` are kept. `results/` (and a shard's
//! directory) is a sealed directory: every file the program writes goes through one atomic
//! write and is listed in a manifest of line counts, sizes and SHA-256 sums, every file it
//! reads goes through the one reader, and an interrupted run resumes from its journal. The
//! rows' schemas are crate `records`'s; this crate links it, never the other way.
//!
//! - [`atomic`]: the atomic write (a temporary file of the program's own prefix, renamed into
//!   place, a kill point after it).
//! - [`owned_dir`]: a directory the program owns; the only way a name read from a file becomes
//!   a path under it (plain names, no symbolic link leaving it).
//! - [`integrity`]: the manifest of what the program wrote (line count, size, SHA-256 per file).
//! - [`tracked_dir`]: an owned directory with its manifest: writes recorded, edits found,
//!   deletions only of files the program provably wrote.
//! - [`results_dir`]: `results/` as one type: lock, layout, traces, pruning.
//! - [`table`], [`runs`], [`timing`], [`dof_cost`], [`control`]: the results files read
//!   through the one reader and written atomically (their rows parsed and serialised by
//!   `records`).
//! - [`journal`]: the checkpoint of finished runs that an interrupted run resumes from;
//!   [`kill_point`]: the test hook that kills the process after any durable step.
//! - [`shard`]: cluster runs: which shard a run belongs to, the shard directory's binding and
//!   manifest, the merge checks; [`fnv`]: the stable hash they use; [`keys`]: run keys held
//!   in a few bytes each (a set of their prints, a multiset's sum).
//! - [`sorted`]: rows in key order, streamed: a `runs.csv` read row by row, sources merged
//!   k-way, the latest row of each key kept (a shard's fold and a merge, in flat memory).
//! - [`migrate`]: results written before run ids (labels as identities), brought up to date once.
//! - [`error`]: the errors of reading and writing the results files, wrapping the schemas'.

#![deny(missing_docs)]

pub mod atomic;
pub mod control;
pub mod dof_cost;
pub mod error;
pub mod fnv;
pub mod integrity;
pub mod journal;
pub mod keys;
pub mod kill_point;
pub mod migrate;
pub mod owned_dir;
pub mod results_dir;
pub mod runs;
pub mod shard;
pub mod sorted;
pub mod table;
pub mod timing;
pub mod tracked_dir;
