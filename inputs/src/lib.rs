//! One way to read a file: experiment files, the inference family and the control task set,
//! the papers' `paper.toml`, `values.csv` and robot files, a trajectory to score, a gate's
//! baseline, a shard's manifest, the integrity manifest of `results/`, `report/` or a shard, and
//! the files of those directories the program reads back (`Kind::Owned`: a pull request or a
//! shard from elsewhere can put anything in their place).
//!
//! Every such file is read by [`read()`] (or [`read_text`], or as a stream by [`open()`]), which
//! - opens without blocking (a FIFO or a device answers at once, and is refused),
//! - reads regular files only, after following symbolic links ([`InputError::NotRegular`]),
//! - refuses a file that, once its links are followed, lies outside the directory it was found
//!   in ([`Origin::Under`], e.g. `experiments/`), or, for a file named on the command line
//!   ([`Origin::Named`]), the directory it is named in; the error says whether a symbolic link
//!   or the path itself (`../`) leads out ([`Via`]),
//! - reads at most the cap of its [`Kind`] plus one byte, and refuses a larger file,
//! - and says what is wrong without quoting the file: [`InputError`] names the path and
//!   the rule, [`TomlError`] (from [`parse_toml`]) a TOML error's message and line and column, without the
//!   source line that `toml`'s own message shows.
//!
//! The formats of trajectories made elsewhere (a CSV table, a MATLAB / Octave MAT-file) are
//! read here too, in [`trajectory`]: they are outside files, not the suite's own.
//!
//! A directory the program keeps for itself outside a checkout (the Python package's data
//! cache) is filled by [`sync_private_dir`]: owner-only, never through a link, never one it
//! did not create, deleting nothing it did not write.
//!
//! Every reader's tests hold it to these rules with one kit, [`assert_refuses_hostile_files`]
//! (a symbolic link out, a FIFO, a file over its cap, TOML errors that must not quote the file;
//! Unix only).
//!
//! Every test of the workspace that writes outside the checkout writes into a [`Scratch`]: a
//! path under the system's temporary directory, unique per process and test, removed when the
//! test ends, also when it panics.
//!
//! What a build compiles into a binary is held to [`embed`] (a public module: the build scripts
//! include it by path): regular files only, reached
//! without a symbolic link, inside the checkout.

// `inputs::` names this crate inside it too: the tests of `embed` (which build scripts and
// robots' test of its build script compile by path) reach `inputs::Scratch` in either crate.
extern crate self as inputs;

pub mod embed;
mod error;
#[cfg(unix)]
mod hostile;
mod kind;
mod private_dir;
mod read;
mod scratch;
mod toml_error;
pub mod trajectory;

pub use error::{InputError, Via};
#[cfg(unix)]
pub use hostile::{assert_refuses_hostile_files, HOSTILE_MARKER, HOSTILE_TIMEOUT};
pub use kind::Kind;
pub use private_dir::{sync as sync_private_dir, PrivateDirError};
pub use read::{open, read, read_text, Capped, Origin};
pub use scratch::Scratch;
pub use toml_error::from_str as parse_toml;
pub use toml_error::TomlError;
// The one way an error shows a text it was given (crate settings), for this crate's errors; a
// TOML error's message follows it ([`TomlError`]).
use settings::{is_control_or_format, shown, SHOWN_MAX_CHARS};
