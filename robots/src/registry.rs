//! The one place that maps the robot names of experiment files to robot models: the runner
//! builds its robot here, experiment files are validated against it, and the figures draw the
//! arm with it.
//!
//! A name gives a [`Model`]: the arm as a [`Robot`] trait object whose joint count is a run-time
//! value, its [`Dynamics`] where it has them, and the pose its check values are stated at. The
//! names are, in this order of precedence:
//!
//! 1. the Rust models: the Jaco2 variants (with dynamics), the Katana 6M180, the Panda;
//! 2. the n-link family `nlink-<n>`, any n from [`NLINK_MIN`] to [`NLINK_MAX`], written in
//!    decimal digits without leading zeros: a name has one spelling, so `nlink-02` is not
//!    `nlink-2` ([`RegistryError::NLinkSpelling`]; a robot file may not take such a name,
//!    [`RobotFileError::Shadows`]) and `nlink-+2` is no robot;
//! 3. the robot files: the built-in `robots/data/*.toml` (embedded in the library; see
//!    [`crate::robot_file`]), registered by file name, e.g. `puma560`, then the files registered
//!    at run time ([`register_file`]: a paper's own `papers/<id>/robots/*.toml`, of the DH
//!    form or the URDF form, whose [`ChainRobot`] has [`Dynamics`] where every moving joint
//!    carries an inertial).
//!
//! Where an arm exists both in Rust and as a built-in file (the Jaco2 variants, the Panda, the
//! n-link arms) the Rust model is the registered one: the Jaco2 carries dynamics, and robots'
//! `tests/data_robots.rs` shows the data twins equal. A file registered at run time may not take
//! a name the suite already has ([`RobotFileError::Shadows`]: a lookup of that name then fails,
//! naming the file).
//!
//! A robot file is validated when it is read; an invalid file is kept with its error, so that
//! only a lookup of its own name fails ([`RegistryError::File`]), naming the file and field.

use crate::chain_robot::ChainRobot;
use crate::data_robot::{builtin_models, DataRobot};
use crate::nlink::{NLINK_MAX, NLINK_MIN};
use crate::robot_file::{RobotFileError, RobotForm};
use crate::{Dynamics, Jaco2, Katana6m180, NLink, Panda, Robot};
use nalgebra::Vector3;
use std::f64::consts::PI;
use std::sync::{Arc, RwLock};

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

/// Why a robot name gives no model, or a robot file cannot be registered.
#[derive(Debug, thiserror::Error)]
pub enum RegistryError {
    /// No robot has this name.
    #[error(
        "unknown robot {}; the robots are: {}, and nlink-<n> for n = {NLINK_MIN}..={NLINK_MAX}",
        settings::shown(name),
        choices.join(", ")
    )]
    Unknown {
        /// The name asked for.
        name: String,
        /// The names the registry knows (the n-link family aside).
        choices: Vec<String>,
    },
    /// Another spelling of an n-link arm's name: `nlink-` and n with leading zeros.
    #[error(
        "robot names have one spelling: the n-link arm of {n} joints is \"nlink-{n}\" \
         (nlink-<n>, n = {NLINK_MIN}..={NLINK_MAX} in decimal digits without leading zeros)"
    )]
    NLinkSpelling {
        /// The joint count the name spells.
        n: usize,
    },
    /// The robot's file is invalid (the error names the file and field).
    #[error("{0}")]
    File(Arc<RobotFileError>),
}

/// A robot of the registry (module documentation).
#[derive(Clone)]
pub struct Model {
    /// The arm's kinematics and limits.
    pub robot: Arc<dyn Robot>,
    /// Its rigid-body dynamics (H, c, g), where it has them.
    pub dynamics: Option<Arc<dyn Dynamics>>,
    /// The pose its check values are stated at: the papers' theta0 for the Jaco2 models (the
    /// group's EXP2 theta0 for `jaco2-pen-exp2`), kong2019's theta*0 for the Katana, Franka's
    /// "ready" pose for the Panda, [`NLink::home`] for the n-link arms, the file's
    /// `stated_pose` for a data robot (zero if it states none).
    pub stated_pose: Vec<f64>,
    /// What the kinematics are, for describing the model (the task cards).
    pub kinematics: Kinematics,
}

