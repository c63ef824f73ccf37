//! The numbers of a task, computed by the suite's own models, that someone setting the same task
//! up in their own code checks theirs against (the task cards of `reproduce::task_card`):
//! the robot's limits, the task point and Jacobian at theta0, the path at a few instants, and
//! the scheme's QP at t = 0 (at the velocity level at theta0; at the acceleration level at
//! theta0 with thetadot = 0).

use crate::run::build_parts;
use crate::run::job_model;
use qp::Qp;
use spec::JobPart;
use spec::Level;
use spec::PathSample;
use spec::RunSpec;
use spec::SetupError;

/// Instants of the path samples, as fractions of the duration T.
pub const PATH_FRACTIONS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// The numbers of a task (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TaskNumbers {
    /// The robot's joint count n.
    pub joints: usize,
    /// theta-, theta+, thetadot-, thetadot+ per joint (infinite where unlimited).
    pub theta_min: Vec<f64>,
    /// Upper joint-angle limits theta+ (rad).
    pub theta_max: Vec<f64>,
    /// Lower joint-velocity limits thetadot- (rad/s).
    pub thetadot_min: Vec<f64>,
    /// Upper joint-velocity limits thetadot+ (rad/s).
    pub thetadot_max: Vec<f64>,
    /// f(theta0), and J(theta0) by rows.
    pub position0: [f64; 3],
    /// J(theta0), 3 rows of n entries.
    pub jacobian0: Vec<Vec<f64>>,
    /// f(theta_ref), where the path starts.
    pub path_start: [f64; 3],
    /// The path at `PATH_FRACTIONS` of T.
    pub path: Vec<PathSample>,
    /// The scheme's name, level and QP at t = 0.
    pub scheme: String,
    /// The scheme's level.
    pub level: Level,
    /// The scheme's terms, one line each ([`schemes::Scheme::terms`]).
    pub terms: Vec<String>,
    /// The scheme's QP at t = 0 (at theta0, with thetadot = 0 at the acceleration level).
    pub qp0: Qp,
}

/// The numbers of `job`'s task (its robot, path, scheme and poses; solver and integrator play
/// no part).
pub fn task_numbers(job: &RunSpec) -> Result<TaskNumbers, SetupError> {
    let model = job_model(job)?;
    let joints = model.dof();
    if job.theta0.len() != joints {
        return Err(SetupError::PoseLength {
            part: JobPart::Theta0,
            given: job.theta0.len(),
            joints,
        });
    }
    let theta0 = &job.theta0[..];
    let theta_ref = &job.theta_ref[..];
    let robot = crate::run::job_robot(job, model.robot, model.dynamics.is_some())?;
    let (path, scheme) = build_parts(job, robot.clone(), model.dynamics)?;
    let mut qp0 = Qp::zeros(scheme.dims());
    scheme.build(0.0, theta0, &vec![0.0; joints], &mut qp0);
    let point = |v: nalgebra::Vector3<f64>| [v.x, v.y, v.z];
    let limits = robot.limits();
    let jacobian = robot.jacobian_matrix(theta0);
    Ok(TaskNumbers {
        joints,
        theta_min: limits.theta_min.as_slice().to_vec(),
        theta_max: limits.theta_max.as_slice().to_vec(),
        thetadot_min: limits.thetadot_min.as_slice().to_vec(),
        thetadot_max: limits.thetadot_max.as_slice().to_vec(),
        position0: point(robot.position(theta0)),
        jacobian0: jacobian
            .row_iter()
            .map(|r| r.iter().copied().collect())
            .collect(),
        path_start: point(robot.position(theta_ref)),
        path: PATH_FRACTIONS
            .iter()
            .map(|f| {
                let t = f * job.path.duration;
                let p = path.at(t);
                PathSample {
                    t,
                    r: point(p.r),
                    rdot: point(p.rdot),
                    rddot: point(p.rddot),
                }
            })
            .collect(),
        scheme: scheme.name(),
        level: scheme.level(),
        terms: scheme.terms(),
        qp0,
    })
}
