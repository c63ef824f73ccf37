//! The QP solvers' registry as data: every per-instant QP method a run or a control tick can
//! use is described by a [`QpSolverInfo`] (its id, the name tables print, and the settings it
//! takes with their ranges and defaults), and is given typed settings, [`QpSolverSettings`].
//!
//! This is the half of the registry the file layers read (an experiment file names a solver by
//! its id and gives its settings; `catalog` and the results layer check and print them without
//! linking a solver). The other half, the constructors, is crate `solvers`' `registry`: its
//! `register` adds an outside solver's [`QpSolverInfo`] here and its constructor there in one
//! call, and its `build` makes a solver from an id and settings checked by
//! [`QpSolverInfo::resolve`].
//!
//! The built-in solvers ([`BUILTIN`]), in this order:
//!
//! | id | name | settings |
//! |---|---|---|
//! | `94lvi`, `e47`, `m3`, `m4`, `m5`, `m6` | robio2018 (22)-(27) | `tolerance` on \|e(U)\|_2 in [1e-12, 1], default 1e-3 (robio2018 Algorithm 1, step 3); `max_iterations` in [1, 10^6], default 10^5 |
//! | `active-set` | the dense active set, hot-started | none |
//! | `clarabel` | Clarabel (interior point) | none |
//! | `osqp` | OSQP (ADMM; built with the `osqp` feature only) | none |
//!
//! The tolerance's range: below 1e-12 the residual |e(U)|_2 of a QP of the papers' sizes
//! (entries of order 1, at most a few hundred) is within a few hundred rounding errors of its
//! own computation and may never be reached; above 1 the "solution" is not one.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::{LazyLock, RwLock};

/// The range and default of one numeric setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits<T> {
    /// Smallest value accepted.
    pub min: T,
    /// Largest value accepted.
    pub max: T,
    /// The value when none is given.
    pub default: T,
}

/// One registered QP solver (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct QpSolverInfo {
    /// Its id in experiment files, run keys and `runs.csv` (a slug).
    pub id: &'static str,
    /// The name tables print, e.g. `94LVI`, `Clarabel` (display only).
    pub name: &'static str,
    /// Its stopping tolerance, when it takes one.
    pub tolerance: Option<Limits<f64>>,
    /// Its iteration cap per solve, when it takes one.
    pub max_iterations: Option<Limits<u32>>,
}

/// A registered solver's id: only the registry makes one ([`QpSolverInfo::key`]), so holding
/// one proves the id is registered. Compared, ordered and hashed as its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct QpSolverKey(&'static str);

impl QpSolverKey {
    /// The id.
    pub fn id(self) -> &'static str {
        self.0
    }

    /// The solver's description.
    pub fn info(self) -> &'static QpSolverInfo {
        lookup(self.0).expect("a key is made by the registry, which never forgets an entry")
    }
}

impl fmt::Display for QpSolverKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl Serialize for QpSolverKey {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

/// Read from a registered id; an unknown one is an error listing the registered ids.
impl<'de> Deserialize<'de> for QpSolverKey {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = std::borrow::Cow::<str>::deserialize(d)?;
        lookup(&text)
            .map(QpSolverInfo::key)
            .map_err(serde::de::Error::custom)
    }
}

/// A solver's settings as given (an experiment file's `tolerance`, `max_iterations`); `None`
/// where not given. After [`QpSolverInfo::resolve`] a field is `Some` exactly when the solver
/// takes that setting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QpSolverSettings {
    /// Stopping tolerance of one solve (the PLPE methods: on |e(U)|_2).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Iterations after which one solve fails.
    #[serde(default)]
    pub max_iterations: Option<u32>,
}

/// Why an id or settings do not fit the registry.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QpSolverError {
    /// No solver is registered under the id.
    #[error("unknown QP solver {} (known: {known})", crate::shown(given))]
    Unknown {
        /// The id given.
        given: String,
        /// The registered ids, comma-separated.
        known: String,
    },
    /// A setting the solver does not take.
    #[error("QP solver {id} takes no setting `{field}` (its settings: {takes})")]
    NotTaken {
        /// The solver's id.
        id: &'static str,
        /// The field given.
        field: &'static str,
        /// The settings it takes, comma-separated, or `none`.
        takes: String,
    },
    /// A setting outside its range.
    #[error("QP solver {id}: {field} = {value} must be within [{min}, {max}]")]
    OutOfRange {
        /// The solver's id.
        id: &'static str,
        /// The field.
        field: &'static str,
        /// The value given.
        value: String,
        /// The smallest accepted.
        min: String,
        /// The largest accepted.
        max: String,
    },
    /// An id that is not a slug, or is taken (by a solver, a network kind or a solver kind of
    /// `runs.csv` that is not a QP solver: `exact`, `trajectory`, `python`).
    #[error("cannot register QP solver {}: {reason}", crate::shown(id))]
    Register {
        /// The id offered.
        id: String,
        /// Why not.
        reason: &'static str,
    },
}

