//! Shared helpers for the robot tests: seeded random configurations, finite differences,
//! an independent 4x4 transcription of classical DH, and singular values.
#![allow(dead_code)]

use nalgebra::{Matrix3, Matrix4, Rotation3, SMatrix, SVector, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Seeded random joint vectors with entries uniform in [-lim, lim].
pub fn random_vectors<const N: usize>(seed: u64, count: usize, lim: f64) -> Vec<SVector<f64, N>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| SVector::from_fn(|_, _| rng.gen_range(-lim..lim)))
        .collect()
}

/// Central-difference Jacobian of a vector function.
pub fn fd_jacobian<const N: usize, const M: usize>(
    f: impl Fn(&SVector<f64, N>) -> SVector<f64, M>,
    x: &SVector<f64, N>,
    h: f64,
) -> SMatrix<f64, M, N> {
    let mut jac = SMatrix::<f64, M, N>::zeros();
    for k in 0..N {
        let mut e = SVector::<f64, N>::zeros();
        e[k] = h;
        jac.set_column(k, &((f(&(x + e)) - f(&(x - e))) / (2.0 * h)));
    }
    jac
}

/// Central-difference derivative of a matrix function along direction `v`.
pub fn fd_directional<const N: usize, const R: usize, const C: usize>(
    f: impl Fn(&SVector<f64, N>) -> SMatrix<f64, R, C>,
    x: &SVector<f64, N>,
    v: &SVector<f64, N>,
    h: f64,
) -> SMatrix<f64, R, C> {
    (f(&(x + v * h)) - f(&(x - v * h))) / (2.0 * h)
}

/// Classical DH link transform written as the literal product Rz(theta) Tz(d) Tx(a) Rx(alpha).
pub fn dh4(a: f64, alpha: f64, d: f64, theta: f64) -> Matrix4<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), theta).to_homogeneous()
        * Translation3::new(0.0, 0.0, d).to_homogeneous()
        * Translation3::new(a, 0.0, 0.0).to_homogeneous()
        * Rotation3::from_axis_angle(&Vector3::x_axis(), alpha).to_homogeneous()
}

/// Independent transcription of the Jaco2 DH table (`docs/robots.md`), D6 given, as (a, alpha, d) rows.
pub fn jaco2_table(d6: f64) -> [(f64, f64, f64); 6] {
    use std::f64::consts::PI;
    let (d1, d2, d3, d4, d5, e2) = (0.2755, 0.41, 0.2073, 0.0741, 0.0741, 0.0098);
    let k = 1.0 / 3f64.sqrt();
    [
        (0.0, PI / 2.0, d1),
        (d2, PI, 0.0),
        (0.0, PI / 2.0, -e2),
        (0.0, PI / 3.0, -(d3 + k * d4)),
        (0.0, PI / 3.0, -k * (d4 + d5)),
        (0.0, PI, -(k * d5 + d6)),
    ]
}

/// Homogeneous transforms T_1..T_6 of the Jaco2 table under `base`.
pub fn jaco2_frames(d6: f64, base: Matrix4<f64>, theta: &SVector<f64, 6>) -> [Matrix4<f64>; 6] {
    let table = jaco2_table(d6);
    let mut out = [Matrix4::identity(); 6];
    let mut t = base;
    for i in 0..6 {
        let (a, alpha, d) = table[i];
        t *= dh4(a, alpha, d, theta[i]);
        out[i] = t;
    }
    out
}

/// Applies a homogeneous transform to a point.
pub fn apply(t: &Matrix4<f64>, p: &Vector3<f64>) -> Vector3<f64> {
    t.fixed_view::<3, 3>(0, 0) * p + t.fixed_view::<3, 1>(0, 3)
}

/// Rotation block of a homogeneous transform.
pub fn rot(t: &Matrix4<f64>) -> Matrix3<f64> {
    t.fixed_view::<3, 3>(0, 0).into_owned()
}

/// Singular values of a 3 x N matrix, descending.
pub fn singular_values<const N: usize>(j: &SMatrix<f64, 3, N>) -> [f64; 3] {
    let eig = (j * j.transpose()).symmetric_eigenvalues();
    let mut s = [
        eig[0].max(0.0).sqrt(),
        eig[1].max(0.0).sqrt(),
        eig[2].max(0.0).sqrt(),
    ];
    s.sort_by(|a, b| b.partial_cmp(a).unwrap());
    s
}

/// The runtime models seen with fixed-size joint vectors, for tests written with `SVector`s.
pub trait Fixed {
    /// [`robots::Robot::position`].
    fn position_n<const N: usize>(&self, theta: &SVector<f64, N>) -> Vector3<f64>;
    /// [`robots::Robot::jacobian`] as a 3 x N matrix.
    fn jacobian_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, 3, N>;
    /// [`robots::Robot::jacobian_dot`] as a 3 x N matrix.
    fn jacobian_dot_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, 3, N>;
    /// [`robots::Robot::skeleton`].
    fn skeleton_n<const N: usize>(&self, theta: &SVector<f64, N>) -> Vec<Vector3<f64>>;
}

impl<R: robots::Robot + ?Sized> Fixed for R {
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
    fn skeleton_n<const N: usize>(&self, theta: &SVector<f64, N>) -> Vec<Vector3<f64>> {
        self.skeleton(theta.as_slice())
    }
}

/// The runtime dynamics seen with fixed-size joint vectors.
pub trait FixedDynamics {
    /// [`robots::Dynamics::inertia`].
    fn inertia_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SMatrix<f64, N, N>;
    /// [`robots::Dynamics::coriolis`].
    fn coriolis_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SVector<f64, N>;
    /// [`robots::Dynamics::coriolis_matrix`].
    fn coriolis_matrix_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N>;
    /// [`robots::Dynamics::gravity`].
    fn gravity_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SVector<f64, N>;
}

impl<R: robots::Dynamics + ?Sized> FixedDynamics for R {
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
    fn coriolis_matrix_n<const N: usize>(
        &self,
        theta: &SVector<f64, N>,
        thetadot: &SVector<f64, N>,
    ) -> SMatrix<f64, N, N> {
        let mut c = SMatrix::<f64, N, N>::zeros();
        self.coriolis_matrix(theta.as_slice(), thetadot.as_slice(), c.as_mut_slice());
        c
    }
    fn gravity_n<const N: usize>(&self, theta: &SVector<f64, N>) -> SVector<f64, N> {
        let mut g = SVector::<f64, N>::zeros();
        self.gravity(theta.as_slice(), g.as_mut_slice());
        g
    }
}

/// The home pose of `nlink-N` ([`robots::NLink::home`]) as a fixed-size vector.
pub fn nlink_home<const N: usize>() -> SVector<f64, N> {
    SVector::from_column_slice(robots::NLink::new(N).unwrap().home().as_slice())
}
