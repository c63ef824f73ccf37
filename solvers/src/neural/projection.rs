//! The projection family's one engine ([`ProjectionNetwork`], built from a point of
//! `settings::projection`'s vocabulary: error form, gain law g(t), activation Phi): the LVI
//! form, ydot = g(t) S Phi(e(y)) with the projection residual e of jia2019 (2.22) and the scaling
//! S = I + M' (LVI-PDNN, jia2019 eq. 2.21-2.23) or S = I (S-LVI-PDNN, zhong2021 eq. 2.35), and
//! the penalty form (VP-RNN-PF, zhong2021 eq. 2.19-2.30; its error and network: `penalty.rs`).
//! The presets `lvi-pdnn`, `s-lvi-pdnn` and `vp-rnn-pf` are points of it. The LVI itself is
//! built here from a generic [`Qp`].
//!
//! # The LVI (jia2019 eq. 2.21, the map of its QP 2.17-2.20)
//!
//! jia2019 writes its QP as min x'Dx/2 + g'x s.t. A x = b, E x <= d, x- <= x <= x+ and
//! stacks the primal-dual vector y = [x; u; v] (u for the equalities, v for the inequalities),
//!
//! ```text
//!     M = [ D  -A'  E' ]      q = [  g ]      y- = [ x-      ]   y+ = [ x+     ]
//!         [ A   0   0  ]          [ -b ]           [ -varpi 1 ]        [ varpi 1 ]
//!         [ -E  0   0  ]          [  d ]           [ 0        ]        [ varpi 1 ]
//! ```
//!
//! For our [`Qp`] (P, q, A, b, G, h, lower, upper) the same map reads D = P, g = q, E = G,
//! d = h, x- = lower, x+ = upper, so y has nx + n_eq + n_in entries. The paper's varpi ("a
//! large constant, which is used to replace +inf numerically") is +inf here: the projection is
//! a clamp, which is exact with infinite limits, so Omega = [lower, upper] x R^n_eq x
//! [0, +inf)^n_in. (A QP built with a finite varpi, as the scheme may, is projected on that finite
//! bound unchanged.)
//!
//! At a solution of (2.21) the multipliers relate to [`qp::QpDuals`] by lambda = -u and
//! mu = v (the stationarity row reads P x + q - A'u + G'v in normal cone of the box).
//!
//! # The LVI form
//!
//! With e(y) = P_Omega(y - (M y + q)) - y (eq. 2.22, whose zeros are the LVI's solutions):
//!
//! ```text
//! ydot = g(t) S Phi(e(y))
//! ```
//!
//! * LVI-PDNN (jia2019 eq. 2.23): S = I + M', g = gamma, Phi linear: ydot = gamma (I + M') e(y),
//!   gamma = 1e7 in the paper.
//! * S-LVI-PDNN (zhong2021 eq. 2.35): S = I, g = beta, Phi linear: ydot = beta e(y), beta = 1e7
//!   in the paper.
//!
//! Phi is applied entry by entry; odd and increasing, it keeps e's zeros, so the equilibria are
//! the LVI's solutions for every gain law and activation. With Dz = diag(1 if y_i^- < z_i <
//! y_i^+ else 0) evaluated at z = y - (M y + q) (the derivative of the clamp; on a kink we take
//! the outside branch), de/dy = Dz (I - M) - I, so dF/dy = g(t) S diag(Phi'(e)) (Dz (I - M) - I)
//! (the QP data frozen). With the linear activation the arithmetic is the presets' own: Phi(e)
//! = e and Phi' = 1 exactly.

use super::activation::Activation;
use super::penalty::PenaltyCore;
use super::{euclidean_norm, NeuralSolver};
use nalgebra::DMatrix;
use qp::{Qp, QpDims};
use settings::projection::{ProjectionErrorForm, ProjectionSpec, Scaling};
use settings::zeroing::GainLaw;
use settings::NetworkError;

/// Dimension of the primal-dual vector y = [x; u; v] for a QP of these sizes.
pub fn primal_dual_dim(dims: QpDims) -> usize {
    dims.nx + dims.n_eq + dims.n_in
}

