//! Geometric Jacobians of points and bodies of a revolute DH chain, and their time derivatives.
//!
//! Joint `j` (1-based) rotates about the unit axis `z_{j-1}` through `o_{j-1}` (world frame).
//! For a point `p` rigidly attached to link `l`, the linear-velocity Jacobian has columns
//!
//! ```text
//! J_j = z_{j-1} x (p - o_{j-1})   for j <= l,     J_j = 0 otherwise,
//! ```
//!
//! and the angular-velocity Jacobian of link `l` has columns `z_{j-1}` (j <= l), 0 otherwise.
//!
//! Time derivatives along `thetadot` follow from the rigid-body velocities of the frames.
//! With `omega_k = sum_{j <= k} thetadot_j z_{j-1}` the angular velocity of frame `k`,
//! `v_k` the velocity of its origin (`v_0 = 0`, `v_k = v_{k-1} + omega_k x (o_k - o_{k-1})`) and
//! `pdot = J thetadot`:
//!
//! ```text
//! d/dt z_{j-1}      = omega_{j-1} x z_{j-1}
//! d/dt J_j          = (omega_{j-1} x z_{j-1}) x (p - o_{j-1}) + z_{j-1} x (pdot - v_{j-1})
//! d/dt (angular)_j  = omega_{j-1} x z_{j-1}.
//! ```
//!
//! The base is fixed in the world (`omega_0 = 0`, `v_0 = 0`).

use nalgebra::{SMatrix, SVector, Vector3};

use crate::dh::ChainFrames;

impl<const N: usize> ChainFrames<N> {
    /// Linear-velocity Jacobian (3 x N) of the world point `p` rigidly attached to link `link`
    /// (`1..=N`; frame `link` moves with it).
    pub fn point_jacobian(&self, link: usize, p: &Vector3<f64>) -> SMatrix<f64, 3, N> {
        let mut jac = SMatrix::<f64, 3, N>::zeros();
        for j in 0..link {
            jac.set_column(j, &self.z(j).cross(&(p - self.origin(j))));
        }
        jac
    }

    /// Time derivative of [`ChainFrames::point_jacobian`] along the joint velocities `thetadot`.
    pub fn point_jacobian_dot(
        &self,
        link: usize,
        p: &Vector3<f64>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N> {
        let pdot = self.point_jacobian(link, p) * thetadot;
        let mut jdot = SMatrix::<f64, 3, N>::zeros();
        let mut omega = Vector3::zeros();
        let mut v_origin = Vector3::zeros();
        for j in 0..link {
            let z = self.z(j);
            let zdot = omega.cross(&z);
            let col = zdot.cross(&(p - self.origin(j))) + z.cross(&(pdot - v_origin));
            jdot.set_column(j, &col);
            omega += z * thetadot[j];
            v_origin += omega.cross(&(self.origin(j + 1) - self.origin(j)));
        }
        jdot
    }

    /// Angular-velocity Jacobian (3 x N) of link `link` (`1..=N`).
    pub fn angular_jacobian(&self, link: usize) -> SMatrix<f64, 3, N> {
        let mut jac = SMatrix::<f64, 3, N>::zeros();
        for j in 0..link {
            jac.set_column(j, &self.z(j));
        }
        jac
    }

    /// Time derivative of [`ChainFrames::angular_jacobian`] along `thetadot`.
    pub fn angular_jacobian_dot(
        &self,
        link: usize,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N> {
        let mut jdot = SMatrix::<f64, 3, N>::zeros();
        let mut omega = Vector3::zeros();
        for j in 0..link {
            let z = self.z(j);
            jdot.set_column(j, &omega.cross(&z));
            omega += z * thetadot[j];
        }
        jdot
    }
}
