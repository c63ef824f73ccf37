//! Seeded random QPs of the four papers' shapes (see [`qp::Qp`] for the form), for
//! testing the exact and the neural solvers on many instances.
//!
//! Every generator is deterministic: the same seed gives the same QP on every platform
//! (ChaCha8 stream, [`ChaCha8Rng::seed_from_u64`]).
//!
//! Feasibility is guaranteed by construction: each generator first draws a point x_f strictly
//! inside the bounds (and strictly inside G x <= h), then sets b = A x_f, and h = G x_f + slack
//! with a positive slack where h is not fixed by the paper's structure. Every equality matrix is
//! redrawn until it has full row rank with a smallest singular value of at least
//! [`MIN_SINGULAR_VALUE`], so the multipliers are unique and well conditioned, and every P is
//! positive definite, so the optimum is unique.
//!
//! | shape | x | P | constraints |
//! |---|---|---|---|
//! | [`QpShape::Jia2019`] | [thetadot; p] in R^7 | diag((phi+tau) I6, 1-phi-tau) | [J 0] x = b, [I -1; -I -1] x <= 0, [zeta-; 0] <= x <= [zeta+; varpi] |
//! | [`QpShape::Zhong2021`] | [thetadot; p] in R^7 | same | [J 0] x = b, B x <= h with B = [s; E; -E], h = [0; x+; -x-], no bounds |
//! | [`QpShape::Zhang2018`] | thetaddot in R^6 | zeta I + (1-zeta) H^2 | J x = b |
//! | [`QpShape::Kong2019`] | thetadot in R^5 | I | J x = b |

use nalgebra::{DMatrix, DVector};
use qp::{Qp, QpDims};
use rand::Rng;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Number of joints of the Jaco2 (jia2019, zhong2021, zhang2018).
const JACO2_JOINTS: usize = 6;
/// Number of joints of the Katana 6M180 (kong2019).
const KATANA_JOINTS: usize = 5;
/// Task-space dimension (end-effector position).
const TASK_DIM: usize = 3;
/// Finite stand-in for +inf on the auxiliary variable p, as the papers' varpi.
pub const VARPI: f64 = 1e3;
/// Smallest singular value accepted for a random equality matrix.
pub const MIN_SINGULAR_VALUE: f64 = 0.05;

/// The QP shapes of the four papers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QpShape {
    /// Velocity-level tri-criteria QP with bounds and the max-norm inequalities (7 variables).
    Jia2019,
    /// As [`QpShape::Jia2019`] with every bound written as an inequality row (26 rows, no bounds).
    Zhong2021,
    /// Acceleration-level equality-only QP, P = zeta I + (1-zeta) H^2 (6 variables).
    Zhang2018,
    /// Velocity-level equality-only QP with P = I (5 variables).
    Kong2019,
}

impl QpShape {
    /// The paper whose scheme's QP the shape is (`jia2019`, `zhong2021`, `zhang2018`,
    /// `kong2019`): the benches group by it, so `cargo bench -- jia2019` selects one paper.
    pub fn paper(self) -> &'static str {
        match self {
            QpShape::Jia2019 => "jia2019",
            QpShape::Zhong2021 => "zhong2021",
            QpShape::Zhang2018 => "zhang2018",
            QpShape::Kong2019 => "kong2019",
        }
    }

    /// All four shapes.
    pub const ALL: [QpShape; 4] = [
        QpShape::Jia2019,
        QpShape::Zhong2021,
        QpShape::Zhang2018,
        QpShape::Kong2019,
    ];

    /// Whether QPs of this shape have equalities only (no inequality rows, no finite bounds).
    pub fn is_equality_only(self) -> bool {
        matches!(self, QpShape::Zhang2018 | QpShape::Kong2019)
    }
}

