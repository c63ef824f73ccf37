//! Running one [`RunSpec`] of an experiment file: build its robot (from the registry), path,
//! scheme and solver from the file's specifications, then [`simulate`] them.

use crate::error::RunError;
use crate::simulate::{simulate, Outcome, Run, Settings, Solver};
use nalgebra::DVector;
use qp::QpDims;
use robots::{robot_by_name, Model};
use robots::{Dynamics, Robot};
use robots::{Mount, Mounted};
use schemes::build_scheme;
use schemes::paths::{build_path, Cyclic, Path};
use schemes::Scheme;
use settings::SolverSpec;
use solvers::neural::NeuralSolver;
use solvers::ode::OdeStats;
use solvers::ExactPathStats;
use spec::JobPart;
use spec::RunSpec;
use spec::SetupError;
use spec::SolverChoice;
use std::sync::Arc;

/// A job and what its simulation produced.
#[derive(Clone, Debug)]
pub struct RunRecord {
    /// The job that was run.
    pub job: RunSpec,
    /// What its simulation produced.
    pub run: Run,
}

/// Builds a network written outside the suite for the QP sizes of a task's scheme.
/// Its error is the run's setup error ([`SetupError::CustomNetwork`] for its own message).
pub type NetworkBuilder<'a> = &'a dyn Fn(QpDims) -> Result<Box<dyn NeuralSolver>, SetupError>;

/// The suite's network `spec` for the QPs (of sizes `dims`) of the scheme named `scheme`; the
/// error names the network and the scheme.
pub fn build_network(
    spec: &SolverSpec,
    dims: QpDims,
    scheme: &str,
) -> Result<Box<dyn NeuralSolver>, SetupError> {
    solvers::neural::build_solver(spec, dims).map_err(|error| SetupError::Network {
        network: spec.display_name(),
        scheme: scheme.to_string(),
        error,
    })
}

/// Runs one job to completion or failure; never panics on bad numerics.
pub fn run_job(job: &RunSpec) -> RunRecord {
    run_job_as(job, None)
}

/// Runs the task of `job` (robot, path, scheme, poses, integrator, scoring, network start) with
/// the network `network` builds in place of the job's solver, as [`run_job`] runs the job's own
/// (a network written outside the suite, e.g. in Python). The record keeps `job` as given.
pub fn run_job_with_network(job: &RunSpec, network: NetworkBuilder<'_>) -> RunRecord {
    run_job_as(job, Some(network))
}

fn run_job_as(job: &RunSpec, network: Option<NetworkBuilder<'_>>) -> RunRecord {
    let result = job_model(job)
        .map_err(RunError::from)
        .and_then(|model| run_with(job, network, model));
    let run = result.unwrap_or_else(|error| Run {
        scheme_name: job.scheme.display_name(),
        outcome: Outcome::Failed {
            t: 0.0,
            error,
            partial: None,
        },
        stats: OdeStats::default(),
        qp: ExactPathStats::default(),
        score_failures: 0,
        observe_seconds: 0.0,
        trace: Vec::new(),
        iterations: None,
    });
    RunRecord {
        job: job.clone(),
        run,
    }
}

/// Builds everything a run builds before integrating (robot, path from f(theta_ref), scheme,
/// and the network for the scheme's QP sizes) without integrating anything, so that an
/// experiment file is rejected, once loaded and before anything runs, for exactly what would
/// make its run fail at t = 0 (the orchestrator checks every run of the files with it). The
/// error names the part (and so the file's field) and the builder's own message.
pub fn check_job(job: &RunSpec) -> Result<(), SetupError> {
    let model = job_model(job)?;
    let joints = model.dof();
    for (part, v) in [
        (JobPart::Theta0, &job.theta0),
        (JobPart::ThetaRef, &job.theta_ref),
    ] {
        if v.len() != joints {
            return Err(SetupError::PoseLength {
                part,
                given: v.len(),
                joints,
            });
        }
        if v.iter().any(|x| !x.is_finite()) {
            return Err(SetupError::PoseNotFinite { part });
        }
    }
    let robot = job_robot(job, model.robot, model.dynamics.is_some())?;
    let (_, scheme) = build_parts(job, robot, model.dynamics)?;
    match &job.solver {
        SolverChoice::Neural(spec) => {
            build_network(spec, scheme.dims(), &scheme.name())?;
            honours_constraints(spec, &*scheme, job)?;
        }
        SolverChoice::Numerical(spec) => {
            solvers::registry::check(spec.method.id(), &spec.settings())
                .map_err(|e| SetupError::QpSolver(e.to_string()))?;
        }
        SolverChoice::Exact => {}
    }
    Ok(())
}