/// Writes the LVI matrix M of `qp` (module docs) into `m`, which must be square of
/// [`primal_dual_dim`]`(qp.dims())` (no allocation).
pub fn lvi_matrix_into(qp: &Qp, m: &mut DMatrix<f64>) {
    let QpDims { nx, n_eq, n_in } = qp.dims();
    debug_assert_eq!(m.shape(), (nx + n_eq + n_in, nx + n_eq + n_in));
    m.fill(0.0);
    for i in 0..nx {
        for j in 0..nx {
            m[(i, j)] = qp.p[(i, j)];
        }
    }
    for k in 0..n_eq {
        for j in 0..nx {
            m[(j, nx + k)] = -qp.a[(k, j)];
            m[(nx + k, j)] = qp.a[(k, j)];
        }
    }
    for k in 0..n_in {
        for j in 0..nx {
            m[(j, nx + n_eq + k)] = qp.g[(k, j)];
            m[(nx + n_eq + k, j)] = -qp.g[(k, j)];
        }
    }
}

/// Omega's limits (y_i^-, y_i^+) for entry i of y (see the module docs).
#[inline]
fn omega(qp: &Qp, nx: usize, n_eq: usize, i: usize) -> (f64, f64) {
    if i < nx {
        (qp.lower[i], qp.upper[i])
    } else if i < nx + n_eq {
        (f64::NEG_INFINITY, f64::INFINITY)
    } else {
        (0.0, f64::INFINITY)
    }
}

/// The LVI of a QP and the scratch to evaluate its residual without allocating.
#[derive(Clone, Debug)]
pub struct LviCore {
    dims: QpDims,
    /// e = P_Omega(y - (M y + q)) - y.
    e: Vec<f64>,
    /// z = y - (M y + q).
    z: Vec<f64>,
    /// M (Jacobian only).
    m: DMatrix<f64>,
    /// Dz (I - M) - I (Jacobian only).
    de: DMatrix<f64>,
}

impl LviCore {
    /// The LVI's scratch for QPs of sizes `dims` (y of [`primal_dual_dim`] entries).
    pub fn new(dims: QpDims) -> Self {
        let n = primal_dual_dim(dims);
        Self {
            dims,
            e: vec![0.0; n],
            z: vec![0.0; n],
            m: DMatrix::zeros(n, n),
            de: DMatrix::zeros(n, n),
        }
    }

    /// The QP sizes it was built for.
    pub fn dims(&self) -> QpDims {
        self.dims
    }

    fn check(&self, qp: &Qp, y: &[f64]) {
        debug_assert_eq!(
            qp.dims(),
            self.dims,
            "QP sizes differ from the sizes the network was built for"
        );
        debug_assert_eq!(y.len(), primal_dual_dim(self.dims));
    }

    /// z = y - (M y + q), blockwise:
    /// M y + q = [P x - A'u + G'v + q; A x - b; -G x + h].
    fn compute_z(&mut self, qp: &Qp, y: &[f64]) {
        let QpDims { nx, n_eq, n_in } = self.dims;
        let (x, rest) = y.split_at(nx);
        let (u, v) = rest.split_at(n_eq);
        for i in 0..nx {
            let mut s = qp.q[i];
            for j in 0..nx {
                s += qp.p[(i, j)] * x[j];
            }
            for k in 0..n_eq {
                s -= qp.a[(k, i)] * u[k];
            }
            for k in 0..n_in {
                s += qp.g[(k, i)] * v[k];
            }
            self.z[i] = x[i] - s;
        }
        for k in 0..n_eq {
            let mut s = -qp.b[k];
            for j in 0..nx {
                s += qp.a[(k, j)] * x[j];
            }
            self.z[nx + k] = u[k] - s;
        }
        for k in 0..n_in {
            let mut s = qp.h[k];
            for j in 0..nx {
                s -= qp.g[(k, j)] * x[j];
            }
            self.z[nx + n_eq + k] = v[k] - s;
        }
    }

