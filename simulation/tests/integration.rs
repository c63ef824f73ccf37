//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The files are unchanged
//! but for `use crate::common;` where they shared `tests/common/`.

mod examples;
mod ftnn_jacobian;
mod numerical_runs;
mod power_type_network;
mod score_trajectory;
mod scoring;
mod sweep_equivalence;