/// Refuses a network that solves only the equality part of a QP (not
/// [`SolverSpec::handles_inequalities`]) on a scheme whose QP has inequality rows or finite
/// bounds: its answer would not be the scheme's QP's. The QP is the scheme's at t = 0 from
/// theta0 at rest (its constraint types do not change along a run).
fn honours_constraints(
    spec: &SolverSpec,
    scheme: &dyn Scheme,
    job: &RunSpec,
) -> Result<(), SetupError> {
    if spec.handles_inequalities() {
        return Ok(());
    }
    let mut qp = scheme.new_qp();
    let rest = vec![0.0; job.theta0.len()];
    scheme.build(0.0, &job.theta0, &rest, &mut qp);
    let bounds = qp
        .lower
        .iter()
        .chain(qp.upper.iter())
        .filter(|v| v.is_finite())
        .count();
    let rows = qp.dims().n_in;
    if rows + bounds == 0 {
        return Ok(());
    }
    Err(SetupError::ConstraintsIgnored {
        network: spec.display_name(),
        scheme: job.scheme.display_name(),
        rows,
        bounds,
    })
}

/// The registry's model of the job's robot, with the job's tool offset and base where it gives
/// them ([`robots::Mounted`]); the error names the valid choices, or the robot's invalid file
/// and field, or why the mount does not fit the robot. A mounted model keeps its dynamics only
/// for a scheme that needs them, where a base that tilts gravity is refused
/// ([`spec::MountError::TiltedGravity`]).
pub fn job_model(job: &RunSpec) -> Result<Model, SetupError> {
    let model = robot_by_name(&job.robot).map_err(|e| SetupError::UnknownRobot(e.to_string()))?;
    let Some(mount) = job_mount(job)? else {
        return Ok(model);
    };
    let dynamics = match model.dynamics {
        Some(d) if job.scheme.needs_dynamics() => {
            Some(Arc::new(Mounted::with_dynamics(d, mount)?) as Arc<dyn Dynamics>)
        }
        _ => None,
    };
    Ok(Model {
        robot: Arc::new(Mounted::new(model.robot, mount)?),
        dynamics,
        ..model
    })
}

/// The job's mount built from its tool offset and base ([`Mount::new`]: entries finite and
/// within their bounds); `None` for the robot as it is.
pub fn job_mount(job: &RunSpec) -> Result<Option<Mount>, SetupError> {
    job.mount
        .map(|m| Mount::new(m.tool, m.xyz, m.rpy))
        .transpose()
        .map_err(SetupError::Mount)
}

/// The shape of the QP the job's scheme poses at every instant: its sizes and whether its
/// decision variable starts with thetadot or thetaddot ([`spec::Level`]). Built as
/// [`check_job`] builds the scheme (robot, path from f(theta_ref), scheme), without running.
pub fn qp_shape(job: &RunSpec) -> Result<(QpDims, spec::Level), SetupError> {
    let model = job_model(job)?;
    let robot = job_robot(job, model.robot, model.dynamics.is_some())?;
    let (_, scheme) = build_parts(job, robot, model.dynamics)?;
    Ok((scheme.dims(), scheme.level()))
}

