//! A scheme of any joint count, seen through slices: what the coupled arm + solver ODE
//! (`simulation::coupled`) needs of a scheme, with the joint count a run-time value.
//!
//! [`Scheme<N>`] is const-generic (stack vectors, no allocation per step at the papers' 5-7
//! joints), so code written against it is compiled once per N. [`SliceScheme`] is the same
//! interface with theta, thetadot and thetaddot as slices of length [`SliceScheme::joints`]:
//!
//! ```text
//! build(t, theta, thetadot)            -> QP(t, theta, thetadot)
//! build_dot(t, theta, thetadot, thetaddot) -> dQP/dt along the motion (crate::scheme docs)
//! ```
//!
//! Every [`Scheme<N>`] is one through [`Fixed`] (the slices copied into stack vectors, the
//! scheme's own code unchanged, so results are bit for bit those of the const-generic call);
//! a scheme written for arms of hundreds of joints implements it directly
//! ([`crate::velocity_rmp_dyn::NLinkZnn`]).

use crate::qp::{Qp, QpDims};
use crate::qp_dot::QpDotScratch;
use crate::scheme::{Level, Scheme};
use nalgebra::SVector;

/// A redundancy-resolution scheme QP(t, theta, thetadot) with the joint count a run-time value.
pub trait SliceScheme: Send + Sync {
    /// Name as the paper writes it.
    fn name(&self) -> String;
    /// Whether x[..n] is thetadot (velocity level) or thetaddot (acceleration level).
    fn level(&self) -> Level;
    /// QP sizes (constant along a run).
    fn dims(&self) -> QpDims;
    /// The number of joints n: the length of every slice below.
    fn joints(&self) -> usize;
    /// Overwrites `qp` with the QP at (t, theta, thetadot), as [`Scheme::build`]. Must not
    /// allocate.
    fn build(&self, t: f64, theta: &[f64], thetadot: &[f64], qp: &mut Qp);
    /// Overwrites `qp_dot` with dQP/dt along the motion, as [`Scheme::build_dot`]. Must not
    /// allocate.
    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        thetaddot: &[f64],
        qp_dot: &mut Qp,
        scratch: &mut QpDotScratch,
    );
    /// A zero QP of this scheme's sizes.
    fn new_qp(&self) -> Qp {
        Qp::zeros(self.dims())
    }
    /// Scratch space for [`SliceScheme::build_dot`].
    fn new_dot_scratch(&self) -> QpDotScratch {
        QpDotScratch::new(self.dims())
    }
}

/// A const-generic [`Scheme<N>`] as a [`SliceScheme`] (`joints() = N`).
#[derive(Clone, Copy)]
pub struct Fixed<'a, const N: usize>(pub &'a dyn Scheme<N>);

impl<const N: usize> SliceScheme for Fixed<'_, N> {
    fn name(&self) -> String {
        self.0.name()
    }

    fn level(&self) -> Level {
        self.0.level()
    }

    fn dims(&self) -> QpDims {
        self.0.dims()
    }

    fn joints(&self) -> usize {
        N
    }

    fn build(&self, t: f64, theta: &[f64], thetadot: &[f64], qp: &mut Qp) {
        self.0.build(
            t,
            &SVector::from_column_slice(theta),
            &SVector::from_column_slice(thetadot),
            qp,
        );
    }

    fn build_dot(
        &self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
        thetaddot: &[f64],
        qp_dot: &mut Qp,
        scratch: &mut QpDotScratch,
    ) {
        self.0.build_dot(
            t,
            &SVector::from_column_slice(theta),
            &SVector::from_column_slice(thetadot),
            &SVector::from_column_slice(thetaddot),
            qp_dot,
            scratch,
        );
    }

    fn new_qp(&self) -> Qp {
        self.0.new_qp()
    }

    fn new_dot_scratch(&self) -> QpDotScratch {
        self.0.new_dot_scratch()
    }
}
