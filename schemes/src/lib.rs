//! Desired paths and the four papers' redundancy-resolution schemes, each turning
//! (t, robot state) into one QP.

pub mod paths;
