//! A robot with other joint limits: an experiment's `joint_limits` / `velocity_limits` replace
//! the model's own (robio2018's Table I and |thetadot| <= 1.5 rad/s, say) without a new model.
//! Kinematics are the wrapped model's; only [`Robot::limits`] changes.

use crate::{JointLimits, Robot};
use nalgebra::{SMatrix, SVector, Vector3};
use std::sync::Arc;

/// `robot` with the limits `limits` (see the module docs).
pub struct Limited<const N: usize> {
    robot: Arc<dyn Robot<N>>,
    limits: JointLimits<N>,
}

impl<const N: usize> Limited<N> {
    /// `robot` with `limits` in place of its own.
    pub fn new(robot: Arc<dyn Robot<N>>, limits: JointLimits<N>) -> Self {
        Self { robot, limits }
    }
}

impl<const N: usize> Robot<N> for Limited<N> {
    fn name(&self) -> &str {
        self.robot.name()
    }

    fn position(&self, theta: &SVector<f64, N>) -> Vector3<f64> {
        self.robot.position(theta)
    }

    fn jacobian(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N> {
        self.robot.jacobian(theta)
    }

    fn jacobian_dot(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N> {
        self.robot.jacobian_dot(theta, thetadot)
    }

    fn limits(&self) -> JointLimits<N> {
        self.limits
    }

    fn skeleton(&self, theta: &SVector<f64, N>) -> Vec<Vector3<f64>> {
        self.robot.skeleton(theta)
    }
}
