//! driftbench's solver settings, as data.
//!
//! What a solver is told before it runs, and nothing of how it runs:
//!
//! - a network and its parameters by the papers' names ([`SolverSpec`]), with its stable id and
//!   display name, and the reference perturbation of zhang2018 ([`ReferencePerturbation`]);
//! - an activation function and all of its parameters as one value ([`ActivationSpec`];
//!   zhong2021 (2.29) and the group's power-sigmoid);
//! - [`zeroing`]: the zeroing family as a vocabulary (gain law, activation, growing gain,
//!   perturbation), of which the papers' zeroing networks are presets;
//! - [`projection`]: the projection family as a vocabulary (error form with its scaling or
//!   penalty, gain law, activation), of which LVI-PDNN, S-LVI-PDNN and VP-RNN-PF are presets;
//! - [`qp_solver`]: the QP solvers' registry as data (id, name, settings with ranges and
//!   defaults; [`qp_solver::QpSolverInfo`]) and their typed settings
//!   ([`qp_solver::QpSolverSettings`]); crate `solvers`' `registry` holds the constructors;
//! - a network's kind ([`NetworkKind`]), its identity in experiment files and `runs.csv`;
//! - the integration method and its tolerances and budgets ([`IntegratorSettings`], [`Method`]);
//! - the system size from which dense LU runs on faer ([`FAER_CROSSOVER`]);
//! - the one rule for ids and file-name stems ([`slug()`], [`is_slug`]);
//! - the one way an error shows a text it was given, from a user's file or the command line
//!   ([`shown()`]: escaped, cut to [`SHOWN_MAX_CHARS`] characters), and what a label or id
//!   ([`is_control_or_format`]) and a text shown in listings and the report ([`is_one_line`])
//!   may hold; every crate that quotes such a text in an error reaches this one, the lowest;
//! - the sign-power function shared by kong2019's finite-time scheme and the finite-time
//!   activations ([`sign_power()`]);
//! - the checks' errors ([`NetworkError`], [`IntegratorError`]).
//!
//! The three vocabularies and the registry are the public modules; everything else is an item
//! at the root.
//!
//! Crate `solvers` builds its networks and integrators from these values; crate `catalog` reads
//! them from experiment files (every type here is serde-readable, and a misspelt field is an
//! error). The crate sits below both so that the numerical crates depend on no file format and
//! the results layer can state a setting without linking a solver.
//!
//! ```
//! use settings::SolverSpec;
//!
//! let spec: SolverSpec = parse("kind = \"vp-rnn-pf\"\np = 1e-4\nsigma = 400.0\ngamma = 2.0\nactivation = \"sinh\"");
//! assert_eq!(spec.id(), "vp-rnn-pf-sinh");
//! assert_eq!(spec.display_name(), "VP-RNN-PF (sinh)");
//! # fn parse(text: &str) -> SolverSpec { toml::from_str(text).unwrap() }
//! ```

#![deny(missing_docs)]

mod activation;
mod error;
mod integrator;
mod linear_algebra;
mod network_kind;
pub mod projection;
pub mod qp_solver;
mod shown;
mod sign_power;
mod slug;
mod solver_spec;
pub mod zeroing;
pub use activation::{
    ActivationKind, ActivationSpec, GROUP_POWER_SIGMOID_P, GROUP_POWER_SIGMOID_XI,
    POWER_SIGMOID_ALPHA, POWER_SIGMOID_CHI,
};
pub use error::{IntegratorError, NetworkError};
pub use integrator::{IntegratorSettings, Method, RHS_EVALS_PER_SECOND};
pub use linear_algebra::FAER_CROSSOVER;
pub use network_kind::NetworkKind;
pub use shown::{is_control_or_format, is_one_line, shown, Shown, SHOWN_MAX_CHARS};
pub use sign_power::{sign_power, sign_power_slope, SIGN_POWER_MIN_ABS};
pub use slug::{is_slug, slug};
pub use solver_spec::{ReferencePerturbation, SolverSpec};