/// What a model's kinematics are.
#[derive(Clone, Debug)]
pub enum Kinematics {
    /// A classical DH chain with a task point ([`DataRobot`]); `file` is the robot file that
    /// declares it (none for a Rust model).
    Dh {
        /// The chain, offsets and task point.
        arm: Box<DataRobot>,
        /// The robot file, e.g. `robots/data/puma560.toml`.
        file: Option<String>,
    },
    /// kong2019's closed form of the Katana 6M180.
    Katana(Katana6m180),
    /// The n-link arm with this many joints ([`crate::NLink`]).
    NLink(usize),
    /// The chain of a URDF between two links, declared by a robot file's URDF form
    /// ([`crate::robot_file::UrdfRobotSpec`]).
    Urdf {
        /// The robot file.
        file: String,
        /// The URDF as the robot file names it.
        urdf: String,
        /// The chain's base link.
        base: String,
        /// The chain's tip link.
        tip: String,
    },
}

impl std::fmt::Debug for Model {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Model")
            .field("name", &self.robot.name())
            .field("dof", &self.robot.dof())
            .field("dynamics", &self.dynamics.is_some())
            .finish()
    }
}

/// The suite's named Rust models.
const RUST_MODELS: [&str; 6] = [
    crate::JACO2_PEN,
    crate::JACO2_PEN_EXP2,
    crate::JACO2,
    crate::JACO2_HAND,
    crate::KATANA6M180,
    crate::PANDA,
];

/// The Rust model called `name`, if there is one.
fn rust_model(name: &str) -> Option<Model> {
    let jaco2 = |arm: Jaco2| {
        let stated_pose = arm.arm().stated_pose().to_vec();
        let kinematics = Kinematics::Dh {
            arm: Box::new(arm.arm().clone()),
            file: None,
        };
        let arm = Arc::new(arm);
        Model {
            robot: arm.clone(),
            dynamics: Some(arm),
            stated_pose,
            kinematics,
        }
    };
    let data = |arm: DataRobot| data_model(arm, None);
    Some(match name {
        crate::JACO2_PEN => jaco2(Jaco2::pen()),
        crate::JACO2_PEN_EXP2 => jaco2(Jaco2::pen_exp2()),
        crate::JACO2 => jaco2(Jaco2::kinova()),
        crate::JACO2_HAND => jaco2(Jaco2::hand()),
        crate::KATANA6M180 => Model {
            robot: Arc::new(Katana6m180::new()),
            dynamics: None,
            stated_pose: vec![2.0 * PI / 5.0, PI / 2.0, 0.0, -PI / 6.0, PI / 3.0],
            kinematics: Kinematics::Katana(Katana6m180::new()),
        },
        crate::PANDA => data(Panda::model()),
        _ => return None,
    })
}

/// The digits of `name` if it is `nlink-` and decimal digits (any, leading zeros too).
fn nlink_digits(name: &str) -> Option<&str> {
    let digits = name.strip_prefix("nlink-")?;
    (!digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())).then_some(digits)
}

/// The n of an n-link arm in the family's range that `name` spells otherwise than
/// `nlink-<n>` (with leading zeros), if it is one.
fn nlink_respelled(name: &str) -> Option<usize> {
    let digits = nlink_digits(name)?;
    let significant = digits.trim_start_matches('0');
    if significant.len() == digits.len() {
        return None;
    }
    let n: usize = significant.parse().ok()?;
    (NLINK_MIN..=NLINK_MAX).contains(&n).then_some(n)
}

