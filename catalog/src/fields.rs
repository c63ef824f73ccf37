//! The fields of a variant a sweep may set (`VARIANT_FIELDS`), which the sweep grammar
//! ([`crate::sweep`]) and its errors ([`crate::error`]) name. (The part of a run that could not
//! be built, with the field it comes from, is `spec::JobPart`.)

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
