//! The n-link family `nlink-{n}` (any n from [`NLINK_MIN`] to [`NLINK_MAX`], a run-time value): a synthetic arm for measuring how a scheme's
//! cost scales with the number of joints, not a physical robot.
//!
//! The papers track the task point in 3-D (m = 3); a strictly planar chain would give `J` a zero
//! row and a rank-deficient equality constraint. So joint 1 is a yaw joint about the world z
//! axis at the base (the world origin), and joints 2..=N are pitch joints with parallel,
//! horizontal axes forming a planar chain in the vertical plane that joint 1 turns. Joint 2 sits
//! on the yaw axis at height `h0 = 0.3` m ([`H0`]); links 2..=N (from joint `k` to joint `k + 1`,
//! joint `N + 1` being the tip) all have length `l = L / (N - 1)`, total reach `L = 1` m
//! ([`REACH`]).
//!
//! With the cumulative pitch angles `phi_k = theta_2 + ... + theta_k` (k = 2..=N), the
//! horizontal reach `r` and height `z`,
//!
//! ```text
//! r = sum_{k=2..N} l cos(phi_k),     z = h0 + sum_{k=2..N} l sin(phi_k),
//! f(theta) = [ cos(theta_1) r,  sin(theta_1) r,  z ].
//! ```
//!
//! Joint `j >= 2` moves links `j..=N`, so with the suffix sums
//! `S_j = sum_{k>=j} l sin(phi_k)`, `C_j = sum_{k>=j} l cos(phi_k)` (so `r = C_2`,
//! `z = h0 + S_2`),
//!
//! ```text
//! J_1 = [ -sin(theta_1) r,  cos(theta_1) r,  0 ],
//! J_j = [ -cos(theta_1) S_j,  -sin(theta_1) S_j,  C_j ]      (j >= 2).
//! ```
//!
//! `Jdot` is its exact time derivative. With `w_1 = thetadot_1`, the angle rates
//! `w_k = thetadot_2 + ... + thetadot_k` of `phi_k`, and the weighted suffix sums
//! `Sw_j = sum_{k>=j} l sin(phi_k) w_k`, `Cw_j = sum_{k>=j} l cos(phi_k) w_k`, we have
//! `d/dt S_j = Cw_j`, `d/dt C_j = -Sw_j`, `rdot = -Sw_2`, and
//!
//! ```text
//! Jdot_1 = [ -cos(theta_1) w_1 r - sin(theta_1) rdot,  -sin(theta_1) w_1 r + cos(theta_1) rdot,  0 ],
//! Jdot_j = [ sin(theta_1) w_1 S_j - cos(theta_1) Cw_j,  -cos(theta_1) w_1 S_j - sin(theta_1) Cw_j,  -Sw_j ].
//! ```
//!
//! The out-of-plane direction `(-sin theta_1, cos theta_1, 0)` is reached by joint 1 alone, so
//! one singular value of `J` is exactly `|r|`; the other two are those of the planar 2 x (N-1)
//! block.
//!
//! Joint limits (this suite's choice, not a datasheet): `theta_1` in `[-pi, pi]`, the pitch
//! joints in `[-2.6, 2.6]` rad, `|thetadot| <= 2` rad/s for every joint.
//!
//! [`NLink::home`]: `theta_1 = 0`, `theta_2 = 1.2`, and every further pitch joint bent by
//! `-3 / (N - 1)` rad, so the chain is a (discrete) circular arc curling down by a total of
//! `3 (N - 2) / (N - 1)` rad; its tip sits 0.665-0.732 m from joint 2 (about two thirds of the
//! reach), in front of the yaw axis and above the base. The smallest Jacobian singular value
//! there is 0.298909 at N = 3 and grows with N to 0.648 (0.645 at N = 30); `tests/nlink.rs`
//! asserts it is above 0.05 for every N = 3..=30 and the N = 3 value to 1e-6.

use std::f64::consts::PI;

use nalgebra::{DVector, Vector3};

use crate::{JointLimits, Robot};

/// Height of joint 2 (the first pitch joint) above the base (m).
pub const H0: f64 = 0.3;

/// Total length of the pitch chain, links 2..=N (m).
pub const REACH: f64 = 1.0;

/// Limit of the pitch joints 2..=N (rad): they range over `[-PITCH_LIMIT, PITCH_LIMIT]`.
pub const PITCH_LIMIT: f64 = 2.6;

/// Joint-velocity limit of every joint (rad/s).
pub const VELOCITY_LIMIT: f64 = 2.0;

/// The fewest joints of an n-link arm: the yaw joint and one pitch joint.
pub const NLINK_MIN: usize = 2;
/// The most joints of an n-link arm the registry builds.
pub const NLINK_MAX: usize = 1000;

/// The n-link arm with its joint count n a run-time value (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct NLink {
    name: String,
    limits: JointLimits,
}

impl NLink {
    /// The arm with `n` joints, or `None` unless `NLINK_MIN <= n <= NLINK_MAX`.
    pub fn new(n: usize) -> Option<Self> {
        if !(NLINK_MIN..=NLINK_MAX).contains(&n) {
            return None;
        }
        let mut theta_max = vec![PITCH_LIMIT; n];
        theta_max[0] = PI;
        Some(NLink {
            name: format!("nlink-{n}"),
            limits: JointLimits::symmetric(&theta_max, &vec![VELOCITY_LIMIT; n]),
        })
    }

