//! [`ChainRobot`]: a [`Chain`] (e.g. a URDF arm, [`crate::urdf`]) as a [`Robot`] whose task point
//! is the chain's tool point, and as a [`Dynamics`] model.
//!
//! # Mathematics
//!
//! Position, position Jacobian and its time derivative are the first three rows of the chain's
//! tool point, geometric Jacobian and `dJ/dt` ([`crate::chain`]). H, c and g are the chain's
//! composite-rigid-body inertia and Newton–Euler torques.
//!
//! The Coriolis matrix is the Christoffel one, `C_ij = sum_k Gamma_ijk thetadot_k` with
//! `Gamma_ijk = (dH_ij/dq_k + dH_ik/dq_j - dH_jk/dq_i) / 2`, for which `c = C thetadot` and
//! `Hdot - 2C` is skew-symmetric. `Gamma_i(u, v) = sum_jk Gamma_ijk u_j v_k` is a symmetric
//! bilinear form in the velocities and `c(q, thetadot) = Gamma(thetadot, thetadot)` its
//! quadratic form (the Newton–Euler `c` is exactly quadratic in `thetadot`). Polarisation gives
//! column `j` of `C`, `C e_j = Gamma(e_j, thetadot)`, exactly from two Newton–Euler passes:
//!
//! ```text
//! C e_j = ( c(q, thetadot + s e_j) - c(q, thetadot - s e_j) ) / (4 s),    any s > 0,
//! ```
//!
//! with no truncation error (only rounding); `s = max(1, |thetadot|_inf)` keeps both terms of
//! the scale of `c`.
//!
//! # Buffers
//!
//! [`Robot`] takes `&self`, the chain's evaluations a [`ChainWorkspace`]: each thread keeps one
//! workspace (and one joint vector) and reuses it, remaking it only when it evaluates a chain
//! of another joint count, so a thread that evaluates one arm allocates nothing after its
//! first call.

use std::cell::RefCell;

use nalgebra::{DVector, Vector3};

use crate::chain::{Chain, ChainWorkspace};
use crate::{Dynamics, JointLimits, Orientation, Robot};

/// A chain with a name and its joint limits, as a robot model (module documentation).
#[derive(Clone, Debug)]
pub struct ChainRobot {
    name: String,
    chain: Chain,
    limits: JointLimits,
}

/// One thread's buffers (module documentation).
struct Scratch {
    ws: ChainWorkspace,
    velocity: Vec<f64>,
}

thread_local! {
    /// This thread's buffers of [`ChainRobot`]'s evaluations.
    static SCRATCH: RefCell<Option<Scratch>> = const { RefCell::new(None) };
}

impl ChainRobot {
    /// The robot `name` of `chain`; its limits are the chain joints' position and velocity
    /// ranges.
    pub fn new(name: &str, chain: Chain) -> Self {
        let column = |f: fn(&crate::chain::JointRange) -> f64| {
            DVector::from_iterator(chain.dof(), chain.joints().iter().map(|j| f(&j.limits)))
        };
        let limits = JointLimits {
            theta_min: column(|r| r.position_min),
            theta_max: column(|r| r.position_max),
            thetadot_min: column(|r| r.velocity_min),
            thetadot_max: column(|r| r.velocity_max),
        };
        ChainRobot {
            name: name.to_string(),
            chain,
            limits,
        }
    }

    /// The same robot with the velocity limits `[-v_i, v_i]` (one entry per joint, > 0).
    pub fn with_velocity_max(mut self, v: &[f64]) -> Self {
        self.limits.thetadot_max = DVector::from_column_slice(v);
        self.limits.thetadot_min = -&self.limits.thetadot_max;
        self
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Whether every joint moves a body with an inertial, so that H is a model of the whole arm
    /// (the registry gives such a robot [`Dynamics`]).
    pub fn has_inertials(&self) -> bool {
        self.chain.joints().iter().all(|j| j.body.is_some())
    }

    /// Runs `f` on this thread's buffers, made for this chain's size.
    fn with_scratch<R>(&self, f: impl FnOnce(&mut ChainWorkspace, &mut [f64]) -> R) -> R {
        SCRATCH.with(|cell| {
            let mut cell = cell.borrow_mut();
            let n = self.chain.dof();
            let scratch = match cell.take() {
                Some(s) if s.ws.dof() == n => s,
                _ => Scratch {
                    ws: self.chain.workspace(),
                    velocity: vec![0.0; n],
                },
            };
            let scratch = cell.insert(scratch);
            f(&mut scratch.ws, &mut scratch.velocity)
        })
    }
}

impl Robot for ChainRobot {
    fn name(&self) -> &str {
        &self.name
    }

