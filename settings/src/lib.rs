//! driftbench's solver settings, as data.
//!
//! What a solver is told before it runs, and nothing of how it runs:
//!
//! - [`solver_spec`]: a network and its parameters by the papers' names
//!   ([`solver_spec::SolverSpec`]), with its stable id and display name, and the reference
//!   perturbation of zhang2018 ([`solver_spec::ReferencePerturbation`]);
//! - [`activation`]: an activation function and all of its parameters as one value
//!   ([`activation::ActivationSpec`]; zhong2021 (2.29) and the group's power-sigmoid);
//! - [`zeroing`]: the zeroing family as a vocabulary (gain law, activation, growing gain,
//!   perturbation), of which the papers' zeroing networks are presets;
//! - [`projection`]: the projection family as a vocabulary (error form with its scaling or
//!   penalty, gain law, activation), of which LVI-PDNN, S-LVI-PDNN and VP-RNN-PF are presets;
//! - [`qp_solver`]: the QP solvers' registry as data (id, name, settings with ranges and
//!   defaults; [`qp_solver::QpSolverInfo`]) and their typed settings
//!   ([`qp_solver::QpSolverSettings`]); crate `solvers`' `registry` holds the constructors;
//! - [`network_kind`]: a network's kind ([`network_kind::NetworkKind`]), its identity in
//!   experiment files and `runs.csv`;
//! - [`integrator`]: the integration method and its tolerances and budgets;
//! - [`linear_algebra`]: the system size from which dense LU runs on faer;
//! - [`slug`]: the one rule for ids and file-name stems;
//! - [`sign_power`]: the sign-power function shared by kong2019's finite-time scheme and the
//!   finite-time activations;
//! - [`error`]: the checks' errors ([`error::NetworkError`], [`error::IntegratorError`]).
//!
//! Crate `solvers` builds its networks and integrators from these values; crate `catalog` reads
//! them from experiment files (every type here is serde-readable, and a misspelt field is an
//! error). The crate sits below both so that the numerical crates depend on no file format and
//! the results layer can state a setting without linking a solver.
//!
//! ```
//! use settings::solver_spec::SolverSpec;
//!
//! let spec: SolverSpec = parse("kind = \"vp-rnn-pf\"\np = 1e-4\nsigma = 400.0\ngamma = 2.0\nactivation = \"sinh\"");
//! assert_eq!(spec.id(), "vp-rnn-pf-sinh");
//! assert_eq!(spec.display_name(), "VP-RNN-PF (sinh)");
//! # fn parse(text: &str) -> SolverSpec { toml::from_str(text).unwrap() }
//! ```

#![deny(missing_docs)]

pub mod activation;
pub mod error;
pub mod integrator;
pub mod linear_algebra;
pub mod network_kind;
pub mod projection;
pub mod qp_solver;
pub mod sign_power;
pub mod slug;
pub mod solver_spec;
pub mod zeroing;
