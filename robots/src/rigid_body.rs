//! Rigid-body dynamics of a revolute DH chain: `H(theta) thetaddot + c(theta, thetadot) + g(theta) = tau`.
//!
//! Link `i` (1-based) has mass `m_i`, centre of mass `c_i` and inertia `I_i` about the centre of
//! mass, both expressed in DH frame `i`. In world coordinates (rotation `R_i` of frame `i`):
//! `p_ci = o_i + R_i c_i` and `I_i^w = R_i I_i R_i^T`. Let `Jv_i` be the linear Jacobian of
//! `p_ci` and `Jw_i` the angular Jacobian of link `i` (see [`crate::geometric_jacobian`]),
//! `omega_i = Jw_i thetadot`, and `g0` the gravity acceleration (world frame).
//!
//! - **Inverse dynamics** ([`RigidChain::inverse_dynamics`]) by the recursive Newton–Euler
//!   algorithm in world coordinates. Forward pass (joint `i` about `z_{i-1}`):
//!   `omega_i = omega_{i-1} + z_{i-1} qd_i`,
//!   `alpha_i = alpha_{i-1} + z_{i-1} qdd_i + qd_i omega_{i-1} x z_{i-1}`,
//!   `a_i = a_{i-1} + alpha_i x (o_i - o_{i-1}) + omega_i x (omega_i x (o_i - o_{i-1}))` with
//!   `a_0 = -g0` (gravity as a fictitious base acceleration), and the link's net force and moment
//!   `F_i = m_i a_ci`, `N_i = I_i^w alpha_i + omega_i x I_i^w omega_i`. Backward pass, moments
//!   about `o_{i-1}`: `f_i = f_{i+1} + F_i`,
//!   `n_i = n_{i+1} + (o_i - o_{i-1}) x f_{i+1} + N_i + (p_ci - o_{i-1}) x F_i`, `tau_i = z_{i-1} . n_i`.
//!   `c(theta, thetadot)` is RNEA with `qdd = 0` and no gravity; `g(theta)` is RNEA with
//!   `qd = qdd = 0` and gravity, i.e. `g = dU/dtheta` with `U = -sum_i m_i g0 . p_ci`.
//! - **Inertia matrix** ([`RigidChain::inertia`]) from the kinetic energy
//!   `T = 1/2 sum_i (m_i |v_ci|^2 + omega_i' I_i^w omega_i)`:
//!   `H = sum_i (m_i Jv_i' Jv_i + Jw_i' I_i^w Jw_i)` (analytic, independent of the RNEA).
//! - **Coriolis matrix** ([`RigidChain::coriolis_matrix`]), analytic and Christoffel-consistent:
//!   `C = sum_i (m_i Jv_i' Jvdot_i + Jw_i' I_i^w Jwdot_i + Jw_i' B_i Jw_i)` with
//!   `B_i = 1/2 ([omega_i]x I_i^w - I_i^w [omega_i]x - [I_i^w omega_i]x)`.
//!   `B_i omega_i = omega_i x I_i^w omega_i` gives `C thetadot = c`, and
//!   `B_i + B_i' = d/dt I_i^w` makes `Hdot - 2C` skew-symmetric. The translational term is exactly
//!   the Christoffel sum `C_jk = sum_l Gamma_jkl thetadot_l`,
//!   `Gamma_jkl = 1/2 (dH_jk/dtheta_l + dH_jl/dtheta_k - dH_kl/dtheta_j)`; the rotational term
//!   is the body-level Christoffel-consistent factorisation of Echeandía & Wensing (2021)
//!   (the tests check it against the Christoffel symbols of finite-difference `dH/dtheta`).
//!
//! Everything uses stack arrays: no call allocates.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::dh::{ChainFrames, DhChain};

/// Inertial parameters of one link, expressed in its DH frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidBody {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the link's DH frame (m).
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass, in the link's DH axes (kg m^2).
    pub inertia: Matrix3<f64>,
}

/// A revolute DH chain with inertial parameters and a gravity vector.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidChain<const N: usize> {
    /// Kinematic chain; its base frame is the frame in which `gravity` is given.
    pub chain: DhChain,
    /// Inertial parameters of links 1..=N.
    pub bodies: [RigidBody; N],
    /// Gravity acceleration in world coordinates (m/s^2).
    pub gravity: Vector3<f64>,
}

/// World-frame centre of mass and inertia tensor of every link at one configuration.
struct LinkMasses<const N: usize> {
    com: [Vector3<f64>; N],
    inertia: [Matrix3<f64>; N],
}

impl<const N: usize> RigidChain<N> {
    fn link_masses(&self, frames: &ChainFrames<'_>) -> LinkMasses<N> {
        let mut com = [Vector3::zeros(); N];
        let mut inertia = [Matrix3::zeros(); N];
        for (i, body) in self.bodies.iter().enumerate() {
            let f = frames.frame(i + 1);
            com[i] = f.transform_point(&body.com);
            inertia[i] = f.rot * body.inertia * f.rot.transpose();
        }
        LinkMasses { com, inertia }
    }