/// The n-link arm `nlink-<n>`, if `name` is one with n in the family's range, written in
/// decimal digits without leading zeros.
fn nlink(name: &str) -> Option<Model> {
    let digits = nlink_digits(name)?;
    if digits.starts_with('0') {
        return None;
    }
    let n: usize = digits.parse().ok()?;
    let arm = NLink::new(n)?;
    Some(Model {
        stated_pose: arm.home().as_slice().to_vec(),
        robot: Arc::new(arm),
        dynamics: None,
        kinematics: Kinematics::NLink(n),
    })
}

/// The model of a DH arm (kinematics only), declared by `file` if given.
fn data_model(arm: DataRobot, file: Option<String>) -> Model {
    Model {
        stated_pose: arm.stated_pose().to_vec(),
        robot: Arc::new(arm.clone()),
        dynamics: None,
        kinematics: Kinematics::Dh {
            arm: Box::new(arm),
            file,
        },
    }
}

/// The name of the n-link arm with `n` joints.
pub fn nlink_name(n: usize) -> String {
    format!("nlink-{n}")
}

/// Whether `name` is a Rust model's or an n-link arm's (those take precedence over a built-in
/// robot file of that name).
fn is_rust_model(name: &str) -> bool {
    RUST_MODELS.contains(&name) || nlink(name).is_some()
}

/// Whether a robot file may not take `name`: a Rust model's, an n-link arm's or another
/// spelling of one (`nlink-02`), a built-in file's, or a file's registered before.
fn is_taken(name: &str) -> bool {
    is_rust_model(name)
        || nlink_respelled(name).is_some()
        || builtin_models().iter().any(|(s, _)| *s == name)
        || runtime_files().iter().any(|(s, _, _)| *s == name)
}

/// The model of a robot file registered at run time, built when it is registered.
#[derive(Clone)]
enum FileArm {
    /// A DH table.
    Dh(DataRobot),
    /// A URDF chain, its stated pose and how it was declared ([`Kinematics::Urdf`]).
    Urdf(Arc<ChainRobot>, Vec<f64>, Kinematics),
}

/// A robot file's model, or why the file was refused, under its robot's name.
type FileModel = (String, String, Result<FileArm, Arc<RobotFileError>>);

/// The robot files registered at run time ([`register_file`]).
static RUNTIME_FILES: RwLock<Vec<FileModel>> = RwLock::new(Vec::new());

/// Registers a robot file read at run time: `file` is its path (its robot's name must be the
/// file's stem), `text` is its content or why it could not be read. A file of the URDF form
/// ([`crate::robot_file::UrdfRobotSpec`]) reads its URDF now, through the `inputs` reader,
/// inside `file`'s directory. It is validated now; an
/// invalid file is kept with its error, which a lookup of its name returns, so that it fails
/// only the commands that use it. A file whose name the suite already has (a built-in model, a
/// built-in or already registered file) is such an error, [`RobotFileError::Shadows`], and
/// takes precedence over the model it shadows; so is a file that takes another spelling of an
/// n-link arm's name (`nlink-02`).
pub fn register_file<E: std::fmt::Display>(path: &std::path::Path, text: Result<&str, E>) {
    let file = &path.display().to_string();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let model = if is_taken(&stem) {
        Err(RobotFileError::Shadows {
            file: file.to_string(),
            name: stem.clone(),
        })
    } else {
        text.map_err(|reason| RobotFileError::Unreadable {
            file: file.to_string(),
            reason: reason.to_string(),
        })
        .and_then(|text| RobotForm::parse_named(file, &stem, text))
        .and_then(|form| match form {
            RobotForm::Dh(spec) => Ok(FileArm::Dh(DataRobot::new(&spec))),
            RobotForm::Urdf(spec) => spec.build(path).map(|(robot, pose)| {
                let kinematics = Kinematics::Urdf {
                    file: file.clone(),
                    urdf: spec.urdf().to_string(),
                    base: spec.base().to_string(),
                    tip: spec.tip().to_string(),
                };
                FileArm::Urdf(Arc::new(robot), pose, kinematics)
            }),
        })
    };
    RUNTIME_FILES
        .write()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .push((stem, file.to_string(), model.map_err(Arc::new)));
}

