//! Classical Denavit–Hartenberg forward kinematics.
//!
//! Link `i` of a serial chain is described by `(a_i, alpha_i, d_i)` and its joint angle
//! `theta_i`; the homogeneous transform from frame `i-1` to frame `i` is
//!
//! ```text
//! A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)
//!     = [ cθ  -sθ cα   sθ sα   a cθ ]
//!       [ sθ   cθ cα  -cθ sα   a sθ ]
//!       [ 0    sα      cα      d    ]
//!       [ 0    0       0       1    ]
//! ```
//!
//! A chain may carry a fixed base transform `B` (e.g. the Jaco2 pen model's tilt), so frame `k`
//! in world coordinates is `T_k = B A_1 ... A_k`, with `T_0 = B`. Joint `i` rotates about the
//! z axis of frame `i-1`, through the origin of frame `i-1`.
//!
//! The frames of one evaluation are written into a buffer of `n` frames: the caller's
//! ([`DhChain::frames`]), or this thread's scratch buffer ([`DhChain::with_frames`]), grown to the
//! longest chain the thread has evaluated and reused, so evaluating a chain allocates nothing
//! after a thread's first evaluation.
//!
//! # Modified (Craig) DH
//!
//! A chain given in modified DH ([`ModifiedDhParam`], e.g. Franka's Panda) has link transforms
//! `M_i = Rx(alpha_i) Tx(a_i) Rz(theta_i) Tz(d_i)` (parameters of row `i` as the manufacturer
//! lists them: `alpha_i`, `a_i` precede the joint), followed by a fixed flange row
//! `F = Rx(alpha_f) Tx(a_f) Tz(d_f)`. Writing `M_i = S_i Z_i(theta_i)` with
//! `S_i = Rx(alpha_i) Tx(a_i)` and `Z_i = Rz(theta_i) Tz(d_i)`, and regrouping,
//!
//! ```text
//! M_1 ... M_N F = S_1 [Z_1 S_2] [Z_2 S_3] ... [Z_{N-1} S_N] [Z_N Rx(alpha_f) Tx(a_f)] Tz(d_f).
//! ```
//!
//! `Rx` and `Tx` commute (rotation about and translation along the same axis), so every bracket
//! `Rz(theta_i) Tz(d_i) Rx(alpha_{i+1}) Tx(a_{i+1}) = A(theta_i; a_{i+1}, alpha_{i+1}, d_i)` is a
//! classical DH link. Hence the equivalent classical chain ([`DhChain::from_modified`]) has
//! base `B = S_1`, links `(a_{i+1}, alpha_{i+1}, d_i)` for `i < N`, last link
//! `(a_f, alpha_f, d_N)`, and the flange origin at `(0, 0, d_f)` in classical frame `N`. Classical
//! frame `i` is modified frame `i` times `S_{i+1}`: its z axis is the axis of joint `i + 1`, as the
//! classical convention requires, and joint `i` still turns about `z_{i-1}` through `o_{i-1}`.

use nalgebra::{Matrix3, Vector3};
use std::cell::RefCell;

/// A rigid transform stored as a rotation matrix and a translation (the origin of the frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Orientation: columns are the frame's x, y, z axes in world coordinates.
    pub rot: Matrix3<f64>,
    /// Position of the frame's origin in world coordinates.
    pub origin: Vector3<f64>,
}

impl Frame {
    /// The identity transform.
    pub fn identity() -> Self {
        Frame {
            rot: Matrix3::identity(),
            origin: Vector3::zeros(),
        }
    }

    /// A pure rotation (origin at zero).
    pub fn rotation(rot: Matrix3<f64>) -> Self {
        Frame {
            rot,
            origin: Vector3::zeros(),
        }
    }

    /// The URDF pose `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`, `rpy = [roll, pitch, yaw]` (rad):
    /// the convention of a URDF `<origin>` and of an experiment's `base`.
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        let [roll, pitch, yaw] = rpy;
        let rot = |axis: Vector3<f64>, angle: f64| {
            nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(axis), angle)
                .into_inner()
        };
        Frame {
            rot: rot(Vector3::z(), yaw) * rot(Vector3::y(), pitch) * rot(Vector3::x(), roll),
            origin: Vector3::from(xyz),
        }
    }

    /// Composition `self * other` (apply `other` first, expressed in `self`).
    pub fn compose(&self, other: &Frame) -> Frame {
        Frame {
            rot: self.rot * other.rot,
            origin: self.origin + self.rot * other.origin,
        }
    }

    /// Maps a point given in this frame's coordinates to world coordinates.
    pub fn transform_point(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.origin + self.rot * p
    }

    /// The frame's z axis in world coordinates.
    pub fn z_axis(&self) -> Vector3<f64> {
        self.rot.column(2).into_owned()
    }
}

/// Classical DH parameters of one link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DhParam {
    /// Common-normal length (along x_i).
    pub a: f64,
    /// Twist about x_i.
    pub alpha: f64,
    /// Offset along z_{i-1}.
    pub d: f64,
}

impl DhParam {
    /// Creates the parameters `(a, alpha, d)`.
    pub const fn new(a: f64, alpha: f64, d: f64) -> Self {
        DhParam { a, alpha, d }
    }

    /// The link transform `A(theta) = Rz(theta) Tz(d) Tx(a) Rx(alpha)`, with
    /// `(sin alpha, cos alpha)` given (a chain computes them once).
    fn transform(&self, theta: f64, (sa, ca): (f64, f64)) -> Frame {
        let (st, ct) = theta.sin_cos();
        Frame {
            rot: Matrix3::new(ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca),
            origin: Vector3::new(self.a * ct, self.a * st, self.d),
        }
    }
}

