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
//! # The two paths
//!
//! - [`fixed`]: N = 3 ... 30 ([`robots::registry::NLINK_SIZES`]), each N a
//!   const-generic instantiation `NLink<N>` of the registry, with jia2019's VLTCO scheme on a
//!   four-leaf clover and kong2019's ZNN scheme (eq. 22) on a circle; every quantity, whole
//!   runs included, at states sampled from one exact run.
//! - [`dynamic`]: N = [`dynamic::SIZES`] (40 ... 200), no instantiation per size: the arm is
//!   [`robots::NLinkDyn`] and kong2019's scheme [`schemes::velocity_rmp_dyn::NLinkZnn`], both on
//!   slices; every quantity, whole runs included, through the same coupled ODE
//!   (`simulation::coupled`) as the fixed path (see [`dynamic`] for what a whole run there
//!   leaves out, and why not jia2019).
//!
//! Both share [`instants::Instants`], the per-instant quantities on a list of QPs; the dense LU
//! quantities (`network-lu`, `kkt-floor`) are timed on both [`solvers::Backend`]s, from which
//! the report reads the crossover that [`settings::linear_algebra::FAER_CROSSOVER`] records.
//!
//! [`measure`](mod@measure) holds the timing ([`measure::Budget`], how samples are taken and summarised).

pub mod case;
pub mod dynamic;
pub mod error;
pub mod fixed;
pub mod instants;
pub mod measure;

pub use case::{backends, Case, PreparedCase};
pub use error::CostError;
pub use measure::{machine, measure, measure_all, Budget};