/// The robot files registered at run time.
fn runtime_files() -> std::sync::RwLockReadGuard<'static, Vec<FileModel>> {
    RUNTIME_FILES
        .read()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The model of the robot file called `name` (built-in first, then registered at run time),
/// with the file's path.
fn file_model(name: &str) -> Option<(String, Result<FileArm, Arc<RobotFileError>>)> {
    if let Some((stem, m)) = builtin_models().iter().find(|(s, _)| *s == name) {
        return Some((
            format!("robots/data/{stem}.toml"),
            m.clone().map(FileArm::Dh),
        ));
    }
    runtime_files()
        .iter()
        .find(|(s, _, _)| s == name)
        .map(|(_, file, m)| (file.clone(), m.clone()))
}

/// The model called `name` in experiment files; an error names the valid choices, or the
/// robot's invalid file and field.
pub fn robot_by_name(name: &str) -> Result<Model, RegistryError> {
    let shadowed = runtime_files().iter().find_map(|(s, _, m)| match m {
        Err(e) if s == name && matches!(**e, RobotFileError::Shadows { .. }) => Some(e.clone()),
        _ => None,
    });
    if let Some(e) = shadowed {
        return Err(RegistryError::File(e));
    }
    if let Some(model) = rust_model(name).or_else(|| nlink(name)) {
        return Ok(model);
    }
    if let Some(n) = nlink_respelled(name) {
        return Err(RegistryError::NLinkSpelling { n });
    }
    match file_model(name) {
        Some((file, Ok(FileArm::Dh(arm)))) => Ok(data_model(arm, Some(file))),
        Some((_, Ok(FileArm::Urdf(robot, stated_pose, kinematics)))) => Ok(Model {
            dynamics: robot
                .has_inertials()
                .then(|| robot.clone() as Arc<dyn Dynamics>),
            robot,
            stated_pose,
            kinematics,
        }),
        Some((_, Err(e))) => Err(RegistryError::File(e)),
        None => Err(RegistryError::Unknown {
            name: name.to_string(),
            choices: robot_names(),
        }),
    }
}

/// The robot names the suite lists, in a fixed order: the Rust models, then the robot files
/// (built-in by file name, then those registered at run time), valid or not. The n-link family
/// (`nlink-<n>`, module documentation) is not listed.
pub fn robot_names() -> Vec<String> {
    RUST_MODELS
        .iter()
        .map(|n| n.to_string())
        .chain(
            builtin_models()
                .iter()
                .map(|(s, _)| s.to_string())
                .filter(|s| !is_rust_model(s)),
        )
        .chain(
            runtime_files()
                .iter()
                .filter(|(_, _, m)| !matches!(m, Err(e) if matches!(**e, RobotFileError::Shadows { .. })))
                .map(|(s, _, _)| s.clone()),
        )
        .collect()
}

/// The names of the robots with rigid-body dynamics (H, c, g), which the acceleration-level
/// zhang2018 scheme needs: the Jaco2 family, then the URDF robot files registered at run time
/// whose every moving joint carries an inertial.
pub fn robots_with_dynamics() -> Vec<String> {
    RUST_MODELS
        .iter()
        .filter(|n| rust_model(n).is_some_and(|m| m.dynamics.is_some()))
        .map(|n| n.to_string())
        .chain(runtime_files().iter().filter_map(|(s, _, m)| match m {
            Ok(FileArm::Urdf(robot, _, _)) if robot.has_inertials() => Some(s.clone()),
            _ => None,
        }))
        .collect()
}

impl Model {
    /// The model's name.
    pub fn name(&self) -> &str {
        self.robot.name()
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.robot.dof()
    }

    /// Whether the model has rigid-body dynamics (H, c, g).
    pub fn has_dynamics(&self) -> bool {
        self.dynamics.is_some()
    }