    /// Recursive Newton–Euler with base acceleration `a0` (`-gravity` to include gravity).
    fn rnea(
        &self,
        frames: &ChainFrames<'_>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
        a0: Vector3<f64>,
    ) -> SVector<f64, N> {
        let masses = self.link_masses(frames);
        let mut force = [Vector3::zeros(); N];
        let mut moment = [Vector3::zeros(); N];
        let mut omega = Vector3::<f64>::zeros();
        let mut alpha = Vector3::<f64>::zeros();
        let mut acc = a0;
        for i in 0..N {
            let z = frames.z(i);
            alpha += z * qdd[i] + omega.cross(&z) * qd[i];
            omega += z * qd[i];
            let r = frames.origin(i + 1) - frames.origin(i);
            acc += alpha.cross(&r) + omega.cross(&omega.cross(&r));
            let rc = masses.com[i] - frames.origin(i + 1);
            let acc_c = acc + alpha.cross(&rc) + omega.cross(&omega.cross(&rc));
            let iw = &masses.inertia[i];
            force[i] = acc_c * self.bodies[i].mass;
            moment[i] = iw * alpha + omega.cross(&(iw * omega));
        }
        let mut tau = SVector::<f64, N>::zeros();
        let mut f = Vector3::<f64>::zeros();
        let mut n = Vector3::<f64>::zeros();
        for i in (0..N).rev() {
            let o = frames.origin(i);
            n += (frames.origin(i + 1) - o).cross(&f)
                + moment[i]
                + (masses.com[i] - o).cross(&force[i]);
            f += force[i];
            tau[i] = frames.z(i).dot(&n);
        }
        tau
    }

    /// Joint torques `tau = H qdd + c + g` by the recursive Newton–Euler algorithm.
    pub fn inverse_dynamics(
        &self,
        theta: &SVector<f64, N>,
        qd: &SVector<f64, N>,
        qdd: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        self.chain.with_frames(
            |i| theta[i],
            |frames| self.rnea(frames, qd, qdd, -self.gravity),
        )
    }

    /// Joint-space inertia matrix `H = sum_i (m_i Jv_i' Jv_i + Jw_i' I_i^w Jw_i)`.
    pub fn inertia(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        self.chain
            .with_frames(|i| theta[i], |frames| self.inertia_at(frames))
    }

    fn inertia_at(&self, frames: &ChainFrames<'_>) -> SMatrix<f64, N, N> {
        let masses = self.link_masses(frames);
        let mut h = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            let jv = point_jacobian::<N>(frames, i + 1, &masses.com[i]);
            let jw = angular_jacobian::<N>(frames, i + 1);
            h +=
                jv.transpose() * jv * self.bodies[i].mass + jw.transpose() * masses.inertia[i] * jw;
        }
        h
    }

    /// Coriolis and centrifugal torques `c(theta, thetadot)` (RNEA, `qdd = 0`, no gravity).
    pub fn coriolis(&self, theta: &SVector<f64, N>, thetadot: &SVector<f64, N>) -> SVector<f64, N> {
        self.chain.with_frames(
            |i| theta[i],
            |frames| self.rnea(frames, thetadot, &SVector::zeros(), Vector3::zeros()),
        )
    }

    /// Christoffel-consistent Coriolis matrix (see the module documentation).
    pub fn coriolis_matrix(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N> {
        self.chain.with_frames(
            |i| theta[i],
            |frames| self.coriolis_matrix_at(frames, thetadot),
        )
    }

    fn coriolis_matrix_at(
        &self,
        frames: &ChainFrames<'_>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N> {
        let masses = self.link_masses(frames);
        let mut c = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            let link = i + 1;
            let iw = &masses.inertia[i];
            let jv = point_jacobian::<N>(frames, link, &masses.com[i]);
            let mut jv_dot = SMatrix::<f64, 3, N>::zeros();
            frames.point_jacobian_dot(
                link,
                &masses.com[i],
                thetadot.as_slice(),
                jv_dot.as_mut_slice(),
            );
            let jw = angular_jacobian::<N>(frames, link);
            let mut jw_dot = SMatrix::<f64, 3, N>::zeros();
            frames.angular_jacobian_dot(link, thetadot.as_slice(), jw_dot.as_mut_slice());
            let omega = jw * thetadot;
            let w = omega.cross_matrix();
            let b = (w * iw - iw * w - (iw * omega).cross_matrix()) * 0.5;
            c += jv.transpose() * jv_dot * self.bodies[i].mass
                + jw.transpose() * (iw * jw_dot + b * jw);
        }
        c
    }

    /// Gravity torques `g(theta) = dU/dtheta` (RNEA with `qd = qdd = 0`).
    pub fn gravity_torques(&self, theta: &SVector<f64, N>) -> SVector<f64, N> {
        self.chain.with_frames(
            |i| theta[i],
            |frames| self.rnea(frames, &SVector::zeros(), &SVector::zeros(), -self.gravity),
        )
    }
}

/// [`ChainFrames::point_jacobian`] as a 3 x N matrix.
fn point_jacobian<const N: usize>(
    frames: &ChainFrames<'_>,
    link: usize,
    p: &Vector3<f64>,
) -> SMatrix<f64, 3, N> {
    let mut jac = SMatrix::<f64, 3, N>::zeros();
    frames.point_jacobian(link, p, jac.as_mut_slice());
    jac
}

/// [`ChainFrames::angular_jacobian`] as a 3 x N matrix.
fn angular_jacobian<const N: usize>(frames: &ChainFrames<'_>, link: usize) -> SMatrix<f64, 3, N> {
    let mut jac = SMatrix::<f64, 3, N>::zeros();
    frames.angular_jacobian(link, jac.as_mut_slice());
    jac
}