/// Modified (Craig) DH parameters of one row: the transform of the row is
/// `Rx(alpha) Tx(a) Rz(theta) Tz(d)` (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModifiedDhParam {
    /// Length along the previous x axis, applied before the joint.
    pub a: f64,
    /// Twist about the previous x axis, applied before the joint.
    pub alpha: f64,
    /// Offset along the joint's own z axis, applied after the joint.
    pub d: f64,
}

impl ModifiedDhParam {
    /// Creates the parameters `(a, alpha, d)`.
    pub const fn new(a: f64, alpha: f64, d: f64) -> Self {
        ModifiedDhParam { a, alpha, d }
    }

    /// The fixed part `S = Rx(alpha) Tx(a)` that precedes the joint.
    fn prefix(&self) -> Frame {
        let (sa, ca) = self.alpha.sin_cos();
        Frame {
            rot: Matrix3::new(1.0, 0.0, 0.0, 0.0, ca, -sa, 0.0, sa, ca),
            origin: Vector3::new(self.a, 0.0, 0.0),
        }
    }
}

/// A serial chain of `n` revolute joints in classical DH convention with a fixed base transform.
#[derive(Clone, Debug, PartialEq)]
pub struct DhChain {
    /// Fixed transform from the world to DH frame 0.
    pub base: Frame,
    /// DH parameters of links 1..=n.
    params: Vec<DhParam>,
    /// `(sin alpha_i, cos alpha_i)` of each link, computed once with `params` (the twists are
    /// constant, so an evaluation takes the sines and cosines of the joint angles alone).
    twists: Vec<(f64, f64)>,
}

thread_local! {
    /// This thread's frames of [`DhChain::with_frames`] (module documentation).
    static SCRATCH: RefCell<Vec<Frame>> = const { RefCell::new(Vec::new()) };
}

impl DhChain {
    /// A chain whose DH frame 0 is the world frame.
    pub fn new(params: Vec<DhParam>) -> Self {
        let twists = params.iter().map(|p| p.alpha.sin_cos()).collect();
        DhChain {
            base: Frame::identity(),
            params,
            twists,
        }
    }

    /// The DH parameters of links 1..=n.
    pub fn params(&self) -> &[DhParam] {
        &self.params
    }

    /// The same chain premultiplied by a fixed base transform.
    pub fn with_base(self, base: Frame) -> Self {
        DhChain { base, ..self }
    }

    /// The number of joints n.
    pub fn dof(&self) -> usize {
        self.params.len()
    }

    /// The classical chain equivalent to the modified-DH rows `rows` followed by the fixed
    /// flange row `flange` (module documentation): returns the chain (base `Rx(alpha_1) Tx(a_1)`,
    /// links `(a_{i+1}, alpha_{i+1}, d_i)`, last link `(a_f, alpha_f, d_n)`) and the flange
    /// origin `(0, 0, d_f)` in classical frame `n`.
    pub fn from_modified(
        rows: &[ModifiedDhParam],
        flange: ModifiedDhParam,
    ) -> (Self, Vector3<f64>) {
        let n = rows.len();
        let params = (0..n)
            .map(|i| {
                let next = if i + 1 < n { rows[i + 1] } else { flange };
                DhParam::new(next.a, next.alpha, rows[i].d)
            })
            .collect();
        let base = rows.first().unwrap_or(&flange).prefix();
        (
            DhChain::new(params).with_base(base),
            Vector3::new(0.0, 0.0, flange.d),
        )
    }

    /// World-frame transforms `T_0 .. T_n` at the DH angles `q(0), ..., q(n - 1)`, written into
    /// `links` (length n).
    pub fn frames<'a>(&self, q: impl Fn(usize) -> f64, links: &'a mut [Frame]) -> ChainFrames<'a> {
        assert_eq!(links.len(), self.params.len(), "dh: one frame per link");
        let mut t = self.base;
        let links_params = self.params.iter().zip(self.twists.iter());
        for (i, (link, (p, twist))) in links.iter_mut().zip(links_params).enumerate() {
            t = t.compose(&p.transform(q(i), *twist));
            *link = t;
        }
        ChainFrames {
            base: self.base,
            links,
        }
    }

    /// Runs `f` on the frames at the DH angles `q` ([`DhChain::frames`]), held in this thread's
    /// scratch buffer (module documentation). `f` must not evaluate a chain itself.
    pub fn with_frames<R>(
        &self,
        q: impl Fn(usize) -> f64,
        f: impl FnOnce(&ChainFrames<'_>) -> R,
    ) -> R {
        SCRATCH.with(|scratch| {
            let mut buffer = scratch.borrow_mut();
            let n = self.params.len();
            if buffer.len() < n {
                buffer.resize(n, Frame::identity());
            }
            f(&self.frames(q, &mut buffer[..n]))
        })
    }
}

/// The world-frame transforms `T_0 = B, T_1, ..., T_n` of a chain at one configuration.
#[derive(Debug, PartialEq)]
pub struct ChainFrames<'a> {
    base: Frame,
    links: &'a [Frame],
}

impl ChainFrames<'_> {
    /// The number of joints n.
    pub fn dof(&self) -> usize {
        self.links.len()
    }

    /// Frame `k` for `k` in `0..=n` (frame 0 is the base).
    pub fn frame(&self, k: usize) -> &Frame {
        if k == 0 {
            &self.base
        } else {
            &self.links[k - 1]
        }
    }

    /// Origin `o_k` of frame `k` in world coordinates.
    pub fn origin(&self, k: usize) -> Vector3<f64> {
        self.frame(k).origin
    }

    /// Axis `z_k` of frame `k` in world coordinates (the axis of joint `k + 1`).
    pub fn z(&self, k: usize) -> Vector3<f64> {
        self.frame(k).z_axis()
    }
}
