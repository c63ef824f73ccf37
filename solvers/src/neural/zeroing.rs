//! The zeroing core shared by every equality-only network of the papers: FP-CDNN and VP-CDNN
//! (zhang2018 eq. 2.15, 2.11, perturbed 3.2, 3.1), kong2019's finite-time network (eq. 17-20)
//! the plain ZNN of kong2019's comparison scheme (eq. 22) and the papers' group's own network
//! (`docs/group-code.md`).
//!
//! # The equation they zero
//!
//! For the equality-only QP min x'Px/2 + q'x s.t. A x = b the Lagrange conditions
//! (zhang2018 eq. 2.7-2.8, kong2019 eq. 15-18) are the linear system
//!
//! ```text
//!     Q y = u,   Q = [ P  A' ],   y = [ x      ],   u = [ -q ]
//!                    [ A  0  ]        [ lambda ]        [  b ]
//! ```
//!
//! (zhang2018 writes Q = [W J'; J 0], u = [-eta; b]; kong2019 writes W = [I J'; J 0],
//! v = [-beta_theta c; rdot* + k_p (r* - f)]), so lambda has the sign convention of
//! [`qp::QpDuals`]. The error E(t) = Q y - u (zhang2018 eq. 2.9, kong2019 eq. 19) is made
//! to obey Edot = -g(t) Phi(E) (zhang2018 eq. 2.10 / 2.14, kong2019 eq. 6); since
//! Edot = Qdot y + Q ydot - udot (zhang2018 eq. 3.4) the network is the implicit system
//!
//! ```text
//!     Q ydot = -Qdot y + udot - g(t) Phi(Q y - u)  [ - DeltaD(t) y + Delta s(t) ]
//! ```
//!
//! with the bracketed perturbation of zhang2018 eq. 3.1-3.2 (see `docs/networks.md`; its terms:
//! [`super::perturbation`]) where given.
//!
//! Three options, all off by default (and then not evaluated at all, so the networks above are
//! unchanged bit for bit), make the group's network (`docs/group-code.md`):
//! - a growing-gain term -nu t E on the right-hand side ([`ZeroingNetwork::with_growing_gain`]);
//! - the perturbation's vector part Delta s(t) alone, without DeltaD(t);
//! - udot without its -qdot part, i.e. udot = [0; bdot].
//!
//! Which network is built is data: a point of `settings::zeroing`'s vocabulary (gain law
//! g(t), activation Phi, nu, perturbation, udot), of which FP-CDNN, VP-CDNN, kong2019's FTNN
//! and ZNN and the group's network are presets ([`ZeroingNetwork::from_spec`]; the papers'
//! derivations of each preset are in `docs/networks.md`).
//!
//! Q is small and invertible (P positive definite on the null space of A, A of full row rank),
//! so ydot is solved for at each evaluation on preallocated buffers
//! (`solvers/src/equality_kkt.rs`): through the Schur complement of P where P is diagonal
//! (kong2019's and the group's schemes, P = I: about 150 flops for kong2019's 8 x 8 system), by
//! an LU with partial pivoting otherwise (zhang2018's dense P). Qdot and udot come from `qp_dot`
//! (P, A, q, b differentiated); with no `qp_dot` the QP is taken as frozen (Qdot = 0,
//! udot = 0).
//!
//! Inequality rows and bounds are outside this structure: a network is built only for
//! `n_in = 0`, and the bounds `lower`/`upper` of the QP are ignored (the schemes that use these
//! networks have none).
//!
//! Jacobian (QP data frozen, as the trait asks):
//! Q dF/dy = -Qdot - DeltaD - (g(t) diag(Phi'(E)) + nu t I) Q.
//!
//! Derivative along the QP data (dQ, du from a direction dP, dq, dA, db; dQdot, dudot from the
//! direction of the QP's time derivative): differentiating Q F = r gives
//! Q dF = dr - dQ F with dr = -(g(t) diag(Phi'(E)) + nu t I)(dQ y - du) - dQdot y + dudot.

use super::activation::Activation;
use super::perturbation::PerturbationTerms;
use super::{euclidean_norm, NeuralSolver};
use crate::equality_kkt::{assemble_q, Kkt};
use nalgebra::DMatrix;
use qp::{Qp, QpDims};
use settings::zeroing::{GainLaw, ZeroingSpec};
use settings::NetworkError;
use settings::ReferencePerturbation;