    /// The residual e(y) = P_Omega(y - (M y + q)) - y of eq. 2.22, kept in `self`.
    pub fn residual(&mut self, qp: &Qp, y: &[f64]) -> &[f64] {
        self.check(qp, y);
        self.compute_z(qp, y);
        let QpDims { nx, n_eq, .. } = self.dims;
        for i in 0..y.len() {
            let (lo, hi) = omega(qp, nx, n_eq, i);
            self.e[i] = self.z[i].max(lo).min(hi) - y[i];
        }
        &self.e
    }

    /// z = y - (M y + q) of the last [`LviCore::residual`] call (so M y + q = y - z there).
    pub fn z(&self) -> &[f64] {
        &self.z
    }

    /// Projects `v` onto Omega in place (the clamp of the module docs).
    pub fn project(&self, qp: &Qp, v: &mut [f64]) {
        let QpDims { nx, n_eq, .. } = self.dims;
        for (i, vi) in v.iter_mut().enumerate() {
            let (lo, hi) = omega(qp, nx, n_eq, i);
            *vi = vi.max(lo).min(hi);
        }
    }

    /// out = scale * (I + M') w for any w of y's size, blockwise:
    /// M' w = [P' w_x + A' w_u - G' w_v; -A w_x; G w_x].
    pub fn i_plus_mt(&self, qp: &Qp, scale: f64, w: &[f64], out: &mut [f64]) {
        let QpDims { nx, n_eq, n_in } = self.dims;
        let (wx, rest) = w.split_at(nx);
        let (wu, wv) = rest.split_at(n_eq);
        for i in 0..nx {
            let mut s = wx[i];
            for j in 0..nx {
                s += qp.p[(j, i)] * wx[j];
            }
            for k in 0..n_eq {
                s += qp.a[(k, i)] * wu[k];
            }
            for k in 0..n_in {
                s -= qp.g[(k, i)] * wv[k];
            }
            out[i] = scale * s;
        }
        for k in 0..n_eq {
            let mut s = wu[k];
            for j in 0..nx {
                s -= qp.a[(k, j)] * wx[j];
            }
            out[nx + k] = scale * s;
        }
        for k in 0..n_in {
            let mut s = wv[k];
            for j in 0..nx {
                s += qp.g[(k, j)] * wx[j];
            }
            out[nx + n_eq + k] = scale * s;
        }
    }

    /// de/dy = Dz (I - M) - I into `self.de` (module docs), at the y of the last
    /// [`LviCore::residual`] (it computed z there).
    fn residual_jacobian(&mut self, qp: &Qp) {
        lvi_matrix_into(qp, &mut self.m);
        let QpDims { nx, n_eq, .. } = self.dims;
        let n = self.z.len();
        for i in 0..n {
            let (lo, hi) = omega(qp, nx, n_eq, i);
            let inside = self.z[i] > lo && self.z[i] < hi;
            for j in 0..n {
                let id = if i == j { 1.0 } else { 0.0 };
                let dz = if inside { id - self.m[(i, j)] } else { 0.0 };
                self.de[(i, j)] = dz - id;
            }
        }
    }
}

/// A projection-family network (module docs): a point of `settings::projection`'s vocabulary.
#[derive(Clone, Debug)]
pub struct ProjectionNetwork {
    name: &'static str,
    gain: GainLaw,
    activation: Activation,
    form: Form,
}

/// The error form with its scratch.
#[derive(Clone, Debug)]
enum Form {
    /// ydot = g(t) S Phi(e), e the projection residual; `phi` holds Phi(e).
    Lvi {
        core: LviCore,
        scaling: Scaling,
        phi: Vec<f64>,
    },
    /// zhong2021 (2.30) on the penalised Lagrangian's gradient.
    Penalty(Box<PenaltyCore>),
}

impl ProjectionNetwork {
    /// The network of `spec` for QPs of sizes `dims`, its gain law, activation and penalty
    /// checked.
    pub fn from_spec(spec: &ProjectionSpec, dims: QpDims) -> Result<Self, NetworkError> {
        spec.gain.validate()?;
        let activation = Activation::from(spec.activation);
        activation.validate()?;
        let form = match spec.error {
            ProjectionErrorForm::Lvi { scaling } => Form::Lvi {
                core: LviCore::new(dims),
                scaling,
                phi: vec![0.0; primal_dual_dim(dims)],
            },
            ProjectionErrorForm::Penalty { p, sigma } => {
                Form::Penalty(Box::new(PenaltyCore::new(p, sigma, dims)?))
            }
        };
        Ok(Self {
            name: spec.name,
            gain: spec.gain.clone(),
            activation,
            form,
        })
    }

