//! The inertial parameters of the Jaco2's links, for its rigid-body dynamics (zhang2018's
//! torque-level criterion; [`crate::jaco2::jaco2_rigid_chain`] builds the arm's rigid chain from
//! them, and [`crate::Jaco2`] implements [`crate::Dynamics`] on it).
//!
//! Inertial parameters: Kinova's URDF cylinder approximations (`kinova_inertial.xacro`),
//! re-expressed in the DH frames of the **D6 = 0.16** chain (`docs/robots.md`). Because
//! the table belongs to the physical arm, the dynamics of *both* variants are computed on the
//! D6 = 0.16 chain with DH frame 0 as the (untilted) base and gravity `(0, 0, -9.81)` m/s^2 in
//! it: the `jaco2-pen` model's shorter D6, pen tip and base tilt only change the task point,
//! never `H`, `c` or `g`.
//!
//! `H`, `c`, `g` and the Christoffel-consistent Coriolis matrix `C` come from
//! [`crate::rigid_body::RigidChain`] (recursive Newton–Euler for `c`, `g` and inverse dynamics;
//! `H = sum (m Jv'Jv + Jw' I Jw)` and an analytic `C` with `c = C thetadot`, `Hdot - 2C` skew).
//!
//! Known deviation: the papers' group did not publish its Jaco2 inertial parameters.

use nalgebra::{Matrix3, Vector3};

use crate::rigid_body::RigidBody;

/// Standard gravity (m/s^2); gravity points along -z of DH frame 0.
pub const G0: f64 = 9.81;

/// Inertial parameters of Jaco2 links 1-6 (link 6 = hand) in the D6 = 0.16 DH frames.
pub fn jaco2_bodies() -> [RigidBody; 6] {
    let body = |mass: f64, com: [f64; 3], inertia: Matrix3<f64>| RigidBody {
        mass,
        com: Vector3::from(com),
        inertia,
    };
    let wrist = Matrix3::new(7.7e-5, 0.0, 0.0, 0.0, 1.26e-4, 2.8e-5, 0.0, 2.8e-5, 9.4e-5);
    [
        body(
            0.7477,
            [0.0, -0.05825, 0.0020],
            Matrix3::from_diagonal(&Vector3::new(1.520e-3, 5.98e-4, 1.520e-3)),
        ),
        body(
            0.99,
            [-0.2035, 0.0, 0.0116],
            Matrix3::from_diagonal(&Vector3::new(7.92e-4, 1.0502e-2, 1.0502e-2)),
        ),
        body(
            0.6763,
            [0.0, 0.0028, -0.0810],
            Matrix3::from_diagonal(&Vector3::new(1.420e-3, 1.420e-3, 3.04e-4)),
        ),
        body(0.426367, [0.0, 0.0, -0.0428], wrist),
        body(0.426367, [0.0, 0.0, -0.0427], wrist),
        body(
            0.99,
            [0.0, 0.0, -0.1000],
            Matrix3::from_diagonal(&Vector3::new(3.45e-4, 3.45e-4, 5.82e-4)),
        ),
    ]
}
