//! The arm between two ticks, integrated exactly for a command held over the tick (a
//! zero-order hold, as a controller applies it).
//!
//! Velocity level (the command is thetadot): theta(t_k + h) = theta_k + h u, thetadot = u.
//! Acceleration level (the command is thetaddot):
//! theta(t_k + h) = theta_k + h thetadot_k + (h^2 / 2) u, thetadot(t_k + h) = thetadot_k + h u.
//! Both are the exact solutions of the arm's kinematic ODE (theta' = u, resp. theta'' = u) for
//! constant u: no integration error.

use spec::Level;

/// Advances (theta, thetadot) over one tick of length `h` under the held `command` (its first
/// N entries; the rest of the QP's x is not a joint command).
pub fn advance(level: Level, h: f64, theta: &mut [f64], thetadot: &mut [f64], command: &[f64]) {
    for i in 0..theta.len() {
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SVector;

    #[test]
    fn a_held_acceleration_moves_the_arm_along_its_parabola() {
        let (mut theta, mut thetadot) = (
            SVector::<f64, 2>::new(0.1, -0.2),
            SVector::<f64, 2>::new(0.5, 0.0),
        );
        advance(
            Level::Acceleration,
            0.01,
            theta.as_mut_slice(),
            thetadot.as_mut_slice(),
            &[2.0, -4.0, 9.0],
        );
        assert!((theta[0] - (0.1 + 0.005 + 0.0001)).abs() < 1e-15);
        assert!((theta[1] - (-0.2 - 0.0002)).abs() < 1e-15);
        assert_eq!(thetadot, SVector::<f64, 2>::new(0.52, -0.04));
        advance(
            Level::Velocity,
            0.01,
            theta.as_mut_slice(),
            thetadot.as_mut_slice(),
            &[1.0, 1.0],
        );
        assert_eq!(thetadot, SVector::<f64, 2>::new(1.0, 1.0));
    }
}