/// Q ydot = -Qdot y + udot - g(t) Phi(Q y - u) (+ perturbation): see the module docs.
#[derive(Clone, Debug)]
pub struct ZeroingNetwork {
    name: String,
    gain: GainLaw,
    activation: Activation,
    perturbation: Option<ReferencePerturbation>,
    dims: QpDims,
    /// The factors of Q.
    kkt: Kkt,
    /// E = Q y - u.
    e: Vec<f64>,
    /// DeltaD(t) scratch (perturbed networks).
    delta_d: DMatrix<f64>,
    delta_s: Vec<f64>,
    /// nu of the growing-gain term -nu t E (0: none).
    nu: f64,
    /// Whether a perturbation's DeltaD(t) is used (else Delta s(t) alone).
    matrix_perturbation: bool,
    /// Whether udot includes -qdot (else udot = [0; bdot]).
    udot_q: bool,
    /// F at the base point of [`NeuralSolver::data_derivative`].
    f_base: Vec<f64>,
    /// Products with Qdot (or a direction dQ): Qdot y in the right-hand side; dQ y, dQ F and
    /// dQdot y in [`NeuralSolver::data_derivative`] (3 n entries).
    products: Vec<f64>,
}

impl ZeroingNetwork {
    /// A zeroing network named `name` (as the paper writes it) for QPs of sizes `dims`
    /// (n_in must be 0; a perturbation needs nx + n_eq = 9).
    pub fn new(
        name: impl Into<String>,
        gain: GainLaw,
        activation: Activation,
        perturbation: Option<ReferencePerturbation>,
        dims: QpDims,
    ) -> Result<Self, NetworkError> {
        let name = name.into();
        if dims.n_in != 0 {
            return Err(NetworkError::EqualityOnly {
                network: name,
                n_in: dims.n_in,
            });
        }
        activation.validate()?;
        let n = dims.nx + dims.n_eq;
        if let Some(p) = &perturbation {
            p.validate(n)?;
        }
        Ok(Self {
            name,
            gain,
            activation,
            perturbation,
            dims,
            kkt: Kkt::new(dims),
            e: vec![0.0; n],
            delta_d: DMatrix::zeros(n, n),
            delta_s: vec![0.0; n],
            nu: 0.0,
            matrix_perturbation: true,
            udot_q: true,
            f_base: vec![0.0; n],
            products: vec![0.0; 3 * n],
        })
    }

    /// The network of a point of the vocabulary (`settings::zeroing`): its gain law (checked
    /// positive), activation, growing gain, perturbation and udot, for QPs of sizes `dims`.
    pub fn from_spec(spec: &ZeroingSpec, dims: QpDims) -> Result<Self, NetworkError> {
        spec.gain.validate()?;
        let mut net = ZeroingNetwork::new(
            spec.name,
            spec.gain.clone(),
            Activation::from(spec.activation),
            spec.perturbation,
            dims,
        )?
        .with_growing_gain(spec.nu)?;
        net.matrix_perturbation = spec.matrix_perturbation;
        net.udot_q = spec.udot_q;
        Ok(net)
    }

    /// Adds the growing-gain term -nu t E to the right-hand side (the group's network;
    /// nu = 0 leaves the network unchanged). nu must be finite and >= 0.
    pub fn with_growing_gain(mut self, nu: f64) -> Result<Self, NetworkError> {
        if !(nu >= 0.0 && nu.is_finite()) {
            return Err(NetworkError::GrowingGain {
                network: self.name,
                nu,
            });
        }
        self.nu = nu;
        Ok(self)
    }

    /// nu of the growing-gain term -nu t E (0: none).
    pub fn growing_gain(&self) -> f64 {
        self.nu
    }
    /// Whether DeltaD(t) of the perturbation is used.
    pub fn uses_matrix_perturbation(&self) -> bool {
        self.perturbation.is_some() && self.matrix_perturbation
    }
    /// Whether udot includes -qdot.
    pub fn udot_includes_q(&self) -> bool {
        self.udot_q
    }

    /// The convergence gain g(t).
    pub fn gain(&self) -> &GainLaw {
        &self.gain
    }
    /// The activation Phi of the error E.
    pub fn activation(&self) -> Activation {
        self.activation
    }
    /// The reference perturbation of zhang2018 (3.1)-(3.2), if the network is perturbed.
    pub fn perturbation(&self) -> Option<&ReferencePerturbation> {
        self.perturbation.as_ref()
    }

