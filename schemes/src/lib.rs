//! Desired paths and the papers' redundancy-resolution schemes, each turning (t, robot state)
//! into one QP (`qp::Qp`, crate `qp`, which the solvers take). A scheme is a list of terms
//! ([`terms`]: objective terms, equality rows, inequality rows, bounds) composed into the one
//! scheme type ([`composed`]); the papers' schemes (jia2019's VLTCO family, zhong2021's CMCO,
//! zhang2018's HL-JDF, kong2019's two, robio2018's RMP) are presets that expand to term lists
//! (their specifications are data, crate `spec`; [`build`] makes the scheme of one). Every scheme takes the joint count as a run-time value: joint vectors are slices,
//! and a scheme allocates its scratch space when it is built, not per QP ([`scheme`]).

#![deny(missing_docs)]

pub mod build;
pub mod composed;
pub mod joint_limits;
pub mod paths;
pub mod scheme;
pub mod terms;