/// The `solver_kind` ids of `runs.csv` that are not QP solvers (besides the network kinds).
pub const RESERVED_IDS: [&str; 3] = ["exact", "trajectory", "python"];

/// The PLPE methods' tolerance (module docs).
const PLPE_TOLERANCE: Limits<f64> = Limits {
    min: 1e-12,
    max: 1.0,
    default: 1e-3,
};
/// The PLPE methods' iteration cap (module docs).
const PLPE_MAX_ITERATIONS: Limits<u32> = Limits {
    min: 1,
    max: 1_000_000,
    default: 100_000,
};

/// A PLPE method of robio2018.
const fn plpe(id: &'static str, name: &'static str) -> QpSolverInfo {
    QpSolverInfo {
        id,
        name,
        tolerance: Some(PLPE_TOLERANCE),
        max_iterations: Some(PLPE_MAX_ITERATIONS),
    }
}

/// A solver that takes no setting.
const fn plain(id: &'static str, name: &'static str) -> QpSolverInfo {
    QpSolverInfo {
        id,
        name,
        tolerance: None,
        max_iterations: None,
    }
}

/// The built-in solvers (module docs' table), in that order.
pub const BUILTIN: [QpSolverInfo; 9] = [
    plpe("94lvi", "94LVI"),
    plpe("e47", "E47"),
    plpe("m3", "M3"),
    plpe("m4", "M4"),
    plpe("m5", "M5"),
    plpe("m6", "M6"),
    plain("active-set", "active set"),
    plain("clarabel", "Clarabel"),
    plain("osqp", "OSQP"),
];

/// The ids of robio2018's six PLPE methods, in its order (22)-(27).
pub const PLPE_IDS: [&str; 6] = ["94lvi", "e47", "m3", "m4", "m5", "m6"];

/// Every registered solver, built-in first, then in order of registration. An entry is
/// leaked once at registration (a program registers a handful), so keys are `'static`.
static REGISTRY: LazyLock<RwLock<Vec<&'static QpSolverInfo>>> =
    LazyLock::new(|| RwLock::new(BUILTIN.iter().collect()));

fn read() -> std::sync::RwLockReadGuard<'static, Vec<&'static QpSolverInfo>> {
    REGISTRY.read().unwrap_or_else(|e| e.into_inner())
}

/// The solver registered as `id`.
pub fn lookup(id: &str) -> Result<&'static QpSolverInfo, QpSolverError> {
    let all = read();
    all.iter()
        .copied()
        .find(|i| i.id == id)
        .ok_or_else(|| QpSolverError::Unknown {
            given: id.to_string(),
            known: all.iter().map(|i| i.id).collect::<Vec<_>>().join(", "),
        })
}

/// Every registered solver (module docs' order).
pub fn all() -> Vec<&'static QpSolverInfo> {
    read().clone()
}

/// Adds `info` to the registry, refusing an id that is not a slug of at most 64 characters
/// or is taken (a solver's, a network kind's or one of [`RESERVED_IDS`]). Crate `solvers`'
/// `registry::register` calls this with the solver's constructor; calling it alone makes a
/// solver that files may name but no run can build.
pub fn register(info: QpSolverInfo) -> Result<&'static QpSolverInfo, QpSolverError> {
    let refuse = |reason| QpSolverError::Register {
        id: info.id.to_string(),
        reason,
    };
    if !(crate::slug::is_slug(info.id) && info.id.len() <= 64 && !info.id.contains('.')) {
        return Err(refuse(
            "an id is a slug of at most 64 characters (lower-case letters, digits, `-`)",
        ));
    }
    let network = crate::network_kind::NetworkKind::ALL
        .iter()
        .any(|k| k.id() == info.id);
    if network || RESERVED_IDS.contains(&info.id) {
        return Err(refuse(
            "the id is a network kind's or a solver kind's of runs.csv",
        ));
    }
    let mut all = REGISTRY.write().unwrap_or_else(|e| e.into_inner());
    if all.iter().any(|i| i.id == info.id) {
        return Err(refuse("a solver is registered under this id"));
    }
    let leaked: &'static QpSolverInfo = Box::leak(Box::new(info));
    all.push(leaked);
    Ok(leaked)
}