    /// E = Q y - u into `self.e`, Q y summed as `qdot_times` sums Qdot y (Q has the
    /// same blocks).
    fn compute_error(&mut self, qp: &Qp, y: &[f64]) {
        let QpDims { nx, .. } = self.dims;
        let e = &mut self.e[..y.len()];
        Self::qdot_times(self.dims, qp, y, e);
        for (ei, qi) in e[..nx].iter_mut().zip(qp.q.as_slice()) {
            *ei -= -qi;
        }
        for (ei, bi) in e[nx..].iter_mut().zip(qp.b.as_slice()) {
            *ei -= bi;
        }
    }

    /// The error E = Q y - u (zhang2018 eq. 2.9, kong2019 eq. 19), e.g. for kong2019's
    /// J_E = ||W y - v||.
    pub fn error(&mut self, qp: &Qp, y: &[f64]) -> &[f64] {
        self.compute_error(qp, y);
        &self.e
    }

    /// out = [P A'; A 0] y for the P and A of `d`: Qdot y for the QP's derivative (Qdot =
    /// [Pdot Adot'; Adot 0]), dQ y for a direction, Q y for the QP itself. Each entry is summed
    /// in ascending column order, the P (or A) part column by column, then A' by rows.
    fn qdot_times(dims: QpDims, d: &Qp, y: &[f64], out: &mut [f64]) {
        let QpDims { nx, n_eq, .. } = dims;
        let (p, a) = (d.p.as_slice(), d.a.as_slice());
        // kong2019's 5 joints and 3 task rows (and 6, 7 joints) compiled with constant sizes:
        // the same operations in the same order.
        match (nx, n_eq) {
            (5, 3) => block_times_fixed::<5, 3>(p, a, y, out),
            (6, 3) => block_times_fixed::<6, 3>(p, a, y, out),
            (7, 3) => block_times_fixed::<7, 3>(p, a, y, out),
            _ => block_times(nx, n_eq, p, a, y, out),
        }
    }

    fn fill_perturbation(&mut self, t: f64) {
        if let Some(p) = &self.perturbation {
            if self.matrix_perturbation {
                p.delta_d(t, &mut self.delta_d);
            }
            p.delta_s(t, &mut self.delta_s);
        }
    }
}

/// out = [P A'; A 0] y for column-major P (nx x nx) and A (n_eq x nx): see
/// `ZeroingNetwork::qdot_times`.
fn block_times(nx: usize, n_eq: usize, p: &[f64], a: &[f64], y: &[f64], out: &mut [f64]) {
    // Column-major: P[i, j] at `i + j nx`, A[k, j] at `k + j n_eq`.
    let (p, a) = (&p[..nx * nx], &a[..n_eq * nx]);
    let (top, bottom) = out[..nx + n_eq].split_at_mut(nx);
    let (yx, ylambda) = y[..nx + n_eq].split_at(nx);
    top.fill(0.0);
    bottom.fill(0.0);
    for (j, yj) in yx.iter().enumerate() {
        for (o, pij) in top.iter_mut().zip(&p[j * nx..(j + 1) * nx]) {
            *o += pij * yj;
        }
        for (o, akj) in bottom.iter_mut().zip(&a[j * n_eq..(j + 1) * n_eq]) {
            *o += akj * yj;
        }
    }
    // A[k, i] for k = 0..n_eq is A's column i.
    for (i, o) in top.iter_mut().enumerate() {
        let mut s = *o;
        for (aki, yk) in a[i * n_eq..(i + 1) * n_eq].iter().zip(ylambda) {
            s += aki * yk;
        }
        *o = s;
    }
}

