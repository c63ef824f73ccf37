//! Franka Emika Panda, 7 revolute joints, from Franka's published kinematic parameters.
//!
//! Source: Franka Control Interface documentation, "Robot and interface specifications"
//! (`frankaemika.github.io/docs/control_parameters.html`), which gives the arm in *modified*
//! (Craig) DH convention: row `i` is the transform `Rx(alpha_i) Tx(a_i) Rz(theta_i) Tz(d_i)`
//! from frame `i-1` to frame `i`, and a fixed flange row follows joint 7:
//!
//! | row    | a (m)   | d (m) | alpha  |
//! |--------|---------|-------|--------|
//! | 1      | 0       | 0.333 | 0      |
//! | 2      | 0       | 0     | -pi/2  |
//! | 3      | 0       | 0.316 | pi/2   |
//! | 4      | 0.0825  | 0     | pi/2   |
//! | 5      | -0.0825 | 0.384 | -pi/2  |
//! | 6      | 0       | 0     | pi/2   |
//! | 7      | 0.088   | 0     | pi/2   |
//! | flange | 0       | 0.107 | 0      |
//!
//! The task point is the flange centre: the origin of the flange frame, 0.107 m along z of
//! frame 7 (no hand or tool attached). The world frame is Franka's base frame 0.
//!
//! The modified chain is evaluated through its equivalent classical chain
//! ([`DhChain::from_modified`], mathematics in [`crate::dh`]): base `Rx(0) Tx(0) = I`, classical
//! links `(a, alpha, d)` = `(0, -pi/2, 0.333)`, `(0, pi/2, 0)`, `(0.0825, pi/2, 0.316)`,
//! `(-0.0825, -pi/2, 0)`, `(0, pi/2, 0.384)`, `(0.088, pi/2, 0)`, `(0, 0, 0)`, and the flange
//! at `(0, 0, 0.107)` in classical frame 7. So `f(theta) = T_7(theta) (0, 0, 0.107)`, its
//! Jacobian is the geometric `J_j = z_{j-1} x (f - o_{j-1})` and `Jdot` its analytic time
//! derivative ([`crate::geometric_jacobian`]), on one DH code path shared with the Jaco2.
//!
//! Joint limits, same datasheet: `q_min = [-2.8973, -1.7628, -2.8973, -3.0718, -2.8973,
//! -0.0175, -2.8973]`, `q_max = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973]` rad,
//! `|qdot| <= [2.1750, 2.1750, 2.1750, 2.1750, 2.6100, 2.6100, 2.6100]` rad/s.
//!
//! Check values (asserted in `tests/panda.rs` against an independent 4 x 4 transcription of
//! the modified-DH table): the flange centre is at `(0.088, 0, 0.926)` at `q = 0` and at
//! `(0.306890566593, 0, 0.590282052303)` m at [`Panda::READY`]; the singular values of the 3 x 7
//! Jacobian at `READY` are `0.581091162405, 0.514564079411, 0.255511614757`.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

use nalgebra::DVector;

use crate::data_robot::DataRobot;
use crate::dh::{DhChain, ModifiedDhParam};
use crate::JointLimits;

/// Model name of the Franka Emika Panda (flange centre).
pub const PANDA: &str = "panda";

/// Franka's modified-DH rows 1..=7 as `(a, alpha, d)` (m, rad).
pub const PANDA_MDH: [ModifiedDhParam; 7] = [
    ModifiedDhParam::new(0.0, 0.0, 0.333),
    ModifiedDhParam::new(0.0, -FRAC_PI_2, 0.0),
    ModifiedDhParam::new(0.0, FRAC_PI_2, 0.316),
    ModifiedDhParam::new(0.0825, FRAC_PI_2, 0.0),
    ModifiedDhParam::new(-0.0825, -FRAC_PI_2, 0.384),
    ModifiedDhParam::new(0.0, FRAC_PI_2, 0.0),
    ModifiedDhParam::new(0.088, FRAC_PI_2, 0.0),
];

/// Franka's flange row (`a = 0, d = 0.107, alpha = 0`).
pub const PANDA_FLANGE: ModifiedDhParam = ModifiedDhParam::new(0.0, 0.0, 0.107);

/// Lower joint-angle limits (rad), Franka's datasheet.
pub const Q_MIN: [f64; 7] = [
    -2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973,
];
/// Upper joint-angle limits (rad), Franka's datasheet.
pub const Q_MAX: [f64; 7] = [2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973];
/// Joint-velocity limits (rad/s), Franka's datasheet; the lower limits are their negatives.
pub const QDOT_MAX: [f64; 7] = [2.1750, 2.1750, 2.1750, 2.1750, 2.6100, 2.6100, 2.6100];

/// The Panda: Franka's modified-DH table as a [`DataRobot`] built in code, task point the
/// flange centre.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Panda;

impl Panda {
    /// Franka's "ready" pose `q = [0, -pi/4, 0, -3pi/4, 0, pi/2, pi/4]` (rad).
    pub const READY: [f64; 7] = [
        0.0,
        -FRAC_PI_4,
        0.0,
        -3.0 * FRAC_PI_4,
        0.0,
        FRAC_PI_2,
        FRAC_PI_4,
    ];

    /// The Panda from Franka's modified-DH table (the equivalent classical chain, module
    /// documentation), task point the flange centre `(0, 0, 0.107)` in classical frame 7,
    /// Franka's limits, check values stated at [`Panda::READY`].
    pub fn model() -> DataRobot {
        let (chain, flange) = DhChain::from_modified(&PANDA_MDH, PANDA_FLANGE);
        DataRobot::from_chain(
            PANDA,
            chain,
            flange,
            JointLimits {
                theta_min: DVector::from_column_slice(&Q_MIN),
                theta_max: DVector::from_column_slice(&Q_MAX),
                thetadot_min: -DVector::from_column_slice(&QDOT_MAX),
                thetadot_max: DVector::from_column_slice(&QDOT_MAX),
            },
            Self::READY.to_vec(),
        )
    }
}