    /// `theta`, or an error naming both counts.
    fn angles<'a>(&self, theta: &'a [f64]) -> Result<&'a [f64], JointCountError> {
        if theta.len() != self.dof() {
            return Err(JointCountError {
                robot: self.name().to_string(),
                given: theta.len(),
                joints: self.dof(),
            });
        }
        Ok(theta)
    }

    /// The arm's points from the base to the task point at joint angles `theta` (see
    /// [`Robot::skeleton`]); an error if `theta` does not have [`Self::dof`] entries.
    pub fn skeleton(&self, theta: &[f64]) -> Result<Vec<Vector3<f64>>, JointCountError> {
        Ok(self.robot.skeleton(self.angles(theta)?))
    }

    /// Tip position and the singular values of J at `theta`, largest first (the check values
    /// `reproduce robots` prints); an error if `theta` does not have [`Self::dof`] entries.
    pub fn check_values(&self, theta: &[f64]) -> Result<(Vector3<f64>, Vec<f64>), JointCountError> {
        let theta = self.angles(theta)?;
        let j = self.robot.jacobian_matrix(theta);
        let mut sv: Vec<f64> = j.singular_values().iter().copied().collect();
        sv.sort_by(|a, b| b.total_cmp(a));
        Ok((self.robot.position(theta), sv))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_builds_the_model_of_that_name() {
        let names = robot_names();
        assert!(names.iter().any(|n| n == "panda"));
        assert!(names.iter().any(|n| n == "puma560"));
        for name in names
            .iter()
            .cloned()
            .chain(["nlink-2", "nlink-4", "nlink-200"].map(String::from))
        {
            let robot = robot_by_name(&name).unwrap();
            assert_eq!(robot.name(), name);
            assert_eq!(robot.stated_pose.len(), robot.dof());
            let points = robot.skeleton(&vec![0.1; robot.dof()]).unwrap();
            assert!(points.len() >= 2);
            assert!(robot.skeleton(&vec![0.1; robot.dof() + 1]).is_err());
        }
        for unknown in ["puma", "nlink-1", "nlink-0", "nlink-x", "nlink-1001"] {
            let error = robot_by_name(unknown).unwrap_err().to_string();
            assert!(
                error.contains("unknown robot") && error.contains("puma560"),
                "{error}"
            );
        }
        let unique: std::collections::BTreeSet<&String> = names.iter().collect();
        assert_eq!(unique.len(), names.len(), "names are unique");
    }

    #[test]
    fn an_nlink_name_has_one_spelling() {
        assert_eq!(robot_by_name("nlink-2").unwrap().dof(), 2);
        assert_eq!(robot_by_name("nlink-1000").unwrap().dof(), 1000);
        for (name, n) in [("nlink-02", 2), ("nlink-007", 7), ("nlink-0100", 100)] {
            let error = robot_by_name(name).unwrap_err();
            assert!(
                matches!(error, RegistryError::NLinkSpelling { n: m } if m == n),
                "{name}: {error}"
            );
            let message = error.to_string();
            assert!(
                message.contains(&format!("\"nlink-{n}\""))
                    && message.contains("without leading zeros")
                    && !message.contains(name),
                "{message}"
            );
        }
        // A sign, or a spelling of no arm of the family, is no robot.
        for name in [
            "nlink-+2",
            "nlink- 2",
            "nlink-00",
            "nlink-01",
            "nlink-01001",
            "nlink-",
        ] {
            assert!(
                matches!(robot_by_name(name), Err(RegistryError::Unknown { .. })),
                "{name}"
            );
        }
        // Nor may a robot file take another spelling of an arm's name.
        let puma = crate::data_robot::builtin_files()
            .iter()
            .find(|(f, _)| *f == "puma560.toml")
            .unwrap()
            .1
            .replace("name = \"puma560\"", "name = \"nlink-03\"");
        register_file::<&str>(
            std::path::Path::new("papers/x/robots/nlink-03.toml"),
            Ok(&puma),
        );
        let error = robot_by_name("nlink-03").unwrap_err().to_string();
        assert!(
            error.contains("papers/x/robots/nlink-03.toml") && error.contains("another spelling"),
            "{error}"
        );
        assert_eq!(robot_by_name("nlink-3").unwrap().dof(), 3);
    }

    #[test]
    fn puma560_is_a_data_robot_with_check_values() {
        let puma = robot_by_name("puma560").unwrap();
        assert!(!puma.has_dynamics());
        assert_eq!(puma.dof(), 6);
        assert_eq!(
            puma.stated_pose,
            [0.0, -PI / 4.0, 0.0, PI / 2.0, -PI / 4.0, 0.0]
        );
        let (tip, sv) = puma.check_values(&puma.stated_pose).unwrap();
        assert!(
            (tip - Vector3::new(0.653136683891, -0.110275243558, 0.013770732342)).norm() < 1e-11
        );
        assert_eq!(sv.len(), 3);
        assert!(puma.check_values(&[0.0; 5]).is_err());
    }

    #[test]
    fn data_twins_of_rust_models_state_the_same_pose_and_check_values() {
        for (name, model) in builtin_models() {
            let model = model.as_ref().unwrap();
            if !is_rust_model(name) {
                continue;
            }
            let rust = robot_by_name(name).unwrap();
            let pose = &rust.stated_pose;
            let close = |a: &[f64], b: &[f64]| {
                a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
            };
            assert!(close(pose, model.stated_pose()), "{name}");
            let data = data_model(model.clone(), None);
            let (tip_r, sv_r) = rust.check_values(pose).unwrap();
            let (tip_d, sv_d) = data.check_values(pose).unwrap();
            assert!((tip_r - tip_d).norm() < 1e-12, "{name}");
            assert!(close(&sv_r, &sv_d), "{name}");
        }
    }

    #[test]
    fn runtime_files_are_validated_and_may_not_shadow() {
        let puma = crate::data_robot::builtin_files()
            .iter()
            .find(|(f, _)| *f == "puma560.toml")
            .unwrap()
            .1;
        let own = puma.replace("name = \"puma560\"", "name = \"registry-test-arm\"");
        let bad = puma
            .replace("name = \"puma560\"", "name = \"registry-test-bad\"")
            .replacen("theta_max = 2.7751", "theta_max = -9.0", 1);
        register_file::<&str>(
            std::path::Path::new("papers/x/robots/registry-test-arm.toml"),
            Ok(&own),
        );
        register_file::<&str>(
            std::path::Path::new("papers/x/robots/registry-test-bad.toml"),
            Ok(&bad),
        );
        register_file(
            std::path::Path::new("papers/x/robots/registry-test-gone.toml"),
            Err("a symbolic link out of its directory"),
        );
        // A model name no other test looks up (the registry is one per process).
        register_file::<&str>(
            std::path::Path::new("papers/x/robots/nlink-999.toml"),
            Ok(&own),
        );
        assert_eq!(robot_by_name("registry-test-arm").unwrap().dof(), 6);
        let error = robot_by_name("registry-test-bad").unwrap_err().to_string();
        assert!(
            error.contains("papers/x/robots/registry-test-bad.toml") && error.contains("theta"),
            "{error}"
        );
        let error = robot_by_name("registry-test-gone").unwrap_err().to_string();
        assert!(error.contains("symbolic link"), "{error}");
        let error = robot_by_name("nlink-999").unwrap_err().to_string();
        assert!(error.contains("papers/x/robots/nlink-999.toml"), "{error}");
        let names = robot_names();
        assert!(names.iter().any(|n| n == "registry-test-bad"));
        assert!(!names.iter().any(|n| n == "nlink-999"));
        assert!(robot_by_name("puma560").is_ok(), "other robots still work");
    }
}
