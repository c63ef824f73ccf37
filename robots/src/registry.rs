//! The one place that maps the robot names of experiment files to robot models: the runner
//! builds its robot here, experiment files are validated against it, and the figures draw the
//! arm with it.
//!
//! Models are generic in their joint count N (fixed-size nalgebra in the hot path), so code that
//! uses a robot by name is written once as a [`RobotVisitor`], generic in N, and
//! [`AnyRobot::visit`] calls it with the model's N. Every N the registry can produce is
//! instantiated at compile time (the whole simulation, ~9 s of release build per N): 5
//! (Katana), 6 (Jaco2), 7 (Panda), and the n-link family at [`NLINK_SIZES`], which spans
//! robots' `nlink-3 ..= nlink-30` in eight steps (a cost-versus-joints curve needs a spread of N,
//! not every N). Adding an N is one entry in that list and in `visit`'s.
//!
//! Robots declared by robot files (`robots/data/*.toml`, embedded in the library; see
//! [`crate::robot_file`]) are registered by their file's name, e.g. `puma560`. A robot file may
//! only have one of the instantiated joint counts ([`crate::joint_counts::JOINT_COUNTS`], checked
//! against this list by a test), so a data robot adds no N. Where an arm exists both in Rust and as
//! data (the Jaco2 variants, the Panda, the n-link arms) the Rust model is the registered one: the
//! Jaco2 carries dynamics, and robots' `tests/data_robots.rs` shows the data twins equal.

use crate::data_robot::{builtin_models, DataRobot, DataVisitor};
use crate::{DataModel, Dynamics, Jaco2, Katana6m180, NLink, Panda, Robot};
use nalgebra::{SVector, Vector3};
use std::sync::Arc;

/// A pose with the wrong number of joint angles for its robot.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{robot}: {given} joint angles given, the robot has {joints} joints")]
pub struct JointCountError {
    /// The robot's name.
    pub robot: String,
    /// Angles given.
    pub given: usize,
    /// The robot's joints.
    pub joints: usize,
}

/// A robot model of any joint count.
#[derive(Clone, Debug)]
pub enum AnyRobot {
    /// A Jaco2 variant (6 joints, with dynamics).
    Jaco2(Arc<Jaco2>),
    /// The Katana 6M180 (5 joints, kinematics only).
    Katana(Arc<Katana6m180>),
    /// The Franka Emika Panda (7 joints, kinematics only).
    Panda(Arc<Panda>),
    /// The synthetic n-link arm `nlink-N` with N joints (kinematics only).
    NLink(usize),
    /// A robot declared by a built-in robot file (kinematics only).
    Data(DataModel),
}

/// Code generic in the joint count, run on a robot of the registry ([`AnyRobot::visit`]).
pub trait RobotVisitor {
    /// What [`RobotVisitor::visit`] returns, whatever the joint count.
    type Output;
    /// Called with the model (and its dynamics, where it has them).
    fn visit<const N: usize>(
        self,
        robot: Arc<dyn Robot<N>>,
        dynamics: Option<Arc<dyn Dynamics<N>>>,
    ) -> Self::Output;
}

/// Builds one model.
type Constructor = fn() -> AnyRobot;

/// The suite's named robot models (the n-link family is [`nlink_name`]), each with its
/// constructor.
const ROBOTS: &[(&str, Constructor)] = &[
    (crate::JACO2_PEN, || AnyRobot::Jaco2(Arc::new(Jaco2::pen()))),
    (crate::JACO2_PEN_EXP2, || {
        AnyRobot::Jaco2(Arc::new(Jaco2::pen_exp2()))
    }),
    (crate::JACO2, || AnyRobot::Jaco2(Arc::new(Jaco2::kinova()))),
    (crate::JACO2_HAND, || {
        AnyRobot::Jaco2(Arc::new(Jaco2::hand()))
    }),
    (crate::KATANA6M180, || {
        AnyRobot::Katana(Arc::new(Katana6m180::new()))
    }),
    (crate::PANDA, || AnyRobot::Panda(Arc::new(Panda::new()))),
];

/// The joint counts of the n-link arms in the registry (`nlink-N`).
pub const NLINK_SIZES: [usize; 8] = [3, 5, 6, 7, 10, 15, 20, 30];

/// The name of the n-link arm with `n` joints.
pub fn nlink_name(n: usize) -> String {
    format!("nlink-{n}")
}

/// Whether `name` is a Rust model's (those take precedence over a robot file of that name).
fn is_rust_model(name: &str) -> bool {
    name.starts_with("nlink-") || ROBOTS.iter().any(|(n, _)| *n == name)
}

/// The built-in data robots registered by name: those without a Rust model of that name.
fn data_robots() -> impl Iterator<Item = &'static DataModel> {
    builtin_models().iter().filter(|m| !is_rust_model(m.name()))
}

