//! Test fixtures: a planar N-link arm with a z coordinate (and a made-up but SPD dynamics), a
//! circle path, and a small ADMM QP solver that also returns multipliers, so its answers can be
//! checked by the QP's own KKT residuals; the papers' scheme specs the tests sweep; and a QP
//! comparison. Shared by the `schemes*.rs` tests (`mod common;`).
#![allow(dead_code)]

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector, SMatrix, SVector, Vector3};
use qp::{Qp, QpDuals};
use robots::{Dynamics, JointLimits, Robot};
use schemes::paths::{Path, PathPoint};
use spec::RmpReading;
use spec::SchemeSpec;

/// Planar arm: joints 1..N-1 rotate in the x-y plane (links `LEN`), joint N moves the tip in z
/// by `Z_GAIN * theta_N`. Joint 2 has finite angle limits [-1, 2.5]; the others [-3, 3];
/// velocity limits +-1.5.
pub struct PlanarZ {
    limits: JointLimits,
}

pub const LEN: f64 = 0.3;
pub const Z_GAIN: f64 = 0.1;

impl PlanarZ {
    /// The arm with `n` joints.
    pub fn new(n: usize) -> Self {
        let mut theta_min = DVector::repeat(n, -3.0);
        let mut theta_max = DVector::repeat(n, 3.0);
        theta_min[1] = -1.0;
        theta_max[1] = 2.5;
        PlanarZ {
            limits: JointLimits {
                theta_min,
                theta_max,
                thetadot_min: DVector::repeat(n, -1.5),
                thetadot_max: DVector::repeat(n, 1.5),
            },
        }
    }

    /// phi_k = theta_1 + ... + theta_k (k from 0), for k < n - 1.
    fn phi(theta: &[f64], k: usize) -> f64 {
        theta[..=k].iter().sum()
    }
}

impl Robot for PlanarZ {
    fn name(&self) -> &'static str {
        "planar-z"
    }

    fn dof(&self) -> usize {
        self.limits.dof()
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        let n = theta.len();
        let (mut x, mut y) = (0.0, 0.0);
        for k in 0..n - 1 {
            let p = Self::phi(theta, k);
            x += LEN * p.cos();
            y += LEN * p.sin();
        }
        Vector3::new(x, y, Z_GAIN * theta[n - 1])
    }

    /// Writes J (no allocation: the scheme tests count allocations).
    fn jacobian(&self, theta: &[f64], j: &mut [f64]) {
        let n = theta.len();
        j.fill(0.0);
        for i in 0..n - 1 {
            for k in i..n - 1 {
                let p = Self::phi(theta, k);
                j[3 * i] -= LEN * p.sin();
                j[3 * i + 1] += LEN * p.cos();
            }
        }
        j[3 * (n - 1) + 2] = Z_GAIN;
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], j: &mut [f64]) {
        let n = theta.len();
        j.fill(0.0);
        for i in 0..n - 1 {
            for k in i..n - 1 {
                let (p, pd) = (Self::phi(theta, k), Self::phi(thetadot, k));
                j[3 * i] -= LEN * p.cos() * pd;
                j[3 * i + 1] -= LEN * p.sin() * pd;
            }
        }
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }
}

/// Made-up smooth dynamics: H = 0.5 I + v v' with v_i = 0.3 cos(theta_i) + 0.2 (SPD),
/// c = 0.1 sin(theta) .* thetadot .* |thetadot|_2, g = 0.98 cos(theta).
impl Dynamics for PlanarZ {
    fn inertia(&self, theta: &[f64], out: &mut [f64]) {
        let n = theta.len();
        let v = |i: usize| 0.3 * theta[i].cos() + 0.2;
        for c in 0..n {
            for r in 0..n {
                out[r + n * c] = if r == c { 0.5 } else { 0.0 } + v(r) * v(c);
            }
        }
    }

    fn coriolis(&self, theta: &[f64], thetadot: &[f64], out: &mut [f64]) {
        let norm = thetadot.iter().map(|v| v * v).sum::<f64>().sqrt();
        for i in 0..theta.len() {
            out[i] = 0.1 * theta[i].sin() * thetadot[i] * norm;
        }
    }

    fn coriolis_matrix(&self, _theta: &[f64], _thetadot: &[f64], out: &mut [f64]) {
        out.fill(0.0);
    }

    fn gravity(&self, theta: &[f64], out: &mut [f64]) {
        for (o, x) in out.iter_mut().zip(theta) {
            *o = 0.98 * x.cos();
        }
    }
}

/// A robot seen with fixed-size joint vectors, for tests written with `SVector`s.
pub trait FixedRobot {
    fn position_n<const N: usize>(&self, theta: &SVector<f64, N>) -> Vector3<f64>;
    fn jacobian_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N>;
    fn jacobian_dot_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N>;
    fn inertia_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N>;
    fn coriolis_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SVector<f64, N>;
    fn gravity_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SVector<f64, N>;
}

