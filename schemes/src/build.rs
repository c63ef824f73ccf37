//! Building a scheme from its specification (crate `spec`: [`spec::SchemeSpec`], the
//! presets, and [`spec::ComposedSpec`], the term lists they expand to): each term's
//! specification becomes its term ([`crate::terms`]) and the list one [`Composed`] scheme.

use std::sync::Arc;

use nalgebra::Vector3;
use robots::{Dynamics, Robot};
use spec::{tracking_axes, ComposedSpec, Penalty, Task, TermSpec};
use spec::{Level, RepetitiveForm, SchemeError, SchemeSpec};

use crate::composed::Composed;
use crate::paths::Path;
use crate::scheme::Scheme;
use crate::terms::acceleration_limits::AccelerationLimits;
use crate::terms::bound_conversion::BoundConversion;
use crate::terms::drift_damping::DriftDamping;
use crate::terms::infinity_norm::InfinityNorm;
use crate::terms::joint_norm::JointNorm;
use crate::terms::repetitive::{Form, Repetitive};
use crate::terms::torque_norm::TorqueNorm;
use crate::terms::tracking::{rotation_exp, Feedback, Tracking};
use crate::terms::velocity_limits::VelocityLimits;
use crate::terms::Term;

/// Builds the scheme a spec names, on `robot` following `path`: the composed scheme of its
/// terms ([`SchemeSpec::expand`]).
///
/// `theta_ref` is the scheme's joint reference: theta0 (the run's initial joint vector) for
/// jia2019, zhong2021 and zhang2018; theta*0 (the desired initial joint vector) for kong2019.
/// A scheme with a torque term (zhang2018) needs `dynamics` (and takes its kinematics from it;
/// it must model the same robot, checked by name); the others ignore it.
pub fn build_scheme(
    spec: &SchemeSpec,
    robot: Arc<dyn Robot>,
    dynamics: Option<Arc<dyn Dynamics>>,
    path: Arc<dyn Path>,
    theta_ref: &[f64],
) -> Result<Box<dyn Scheme>, SchemeError> {
    spec.validate()?;
    let scheme = build_composed(
        &spec.expand(),
        spec.kind(),
        spec.scheme_name(),
        robot,
        dynamics,
        path,
        theta_ref,
    )?;
    Ok(Box::new(scheme))
}

/// Builds the scheme `name` of the terms `composed` lists (checked first) on `robot` following `path`,
/// with the joint reference `theta_ref` (one entry per joint); errors name the scheme by
/// its `kind` tag. A scheme with a torque term
/// needs `dynamics`, a model of the same robot by name, and takes its kinematics from it.
pub fn build_composed(
    composed: &ComposedSpec,
    kind: &'static str,
    name: String,
    robot: Arc<dyn Robot>,
    dynamics: Option<Arc<dyn Dynamics>>,
    path: Arc<dyn Path>,
    theta_ref: &[f64],
) -> Result<Composed, SchemeError> {
    composed.validate()?;
    let (robot, dynamics) = if composed.needs_dynamics() {
        let dynamics = dynamics.ok_or(SchemeError::MissingDynamics { scheme: kind })?;
        if dynamics.name() != robot.name() {
            return Err(SchemeError::RobotMismatch {
                scheme: kind,
                robot: robot.name().to_string(),
                dynamics: dynamics.name().to_string(),
            });
        }
        (dynamics.clone() as Arc<dyn Robot>, Some(dynamics))
    } else {
        (robot, None)
    };
    let n = robot.dof();
    if theta_ref.len() != n {
        return Err(SchemeError::ReferenceLength {
            joints: n,
            given: theta_ref.len(),
        });
    }
    let terms = composed
        .terms
        .iter()
        .enumerate()
        .map(|(index, spec)| -> Result<Box<dyn Term>, SchemeError> {
            Ok(match *spec {
                TermSpec::VelocityNorm { weight } => Box::new(JointNorm {
                    joints: n,
                    weight,
                    level: Level::Velocity,
                }),
                TermSpec::AccelerationNorm { weight } => Box::new(JointNorm {
                    joints: n,
                    weight,
                    level: Level::Acceleration,
                }),
                TermSpec::Repetitive {
                    form,
                    lambda,
                    alpha,
                    weight,
                    squared,
                } => Box::new(Repetitive {
                    theta_ref: theta_ref.to_vec(),
                    weight,
                    lambda,
                    form: match form {
                        RepetitiveForm::Linear => Form::Linear,
                        RepetitiveForm::SignPower => Form::SignPower {
                            alpha: alpha.unwrap_or(1.0),
                        },
                    },
                    squared,
                }),
                TermSpec::DriftDamping {
                    alpha,
                    beta,
                    weight,
                } => Box::new(DriftDamping {
                    theta0: theta_ref.to_vec(),
                    weight,
                    alpha,
                    beta,
                }),
                TermSpec::TorqueNorm { weight } => Box::new(TorqueNorm::new(
                    dynamics
                        .clone()
                        .expect("checked: a torque term has dynamics"),
                    weight,
                )),
                TermSpec::InfinityNorm {
                    weight,
                    penalty,
                    varpi,
                } => Box::new(InfinityNorm {
                    squared: penalty == Penalty::Squared,
                    joints: n,
                    weight,
                    varpi,
                }),
                TermSpec::Tracking {
                    task,
                    ref axes,
                    k_p,
                    rho_v,
                    rho_p,
                    orientation,
                } => {
                    let feedback = match composed.level {
                        Level::Velocity => Feedback::Velocity {
                            k_p: k_p.unwrap_or(0.0),
                        },
                        Level::Acceleration => Feedback::Acceleration {
                            rho_v: rho_v.unwrap_or(f64::NAN),
                            rho_p: rho_p.unwrap_or(f64::NAN),
                        },
                    };
                    let axes = tracking_axes(task, axes);
                    if task != Some(Task::Pose) {
                        Box::new(Tracking::new(robot.clone(), path.clone(), axes, feedback))
                    } else {
                        let no_orientation = || SchemeError::NoOrientation {
                            index,
                            robot: robot.name().to_string(),
                        };
                        let target = match orientation {
                            Some(phi) => rotation_exp(&Vector3::from(phi)),
                            None => robot
                                .orientation()
                                .ok_or_else(no_orientation)?
                                .tool_rotation(theta_ref),
                        };
                        Box::new(
                            Tracking::with_orientation(
                                robot.clone(),
                                path.clone(),
                                axes,
                                feedback,
                                target,
                            )
                            .map_err(|_| no_orientation())?,
                        )
                    }
                }
                TermSpec::BoundConversion { gain } => Box::new(BoundConversion {
                    robot: robot.clone(),
                    gain,
                }),
                TermSpec::VelocityLimits => Box::new(VelocityLimits {
                    robot: robot.clone(),
                }),
                TermSpec::AccelerationLimits {
                    a_max,
                    velocity_gain,
                } => Box::new(AccelerationLimits {
                    robot: robot.clone(),
                    a_max,
                    velocity_gain,
                }),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Composed::new(
        name,
        composed.level,
        n,
        composed.bounds,
        terms,
    ))
}
