//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The files are unchanged
//! but for `use crate::common;` where they shared `tests/common/`.

mod common;

mod any_arm;
mod cli;
mod composed_schemes;
mod cost_paths;
mod exit_codes;
mod experiment_files;
mod fifth_paper;
mod fuzz_experiment_files;
mod gate_explanation;
mod hostile;
mod hostile_inputs;
mod hostile_text;
mod kubernetes;
mod layering;
mod octave;
mod paper_literals;
mod presentation_renders;
mod public_modules;
mod regression;
mod robot_files;
mod run_ids;
mod score;
mod self_contained;
mod shards;
mod slurm;
mod sweep_plan;
mod task_cards;
mod test_targets;
mod typed_errors;
mod typed_identity;
