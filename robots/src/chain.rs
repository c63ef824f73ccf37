//! A serial kinematic chain of runtime size ([`Chain`]): revolute, continuous and prismatic
//! joints with fixed origin transforms, limits and optional link inertials; forward kinematics
//! of a tool frame, the geometric Jacobian and its time derivative, and the rigid-body dynamics
//! `H(theta) thetaddot + c(theta, thetadot) + g(theta) = tau`, all evaluated into a
//! [`ChainWorkspace`] allocated once, so that no call allocates.
//!
//! A chain is what a URDF describes ([`crate::urdf`]) and what a DH table is a special case of
//! ([`Chain::from_dh`]).
//!
//! # Frames
//!
//! The world frame is `W`; the chain's base `B` is a fixed transform from `W`. Joint `i`
//! (`1..=n`) has a fixed origin `O_i` (rotation and translation from the frame of the body
//! before it, the base for `i = 1`), a unit axis `a_i` in its own frame, and a motion
//! `M_i(q_i)`: the rotation by `q_i` about `a_i` (revolute, continuous) or the translation
//! `q_i a_i` (prismatic). The frame of body `i` (the link joint `i` moves) is
//!
//! ```text
//! F_0 = B,    F_i = F_{i-1} O_i M_i(q_i),
//! ```
//!
//! and the tool frame is `T = F_n X` with `X` a fixed transform in the last body's frame; the
//! tool point `p` is the origin of `T`. In world coordinates (rotation `R_i` of `F_i`, origin
//! `o_i`) joint `i`'s axis is `z_i = R_i a_i` (a rotation about `a_i` leaves `a_i` fixed, so
//! `z_i` is also `R(F_{i-1} O_i) a_i`: it is fixed in body `i - 1` and in body `i`).
//!
//! # Jacobian
//!
//! The geometric Jacobian `J` (6 x n, rows `[v; omega]`: the tool point's linear velocity and
//! the tool frame's angular velocity, both in world axes) has columns
//!
//! ```text
//! revolute, continuous:  J_i = [ z_i x (p - o_i) ;  z_i ]
//! prismatic:             J_i = [ z_i             ;  0   ]
//! ```
//!
//! and the position Jacobian is its first three rows. Along `thetadot`, with
//! `omega_i = sum_{k <= i, k revolute} thetadot_k z_k` the angular velocity of body `i`,
//! `v_i` the velocity of `o_i` (`v_0 = 0`,
//! `v_i = v_{i-1} + omega_{i-1} x (o_i - o_{i-1}) + [i prismatic] thetadot_i z_i`),
//! `pdot = J_v thetadot` and `zdot_i = omega_{i-1} x z_i`:
//!
//! ```text
//! revolute:   Jdot_i = [ zdot_i x (p - o_i) + z_i x (pdot - v_i) ;  zdot_i ]
//! prismatic:  Jdot_i = [ zdot_i                                   ;  0      ]
//! ```
//!
//! # Dynamics
//!
//! Body `i` has mass `m_i`, centre of mass `c_i` and inertia `I_i` about the centre of mass,
//! in `F_i`; in world coordinates `p_ci = o_i + R_i c_i`, `I_i^w = R_i I_i R_i'`. A joint with
//! no inertial moves a massless body. The recursive Newton–Euler algorithm, in world
//! coordinates, with gravity `g0` (default `(0, 0, -9.81)` m/s^2 in the world frame) entered as
//! a base acceleration `a_0 = -g0` and `omega_0 = alpha_0 = 0`:
//!
//! ```text
//! forward, i = 1..n, r_i = o_i - o_{i-1}:
//!   omega_i = omega_{i-1} + [rev] qd_i z_i
//!   alpha_i = alpha_{i-1} + [rev] (qdd_i z_i + qd_i omega_{i-1} x z_i)
//!   a_i     = a_{i-1} + alpha_{i-1} x r_i + omega_{i-1} x (omega_{i-1} x r_i)
//!             + [pris] (qdd_i z_i + 2 qd_i omega_{i-1} x z_i)          (acceleration of o_i)
//!   a_ci    = a_i + alpha_i x (p_ci - o_i) + omega_i x (omega_i x (p_ci - o_i))
//!   F_i = m_i a_ci,   N_i = I_i^w alpha_i + omega_i x (I_i^w omega_i)
//! backward, i = n..1 (f_{n+1} = n_{n+1} = 0; moments about o_i):
//!   f_i = F_i + f_{i+1}
//!   n_i = N_i + (p_ci - o_i) x F_i + n_{i+1} + (o_{i+1} - o_i) x f_{i+1}
//!   tau_i = z_i . n_i (revolute),   tau_i = z_i . f_i (prismatic)
//! ```
//!
//! Then `tau = RNEA(q, qd, qdd, g0) = H qdd + c + g`, so
//! `g(q) = RNEA(q, 0, 0, g0)` (the gradient of the potential `U = -sum m_i g0 . p_ci`) and
//! `c(q, qd) = RNEA(q, qd, 0, 0)`.
//!
//! `H(q)` (column `j` would be `RNEA(q, 0, e_j, 0)`) comes from the composite-rigid-body
//! algorithm, in `O(n^2)` small steps instead of `n` passes of the recursion. The bodies
//! `j..n` held rigid form a composite of mass `M_j`, first moment `h_j = sum m_k p_ck` and
//! inertia about the world origin `J_j = sum (I_k^w + m_k (|p_ck|^2 E - p_ck p_ck'))`, added up
//! from the tip. At rest, a unit acceleration of joint `j` alone needs on the composite the
//! force and moment about `o_j`
//!
//! ```text
//! revolute:   f = z_j x (h_j - M_j o_j),   n = J_j(o_j) z_j,
//!             J_j(o) = J_j + (M_j |o|^2 - 2 o . h_j) E - (M_j o o' - h_j o' - o h_j')
//! prismatic:  f = M_j z_j,                  n = (h_j - M_j o_j) x z_j,
//! ```
//!
//! (`J_j(o)` is the composite's inertia about `o`, by the parallel-axis theorem written without
//! dividing by the mass), and for `i <= j` the torque at joint `i` is
//! `H_ij = H_ji = z_i . (n + (o_j - o_i) x f)` (revolute `i`) or `z_i . f` (prismatic `i`).
//! `H` is symmetric positive definite when every body has positive mass and a positive definite
//! inertia.
//!
//! # From DH tables
//!
//! A classical DH link `A_i = Rz(theta_i + offset_i) Tz(d_i) Tx(a_i) Rx(alpha_i)` is a
//! revolute joint about `z` whose fixed part `D_i = Tz(d_i) Tx(a_i) Rx(alpha_i)` follows the
//! motion: the chain has `O_1 = Rz(offset_1)`, `O_{i+1} = D_i Rz(offset_{i+1})`, axes `z`, and
//! `X = D_n Trans(tool)`. A modified (Craig) row `Rx(alpha_i) Tx(a_i) Rz(theta_i + offset_i)
//! Tz(d_i)` with the flange row `Rx(alpha_f) Tx(a_f) Tz(d_f)` gives
//! `O_1 = Rx(alpha_1) Tx(a_1) Rz(offset_1)`, `O_{i+1} = Tz(d_i) Rx(alpha_{i+1}) Tx(a_{i+1})
//! Rz(offset_{i+1})` and `X = Tz(d_n) Rx(alpha_f) Tx(a_f) Tz(d_f) Trans(tool)`. A robot file
//! gives a link's inertia in its DH frame: frame `i` of the table is `F_i D_i` (standard) or
//! `F_i Tz(d_i)` (modified), so the centre of mass and inertia are carried into `F_i` by that
//! fixed transform ([`Chain::from_dh`]).