/// The job's robot: the registry's model `robot`, with the job's `joint_limits` and
/// `velocity_limits` in place of its own where the job gives them ([`robots::Limited`]).
/// A model that carries dynamics (`has_dynamics`: the acceleration-level scheme takes its
/// kinematics and limits from the dynamics model) keeps its own limits: overriding them is an
/// error rather than a silent half-override.
pub fn job_robot(
    job: &RunSpec,
    robot: Arc<dyn Robot>,
    has_dynamics: bool,
) -> Result<Arc<dyn Robot>, SetupError> {
    if job.joint_limits.is_none() && job.velocity_limits.is_none() {
        return Ok(robot);
    }
    if has_dynamics && job.scheme.needs_dynamics() {
        return Err(SetupError::LimitsWithDynamics {
            robot: job.robot.clone(),
        });
    }
    let joints = robot.dof();
    let mut limits = robot.limits().clone();
    let set = |spec: &Option<spec::LimitsSpec>,
               lo: &mut DVector<f64>,
               hi: &mut DVector<f64>|
     -> Result<(), SetupError> {
        if let Some(l) = spec {
            if l.lower.len() != joints || l.upper.len() != joints {
                return Err(SetupError::PoseLength {
                    part: JobPart::Limits,
                    given: l.lower.len().max(l.upper.len()),
                    joints,
                });
            }
            *lo = DVector::from_column_slice(&l.lower);
            *hi = DVector::from_column_slice(&l.upper);
        }
        Ok(())
    };
    set(
        &job.joint_limits,
        &mut limits.theta_min,
        &mut limits.theta_max,
    )?;
    set(
        &job.velocity_limits,
        &mut limits.thetadot_min,
        &mut limits.thetadot_max,
    )?;
    let limited = robots::Limited::new(robot, limits).expect("limits checked per joint");
    Ok(Arc::new(limited))
}

/// The path (starting at f(theta_ref)) and the scheme of a run.
#[allow(clippy::type_complexity)]
pub(crate) fn build_parts(
    job: &RunSpec,
    robot: Arc<dyn Robot>,
    dynamics: Option<Arc<dyn Dynamics>>,
) -> Result<(Arc<dyn Path>, Box<dyn Scheme>), SetupError> {
    build_cyclic_parts(job, robot, dynamics, 1)
}

/// `build_parts` with the job's path repeated `cycles` times ([`Cyclic`]; the path itself
/// when `cycles` is 1), the scheme built on the repeated path.
#[allow(clippy::type_complexity)]
pub fn build_cyclic_parts(
    job: &RunSpec,
    robot: Arc<dyn Robot>,
    dynamics: Option<Arc<dyn Dynamics>>,
    cycles: usize,
) -> Result<(Arc<dyn Path>, Box<dyn Scheme>), SetupError> {
    let theta_ref = &job.theta_ref;
    if theta_ref.len() != robot.dof() {
        return Err(SetupError::PoseLength {
            part: JobPart::ThetaRef,
            given: theta_ref.len(),
            joints: robot.dof(),
        });
    }
    let start = robot.position(theta_ref);
    let once = build_path(&job.path, start)?;
    let path: Arc<dyn Path> = if cycles > 1 {
        Arc::new(Cyclic::new(once, cycles))
    } else {
        Arc::from(once)
    };
    let scheme = build_scheme(
        &job.scheme,
        robot.clone(),
        dynamics,
        path.clone(),
        theta_ref,
    )
    .map_err(|error| {
        let hint = match error {
            spec::SchemeError::MissingDynamics { .. } => format!(
                " (robot \"{}\" is kinematic only; robots with dynamics: {})",
                job.robot,
                robots::robots_with_dynamics().join(", ")
            ),
            _ => String::new(),
        };
        SetupError::Scheme { error, hint }
    })?;
    Ok((path, scheme))
}

fn run_with(
    job: &RunSpec,
    custom: Option<NetworkBuilder<'_>>,
    model: Model,
) -> Result<Run, RunError> {
    let robot = job_robot(job, model.robot, model.dynamics.is_some())?;
    let (path, scheme) = build_parts(job, robot.clone(), model.dynamics)?;
    let dims = scheme.dims();
    let scheme_name = scheme.name();
    let network = |spec: &SolverSpec| build_network(spec, dims, &scheme_name);
    let (build, build_custom);
    let solver = match (custom, &job.solver) {
        (Some(custom), _) => {
            build_custom = move || custom(dims);
            Solver::Network(&build_custom)
        }
        (None, SolverChoice::Exact) => Solver::Exact,
        (None, SolverChoice::Neural(spec)) => {
            build = move || network(spec);
            Solver::Network(&build)
        }
        (None, SolverChoice::Numerical(spec)) => Solver::Numerical(spec),
    };
    let settings = Settings {
        integrator: job.integrator,
        scoring: job.scoring,
        network_init: job.network_init,
    };
    simulate(
        robot.as_ref(),
        path.as_ref(),
        scheme.as_ref(),
        solver,
        &job.theta0,
        &job.theta_ref,
        &settings,
    )
}