impl<R: Dynamics + ?Sized> FixedRobot for R {
    fn position_n<const N: usize>(&self, theta: &SVector<f64, N>) -> Vector3<f64> {
        self.position(theta.as_slice())
    }
    fn jacobian_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N> {
        let mut j = SMatrix::<f64, 3, N>::zeros();
        self.jacobian(theta.as_slice(), j.as_mut_slice());
        j
    }
    fn jacobian_dot_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N> {
        let mut j = SMatrix::<f64, 3, N>::zeros();
        self.jacobian_dot(theta.as_slice(), thetadot.as_slice(), j.as_mut_slice());
        j
    }
    fn inertia_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N> {
        let mut h = SMatrix::<f64, N, N>::zeros();
        self.inertia(theta.as_slice(), h.as_mut_slice());
        h
    }
    fn coriolis_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SVector<f64, N> {
        let mut c = SVector::<f64, N>::zeros();
        self.coriolis(theta.as_slice(), thetadot.as_slice(), c.as_mut_slice());
        c
    }
    fn gravity_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SVector<f64, N> {
        let mut g = SVector::<f64, N>::zeros();
        self.gravity(theta.as_slice(), g.as_mut_slice());
        g
    }
}

/// r = r0 + [a (cos phi - 1), a sin phi, 0.02 sin phi], phi = 2 pi sin^2(pi t / 2T).
pub struct Circle {
    pub r0: Vector3<f64>,
    pub a: f64,
    pub t_end: f64,
}

impl Path for Circle {
    fn duration(&self) -> f64 {
        self.t_end
    }

    fn at(&self, t: f64) -> PathPoint {
        let tt = self.t_end;
        let phi = 2.0 * PI * (PI * t / (2.0 * tt)).sin().powi(2);
        let phid = PI * PI / tt * (PI * t / tt).sin();
        let phidd = PI.powi(3) / (tt * tt) * (PI * t / tt).cos();
        let (s, c) = phi.sin_cos();
        let d = Vector3::new(self.a * (c - 1.0), self.a * s, 0.02 * s);
        let d1 = Vector3::new(-self.a * s, self.a * c, 0.02 * c);
        let d2 = Vector3::new(-self.a * c, -self.a * s, -0.02 * s);
        PathPoint {
            r: self.r0 + d,
            rdot: d1 * phid,
            rddot: d2 * phid * phid + d1 * phidd,
        }
    }
}

/// Solves the QP by ADMM (OSQP's iteration, fixed rho, many iterations) on
/// [A; G; I] x in [[b; -inf; lower], [b; h; upper]]; returns x and the multipliers in the
/// conventions of `qp`.
pub fn admm(qp: &Qp, iters: usize) -> (DVector<f64>, QpDuals) {
    let n = qp.q.len();
    let (me, mi) = (qp.b.len(), qp.h.len());
    let m = me + mi + n;
    let mut c = DMatrix::zeros(m, n);
    c.view_mut((0, 0), (me, n)).copy_from(&qp.a);
    c.view_mut((me, 0), (mi, n)).copy_from(&qp.g);
    c.view_mut((me + mi, 0), (n, n)).fill_with_identity();
    let mut lo = DVector::zeros(m);
    let mut hi = DVector::zeros(m);
    for i in 0..me {
        lo[i] = qp.b[i];
        hi[i] = qp.b[i];
    }
    for i in 0..mi {
        lo[me + i] = f64::NEG_INFINITY;
        hi[me + i] = qp.h[i];
    }
    for i in 0..n {
        lo[me + mi + i] = qp.lower[i];
        hi[me + mi + i] = qp.upper[i];
    }
    let rho_base = 0.1;
    let rho = DVector::from_fn(m, |i, _| {
        if lo[i] == hi[i] {
            1e3 * rho_base
        } else {
            rho_base
        }
    });
    let sigma = 1e-6;
    let alpha = 1.6;
    let k =
        &qp.p + DMatrix::identity(n, n) * sigma + c.transpose() * DMatrix::from_diagonal(&rho) * &c;
    let lu = k.lu();
    let mut x = DVector::zeros(n);
    let mut z = DVector::zeros(m);
    let mut y = DVector::zeros(m);
    for _ in 0..iters {
        let rhs = &x * sigma - &qp.q + c.transpose() * (rho.component_mul(&z) - &y);
        let xt = lu.solve(&rhs).unwrap();
        let zt = &c * &xt;
        x = &xt * alpha + &x * (1.0 - alpha);
        let zr = &zt * alpha + &z * (1.0 - alpha);
        let mut zn = &zr + y.component_div(&rho);
        for i in 0..m {
            zn[i] = zn[i].max(lo[i]).min(hi[i]);
        }
        y += rho.component_mul(&(&zr - &zn));
        z = zn;
    }
    let duals = QpDuals {
        lambda: y.rows(0, me).into_owned(),
        mu: y.rows(me, mi).map(|v| v.max(0.0)),
        z_lower: y.rows(me + mi, n).map(|v| (-v).max(0.0)),
        z_upper: y.rows(me + mi, n).map(|v| v.max(0.0)),
    };
    (x, duals)
}