use nalgebra::{DMatrix, DVector, Dyn, Matrix3, MatrixView, Rotation3, Unit, Vector3, U1, U3};

use crate::dh::Frame;
use crate::rigid_body::RigidBody;
use crate::robot_file::{Convention, RobotSpec};

/// Standard gravity in the world frame (m/s^2), the default of [`Chain::gravity`].
pub const DEFAULT_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// What a joint does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A rotation about the axis, between position limits (rad).
    Revolute,
    /// A rotation about the axis without position limits.
    Continuous,
    /// A translation along the axis (m).
    Prismatic,
}

impl JointKind {
    /// Whether the joint rotates (revolute or continuous).
    pub fn rotates(self) -> bool {
        !matches!(self, JointKind::Prismatic)
    }
}

/// The limits of one joint, infinite where unlimited. Units are rad (revolute, continuous) or
/// m (prismatic), per second, per second squared; effort is N m or N.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointRange {
    /// Lower position limit.
    pub position_min: f64,
    /// Upper position limit.
    pub position_max: f64,
    /// Lower velocity limit (< 0).
    pub velocity_min: f64,
    /// Upper velocity limit (> 0).
    pub velocity_max: f64,
    /// Symmetric acceleration limit (> 0).
    pub acceleration_max: f64,
    /// Symmetric effort limit (> 0).
    pub effort_max: f64,
}