    /// The error the network drives to zero at its last evaluation ([`NeuralSolver::rhs`],
    /// [`NeuralSolver::error_norm`] or [`NeuralSolver::jacobian`]): the LVI form's e(y) of
    /// jia2019 (2.22), the penalty form's phi of zhong2021 (2.25).
    pub fn error(&self) -> &[f64] {
        match &self.form {
            Form::Lvi { core, .. } => &core.e,
            Form::Penalty(core) => core.error(),
        }
    }
}

impl NeuralSolver for ProjectionNetwork {
    fn name(&self) -> String {
        self.name.into()
    }
    fn state_dim(&self, dims: QpDims) -> usize {
        match self.form {
            Form::Lvi { .. } => primal_dual_dim(dims),
            Form::Penalty(_) => dims.nx + dims.n_eq,
        }
    }
    fn needs_qp_dot(&self) -> bool {
        matches!(self.form, Form::Penalty(_))
    }
    fn error_norm(&mut self, qp: &Qp, y: &[f64]) -> Option<f64> {
        match &mut self.form {
            Form::Lvi { core, .. } => Some(euclidean_norm(core.residual(qp, y))),
            Form::Penalty(_) => None,
        }
    }
    fn rhs(&mut self, t: f64, y: &[f64], qp: &Qp, qp_dot: Option<&Qp>, ydot: &mut [f64]) {
        let g = self.gain.at(t);
        match &mut self.form {
            Form::Lvi { core, scaling, phi } => {
                for (a, e) in phi.iter_mut().zip(core.residual(qp, y)) {
                    *a = self.activation.value(*e);
                }
                match scaling {
                    Scaling::IPlusMt => core.i_plus_mt(qp, g, phi, ydot),
                    Scaling::Identity => {
                        for (d, a) in ydot.iter_mut().zip(phi.iter()) {
                            *d = g * a;
                        }
                    }
                }
            }
            Form::Penalty(core) => {
                core.evaluate(g, &self.activation, y, qp, qp_dot);
                ydot.copy_from_slice(core.ydot());
            }
        }
    }
    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        let g = self.gain.at(t);
        let (core, scaling) = match &mut self.form {
            Form::Lvi { core, scaling, .. } => (core, *scaling),
            Form::Penalty(core) => return core.jacobian(g, &self.activation, y, qp, qp_dot, jac),
        };
        core.residual(qp, y);
        core.residual_jacobian(qp);
        // diag(Phi'(e)) de, row by row; the linear activation's Phi' = 1 leaves de as it is.
        let n = y.len();
        if self.activation != Activation::Linear {
            for k in 0..n {
                let slope = self.activation.derivative(core.e[k]);
                for j in 0..n {
                    core.de[(k, j)] *= slope;
                }
            }
        }
        let (m, de) = (&core.m, &core.de);
        match scaling {
            // jac = g (I + M') diag(Phi') de: entry (i, j) is de_ij + (column i of M) . (column
            // j of de), summed over k in order (the matrices are column-major).
            Scaling::IPlusMt => {
                let (m, de) = (m.as_slice(), de.as_slice());
                for (i, m_i) in m.chunks_exact(n).enumerate() {
                    for (j, de_j) in de.chunks_exact(n).enumerate() {
                        let mut s = de_j[i];
                        for (a, b) in m_i.iter().zip(de_j) {
                            s += a * b;
                        }
                        jac[(i, j)] = g * s;
                    }
                }
            }
            // jac = g diag(Phi') de.
            Scaling::Identity => {
                for i in 0..n {
                    for j in 0..n {
                        jac[(i, j)] = g * de[(i, j)];
                    }
                }
            }
        }
        true
    }
}