/// The model called `name` in experiment files, if the suite knows it.
pub fn robot_by_name(name: &str) -> Option<AnyRobot> {
    if let Some(n) = name
        .strip_prefix("nlink-")
        .and_then(|n| n.parse::<usize>().ok())
    {
        return NLINK_SIZES.contains(&n).then_some(AnyRobot::NLink(n));
    }
    ROBOTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, build)| build())
        .or_else(|| {
            data_robots()
                .find(|m| m.name() == name)
                .cloned()
                .map(AnyRobot::Data)
        })
}

/// The robot names the suite knows, in a fixed order: the Rust models, the data robots (by file
/// name), the n-link family last, by N.
pub fn robot_names() -> impl Iterator<Item = String> {
    ROBOTS
        .iter()
        .map(|(n, _)| n.to_string())
        .chain(data_robots().map(|m| m.name().to_string()))
        .chain(NLINK_SIZES.iter().map(|&n| nlink_name(n)))
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

/// Calls `$visitor.visit::<N>` with `NLink::<N>` for the N in `$n` (one arm per N of the family).
macro_rules! visit_nlink {
    ($n:expr, $visitor:expr, [$($k:literal),*]) => {
        match $n {
            $($k => $visitor.visit::<$k>(Arc::new(NLink::<$k>::new()), None),)*
            n => unreachable!("nlink-{n} is not in the registry (NLINK_SIZES)"),
        }
    };
}

/// `theta` as the joint vector of `robot`, or an error naming both counts.
fn angles<const N: usize>(
    robot: &dyn Robot<N>,
    theta: &[f64],
) -> Result<SVector<f64, N>, JointCountError> {
    if theta.len() != N {
        return Err(JointCountError {
            robot: robot.name().to_string(),
            given: theta.len(),
            joints: N,
        });
    }
    Ok(SVector::from_column_slice(theta))
}

/// A [`RobotVisitor`] run on a data robot (which has no dynamics).
struct OnData<V>(V);

impl<V: RobotVisitor> DataVisitor for OnData<V> {
    type Output = V::Output;
    fn visit<const N: usize>(self, robot: Arc<DataRobot<N>>) -> V::Output {
        self.0.visit::<N>(robot, None)
    }
}

impl AnyRobot {
    /// Runs `visitor` on this model with its joint count.
    pub fn visit<V: RobotVisitor>(&self, visitor: V) -> V::Output {
        match self {
            AnyRobot::Jaco2(r) => visitor.visit::<6>(r.clone(), Some(r.clone())),
            AnyRobot::Katana(r) => visitor.visit::<5>(r.clone(), None),
            AnyRobot::Panda(r) => visitor.visit::<7>(r.clone(), None),
            AnyRobot::NLink(n) => visit_nlink!(*n, visitor, [3, 5, 6, 7, 10, 15, 20, 30]),
            AnyRobot::Data(m) => m.visit(OnData(visitor)),
        }
    }

    /// The pose the model's check values are stated at: the papers' theta0 for the Jaco2
    /// models (the group's EXP2 theta0 for `jaco2-pen-exp2`), kong2019's theta*0 for the
    /// Katana, Franka's "ready" pose for the Panda, [`NLink::home`] for the n-link arms, the
    /// file's `stated_pose` for a data robot (zero if it states none).
    pub fn stated_pose(&self) -> Vec<f64> {
        struct Home;
        impl RobotVisitor for Home {
            type Output = Vec<f64>;
            fn visit<const N: usize>(
                self,
                _: Arc<dyn Robot<N>>,
                _: Option<Arc<dyn Dynamics<N>>>,
            ) -> Vec<f64> {
                NLink::<N>::home().as_slice().to_vec()
            }
        }
        let pi = std::f64::consts::PI;
        match self {
            AnyRobot::Jaco2(r) if r.name() == crate::JACO2_PEN_EXP2 => {
                vec![1.670, 2.845, -3.218, 4.182, -1.715, -2.655]
            }
            AnyRobot::Jaco2(_) => vec![1.675, 2.79, -3.216, 4.187, -1.71, -2.95],
            AnyRobot::Katana(_) => vec![2.0 * pi / 5.0, pi / 2.0, 0.0, -pi / 6.0, pi / 3.0],
            AnyRobot::Panda(_) => Panda::READY.to_vec(),
            AnyRobot::NLink(_) => self.visit(Home),
            AnyRobot::Data(m) => m.stated_pose().to_vec(),
        }
    }

    /// Whether the model has rigid-body dynamics (H, c, g).
    pub fn has_dynamics(&self) -> bool {
        matches!(self, AnyRobot::Jaco2(_))
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        match self {
            AnyRobot::Jaco2(_) => 6,
            AnyRobot::Katana(_) => 5,
            AnyRobot::Panda(_) => 7,
            AnyRobot::NLink(n) => *n,
            AnyRobot::Data(m) => m.dof(),
        }
    }

    /// The model's name.
    pub fn name(&self) -> String {
        struct Name;
        impl RobotVisitor for Name {
            type Output = String;
            fn visit<const N: usize>(
                self,
                robot: Arc<dyn Robot<N>>,
                _: Option<Arc<dyn Dynamics<N>>>,
            ) -> String {
                robot.name().to_string()
            }
        }
        self.visit(Name)
    }

    /// The arm's points from the base to the task point at joint angles `theta` (see
    /// [`Robot::skeleton`]); an error if `theta` does not have [`Self::dof`] entries.
    pub fn skeleton(&self, theta: &[f64]) -> Result<Vec<Vector3<f64>>, JointCountError> {
        struct Skeleton<'a>(&'a [f64]);
        impl RobotVisitor for Skeleton<'_> {
            type Output = Result<Vec<Vector3<f64>>, JointCountError>;
            fn visit<const N: usize>(
                self,
                robot: Arc<dyn Robot<N>>,
                _: Option<Arc<dyn Dynamics<N>>>,
            ) -> Self::Output {
                Ok(robot.skeleton(&angles(robot.as_ref(), self.0)?))
            }
        }
        self.visit(Skeleton(theta))
    }

    /// Tip position and the singular values of J at `theta` (the check values `reproduce
    /// --robots` prints); an error if `theta` does not have [`Self::dof`] entries.
    pub fn check_values(&self, theta: &[f64]) -> Result<(Vector3<f64>, Vec<f64>), JointCountError> {
        struct Check<'a>(&'a [f64]);
        impl RobotVisitor for Check<'_> {
            type Output = Result<(Vector3<f64>, Vec<f64>), JointCountError>;
            fn visit<const N: usize>(
                self,
                robot: Arc<dyn Robot<N>>,
                _: Option<Arc<dyn Dynamics<N>>>,
            ) -> Self::Output {
                let theta = angles(robot.as_ref(), self.0)?;
                let j =
                    nalgebra::DMatrix::from_column_slice(3, N, robot.jacobian(&theta).as_slice());
                let mut sv: Vec<f64> = j.singular_values().iter().copied().collect();
                sv.sort_by(|a, b| b.total_cmp(a));
                Ok((robot.position(&theta), sv))
            }
        }
        self.visit(Check(theta))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_builds_the_model_of_that_name() {
        let names: Vec<String> = robot_names().collect();
        assert!(names.iter().any(|n| n == "panda"));
        assert!(names.iter().any(|n| n == "nlink-3") && names.iter().any(|n| n == "nlink-30"));
        for name in &names {
            let robot = robot_by_name(name).unwrap();
            assert_eq!(&robot.name(), name);
            let points = robot.skeleton(&vec![0.1; robot.dof()]).unwrap();
            assert!(points.len() >= 2);
            assert!(robot.skeleton(&vec![0.1; robot.dof() + 1]).is_err());
        }
        assert_eq!(
            names.iter().filter(|n| n.starts_with("nlink-")).count(),
            NLINK_SIZES.len()
        );
        assert!(names.iter().any(|n| n == "puma560"));
        for unknown in ["puma", "nlink-2", "nlink-4", "nlink-31", "nlink-x"] {
            assert!(robot_by_name(unknown).is_none(), "{unknown}");
        }
        let unique: std::collections::BTreeSet<&String> = names.iter().collect();
        assert_eq!(unique.len(), names.len(), "names are unique");
    }

    #[test]
    fn puma560_is_a_data_robot_with_check_values() {
        let puma = robot_by_name("puma560").unwrap();
        assert!(matches!(puma, AnyRobot::Data(_)) && !puma.has_dynamics());
        assert_eq!(puma.dof(), 6);
        let pi = std::f64::consts::PI;
        assert_eq!(
            puma.stated_pose(),
            [0.0, -pi / 4.0, 0.0, pi / 2.0, -pi / 4.0, 0.0]
        );
        let (tip, sv) = puma.check_values(&puma.stated_pose()).unwrap();
        assert!(
            (tip - Vector3::new(0.653136683891, -0.110275243558, 0.013770732342)).norm() < 1e-11
        );
        assert_eq!(sv.len(), 3);
        assert!(puma.check_values(&[0.0; 5]).is_err());
    }

    #[test]
    fn data_robots_have_instantiated_joint_counts() {
        for n in crate::joint_counts::JOINT_COUNTS {
            assert!([5, 6, 7].contains(n) || NLINK_SIZES.contains(n), "{n}");
        }
    }

    #[test]
    fn data_twins_of_rust_models_state_the_same_pose_and_check_values() {
        for model in builtin_models() {
            let Some(rust) = robot_by_name(model.name()) else {
                continue;
            };
            if matches!(rust, AnyRobot::Data(_)) {
                continue;
            }
            let data = AnyRobot::Data(model.clone());
            let pose = rust.stated_pose();
            let close = |a: &[f64], b: &[f64]| {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
            };
            assert!(close(&pose, &data.stated_pose()), "{}", model.name());
            let (tip_r, sv_r) = rust.check_values(&pose).unwrap();
            let (tip_d, sv_d) = data.check_values(&pose).unwrap();
            assert!((tip_r - tip_d).norm() < 1e-12, "{}", model.name());
            assert!(close(&sv_r, &sv_d), "{}", model.name());
        }
    }
}
