//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The files are unchanged
//! but for `use crate::common;` where they shared `tests/common/`.

mod files;
mod fuzz_results;