/// The deterministic generator used by every seeded function here.
pub fn rng_from_seed(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A random feasible QP of the given shape, deterministic in `seed`.
///
/// For [`QpShape::Jia2019`] one seed in four gives varpi = +inf (the bound on p absent) and the
/// others varpi = [`VARPI`], so both forms are exercised.
pub fn random_qp(shape: QpShape, seed: u64) -> Qp {
    let mut rng = rng_from_seed(seed);
    match shape {
        QpShape::Jia2019 => {
            let varpi = if rng.gen_bool(0.25) {
                f64::INFINITY
            } else {
                VARPI
            };
            jia2019(&mut rng, varpi)
        }
        QpShape::Zhong2021 => zhong2021(&mut rng),
        QpShape::Zhang2018 => zhang2018(&mut rng),
        QpShape::Kong2019 => kong2019(&mut rng),
    }
}

/// Random jia2019 QP (x = [thetadot; p] in R^7) with upper bound `varpi` on p (finite or +inf).
///
/// phi in [0.05, 0.6) and tau in [0, 0.9 - phi) so that 0.05 <= phi + tau < 0.9 and P is
/// positive definite; q = [random in [-s, s); 0] with s in [0, 3) (so that the bounds
/// bind in some QPs and not in others); J is a random 3 x 6 matrix of full row rank;
/// zeta- in [-1.5, -0.1), zeta+ in [0.1, 1.5). The feasible point is thetadot_f strictly inside
/// (zeta-, zeta+) and p_f = |thetadot_f|_inf + 0.1, strictly inside every inequality and bound.
pub fn jia2019<R: Rng>(rng: &mut R, varpi: f64) -> Qp {
    let d = TrackingData::draw(rng);
    let n = JACO2_JOINTS;
    let mut qp = Qp::zeros(QpDims {
        nx: n + 1,
        n_eq: TASK_DIM,
        n_in: 2 * n,
    });
    d.fill_objective_and_equalities(&mut qp);
    for i in 0..n {
        qp.g[(i, i)] = 1.0;
        qp.g[(n + i, i)] = -1.0;
        qp.g[(i, n)] = -1.0;
        qp.g[(n + i, n)] = -1.0;
        qp.lower[i] = d.zeta_lower[i];
        qp.upper[i] = d.zeta_upper[i];
    }
    qp.lower[n] = 0.0;
    qp.upper[n] = varpi;
    qp
}

/// Random zhong2021 QP: the data of [`jia2019`] (with varpi = [`VARPI`]) but the bounds written
/// as inequality rows, B = [I -1; -I -1; E; -E] (E the 7 x 7 identity), h = [0; x+; -x-],
/// and lower/upper all infinite, as the paper's eq. 2.18 (with h's last block -x-).
pub fn zhong2021<R: Rng>(rng: &mut R) -> Qp {
    let bounded = jia2019(rng, VARPI);
    let nx = bounded.q.len();
    let n_s = bounded.h.len();
    let mut qp = Qp::zeros(QpDims {
        nx,
        n_eq: TASK_DIM,
        n_in: n_s + 2 * nx,
    });
    qp.p.copy_from(&bounded.p);
    qp.q.copy_from(&bounded.q);
    qp.a.copy_from(&bounded.a);
    qp.b.copy_from(&bounded.b);
    qp.g.rows_mut(0, n_s).copy_from(&bounded.g);
    for i in 0..nx {
        qp.g[(n_s + i, i)] = 1.0;
        qp.h[n_s + i] = bounded.upper[i];
        qp.g[(n_s + nx + i, i)] = -1.0;
        qp.h[n_s + nx + i] = -bounded.lower[i];
    }
    qp
}

/// Random zhang2018 QP (x = thetaddot in R^6), equality-only: P = zeta I + (1-zeta) H^2 with
/// zeta in [0, 1] and H = M M'/6 + 0.05 I (M with entries in [-1, 1), so H is SPD like an
/// inertia matrix), q in [-5, 5)^6, A = J random 3 x 6 of full row rank, b in [-1, 1)^3.
pub fn zhang2018<R: Rng>(rng: &mut R) -> Qp {
    let n = JACO2_JOINTS;
    let zeta = rng.gen_range(0.0..=1.0);
    let m = uniform_matrix(rng, n, n, 1.0);
    let h = &m * m.transpose() / n as f64 + DMatrix::identity(n, n) * 0.05;
    let mut qp = Qp::zeros(QpDims {
        nx: n,
        n_eq: TASK_DIM,
        n_in: 0,
    });
    qp.p = DMatrix::identity(n, n) * zeta + &h * &h * (1.0 - zeta);
    qp.p = (&qp.p + qp.p.transpose()) * 0.5;
    qp.q = uniform_vector(rng, n, 5.0);
    qp.a = full_row_rank_matrix(rng, TASK_DIM, n);
    qp.b = uniform_vector(rng, TASK_DIM, 1.0);
    qp
}

/// Random kong2019 QP (x = thetadot in R^5), equality-only: P = I, q in [-5, 5)^5,
/// A random 3 x 5 of full row rank, b in [-1, 1)^3.
pub fn kong2019<R: Rng>(rng: &mut R) -> Qp {
    let n = KATANA_JOINTS;
    let mut qp = Qp::zeros(QpDims {
        nx: n,
        n_eq: TASK_DIM,
        n_in: 0,
    });
    qp.p = DMatrix::identity(n, n);
    qp.q = uniform_vector(rng, n, 5.0);
    qp.a = full_row_rank_matrix(rng, TASK_DIM, n);
    qp.b = uniform_vector(rng, TASK_DIM, 1.0);
    qp
}

/// A random feasible QP of arbitrary sizes (requires `dims.n_eq <= dims.nx`), deterministic in
/// `seed`.
///
/// P = M M' + 0.1 I (positive definite), q in [-5, 5); a feasible point x_f in [-1, 1); each
/// variable independently has both bounds, only a lower, only an upper or no bound (each with
/// probability 1/4), at distance 0.1..1 from x_f; A of full row rank, b = A x_f;
/// G in [-1, 1), h = G x_f + slack with slack in [0.1, 1), so x_f is strictly feasible for
/// every inequality and bound.
pub fn random_feasible(dims: QpDims, seed: u64) -> Qp {
    assert!(
        dims.n_eq <= dims.nx,
        "random_feasible: more equalities ({}) than variables ({})",
        dims.n_eq,
        dims.nx
    );
    let mut rng = rng_from_seed(seed);
    let QpDims { nx, n_eq, n_in } = dims;
    let mut qp = Qp::zeros(dims);
    let m = uniform_matrix(&mut rng, nx, nx, 1.0);
    qp.p = &m * m.transpose() + DMatrix::identity(nx, nx) * 0.1;
    qp.q = uniform_vector(&mut rng, nx, 5.0);
    let x_f = uniform_vector(&mut rng, nx, 1.0);
    for i in 0..nx {
        let kind: u8 = rng.gen_range(0..4);
        if kind & 1 == 1 {
            qp.lower[i] = x_f[i] - rng.gen_range(0.1..1.0);
        }
        if kind & 2 == 2 {
            qp.upper[i] = x_f[i] + rng.gen_range(0.1..1.0);
        }
    }
    if n_eq > 0 {
        qp.a = full_row_rank_matrix(&mut rng, n_eq, nx);
        qp.b = &qp.a * &x_f;
    }
    if n_in > 0 {
        qp.g = uniform_matrix(&mut rng, n_in, nx, 1.0);
        qp.h = &qp.g * &x_f + DVector::from_fn(n_in, |_, _| rng.gen_range(0.1..1.0));
    }
    qp
}

/// The random data shared by the jia2019 and zhong2021 shapes.
struct TrackingData {
    /// phi + tau, the weight of the joint-velocity block of P.
    weight: f64,
    q_theta: DVector<f64>,
    jacobian: DMatrix<f64>,
    zeta_lower: DVector<f64>,
    zeta_upper: DVector<f64>,
    /// Strictly feasible joint velocities; b = J thetadot_f.
    thetadot_f: DVector<f64>,
}

impl TrackingData {
    fn draw<R: Rng>(rng: &mut R) -> Self {
        let n = JACO2_JOINTS;
        let phi = rng.gen_range(0.05..0.6);
        let tau = rng.gen_range(0.0..0.9 - phi);
        let q_scale = rng.gen_range(0.0..3.0);
        let q_theta = uniform_vector(rng, n, q_scale);
        let jacobian = full_row_rank_matrix(rng, TASK_DIM, n);
        let zeta_lower = DVector::from_fn(n, |_, _| rng.gen_range(-1.5..-0.1));
        let zeta_upper = DVector::from_fn(n, |_, _| rng.gen_range(0.1..1.5));
        let thetadot_f = DVector::from_fn(n, |i, _| {
            zeta_lower[i] + (zeta_upper[i] - zeta_lower[i]) * rng.gen_range(0.05..0.95)
        });
        Self {
            weight: phi + tau,
            q_theta,
            jacobian,
            zeta_lower,
            zeta_upper,
            thetadot_f,
        }
    }

    /// P, q, A = [J 0] and b = J thetadot_f of a QP in x = [thetadot; p].
    fn fill_objective_and_equalities(&self, qp: &mut Qp) {
        let n = JACO2_JOINTS;
        for i in 0..n {
            qp.p[(i, i)] = self.weight;
        }
        qp.p[(n, n)] = 1.0 - self.weight;
        qp.q.rows_mut(0, n).copy_from(&self.q_theta);
        qp.a.columns_mut(0, n).copy_from(&self.jacobian);
        qp.b = &self.jacobian * &self.thetadot_f;
    }
}

/// Entries uniform in [-scale, scale).
fn uniform_matrix<R: Rng>(rng: &mut R, rows: usize, cols: usize, scale: f64) -> DMatrix<f64> {
    DMatrix::from_fn(rows, cols, |_, _| rng.gen_range(-scale..scale))
}

/// Entries uniform in [-scale, scale).
fn uniform_vector<R: Rng>(rng: &mut R, len: usize, scale: f64) -> DVector<f64> {
    DVector::from_fn(len, |_, _| rng.gen_range(-scale..scale))
}

/// A rows x cols (rows <= cols) matrix with entries in [-1, 1), redrawn until its smallest
/// singular value is at least [`MIN_SINGULAR_VALUE`].
fn full_row_rank_matrix<R: Rng>(rng: &mut R, rows: usize, cols: usize) -> DMatrix<f64> {
    loop {
        let m = uniform_matrix(rng, rows, cols, 1.0);
        if m.singular_values().min() >= MIN_SINGULAR_VALUE {
            return m;
        }
    }
}
