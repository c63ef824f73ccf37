//! The cost harness: what one instant and one whole run cost against the number of joints on
//! the n-link arms, per dense LU backend, written to `results/dof-cost.csv` by `reproduce cost`
//! and benched with criterion's statistics by `benches/benches/dof.rs`.
//!
//! # Why a crate of its own
//!
//! The harness measures the engine; it is not part of it: `simulation` (the engine) no longer
//! carries timing code, and `records` keeps only the plain data the harness hands over
//! ([`records::dof_cost`]: the quantities, summaries, fits and rows). It is not in `benches`
//! either: that crate is criterion's (its library is bench fixtures, built with criterion),
//! while the harness is a dependency of the `reproduce` binary, which must not pull in a bench
//! framework. Both `reproduce` and the criterion bench call this crate, so the two measure the
//! same calls.
//!
//! # One harness
//!
//! [`harness`]: any N, no instantiation per size: the registry's n-link arm `nlink-N` and the
//! scheme (jia2019's VLTCO on a four-leaf clover, kong2019's ZNN scheme, eq. 22, on a circle)
//! through the engine's one path, every quantity, whole runs included, at states sampled from
//! one exact run. Both schemes at [`harness::SWEEP_SIZES`] (N = 3 ... 30), kong2019's alone at
//! [`harness::LARGE_SIZES`] (40 ... 200). The per-instant quantities are [`instants::Instants`]';
//! the dense LU quantities (`network-lu`, `kkt-floor`) are timed on both [`solvers::Backend`]s,
//! from which the report reads the crossover that [`settings::linear_algebra::FAER_CROSSOVER`]
//! records.
//!
//! [`measure`](mod@measure) holds the timing ([`measure::Budget`], how samples are taken and summarised).

pub mod case;
pub mod error;
pub mod harness;
pub mod instants;
pub mod measure;

pub use case::{backends, Case, PreparedCase};
pub use error::CostError;
pub use measure::{machine, measure, measure_all, Budget};