impl QpSolverInfo {
    /// Its key ([`QpSolverKey`]).
    pub fn key(&'static self) -> QpSolverKey {
        QpSolverKey(self.id)
    }

    /// The settings it takes, comma-separated, or `none`.
    fn takes(&self) -> String {
        let names: Vec<&str> = [
            self.tolerance.map(|_| "tolerance"),
            self.max_iterations.map(|_| "max_iterations"),
        ]
        .into_iter()
        .flatten()
        .collect();
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    }

    /// The settings `given`, checked and completed: a setting the solver does not take is an
    /// error, one it takes is within its range (a NaN is not), and one not given takes its
    /// default. The result's field is `Some` exactly when the solver takes it.
    pub fn resolve(&self, given: &QpSolverSettings) -> Result<QpSolverSettings, QpSolverError> {
        let not_taken = |field| QpSolverError::NotTaken {
            id: self.id,
            field,
            takes: self.takes(),
        };
        let tolerance = match (self.tolerance, given.tolerance) {
            (None, Some(_)) => return Err(not_taken("tolerance")),
            (None, None) => None,
            (Some(l), value) => {
                let v = value.unwrap_or(l.default);
                if !(l.min..=l.max).contains(&v) {
                    return Err(QpSolverError::OutOfRange {
                        id: self.id,
                        field: "tolerance",
                        value: format!("{v:e}"),
                        min: format!("{:e}", l.min),
                        max: format!("{:e}", l.max),
                    });
                }
                Some(v)
            }
        };
        let max_iterations = match (self.max_iterations, given.max_iterations) {
            (None, Some(_)) => return Err(not_taken("max_iterations")),
            (None, None) => None,
            (Some(l), value) => {
                let v = value.unwrap_or(l.default);
                if !(l.min..=l.max).contains(&v) {
                    return Err(QpSolverError::OutOfRange {
                        id: self.id,
                        field: "max_iterations",
                        value: v.to_string(),
                        min: l.min.to_string(),
                        max: l.max.to_string(),
                    });
                }
                Some(v)
            }
        };
        Ok(QpSolverSettings {
            tolerance,
            max_iterations,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_resolve_with_their_ranges_and_defaults() {
        let m4 = lookup("m4").unwrap();
        let d = m4.resolve(&QpSolverSettings::default()).unwrap();
        assert_eq!(d.tolerance, Some(1e-3));
        assert_eq!(d.max_iterations, Some(100_000));
        for bad in [f64::NAN, 0.0, 1e-15, 2.0] {
            let e = m4
                .resolve(&QpSolverSettings {
                    tolerance: Some(bad),
                    max_iterations: None,
                })
                .unwrap_err();
            assert!(e.to_string().contains("must be within [1e-12, 1e0]"), "{e}");
        }
        let e = m4
            .resolve(&QpSolverSettings {
                tolerance: None,
                max_iterations: Some(4_000_000_000),
            })
            .unwrap_err();
        assert!(
            e.to_string()
                .contains("max_iterations = 4000000000 must be within [1, 1000000]"),
            "{e}"
        );
        let clarabel = lookup("clarabel").unwrap();
        let e = clarabel
            .resolve(&QpSolverSettings {
                tolerance: Some(1e-6),
                max_iterations: None,
            })
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "QP solver clarabel takes no setting `tolerance` (its settings: none)"
        );
        let e = lookup("m7").unwrap_err();
        assert!(e.to_string().contains("known: 94lvi, e47, m3"), "{e}");
    }

    #[test]
    fn registration_refuses_taken_and_malformed_ids() {
        for id in ["m4", "lvi-pdnn", "exact", "Bad Id", "", "a.b"] {
            assert!(register(plain(id, "x")).is_err(), "{id}");
        }
        let info = register(plain("settings-test-solver", "Test")).unwrap();
        assert_eq!(lookup("settings-test-solver").unwrap(), info);
        assert_eq!(info.key().info(), info);
        assert!(register(plain("settings-test-solver", "Again")).is_err());
    }
}
