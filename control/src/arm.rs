//! The arm between two ticks, integrated exactly for a command held over the tick (a
//! zero-order hold, as a controller applies it).
//!
//! Velocity level (the command is thetadot): theta(t_k + h) = theta_k + h u, thetadot = u.
//! Acceleration level (the command is thetaddot):
//! theta(t_k + h) = theta_k + h thetadot_k + (h^2 / 2) u, thetadot(t_k + h) = thetadot_k + h u.
//! Both are the exact solutions of the arm's kinematic ODE (theta' = u, resp. theta'' = u) for
//! constant u: no integration error.

use nalgebra::SVector;
use schemes::scheme::Level;

/// Advances (theta, thetadot) over one tick of length `h` under the held `command` (its first
/// N entries; the rest of the QP's x is not a joint command).
pub fn advance<const N: usize>(
    level: Level,
    h: f64,
    theta: &mut SVector<f64, N>,
    thetadot: &mut SVector<f64, N>,
    command: &[f64],
) {
    for i in 0..N {
        let u = command[i];
        match level {
            Level::Velocity => {
                thetadot[i] = u;
                theta[i] += h * u;
            }
            Level::Acceleration => {
                theta[i] += h * thetadot[i] + 0.5 * h * h * u;
                thetadot[i] += h * u;
            }
        }
    }
}
