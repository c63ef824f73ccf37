//! The registry of QP solvers: id -> constructor from typed settings. Every per-instant QP
//! method a numerical run (`simulation`) or a control tick (`control`) uses is built here,
//! through the one seam [`QpSolver`]; which one is data (an experiment file's
//! `numerical = [{ method = "<id>", ... }]`, a control method's id).
//!
//! Each solver is described by a [`QpSolverInfo`] (crate `settings`' `qp_solver`: id, name,
//! the settings it takes with their ranges and defaults), the half of the registry the file
//! layers read without linking a solver, and built by its constructor, this half:
//!
//! - the built-in ones ([`settings::qp_solver::BUILTIN`]): robio2018's six PLPE methods
//!   ([`LviSolver`]), the hot-started active set ([`HotActiveSet`]), Clarabel
//!   ([`ExactSolver`]) and, with the `osqp` feature, OSQP;
//! - an outside solver, added at run time with [`register`]: its description and its
//!   constructor in one call, after which experiment files may name it and runs build it like
//!   a built-in one (the workspace's `outside-solver` crate does so in its tests).
//!
//! [`build`] checks the settings against the description ([`QpSolverInfo::resolve`]: a
//! setting the solver does not take, or one out of range, is an error naming it) and hands the
//! constructor the completed settings (a field is `Some` exactly when the solver takes it).

use crate::exact::ExactSolver;
use crate::lvi_numerical::{LviMethod, LviSettings, LviSolver};
use crate::qp_solver::HotActiveSet;
use qp::{QpDims, QpSolver};
pub use settings::qp_solver::{QpSolverError, QpSolverInfo, QpSolverKey, QpSolverSettings};
use std::collections::HashMap;
use std::sync::{Arc, LazyLock, RwLock};

/// A QP solver as the registry hands it out: owned, movable to another thread.
pub type BoxedQpSolver = Box<dyn QpSolver + Send>;

/// A solver's constructor: QPs of sizes `dims`, with settings completed by
/// [`QpSolverInfo::resolve`].
pub type Constructor = Arc<dyn Fn(QpDims, &QpSolverSettings) -> BoxedQpSolver + Send + Sync>;

/// Why [`build`] or [`register`] failed.
#[derive(Debug, thiserror::Error)]
pub enum RegistryError {
    /// The id is unknown, a setting is not taken or out of range, or an id cannot be
    /// registered: the description's error.
    #[error(transparent)]
    Settings(#[from] QpSolverError),
    /// The solver is described but this build has no constructor for it (OSQP without the
    /// `osqp` feature).
    #[error("QP solver {id} is not built into this program ({hint})")]
    NotBuilt {
        /// The solver's id.
        id: &'static str,
        /// How to get it.
        hint: &'static str,
    },
}

/// The outside solvers' constructors, by id.
static OUTSIDE: LazyLock<RwLock<HashMap<&'static str, Constructor>>> =
    LazyLock::new(|| RwLock::new(HashMap::new()));

/// Registers an outside solver: `info` (its id must be new: [`settings::qp_solver::register`])
/// and its constructor. From then on experiment files may name it and [`build`] makes it.
pub fn register(
    info: QpSolverInfo,
    constructor: Constructor,
) -> Result<QpSolverKey, RegistryError> {
    // The constructor is in place before the id is visible, so a reader that finds the id
    // finds its constructor.
    let id = info.id;
    let mut outside = OUTSIDE.write().unwrap_or_else(|e| e.into_inner());
    let entry = settings::qp_solver::register(info)?;
    outside.insert(id, constructor);
    Ok(entry.key())
}

/// The solver `id` for QPs of sizes `dims`, with the settings `given` checked and completed
/// (module docs).
pub fn build(
    id: &str,
    given: &QpSolverSettings,
    dims: QpDims,
) -> Result<BoxedQpSolver, RegistryError> {
    let (info, settings) = check(id, given)?;
    if let Some(solver) = builtin(info.id, &settings, dims) {
        return Ok(solver);
    }
    let outside = OUTSIDE.read().unwrap_or_else(|e| e.into_inner());
    match outside.get(info.id) {
        Some(make) => Ok(make(dims, &settings)),
        None => Err(RegistryError::NotBuilt {
            id: info.id,
            hint: "OSQP needs the `osqp` feature",
        }),
    }
}

/// The description of `id` and the settings `given` completed, as [`build`] would use them,
/// or why it would fail; builds nothing.
pub fn check(
    id: &str,
    given: &QpSolverSettings,
) -> Result<(&'static QpSolverInfo, QpSolverSettings), RegistryError> {
    let info = settings::qp_solver::lookup(id)?;
    let settings = info.resolve(given)?;
    if !cfg!(feature = "osqp") && info.id == "osqp" {
        return Err(RegistryError::NotBuilt {
            id: info.id,
            hint: "OSQP needs the `osqp` feature",
        });
    }
    Ok((info, settings))
}

/// A built-in solver (module docs), or `None` for an outside id.
fn builtin(id: &'static str, settings: &QpSolverSettings, dims: QpDims) -> Option<BoxedQpSolver> {
    if let Some(method) = LviMethod::from_id(id) {
        // resolve gives both settings to a PLPE method; the fallbacks are never taken.
        let plpe = LviSettings {
            tolerance: settings
                .tolerance
                .unwrap_or(LviSettings::default().tolerance),
            max_iterations: settings
                .max_iterations
                .unwrap_or(LviSettings::default().max_iterations),
        };
        return Some(Box::new(LviSolver::new(method, dims, plpe)));
    }
    match id {
        "active-set" => Some(Box::new(HotActiveSet::new(dims))),
        "clarabel" => Some(Box::new(ExactSolver::new())),
        #[cfg(feature = "osqp")]
        "osqp" => Some(Box::new(crate::osqp_qp::OsqpQp::new(
            dims,
            crate::osqp_qp::OsqpSettings::default(),
        ))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_builds_with_its_id_and_bad_settings_name_the_field() {
        let dims = QpDims {
            nx: 3,
            n_eq: 1,
            n_in: 1,
        };
        for info in settings::qp_solver::BUILTIN {
            match build(info.id, &QpSolverSettings::default(), dims) {
                Ok(s) => assert_eq!(s.id().as_str(), info.id),
                Err(RegistryError::NotBuilt { id, .. }) => {
                    assert_eq!((id, cfg!(feature = "osqp")), ("osqp", false));
                }
                Err(e) => panic!("{}: {e}", info.id),
            }
        }
        let e = build(
            "active-set",
            &QpSolverSettings {
                tolerance: None,
                max_iterations: Some(5),
            },
            dims,
        )
        .err()
        .unwrap();
        assert!(
            e.to_string().contains("takes no setting `max_iterations`"),
            "{e}"
        );
        let e = build("nope", &QpSolverSettings::default(), dims)
            .err()
            .unwrap();
        assert!(e.to_string().contains("known: 94lvi"), "{e}");
    }
}