impl JointRange {
    /// No limit on anything.
    pub const UNLIMITED: JointRange = JointRange {
        position_min: f64::NEG_INFINITY,
        position_max: f64::INFINITY,
        velocity_min: f64::NEG_INFINITY,
        velocity_max: f64::INFINITY,
        acceleration_max: f64::INFINITY,
        effort_max: f64::INFINITY,
    };
}

/// One joint of a [`Chain`] and the body it moves (module documentation, "Frames").
#[derive(Clone, Debug, PartialEq)]
pub struct ChainJoint {
    /// The joint's name (from the URDF, or `joint <i>` for a DH table).
    pub name: String,
    /// `O_i`: the joint's frame at zero motion, in the frame of the body before it.
    pub origin: Frame,
    /// What the joint does.
    pub kind: JointKind,
    /// `a_i`: the axis in the joint's frame (unit after [`Chain::new`]).
    pub axis: Vector3<f64>,
    /// The joint's limits.
    pub limits: JointRange,
    /// The inertial of the body the joint moves, in the joint's frame `F_i` (`None`: massless).
    pub body: Option<RigidBody>,
}

/// Why a chain was not built ([`Chain::new`]); joints are named and numbered from 1.
#[derive(Debug, thiserror::Error)]
pub enum ChainError {
    /// No joint between base and tool.
    #[error("a chain needs at least one moving joint")]
    NoJoints,
    /// A number of the chain is NaN or infinite where it must be finite.
    #[error("joint {index} ({}): {field} is not finite", settings::shown(name))]
    NotFinite {
        /// The joint, from 1.
        index: usize,
        /// Its name.
        name: String,
        /// The field: `origin`, `axis`, `mass`, `center of mass` or `inertia`.
        field: &'static str,
    },
    /// A joint's axis has zero length.
    #[error("joint {index} ({}): the axis has zero length", settings::shown(name))]
    ZeroAxis {
        /// The joint, from 1.
        index: usize,
        /// Its name.
        name: String,
    },
    /// A joint's limits are inconsistent.
    #[error("joint {index} ({}): {problem}", settings::shown(name))]
    Limits {
        /// The joint, from 1.
        index: usize,
        /// Its name.
        name: String,
        /// What is wrong.
        problem: &'static str,
    },
    /// A body's inertial is not physical.
    #[error("joint {index} ({}): the body's {problem}", settings::shown(name))]
    Inertial {
        /// The joint, from 1.
        index: usize,
        /// Its name.
        name: String,
        /// What is wrong.
        problem: &'static str,
    },
    /// The tool transform has a non-finite entry.
    #[error("the tool transform is not finite")]
    ToolNotFinite,
}

/// A serial chain of runtime size (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    base: Frame,
    joints: Vec<ChainJoint>,
    tool: Frame,
    gravity: Vector3<f64>,
}

/// Whether a frame's entries are all finite.
fn finite_frame(f: &Frame) -> bool {
    f.rot.iter().chain(f.origin.iter()).all(|x| x.is_finite())
}

/// A translation.
fn translation(x: f64, y: f64, z: f64) -> Frame {
    Frame {
        rot: Matrix3::identity(),
        origin: Vector3::new(x, y, z),
    }
}

/// A rotation by `angle` about the unit `axis`.
fn rotation(axis: &Vector3<f64>, angle: f64) -> Matrix3<f64> {
    Rotation3::from_axis_angle(&Unit::new_unchecked(*axis), angle).into_inner()
}

