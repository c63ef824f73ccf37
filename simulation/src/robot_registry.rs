//! The one place that maps the robot names of experiment files to robot models: the runner
//! builds its robot here, experiment files are validated against it, and the figures draw the
//! arm with it.

use nalgebra::{SVector, Vector3};
use robots::{Jaco2, Katana6m180, Robot};
use std::sync::Arc;

/// A robot model of any joint count.
#[derive(Clone, Debug)]
pub enum AnyRobot {
    /// A Jaco2 variant (6 joints, with dynamics).
    Jaco2(Arc<Jaco2>),
    /// The Katana 6M180 (5 joints, kinematics only).
    Katana(Arc<Katana6m180>),
}

/// Builds one model.
type Constructor = fn() -> AnyRobot;

/// The suite's robot names, each with its constructor.
const ROBOTS: &[(&str, Constructor)] = &[
    (robots::JACO2_PEN, || {
        AnyRobot::Jaco2(Arc::new(Jaco2::pen()))
    }),
    (robots::JACO2_PEN_EXP2, || {
        AnyRobot::Jaco2(Arc::new(Jaco2::pen_exp2()))
    }),
    (robots::JACO2, || AnyRobot::Jaco2(Arc::new(Jaco2::kinova()))),
    (robots::JACO2_HAND, || {
        AnyRobot::Jaco2(Arc::new(Jaco2::hand()))
    }),
    (robots::KATANA6M180, || {
        AnyRobot::Katana(Arc::new(Katana6m180::new()))
    }),
];

/// The model called `name` in experiment files, if the suite knows it.
pub fn robot_by_name(name: &str) -> Option<AnyRobot> {
    ROBOTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, build)| build())
}

/// The robot names the suite knows, in a fixed order.
pub fn robot_names() -> impl Iterator<Item = &'static str> {
    ROBOTS.iter().map(|(n, _)| *n)
}

/// The names of the robots with rigid-body dynamics (H, c, g), which the acceleration-level
/// zhang2018 scheme needs: the Jaco2 family.
pub fn robots_with_dynamics() -> Vec<&'static str> {
    ROBOTS
        .iter()
        .filter(|(_, build)| build().has_dynamics())
        .map(|(n, _)| *n)
        .collect()
}

impl AnyRobot {
    /// Whether the model has rigid-body dynamics (H, c, g).
    pub fn has_dynamics(&self) -> bool {
        matches!(self, AnyRobot::Jaco2(_))
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        match self {
            AnyRobot::Jaco2(_) => 6,
            AnyRobot::Katana(_) => 5,
        }
    }

    /// The arm's points from the base to the task point at joint angles `theta` (see
    /// [`Robot::skeleton`]); an error if `theta` does not have [`Self::dof`] entries.
    pub fn skeleton(&self, theta: &[f64]) -> Result<Vec<Vector3<f64>>, String> {
        fn of<const N: usize>(
            robot: &dyn Robot<N>,
            theta: &[f64],
        ) -> Result<Vec<Vector3<f64>>, String> {
            if theta.len() != N {
                return Err(format!(
                    "{}: {} joint angles given, the robot has {N} joints",
                    robot.name(),
                    theta.len()
                ));
            }
            Ok(robot.skeleton(&SVector::<f64, N>::from_column_slice(theta)))
        }
        match self {
            AnyRobot::Jaco2(r) => of::<6>(r.as_ref(), theta),
            AnyRobot::Katana(r) => of::<5>(r.as_ref(), theta),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_builds_the_model_of_that_name() {
        for name in robot_names() {
            let robot = robot_by_name(name).unwrap();
            let model = match &robot {
                AnyRobot::Jaco2(r) => Robot::<6>::name(r.as_ref()),
                AnyRobot::Katana(r) => Robot::<5>::name(r.as_ref()),
            };
            assert_eq!(model, name);
            let points = robot.skeleton(&vec![0.1; robot.dof()]).unwrap();
            assert!(points.len() >= 2);
            assert!(robot.skeleton(&vec![0.1; robot.dof() + 1]).is_err());
        }
        assert!(robot_by_name("puma560").is_none());
    }
}
