//! The experiment file's fields that its errors name: the part of a run's specification that
//! could not be built ([`JobPart`], with the field it comes from) and the fields of a variant a
//! sweep may set (`VARIANT_FIELDS`). Below the format ([`crate::experiment`],
//! [`crate::sweep`]) and its errors ([`crate::error`]) alike, which all name them.

/// Which part of a run ([`crate::experiment::Job`]) could not be built (see
/// [`crate::experiment::CheckJob`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JobPart {
    /// The robot (`robot`).
    Robot,
    /// The initial joint vector (`theta0`).
    Theta0,
    /// The scheme's joint reference (`theta_ref`).
    ThetaRef,
    /// The path (`path`).
    Path,
    /// The scheme (`scheme`).
    Scheme,
    /// The network or numerical method (`solvers`, `numerical`).
    Solver,
    /// The `joint_limits` / `velocity_limits` override.
    Limits,
    /// The tool offset (`tool`).
    Tool,
    /// The base transform (`base`).
    Base,
}

impl JobPart {
    /// The experiment-file field the part comes from.
    pub fn field(&self) -> &'static str {
        match self {
            JobPart::Robot => "robot",
            JobPart::Theta0 => "theta0",
            JobPart::ThetaRef => "theta_ref",
            JobPart::Path => "path",
            JobPart::Scheme => "scheme",
            JobPart::Solver => "solvers",
            JobPart::Limits => "joint_limits",
            JobPart::Tool => "tool",
            JobPart::Base => "base",
        }
    }
}

/// The fields of a variant a sweep may set (`label` is the template, not a parameter).
pub(crate) const VARIANT_FIELDS: &[&str] = &[
    "scheme",
    "solvers",
    "exact",
    "robot",
    "tool",
    "base",
    "path",
    "theta0",
    "theta_ref",
    "integrator",
    "network_init",
    "expected_failure",
    "explain",
];