    /// Length of every pitch link, `L / (n - 1)` (m).
    pub fn link_length(&self) -> f64 {
        link_length(self.dof())
    }

    /// The stated home pose: `theta_1 = 0`, `theta_2 = 1.2`, `theta_k = -3 / (n - 1)` for
    /// k = 3..=n (module documentation).
    pub fn home(&self) -> DVector<f64> {
        let mut theta = DVector::zeros(self.dof());
        home_into(theta.as_mut_slice());
        theta
    }
}

impl Robot for NLink {
    fn name(&self) -> &str {
        &self.name
    }

    fn dof(&self) -> usize {
        self.limits.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        assert_eq!(theta.len(), self.dof(), "nlink: one angle per joint");
        position_of(theta)
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        assert_eq!(theta.len(), self.dof(), "nlink: one angle per joint");
        jacobian_into(theta, jac);
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        assert_eq!(theta.len(), self.dof(), "nlink: one angle per joint");
        assert_eq!(thetadot.len(), self.dof(), "nlink: one rate per joint");
        jacobian_dot_into(theta, thetadot, jdot);
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }

    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        let n = self.dof();
        let l = self.link_length();
        let (s1, c1) = theta[0].sin_cos();
        let mut points = Vec::with_capacity(n + 1);
        points.push(Vector3::zeros());
        let (mut r, mut z, mut phi) = (0.0, H0, 0.0);
        points.push(Vector3::new(0.0, 0.0, z));
        for t in &theta[1..n] {
            phi += t;
            let (s, c) = f64::sin_cos(phi);
            r += l * c;
            z += l * s;
            points.push(Vector3::new(c1 * r, s1 * r, z));
        }
        points
    }
}

/// Length of every pitch link of an n-joint arm, `L / (n - 1)` (m).
fn link_length(n: usize) -> f64 {
    REACH / (n - 1) as f64
}

/// Writes the home pose of an `theta.len()`-joint arm (module documentation).
fn home_into(theta: &mut [f64]) {
    let bend = -3.0 / (theta.len() - 1) as f64;
    for (k, t) in theta.iter_mut().enumerate() {
        *t = match k {
            0 => 0.0,
            1 => 1.2,
            _ => bend,
        };
    }
}

/// f(theta).
fn position_of(theta: &[f64]) -> Vector3<f64> {
    let l = link_length(theta.len());
    let mut r = 0.0;
    let mut z = H0;
    let mut phi = 0.0;
    for t in &theta[1..] {
        phi += t;
        let (s, c) = f64::sin_cos(phi);
        r += l * c;
        z += l * s;
    }
    let (s1, c1) = theta[0].sin_cos();
    Vector3::new(c1 * r, s1 * r, z)
}

/// Writes J(theta) into `jac`, the 3 x n column-major storage (length 3n). A first pass stores
/// (sin phi_k, cos phi_k) in column k's rows 0 and 1; the backward pass over the suffix sums
/// reads column j before it overwrites it, so no other scratch is needed.
fn jacobian_into(theta: &[f64], jac: &mut [f64]) {
    let n = theta.len();
    assert_eq!(jac.len(), 3 * n, "nlink: J is 3 x n");
    let l = link_length(n);
    let mut phi = 0.0;
    for k in 1..n {
        phi += theta[k];
        (jac[3 * k], jac[3 * k + 1]) = phi.sin_cos();
    }
    let (s1, c1) = theta[0].sin_cos();
    let (mut sj, mut cj) = (0.0, 0.0);
    for j in (1..n).rev() {
        let (s, c) = (jac[3 * j], jac[3 * j + 1]);
        sj += l * s;
        cj += l * c;
        jac[3 * j] = -c1 * sj;
        jac[3 * j + 1] = -s1 * sj;
        jac[3 * j + 2] = cj;
    }
    jac[0] = -s1 * cj;
    jac[1] = c1 * cj;
    jac[2] = 0.0;
}

/// Writes Jdot(theta, thetadot) into `jdot`, the 3 x n column-major storage: as
/// [`jacobian_into`], column k first holds (sin phi_k, cos phi_k, w_k).
fn jacobian_dot_into(theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
    let n = theta.len();
    assert_eq!(jdot.len(), 3 * n, "nlink: Jdot is 3 x n");
    let l = link_length(n);
    let (mut phi, mut rate) = (0.0, 0.0);
    for k in 1..n {
        phi += theta[k];
        rate += thetadot[k];
        (jdot[3 * k], jdot[3 * k + 1]) = phi.sin_cos();
        jdot[3 * k + 2] = rate;
    }
    let (s1, c1) = theta[0].sin_cos();
    let w1 = thetadot[0];
    let (mut sj, mut cj, mut swj, mut cwj) = (0.0, 0.0, 0.0, 0.0);
    for j in (1..n).rev() {
        let (s, c, w) = (jdot[3 * j], jdot[3 * j + 1], jdot[3 * j + 2]);
        sj += l * s;
        cj += l * c;
        swj += l * s * w;
        cwj += l * c * w;
        jdot[3 * j] = s1 * w1 * sj - c1 * cwj;
        jdot[3 * j + 1] = -c1 * w1 * sj - s1 * cwj;
        jdot[3 * j + 2] = -swj;
    }
    let (r, rdot) = (cj, -swj);
    jdot[0] = -c1 * w1 * r - s1 * rdot;
    jdot[1] = -s1 * w1 * r + c1 * rdot;
    jdot[2] = 0.0;
}
