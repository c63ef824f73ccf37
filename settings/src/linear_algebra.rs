//! The dense linear algebra setting the solvers and the report share: the system size from which
//! a dense, unstructured LU factorisation runs on faer instead of nalgebra (`solvers::dense_lu`,
//! whose module docs give the measurement it comes from). It lives here, below both the solvers
//! and the results layer, so that the report can state it without linking the solvers.

/// The system size n (rows of the square matrix) from which `solvers::dense_lu` factorises on
/// faer: measured by the cost harness (`results/dof-cost.csv`, the network Jacobian's LU), not
/// tuned by hand.
pub const FAER_CROSSOVER: usize = 64;
