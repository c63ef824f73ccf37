//! Why a QP's data is malformed ([`QpError`], from [`crate::qp::Qp::validate`]). The bottom
//! layer of the data a run passes through: the solvers' errors (`ExactError`,
//! `ActiveSetError`) wrap it. The schemes' own errors are [`crate::spec::SchemeError`] and
//! [`crate::paths::PathError`].

/// Which check of [`crate::qp::Qp::validate`] failed; each variant names the field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QpError {
    /// A matrix or vector does not have the size q, b and h imply.
    #[error("{field} is {got:?}, expected {expected:?}")]
    Shape {
        field: &'static str,
        got: (usize, usize),
        expected: (usize, usize),
    },
    /// P, q, A, b or G has a NaN or infinite entry.
    #[error("{field} has a non-finite entry")]
    NonFinite { field: &'static str },
    /// One-sided data (h, upper, lower) has a NaN or an infinity on the wrong side (`wrong`).
    #[error("{field} has a NaN or {wrong} entry")]
    WrongSide { field: &'static str, wrong: f64 },
}
