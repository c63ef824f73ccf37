//! Desired paths and the papers' redundancy-resolution schemes, each turning (t, robot state)
//! into one QP (`qp::Qp`, crate `qp`, which the solvers take). The velocity-level repetitive-motion
//! scheme is composed from the vocabulary's terms ([`velocity_rmp`]); kong2019's two schemes
//! and robio2018's RMP are presets of it. jia2019's VLTCO family and zhong2021's CMCO are the
//! two presets of the tri-criteria scheme ([`tri_criteria`]); zhang2018's acceleration-level
//! HL-JDF stays a scheme of its own ([`zhang2018`]). Every scheme takes the joint count as a
//! run-time value: joint vectors are slices, and a scheme allocates its scratch space when it is
//! built, not per QP ([`scheme`]).

#![deny(missing_docs)]

pub mod joint_limits;
pub mod paths;
pub mod rmp;
pub mod scheme;
pub mod spec;
pub mod tri_criteria;
pub mod velocity_rmp;
pub mod zhang2018;
