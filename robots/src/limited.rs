//! A robot with other joint limits: an experiment's `joint_limits` / `velocity_limits` replace
//! the model's own (robio2018's Table I and |thetadot| <= 1.5 rad/s, say) without a new model.
//! Kinematics are the wrapped model's; only [`Robot::limits`] changes.

use crate::{JointLimits, Orientation, Robot};
use nalgebra::Vector3;
use std::sync::Arc;

/// `robot` with the limits `limits` (see the module docs).
pub struct Limited {
    robot: Arc<dyn Robot>,
    limits: JointLimits,
}

impl Limited {
    /// `robot` with `limits` in place of its own; `None` unless `limits` has one entry per joint.
    pub fn new(robot: Arc<dyn Robot>, limits: JointLimits) -> Option<Self> {
        let n = robot.dof();
        [
            &limits.theta_min,
            &limits.theta_max,
            &limits.thetadot_min,
            &limits.thetadot_max,
        ]
        .iter()
        .all(|v| v.len() == n)
        .then_some(Self { robot, limits })
    }
}

impl Robot for Limited {
    fn name(&self) -> &str {
        self.robot.name()
    }

    fn dof(&self) -> usize {
        self.robot.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        self.robot.position(theta)
    }

    fn jacobian(&self, theta: &[f64], jac: &mut [f64]) {
        self.robot.jacobian(theta, jac)
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        self.robot.jacobian_dot(theta, thetadot, jdot)
    }

    fn position_jacobian(&self, theta: &[f64], jac: &mut [f64]) -> Vector3<f64> {
        self.robot.position_jacobian(theta, jac)
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }

    fn skeleton(&self, theta: &[f64]) -> Vec<Vector3<f64>> {
        self.robot.skeleton(theta)
    }

    fn orientation(&self) -> Option<&dyn Orientation> {
        self.robot.orientation()
    }
}
