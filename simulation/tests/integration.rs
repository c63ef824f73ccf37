//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The files are unchanged
//! but for `use crate::common;` where they shared `tests/common/`.

mod any_arm;
mod checked;
mod composed_schemes;
mod examples;
mod experiment_files;
mod ftnn_jacobian;
mod fuzz_experiment_files;
mod numerical_runs;
mod power_type_network;
mod score_trajectory;
mod scoring;
mod sweep_equivalence;