/// An inertial expressed in frame `A` carried into frame `F` where `A = F X`.
fn carry(body: RigidBody, x: &Frame) -> RigidBody {
    RigidBody {
        mass: body.mass,
        com: x.transform_point(&body.com),
        inertia: x.rot * body.inertia * x.rot.transpose(),
    }
}

impl Chain {
    /// A chain of `joints` from the base (identity) to the tool frame `tool` (in the last body's
    /// frame), with gravity `DEFAULT_GRAVITY`. Axes are normalised (divided by their largest
    /// entry, then by their length, so that no finite axis overflows); refused: no joint,
    /// non-finite numbers, a zero axis, empty position ranges or non-positive velocity,
    /// acceleration or effort limits, a negative mass, an inertia that is not symmetric
    /// positive semi-definite (to 1e-12 relative), a continuous joint with position limits.
    pub fn new(mut joints: Vec<ChainJoint>, tool: Frame) -> Result<Chain, ChainError> {
        if joints.is_empty() {
            return Err(ChainError::NoJoints);
        }
        if !finite_frame(&tool) {
            return Err(ChainError::ToolNotFinite);
        }
        for (k, j) in joints.iter_mut().enumerate() {
            let index = k + 1;
            let not_finite = |field| ChainError::NotFinite {
                index,
                name: j.name.clone(),
                field,
            };
            if !finite_frame(&j.origin) {
                return Err(not_finite("origin"));
            }
            if !j.axis.iter().all(|x| x.is_finite()) {
                return Err(not_finite("axis"));
            }
            // Scaled by its largest entry before squaring, so that neither a huge axis
            // (`1e308 1e308 0`, whose squares overflow) nor a tiny one (whose squares
            // underflow) loses its direction.
            let largest = j.axis.amax();
            if largest == 0.0 {
                return Err(ChainError::ZeroAxis {
                    index,
                    name: j.name.clone(),
                });
            }
            let scaled = j.axis / largest;
            j.axis = scaled / scaled.norm();
            let r = &j.limits;
            let limit_problem = if r.position_min.is_nan() || r.position_max.is_nan() {
                Some("a position limit is NaN")
            } else if r.position_min >= r.position_max {
                Some("the lower position limit is not below the upper")
            } else if j.kind == JointKind::Continuous
                && (r.position_min.is_finite() || r.position_max.is_finite())
            {
                Some("a continuous joint has no position limits")
            } else if !(r.velocity_min < 0.0 && r.velocity_max > 0.0) {
                Some("the velocity limits must be < 0 (lower) and > 0 (upper)")
            } else if !(r.acceleration_max > 0.0 && r.effort_max > 0.0) {
                Some("the acceleration and effort limits must be > 0")
            } else {
                None
            };
            if let Some(problem) = limit_problem {
                return Err(ChainError::Limits {
                    index,
                    name: j.name.clone(),
                    problem,
                });
            }
            if let Some(b) = &j.body {
                if !b.mass.is_finite() {
                    return Err(not_finite("mass"));
                }
                if !b.com.iter().all(|x| x.is_finite()) {
                    return Err(not_finite("center of mass"));
                }
                if !b.inertia.iter().all(|x| x.is_finite()) {
                    return Err(not_finite("inertia"));
                }
                let problem = if b.mass < 0.0 {
                    Some("mass is negative")
                } else if !is_psd(&b.inertia) {
                    Some("inertia is not symmetric positive semi-definite")
                } else {
                    None
                };
                if let Some(problem) = problem {
                    return Err(ChainError::Inertial {
                        index,
                        name: j.name.clone(),
                        problem,
                    });
                }
            }
        }
        Ok(Chain {
            base: Frame::identity(),
            joints,
            tool,
            gravity: Vector3::from(DEFAULT_GRAVITY),
        })
    }