    fn dof(&self) -> usize {
        self.chain.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        self.with_scratch(|ws, _| self.chain.tool_position(ws, theta))
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.with_scratch(|ws, _| three_rows(self.chain.jacobian(ws, theta), 0, jac))
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.with_scratch(|ws, _| three_rows(self.chain.jacobian_dot(ws, theta, thetadot), 0, jdot))
    }

    /// p and J from one evaluation of the chain's kinematics.
    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        self.with_scratch(|ws, _| {
            let (p, j) = self.chain.tool_position_and_jacobian(ws, theta);
            three_rows(j, 0, jac);
            p
        })
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }

    fn orientation(&self) -> Option<&dyn Orientation> {
        Some(self)
    }

    /// The world base origin, the joint origins and the tool point.
    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        self.with_scratch(|ws, _| {
            let mut points = vec![self.chain.base().origin];
            points.extend(self.chain.body_frames(ws, theta).iter().map(|f| f.origin));
            points.push(self.chain.tool_position(ws, theta));
            points
        })
    }
}

/// The chain's tool frame; J_w and its derivative are the last three rows of the chain's
/// geometric Jacobian and `dJ/dt` (a prismatic joint's angular column is zero).
impl Orientation for ChainRobot {
    fn tool_rotation(&self, theta: &[f64]) -> nalgebra::Matrix3<f64> {
        self.with_scratch(|ws, _| self.chain.tool_pose(ws, theta).rot)
    }

    fn angular_jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.with_scratch(|ws, _| three_rows(self.chain.jacobian(ws, theta), 3, jac))
    }

    fn angular_jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.with_scratch(|ws, _| three_rows(self.chain.jacobian_dot(ws, theta, thetadot), 3, jdot))
    }
}

/// Copies rows `first..first + 3` of the 6 x n matrix `six` (0: the linear rows, 3: the
/// angular ones) into the 3 x n column-major `out`.
fn three_rows(six: &nalgebra::DMatrix<f64>, first: usize, out: &mut [f64]) {
    for (col, out) in out.chunks_exact_mut(3).enumerate() {
        out.copy_from_slice(&six.as_slice()[6 * col + first..6 * col + first + 3]);
    }
}

impl Dynamics for ChainRobot {
    fn inertia(&self, theta: &[f64], h: &mut [f64]) {
        self.with_scratch(|ws, _| h.copy_from_slice(self.chain.inertia(ws, theta).as_slice()))
    }

    fn coriolis(&self, theta: &[f64], thetadot: &[f64], c: &mut [f64]) {
        self.with_scratch(|ws, _| {
            c.copy_from_slice(self.chain.coriolis(ws, theta, thetadot).as_slice())
        })
    }

    fn coriolis_matrix(&self, theta: &[f64], thetadot: &[f64], cm: &mut [f64]) {
        let n = self.chain.dof();
        let s = thetadot.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
        self.with_scratch(|ws, velocity| {
            velocity.copy_from_slice(thetadot);
            for (j, column) in cm.chunks_exact_mut(n).enumerate() {
                velocity[j] = thetadot[j] + s;
                column.copy_from_slice(self.chain.coriolis(ws, theta, velocity).as_slice());
                velocity[j] = thetadot[j] - s;
                let minus = self.chain.coriolis(ws, theta, velocity);
                for (out, m) in column.iter_mut().zip(minus.iter()) {
                    *out = (*out - m) / (4.0 * s);
                }
                velocity[j] = thetadot[j];
            }
        })
    }

    fn gravity(&self, theta: &[f64], g: &mut [f64]) {
        self.with_scratch(|ws, _| {
            g.copy_from_slice(self.chain.gravity_torques(ws, theta).as_slice())
        })
    }
}
