//! The n-link arm of [`crate::nlink`] with the number of joints chosen at run time: the same
//! kinematics (f, J, Jdot of that module's docs, one implementation on slices), on nalgebra's
//! dynamic-size types (`DVector`, `Matrix3xX`), for arms of hundreds of joints that no
//! const-generic instantiation `NLink<N>` (N = 3..=30) is compiled for.
//!
//! It is not a [`crate::Robot`]: that trait and the schemes written on it are const-generic in
//! N (stack-allocated vectors, no allocation per step for the papers' 5-7 joints). kong2019's
//! ZNN scheme is written on it for any N (`schemes::velocity_rmp_dyn`), which the cost harness
//! (`cost`) runs whole at N = 40 ... 200 through the same coupled ODE as every run.

use nalgebra::{DVector, Matrix3xX, Vector3};

use crate::nlink::{home_into, jacobian_dot_into, jacobian_into, link_length, position_of};

/// The n-link arm with `n` joints, n >= 3 (no upper limit).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NLinkDyn {
    n: usize,
}

impl NLinkDyn {
    /// The arm with `n` joints; `None` below [`crate::nlink::NLINK_MIN`].
    pub fn new(n: usize) -> Option<Self> {
        (n >= crate::nlink::NLINK_MIN).then_some(NLinkDyn { n })
    }

    /// The number of joints.
    pub fn joints(&self) -> usize {
        self.n
    }

    /// `nlink-<n>`.
    pub fn name(&self) -> String {
        format!("nlink-{}", self.n)
    }

    /// Length of every pitch link, `L / (n - 1)` (m).
    pub fn link_length(&self) -> f64 {
        link_length(self.n)
    }

    /// The home pose of the module docs of [`crate::nlink`].
    pub fn home(&self) -> DVector<f64> {
        let mut theta = DVector::zeros(self.n);
        home_into(theta.as_mut_slice());
        theta
    }

    /// f(theta), the tip position.
    pub fn position(&self, theta: &DVector<f64>) -> Vector3<f64> {
        self.tip(theta.as_slice())
    }

    /// f(theta) from a slice of n joint angles.
    pub fn tip(&self, theta: &[f64]) -> Vector3<f64> {
        assert_eq!(theta.len(), self.n, "nlink: theta has n entries");
        position_of(theta)
    }

    /// Writes J(theta) into `jac`, 3 x n column-major storage (length 3n), from a slice of n
    /// joint angles, without allocating.
    pub fn jacobian_to(&self, theta: &[f64], jac: &mut [f64]) {
        assert_eq!(theta.len(), self.n, "nlink: theta has n entries");
        jacobian_into(theta, jac);
    }

    /// Writes Jdot(theta, thetadot) into `jdot`, 3 x n column-major storage, without
    /// allocating.
    pub fn jacobian_dot_to(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        assert_eq!(theta.len(), self.n, "nlink: theta has n entries");
        assert_eq!(thetadot.len(), self.n, "nlink: thetadot has n entries");
        jacobian_dot_into(theta, thetadot, jdot);
    }

    /// Writes J(theta) (3 x n) into `jac` without allocating.
    pub fn jacobian_into(&self, theta: &DVector<f64>, jac: &mut Matrix3xX<f64>) {
        self.jacobian_to(theta.as_slice(), jac.as_mut_slice());
    }

    /// J(theta), 3 x n.
    pub fn jacobian(&self, theta: &DVector<f64>) -> Matrix3xX<f64> {
        let mut jac = Matrix3xX::zeros(self.n);
        self.jacobian_into(theta, &mut jac);
        jac
    }

    /// Jdot(theta, thetadot), 3 x n.
    pub fn jacobian_dot(&self, theta: &DVector<f64>, thetadot: &DVector<f64>) -> Matrix3xX<f64> {
        let mut jdot = Matrix3xX::zeros(self.n);
        self.jacobian_dot_to(theta.as_slice(), thetadot.as_slice(), jdot.as_mut_slice());
        jdot
    }
}
