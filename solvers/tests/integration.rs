//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The allocation tests count
//! with the workspace's one counting allocator (crate `alloc-count`).

mod active_set;
mod active_set_alloc;
mod auxiliary;
mod conformance;
mod dense_lu;
mod exact;
mod lvi_numerical;
mod neural;
mod neural_alloc;
mod ode;
mod ode_alloc;
mod plpe_alloc;
mod schemes_robots;