    /// The chain of a validated robot file's DH table (module documentation, "From DH
    /// tables"): revolute joints about `z`, the file's base, offsets, limits (`effort_max`
    /// unlimited) and link inertias (carried from the DH frames into the joints' frames), the
    /// tool point as the tool frame's origin (axes of the last DH frame, or of the flange).
    pub fn from_dh(spec: &RobotSpec) -> Result<Chain, ChainError> {
        let rz = |angle: f64| Frame::rotation(rotation(&Vector3::z(), angle));
        let rx = |angle: f64| Frame::rotation(rotation(&Vector3::x(), angle));
        let rows = spec.joints();
        // Per joint: the fixed part before the joint (after the previous joint's motion), and
        // the fixed part `D` from the joint's frame to the DH frame its link inertia is in.
        let (before, after): (Vec<Frame>, Vec<Frame>) = rows
            .iter()
            .map(|j| {
                let r = j.row;
                match spec.convention() {
                    Convention::Standard => (
                        rz(j.offset),
                        translation(0.0, 0.0, r.d)
                            .compose(&translation(r.a, 0.0, 0.0))
                            .compose(&rx(r.alpha)),
                    ),
                    Convention::Modified => (
                        rx(r.alpha)
                            .compose(&translation(r.a, 0.0, 0.0))
                            .compose(&rz(j.offset)),
                        translation(0.0, 0.0, r.d),
                    ),
                }
            })
            .unzip();
        let mut previous = Frame::identity();
        let joints = rows
            .iter()
            .enumerate()
            .map(|(i, j)| {
                let origin = previous.compose(&before[i]);
                previous = after[i];
                ChainJoint {
                    name: format!("joint {}", i + 1),
                    origin,
                    kind: JointKind::Revolute,
                    axis: Vector3::z(),
                    limits: JointRange {
                        position_min: j.theta_min,
                        position_max: j.theta_max,
                        velocity_min: j.velocity_min,
                        velocity_max: j.velocity_max,
                        acceleration_max: j.acceleration_max,
                        effort_max: f64::INFINITY,
                    },
                    body: j.link.map(|l| {
                        let [xx, yy, zz, xy, yz, xz] = l.inertia;
                        carry(
                            RigidBody {
                                mass: l.mass,
                                com: Vector3::from(l.center_of_mass),
                                inertia: Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz),
                            },
                            &after[i],
                        )
                    }),
                }
            })
            .collect();
        let flange = spec.flange().map_or_else(Frame::identity, |f| {
            rx(f.alpha)
                .compose(&translation(f.a, 0.0, 0.0))
                .compose(&translation(0.0, 0.0, f.d))
        });
        let t = spec.tool();
        let tool = previous
            .compose(&flange)
            .compose(&translation(t.x, t.y, t.z));
        Ok(Chain::new(joints, tool)?.with_base(spec.base()))
    }

    /// The same chain with the base transform `base` (world from the base frame).
    pub fn with_base(self, base: Frame) -> Chain {
        Chain { base, ..self }
    }

    /// The same chain with the tool frame `tool` (in the last body's frame).
    pub fn with_tool(self, tool: Frame) -> Chain {
        Chain { tool, ..self }
    }

    /// The same chain with gravity `gravity` (world frame, m/s^2).
    pub fn with_gravity(self, gravity: Vector3<f64>) -> Chain {
        Chain { gravity, ..self }
    }

    /// The number of joints `n`.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The joints, base to tip.
    pub fn joints(&self) -> &[ChainJoint] {
        &self.joints
    }

    /// The base transform `B`.
    pub fn base(&self) -> &Frame {
        &self.base
    }

    /// The tool frame `X` in the last body's frame.
    pub fn tool(&self) -> &Frame {
        &self.tool
    }

    /// The gravity acceleration `g0` in the world frame (m/s^2).
    pub fn gravity(&self) -> Vector3<f64> {
        self.gravity
    }

    /// A workspace for this chain's size: every buffer the evaluations use, allocated here once.
    pub fn workspace(&self) -> ChainWorkspace {
        let n = self.dof();
        ChainWorkspace {
            frames: vec![Frame::identity(); n],
            axes: vec![Vector3::zeros(); n],
            tool: Frame::identity(),
            com: vec![Vector3::zeros(); n],
            inertia: vec![Matrix3::zeros(); n],
            force: vec![Vector3::zeros(); n],
            moment: vec![Vector3::zeros(); n],
            jacobian: DMatrix::zeros(6, n),
            jacobian_dot: DMatrix::zeros(6, n),
            mass_matrix: DMatrix::zeros(n, n),
            torque: DVector::zeros(n),
        }
    }

    /// Forward kinematics into `ws`: body frames, joint axes, the tool frame.
    fn kinematics(&self, ws: &mut ChainWorkspace, theta: &[f64]) {
        let n = self.dof();
        assert_eq!(
            theta.len(),
            n,
            "joint vector of length {} for a chain of {n} joints",
            theta.len()
        );
        assert_eq!(
            ws.frames.len(),
            n,
            "workspace of {} joints for a chain of {n} joints",
            ws.frames.len()
        );
        let mut f = self.base;
        for (i, j) in self.joints.iter().enumerate() {
            f = f.compose(&j.origin);
            let z = f.rot * j.axis;
            f = match j.kind {
                JointKind::Revolute | JointKind::Continuous => Frame {
                    rot: f.rot * rotation(&j.axis, theta[i]),
                    origin: f.origin,
                },
                JointKind::Prismatic => Frame {
                    rot: f.rot,
                    origin: f.origin + z * theta[i],
                },
            };
            ws.frames[i] = f;
            ws.axes[i] = z;
        }
        ws.tool = f.compose(&self.tool);
    }

    /// The tool frame `T = F_n X` in world coordinates at `theta` (origin: the tool point).
    pub fn tool_pose(&self, ws: &mut ChainWorkspace, theta: &[f64]) -> Frame {
        self.kinematics(ws, theta);
        ws.tool
    }

    /// The tool point `p(theta)` in world coordinates.
    pub fn tool_position(&self, ws: &mut ChainWorkspace, theta: &[f64]) -> Vector3<f64> {
        self.tool_pose(ws, theta).origin
    }

    /// The world frames `F_1 .. F_n` of the bodies at `theta` (for drawing and checks).
    pub fn body_frames<'w>(&self, ws: &'w mut ChainWorkspace, theta: &[f64]) -> &'w [Frame] {
        self.kinematics(ws, theta);
        &ws.frames
    }

    /// The geometric Jacobian `J(theta)` (6 x n: linear rows, then angular; module
    /// documentation).
    pub fn jacobian<'w>(&self, ws: &'w mut ChainWorkspace, theta: &[f64]) -> &'w DMatrix<f64> {
        self.kinematics(ws, theta);
        let p = ws.tool.origin;
        for (i, j) in self.joints.iter().enumerate() {
            let z = ws.axes[i];
            let (v, w) = if j.kind.rotates() {
                (z.cross(&(p - ws.frames[i].origin)), z)
            } else {
                (z, Vector3::zeros())
            };
            ws.jacobian.fixed_view_mut::<3, 1>(0, i).copy_from(&v);
            ws.jacobian.fixed_view_mut::<3, 1>(3, i).copy_from(&w);
        }
        &ws.jacobian
    }

    /// The position Jacobian `dp/dtheta` (3 x n): the first three rows of [`Chain::jacobian`].
    pub fn position_jacobian<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
    ) -> MatrixView<'w, f64, U3, Dyn, U1, Dyn> {
        self.jacobian(ws, theta).fixed_rows::<3>(0)
    }

    /// The tool point `p(theta)` and the geometric Jacobian (6 x n) from one evaluation of the
    /// kinematics (what [`Chain::tool_position`] and [`Chain::jacobian`] give).
    pub fn tool_position_and_jacobian<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
    ) -> (Vector3<f64>, &'w DMatrix<f64>) {
        self.jacobian(ws, theta);
        (ws.tool.origin, &ws.jacobian)
    }

    /// The time derivative `dJ/dt` (6 x n) along `thetadot` (module documentation).
    pub fn jacobian_dot<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
        thetadot: &[f64],
    ) -> &'w DMatrix<f64> {
        assert_eq!(
            thetadot.len(),
            self.dof(),
            "velocity vector of the wrong length"
        );
        self.jacobian(ws, theta);
        let p = ws.tool.origin;
        let mut pdot = Vector3::zeros();
        for (i, qd) in thetadot.iter().enumerate() {
            pdot += ws.jacobian.fixed_view::<3, 1>(0, i) * *qd;
        }
        let mut omega = Vector3::zeros();
        let mut v = Vector3::zeros();
        let mut o_prev = self.base.origin;
        for (i, j) in self.joints.iter().enumerate() {
            let z = ws.axes[i];
            let o = ws.frames[i].origin;
            let zdot = omega.cross(&z);
            v += omega.cross(&(o - o_prev));
            let (dv, dw) = if j.kind.rotates() {
                (zdot.cross(&(p - o)) + z.cross(&(pdot - v)), zdot)
            } else {
                v += z * thetadot[i];
                (zdot, Vector3::zeros())
            };
            if j.kind.rotates() {
                omega += z * thetadot[i];
            }
            ws.jacobian_dot.fixed_view_mut::<3, 1>(0, i).copy_from(&dv);
            ws.jacobian_dot.fixed_view_mut::<3, 1>(3, i).copy_from(&dw);
            o_prev = o;
        }
        &ws.jacobian_dot
    }

    /// World centres of mass and inertia tensors of the bodies, from the frames in `ws`.
    fn masses(&self, ws: &mut ChainWorkspace) {
        for (i, j) in self.joints.iter().enumerate() {
            let f = &ws.frames[i];
            let (com, inertia) = j
                .body
                .as_ref()
                .map_or((Vector3::zeros(), Matrix3::zeros()), |b| (b.com, b.inertia));
            ws.com[i] = f.transform_point(&com);
            ws.inertia[i] = f.rot * inertia * f.rot.transpose();
        }
    }

    /// The recursive Newton–Euler algorithm (module documentation) on the frames and masses in
    /// `ws`, with base acceleration `a0`; writes `tau` into `ws.torque`.
    fn rnea(
        &self,
        ws: &mut ChainWorkspace,
        qd: Option<&[f64]>,
        qdd: Option<&[f64]>,
        a0: Vector3<f64>,
    ) {
        let mut omega = Vector3::<f64>::zeros();
        let mut alpha = Vector3::<f64>::zeros();
        let mut acc = a0;
        let mut o_prev = self.base.origin;
        for (i, j) in self.joints.iter().enumerate() {
            let z = ws.axes[i];
            let o = ws.frames[i].origin;
            let (v, a) = (qd.map_or(0.0, |q| q[i]), qdd.map_or(0.0, |q| q[i]));
            let r = o - o_prev;
            acc += alpha.cross(&r) + omega.cross(&omega.cross(&r));
            if j.kind.rotates() {
                alpha += z * a + omega.cross(&z) * v;
                omega += z * v;
            } else {
                acc += z * a + omega.cross(&z) * (2.0 * v);
            }
            let rc = ws.com[i] - o;
            let acc_c = acc + alpha.cross(&rc) + omega.cross(&omega.cross(&rc));
            let mass = j.body.as_ref().map_or(0.0, |b| b.mass);
            let iw = &ws.inertia[i];
            ws.force[i] = acc_c * mass;
            ws.moment[i] = iw * alpha + omega.cross(&(iw * omega));
            o_prev = o;
        }
        let mut f = Vector3::<f64>::zeros();
        let mut n = Vector3::<f64>::zeros();
        let mut o_next = Vector3::<f64>::zeros();
        for (i, j) in self.joints.iter().enumerate().rev() {
            let o = ws.frames[i].origin;
            n += (o_next - o).cross(&f) + ws.moment[i] + (ws.com[i] - o).cross(&ws.force[i]);
            f += ws.force[i];
            ws.torque[i] = if j.kind.rotates() {
                ws.axes[i].dot(&n)
            } else {
                ws.axes[i].dot(&f)
            };
            o_next = o;
        }
    }

    /// Joint torques `tau = H qdd + c + g` (recursive Newton–Euler).
    pub fn inverse_dynamics<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
        thetadot: &[f64],
        thetaddot: &[f64],
    ) -> &'w DVector<f64> {
        self.dynamics_prelude(ws, theta, &[thetadot, thetaddot]);
        self.rnea(ws, Some(thetadot), Some(thetaddot), -self.gravity);
        &ws.torque
    }

    /// The joint-space inertia matrix `H(theta)` (n x n) by the composite-rigid-body algorithm
    /// (module documentation).
    pub fn inertia<'w>(&self, ws: &'w mut ChainWorkspace, theta: &[f64]) -> &'w DMatrix<f64> {
        self.dynamics_prelude(ws, theta, &[]);
        let mut mass = 0.0;
        let mut moment = Vector3::<f64>::zeros();
        let mut about_origin = Matrix3::<f64>::zeros();
        for (j, joint) in self.joints.iter().enumerate().rev() {
            let m = joint.body.as_ref().map_or(0.0, |b| b.mass);
            let c = ws.com[j];
            mass += m;
            moment += c * m;
            about_origin +=
                ws.inertia[j] + (Matrix3::identity() * c.norm_squared() - c * c.transpose()) * m;
            let (z, o) = (ws.axes[j], ws.frames[j].origin);
            let offset = moment - o * mass;
            let (f, n) = if joint.kind.rotates() {
                let about_o = about_origin
                    + Matrix3::identity() * (mass * o.norm_squared() - 2.0 * o.dot(&moment))
                    - (o * o.transpose() * mass - moment * o.transpose() - o * moment.transpose());
                (z.cross(&offset), about_o * z)
            } else {
                (z * mass, offset.cross(&z))
            };
            for (i, joint_i) in self.joints[..=j].iter().enumerate() {
                let h = if joint_i.kind.rotates() {
                    ws.axes[i].dot(&(n + (o - ws.frames[i].origin).cross(&f)))
                } else {
                    ws.axes[i].dot(&f)
                };
                ws.mass_matrix[(i, j)] = h;
                ws.mass_matrix[(j, i)] = h;
            }
        }
        &ws.mass_matrix
    }

    /// Coriolis and centrifugal torques `c(theta, thetadot) = RNEA(q, qd, 0, 0)`.
    pub fn coriolis<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
        thetadot: &[f64],
    ) -> &'w DVector<f64> {
        self.dynamics_prelude(ws, theta, &[thetadot]);
        self.rnea(ws, Some(thetadot), None, Vector3::zeros());
        &ws.torque
    }

    /// Gravity torques `g(theta) = RNEA(q, 0, 0, g0) = dU/dtheta`.
    pub fn gravity_torques<'w>(
        &self,
        ws: &'w mut ChainWorkspace,
        theta: &[f64],
    ) -> &'w DVector<f64> {
        self.dynamics_prelude(ws, theta, &[]);
        self.rnea(ws, None, None, -self.gravity);
        &ws.torque
    }

    /// Kinematics and world masses at `theta`; checks the other vectors' lengths.
    fn dynamics_prelude(&self, ws: &mut ChainWorkspace, theta: &[f64], vectors: &[&[f64]]) {
        for v in vectors {
            assert_eq!(v.len(), self.dof(), "joint vector of the wrong length");
        }
        self.kinematics(ws, theta);
        self.masses(ws);
    }
}

