//! Every integration test of this crate, one module per file of `tests/`, in one test
//! binary: one build and link instead of one per file (issue 29). The files are unchanged
//! but for `use crate::common;` where they shared `tests/common/`.

mod common;

mod build_script;

mod chain;
mod chain_robot;
mod data_robots;
mod fuzz_robot_file;
mod jaco2_dynamics;
mod jaco2_kinematics;
mod katana;
mod nlink;
mod nlink_dyn;
mod orientation;
mod panda;
mod pinocchio;
mod position_jacobian;
mod robot_file;
mod skeleton;
mod urdf;
