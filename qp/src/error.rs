//! Why a QP's data is malformed ([`QpError`], from [`crate::Qp::validate`]). The bottom
//! layer of the data a run passes through: the solvers' errors (`ExactError`,
//! `ActiveSetError`) wrap it.

/// Which check of [`crate::Qp::validate`] failed; each variant names the field.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QpError {
    /// A matrix or vector does not have the size q, b and h imply.
    #[error("{field} is {got:?}, expected {expected:?}")]
    Shape {
        /// The field: `P`, `A`, `G`, `lower` or `upper`.
        field: &'static str,
        /// Its (rows, columns).
        got: (usize, usize),
        /// The (rows, columns) that q, b and h imply.
        expected: (usize, usize),
    },
    /// P, q, A, b or G has a NaN or infinite entry.
    #[error("{field} has a non-finite entry")]
    NonFinite {
        /// The field: `P`, `q`, `A`, `b` or `G`.
        field: &'static str,
    },
    /// One-sided data (h, upper, lower) has a NaN or an infinity on the wrong side (`wrong`).
    #[error("{field} has a NaN or {wrong} entry")]
    WrongSide {
        /// The field: `h`, `upper` or `lower`.
        field: &'static str,
        /// The infinity it must not hold: -inf for h and upper, +inf for lower.
        wrong: f64,
    },
}