/// [`block_times`] for nx = NX and n_eq = M known when it is compiled: P as NX columns of NX
/// entries and A as NX columns of M (so no index is checked at run time), the sums in the
/// same order.
#[inline(always)]
fn block_times_fixed<const NX: usize, const M: usize>(
    p: &[f64],
    a: &[f64],
    y: &[f64],
    out: &mut [f64],
) {
    let p: &[[f64; NX]; NX] = p[..NX * NX]
        .as_chunks::<NX>()
        .0
        .try_into()
        .expect("NX * NX entries are NX columns of NX");
    let a: &[[f64; M]; NX] = a[..M * NX]
        .as_chunks::<M>()
        .0
        .try_into()
        .expect("M * NX entries are NX columns of M");
    let (yx, ylambda) = y[..NX + M].split_at(NX);
    let mut top = [0.0; NX];
    let mut bottom = [0.0; M];
    for ((pj, aj), yj) in p.iter().zip(a).zip(yx) {
        for (o, pij) in top.iter_mut().zip(pj) {
            *o += pij * yj;
        }
        for (o, akj) in bottom.iter_mut().zip(aj) {
            *o += akj * yj;
        }
    }
    for (o, ai) in top.iter_mut().zip(a) {
        let mut s = *o;
        for (aki, yk) in ai.iter().zip(ylambda) {
            s += aki * yk;
        }
        *o = s;
    }
    out[..NX].copy_from_slice(&top);
    out[NX..NX + M].copy_from_slice(&bottom);
}

impl NeuralSolver for ZeroingNetwork {
    fn error_norm(&mut self, qp: &Qp, y: &[f64]) -> Option<f64> {
        Some(euclidean_norm(self.error(qp, y)))
    }
    fn name(&self) -> String {
        self.name.clone()
    }
    fn state_dim(&self, dims: QpDims) -> usize {
        dims.nx + dims.n_eq
    }
    fn needs_qp_dot(&self) -> bool {
        true
    }
    fn rhs(&mut self, t: f64, y: &[f64], qp: &Qp, qp_dot: Option<&Qp>, ydot: &mut [f64]) {
        let nx = self.dims.nx;
        let n = y.len();
        debug_assert_eq!(n, self.dims.nx + self.dims.n_eq);
        self.compute_error(qp, y);
        self.fill_perturbation(t);
        let g = self.gain.at(t);
        let matrix_perturbation = self.uses_matrix_perturbation();
        if let Some(d) = qp_dot {
            Self::qdot_times(self.dims, d, y, &mut self.products[..n]);
        }
        // The fields and buffers read once, as slices of n entries. The right-hand side
        // r_i = -g Phi(E_i) [- nu t E_i] [+ udot_i - (Qdot y)_i] [+ perturbation_i] is built
        // one term at a time over all i (each a loop without the options' branches inside),
        // every r_i taking its terms in that order, as a loop over i adding them all did.
        let (activation, nu, udot_q) = (self.activation, self.nu, self.udot_q);
        let (e, products, ydot) = (&self.e[..n], &self.products[..n], &mut ydot[..n]);
        if matches!(activation, Activation::Linear) {
            for (r, ei) in ydot.iter_mut().zip(e) {
                *r = -g * ei;
            }
        } else {
            for (r, &ei) in ydot.iter_mut().zip(e) {
                *r = -g * activation.value(ei);
            }
        }
        if nu != 0.0 {
            for (r, ei) in ydot.iter_mut().zip(e) {
                *r -= nu * t * ei;
            }
        }
        if let Some(d) = qp_dot {
            let (top, bottom) = ydot.split_at_mut(nx);
            let (p_top, p_bottom) = products.split_at(nx);
            for ((r, q_dot), p) in top.iter_mut().zip(d.q.as_slice()).zip(p_top) {
                let udot = if udot_q { -q_dot } else { 0.0 };
                *r += udot - p;
            }
            for ((r, b_dot), p) in bottom.iter_mut().zip(d.b.as_slice()).zip(p_bottom) {
                *r += b_dot - p;
            }
        }
        if matrix_perturbation {
            for (i, r) in ydot.iter_mut().enumerate() {
                let mut dy = 0.0;
                for j in 0..n {
                    dy += self.delta_d[(i, j)] * y[j];
                }
                *r += self.delta_s[i] - dy;
            }
        } else if self.perturbation.is_some() {
            for (r, ds) in ydot.iter_mut().zip(&self.delta_s) {
                *r += ds;
            }
        }
        if !self.kkt.factor(qp) {
            ydot.fill(f64::NAN);
            return;
        }
        self.kkt.solve(ydot);
    }
    fn data_derivative(
        &mut self,
        t: f64,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        dqp: &Qp,
        dqp_dot: Option<&Qp>,
        out: &mut [f64],
    ) -> bool {
        // Given for the sign-power activation only (kong2019's finite-time network), whose band
        // of width delta makes the coupled loop's forward difference of F wrong; the networks
        // with smooth activations keep that difference, and their runs stay bit for bit.
        if !matches!(
            self.activation,
            Activation::SignPower { .. } | Activation::SignBiPower { .. }
        ) {
            return false;
        }
        let nx = self.dims.nx;
        let n = y.len();
        // F at the base point; leaves E in `self.e` and the factors of Q in `self.kkt`.
        let mut f = std::mem::take(&mut self.f_base);
        self.rhs(t, y, qp, qp_dot, &mut f);
        if f.iter().any(|v| !v.is_finite()) {
            self.f_base = f;
            return false;
        }
        let g = self.gain.at(t);
        let (dq_y, rest) = self.products.split_at_mut(n);
        let (dq_f, rest) = rest.split_at_mut(n);
        let dqdot_y = &mut rest[..n];
        Self::qdot_times(self.dims, dqp, y, dq_y);
        Self::qdot_times(self.dims, dqp, &f, dq_f);
        if let (Some(_), Some(dd)) = (qp_dot, dqp_dot) {
            Self::qdot_times(self.dims, dd, y, dqdot_y);
        }
        for i in 0..n {
            // dE = dQ y - du, du = [-dq; db].
            let du = if i < nx { -dqp.q[i] } else { dqp.b[i - nx] };
            let de = dq_y[i] - du;
            let mut s = g * self.activation.derivative(self.e[i]);
            if self.nu != 0.0 {
                s += self.nu * t;
            }
            let mut r = -s * de - dq_f[i];
            if let (Some(_), Some(dd)) = (qp_dot, dqp_dot) {
                let dudot = if i >= nx {
                    dd.b[i - nx]
                } else if self.udot_q {
                    -dd.q[i]
                } else {
                    0.0
                };
                r += dudot - dqdot_y[i];
            }
            out[i] = r;
        }
        self.f_base = f;
        self.kkt.solve(out);
        true
    }
    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        let QpDims { nx, n_eq, .. } = self.dims;
        let n = y.len();
        assemble_q(self.dims, qp, jac);
        self.compute_error(qp, y);
        self.fill_perturbation(t);
        let g = self.gain.at(t);
        // Right-hand side -Qdot - DeltaD - (g diag(Phi'(E)) + nu t I) Q.
        for i in 0..n {
            let mut s = g * self.activation.derivative(self.e[i]);
            if self.nu != 0.0 {
                s += self.nu * t;
            }
            for j in 0..n {
                jac[(i, j)] *= -s;
            }
        }
        if let Some(d) = qp_dot {
            for i in 0..nx {
                for j in 0..nx {
                    jac[(i, j)] -= d.p[(i, j)];
                }
            }
            for k in 0..n_eq {
                for j in 0..nx {
                    jac[(j, nx + k)] -= d.a[(k, j)];
                    jac[(nx + k, j)] -= d.a[(k, j)];
                }
            }
        }
        if self.uses_matrix_perturbation() {
            for i in 0..n {
                for j in 0..n {
                    jac[(i, j)] -= self.delta_d[(i, j)];
                }
            }
        }
        if !self.kkt.factor(qp) {
            return false;
        }
        self.kkt.solve_columns(jac);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::{block_times, block_times_fixed};