/// Whether `m` is symmetric and positive semi-definite, to 1e-12 relative to its largest entry.
fn is_psd(m: &Matrix3<f64>) -> bool {
    let scale = m.amax().max(f64::MIN_POSITIVE);
    if (m - m.transpose()).amax() > 1e-12 * scale {
        return false;
    }
    let sym = (m + m.transpose()) * 0.5;
    sym.symmetric_eigenvalues()
        .iter()
        .all(|&l| l >= -1e-12 * scale)
}

/// The buffers of a chain's evaluations ([`Chain::workspace`]): allocated once for a chain's
/// size, reused by every call. The results the evaluations return borrow from it.
///
/// # Panics
///
/// Every evaluation panics if the workspace was made for a chain with another number of
/// joints, or a joint vector has not [`Chain::dof`] entries: both are errors of the calling
/// code, not of any input file.
#[derive(Clone, Debug)]
pub struct ChainWorkspace {
    frames: Vec<Frame>,
    axes: Vec<Vector3<f64>>,
    tool: Frame,
    com: Vec<Vector3<f64>>,
    inertia: Vec<Matrix3<f64>>,
    force: Vec<Vector3<f64>>,
    moment: Vec<Vector3<f64>>,
    jacobian: DMatrix<f64>,
    jacobian_dot: DMatrix<f64>,
    mass_matrix: DMatrix<f64>,
    torque: DVector<f64>,
}

impl ChainWorkspace {
    /// The number of joints the workspace was made for.
    pub fn dof(&self) -> usize {
        self.frames.len()
    }
}
