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

//! Every matrix is 3 x n, column-major, written into the caller's slice of length `3 n`;
//! columns past `link` are zero.

use nalgebra::Vector3;

use crate::dh::ChainFrames;

/// Writes column `j` of a 3 x n column-major matrix.
fn set_column(out: &mut [f64], j: usize, col: &Vector3<f64>) {
    out[3 * j..3 * j + 3].copy_from_slice(col.as_slice());
}

impl ChainFrames<'_> {
    /// Writes the linear-velocity Jacobian (3 x n) of the world point `p` rigidly attached to
    /// link `link` (`1..=n`; frame `link` moves with it) into `jac`.
    pub fn point_jacobian(&self, link: usize, p: &Vector3<f64>, jac: &mut [f64]) {
        assert_eq!(jac.len(), 3 * self.dof(), "J is 3 x n");
        jac.fill(0.0);
        for j in 0..link {
            set_column(jac, j, &self.z(j).cross(&(p - self.origin(j))));
        }
    }

    /// Writes the time derivative of [`ChainFrames::point_jacobian`] along the joint
    /// velocities `thetadot` into `jdot`.
    pub fn point_jacobian_dot(
        &self,
        link: usize,
        p: &Vector3<f64>,
        thetadot: &[f64],
        jdot: &mut [f64],
    ) {
        assert_eq!(jdot.len(), 3 * self.dof(), "Jdot is 3 x n");
        // pdot = J thetadot, column by column in joint order.
        let mut pdot = Vector3::zeros();
        for (j, v) in thetadot.iter().enumerate().take(link) {
            pdot += self.z(j).cross(&(p - self.origin(j))) * *v;
        }
        jdot.fill(0.0);
        let mut omega = Vector3::zeros();
        let mut v_origin = Vector3::zeros();
        for (j, &v) in thetadot.iter().enumerate().take(link) {
            let z = self.z(j);
            let zdot = omega.cross(&z);
            let col = zdot.cross(&(p - self.origin(j))) + z.cross(&(pdot - v_origin));
            set_column(jdot, j, &col);
            omega += z * v;
            v_origin += omega.cross(&(self.origin(j + 1) - self.origin(j)));
        }
    }

    /// Writes the angular-velocity Jacobian (3 x n) of link `link` (`1..=n`) into `jac`.
    pub fn angular_jacobian(&self, link: usize, jac: &mut [f64]) {
        assert_eq!(jac.len(), 3 * self.dof(), "J is 3 x n");
        jac.fill(0.0);
        for j in 0..link {
            set_column(jac, j, &self.z(j));
        }
    }

    /// Writes the time derivative of [`ChainFrames::angular_jacobian`] along `thetadot` into
    /// `jdot`.
    pub fn angular_jacobian_dot(&self, link: usize, thetadot: &[f64], jdot: &mut [f64]) {
        assert_eq!(jdot.len(), 3 * self.dof(), "Jdot is 3 x n");
        jdot.fill(0.0);
        let mut omega = Vector3::zeros();
        for (j, &v) in thetadot.iter().enumerate().take(link) {
            let z = self.z(j);
            set_column(jdot, j, &omega.cross(&z));
            omega += z * v;
        }
    }
}