    /// The compiled sizes give the run-time loop's products bit for bit (zeros and a NaN among
    /// the entries included).
    #[test]
    fn compiled_block_products_match_the_run_time_loop() {
        let mut state = 7u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let v = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            // About one entry in eight is zero, as in a QP's blocks.
            if state >> 61 == 0 {
                0.0
            } else {
                v
            }
        };
        for (nx, m) in [(5usize, 3usize), (6, 3), (7, 3)] {
            for case in 0..200 {
                let p: Vec<f64> = (0..nx * nx).map(|_| next()).collect();
                let mut a: Vec<f64> = (0..m * nx).map(|_| next()).collect();
                let y: Vec<f64> = (0..nx + m).map(|_| next()).collect();
                if case == 0 {
                    a[1] = f64::NAN;
                }
                let (mut fixed, mut dynamic) = (vec![0.0; nx + m], vec![0.0; nx + m]);
                match nx {
                    5 => block_times_fixed::<5, 3>(&p, &a, &y, &mut fixed),
                    6 => block_times_fixed::<6, 3>(&p, &a, &y, &mut fixed),
                    _ => block_times_fixed::<7, 3>(&p, &a, &y, &mut fixed),
                }
                block_times(nx, m, &p, &a, &y, &mut dynamic);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fixed), bits(&dynamic), "nx = {nx}, case {case}");
            }
        }
    }
}