/// Solves an equality-only QP (P nonsingular on null(A)) by its KKT linear system.
pub fn kkt_solve(qp: &Qp) -> DVector<f64> {
    let n = qp.q.len();
    let me = qp.b.len();
    let mut k = DMatrix::zeros(n + me, n + me);
    k.view_mut((0, 0), (n, n)).copy_from(&qp.p);
    k.view_mut((0, n), (n, me)).copy_from(&qp.a.transpose());
    k.view_mut((n, 0), (me, n)).copy_from(&qp.a);
    let mut rhs = DVector::zeros(n + me);
    rhs.rows_mut(0, n).copy_from(&(-&qp.q));
    rhs.rows_mut(n, me).copy_from(&qp.b);
    k.lu().solve(&rhs).unwrap().rows(0, n).into_owned()
}

/// Every paper's scheme at the parameters the papers use (and MVN / MVN-INVM / MTN).
pub fn paper_specs() -> Vec<SchemeSpec> {
    vec![
        SchemeSpec::Vltco {
            phi: 1.0,
            tau: 0.0,
            kappa: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            mu: 5.0,
        },
        SchemeSpec::Vltco {
            phi: 0.2,
            tau: 0.0,
            kappa: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            mu: 5.0,
        },
        SchemeSpec::Vltco {
            phi: 0.2,
            tau: 0.4,
            kappa: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            mu: 5.0,
        },
        SchemeSpec::Cmco {
            eta: 0.2,
            delta: 0.4,
            upsilon: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            tau: 10.0,
        },
        SchemeSpec::Cmco {
            eta: 0.1,
            delta: 0.8,
            upsilon: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            tau: 10.0,
        },
        SchemeSpec::HlJdf {
            zeta: 0.0,
            alpha: 20.0,
            beta: 20.0,
            rho_v: 20.0,
            rho_p: 20.0,
        },
        SchemeSpec::HlJdf {
            zeta: 0.6,
            alpha: 20.0,
            beta: 20.0,
            rho_v: 20.0,
            rho_p: 20.0,
        },
        SchemeSpec::FiniteTimeRmp {
            beta_theta: 1.0,
            k_p: 1.0,
            alpha: 0.1,
        },
        SchemeSpec::ZnnRmp { mu: 1.0, k_p: 1.0 },
        // The vocabulary's composed scheme with every term on (robio2018's RMP with a weight and
        // feedback), and its sign-power form.
        SchemeSpec::VelocityRmp {
            weight: 2.0,
            repetitive: spec::RepetitiveForm::Linear,
            lambda: 4.0,
            alpha: None,
            k_p: 1.0,
            upsilon: Some(2.0),
        },
        SchemeSpec::VelocityRmp {
            weight: 1.0,
            repetitive: spec::RepetitiveForm::SignPower,
            lambda: 1.0,
            alpha: Some(0.5),
            k_p: 0.0,
            upsilon: None,
        },
    ]
}

/// Schemes of their own terms, as files write them: every velocity-level term with the bounds
/// as rows (the proof of composition: no preset combines an infinity norm with a sign-power
/// repetitive term, feedback and a bound conversion), a task on the x and z axes with the
/// velocity limits and a linear infinity-norm penalty, and an acceleration-level planar task with the drift damping.
pub fn composed_specs() -> Vec<SchemeSpec> {
    [
        r#"kind = "composed"
level = "velocity"
name = "own (inf-norm + sign-power + feedback)"
bounds = "rows"
[[terms]]
kind = "velocity-norm"
weight = 0.5
[[terms]]
kind = "infinity-norm"
weight = 0.3
varpi = 10.0
[[terms]]
kind = "repetitive"
form = "sign-power"
lambda = 2.0
alpha = 0.5
[[terms]]
kind = "tracking"
k_p = 3.0
[[terms]]
kind = "bound-conversion"
gain = 5.0
[[terms]]
kind = "velocity-limits"
"#,
        r#"kind = "composed"
level = "velocity"
[[terms]]
kind = "velocity-norm"
[[terms]]
kind = "repetitive"
lambda = 1.0
weight = 0.5
squared = true
[[terms]]
kind = "tracking"
axes = ["x", "z"]
k_p = 1.0
[[terms]]
kind = "velocity-limits"
[[terms]]
kind = "infinity-norm"
penalty = "linear"
weight = 0.2
"#,
        r#"kind = "composed"
level = "acceleration"
[[terms]]
kind = "acceleration-norm"
[[terms]]
kind = "drift-damping"
alpha = 5.0
beta = 5.0
[[terms]]
kind = "tracking"
task = "planar"
rho_v = 10.0
rho_p = 10.0
"#,
    ]
    .iter()
    .map(|text| toml::from_str(text).expect("a valid composed scheme"))
    .collect()
}
