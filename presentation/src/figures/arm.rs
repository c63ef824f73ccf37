//! The arm's motion for panel (a): the arm's skeleton (base, joint origins, task point, see
//! [`robots::Robot::skeleton`]) at a few instants evenly spaced in time, projected on the x-y
//! plane, as the papers draw it under the end-effector path.

use super::trace::Trace;
use records::RunRow;
use robots::robot_by_name;

/// Number of poses drawn, the first at t = 0 and the last at the end of the trace.
pub const POSES: usize = 12;

/// The arm's x-y polylines at [`POSES`] instants evenly spaced over the trace, the start pose
/// first. Empty for a robot the suite does not know or a trace whose joint count does not fit
/// the robot: the panel then draws no arm.
pub fn poses(run: &RunRow, trace: &Trace) -> Vec<Vec<(f64, f64)>> {
    let Ok(robot) = robot_by_name(&run.robot) else {
        return Vec::new();
    };
    trace
        .spread(POSES)
        .into_iter()
        .map(|k| robot.skeleton(&trace.theta_at(k)))
        .map(|points| points.map(|p| p.iter().map(|q| (q.x, q.y)).collect()))
        .collect::<Result<_, _>>()
        .unwrap_or_default()
}
