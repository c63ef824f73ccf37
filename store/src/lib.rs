//! driftbench's store: where the rows of crate `records` are kept. `results/` (and a shard's
//! directory) is a sealed directory: every file the program writes goes through one atomic
//! write and is listed in a manifest of line counts, sizes and SHA-256 sums, every file it
//! reads goes through the one reader, and an interrupted run resumes from its journal. The
//! rows' schemas are crate `records`'s; this crate links it, never the other way.
//!
//! - [`write_atomic`]: the atomic write (a temporary file of the program's own prefix, renamed into
//!   place, a kill point after it).
//! - [`OwnedDir`]: a directory the program owns; the only way a name read from a file becomes
//!   a path under it (plain names, no symbolic link leaving it).
//! - [`integrity`]: the manifest of what the program wrote (line count, size, SHA-256 per file).
//! - [`TrackedDir`]: an owned directory with its manifest: writes recorded, edits found,
//!   deletions only of files the program provably wrote.
//! - [`results_dir`]: `results/` as one type: lock, layout, traces, pruning.
//! - [`table`], [`read_runs`], [`timing`], [`dof_cost`], [`control`]: the results files read
//!   through the one reader and written atomically (their rows parsed and serialised by
//!   `records`).
//! - [`journal`]: the checkpoint of finished runs that an interrupted run resumes from;
//!   [`KILL_POINT_VAR`]: the test hook's variable, a hook that kills the process after any durable step.
//! - [`shard`]: cluster runs: which shard a run belongs to, the shard directory's binding and
//!   manifest, the merge checks; [`fnv1a64`]: the stable hash they use; run keys held in a
//!   few bytes each ([`KeySet`], a set of their prints; [`KeySum`], a multiset's sum).
//! - [`sorted`]: rows in key order, streamed: a `runs.csv` read row by row, sources merged
//!   k-way, the latest row of each key kept (a shard's fold and a merge, in flat memory).
//! - [`add_ids`]: results written before run ids (labels as identities), brought up to date once.
//! - [`IoError`], [`RunsError`], [`DofCostError`], [`ControlFileError`]: the errors of reading
//!   and writing the results files, wrapping the schemas'.
//!
//! The public modules are the results files and directories with a vocabulary of their own
//! (`read` and `write` by the same name, a layout's constants, a shard's manifest); the rest
//! is an item at the root.

#![deny(missing_docs)]

mod atomic;
pub mod control;
pub mod dof_cost;
mod error;
mod fnv;
pub mod integrity;
pub mod journal;
mod keys;
mod kill_point;
mod migrate;
mod owned_dir;
pub mod results_dir;
mod runs;
pub mod shard;
pub mod sorted;
pub mod table;
pub mod timing;
mod tracked_dir;
pub use atomic::write_atomic;
pub use error::{ControlFileError, DofCostError, IoAction, IoError, RunsError};
pub use fnv::fnv1a64;
pub use keys::{KeySet, KeySum};
pub use kill_point::VAR as KILL_POINT_VAR;
pub use migrate::{add_ids, LabelIndex, MigrateError};
pub use owned_dir::{read_file as read_owned_file, OwnedDir, PathError};
pub use runs::{check_writable, read_runs};
pub use tracked_dir::{Edits, Removal, TrackedDir, TrackedError};
