//! The arm and its solver as one ODE, as the papers' group wrote it in MATLAB.
//!
//! Velocity level: state [theta; y], theta' = x[..n].
//! Acceleration level: state [theta; thetadot; y], theta' = thetadot, thetadot' = x[..n].
//!
//! - Exact loop ([`ExactLoop`]): no network state; x = x*(t, theta, thetadot), the optimum of
//!   the scheme's QP at every evaluation (certified active set, Clarabel as fallback and check).
//! - Neural loop ([`NeuralLoop`]): y is the network state, x = y[..nx] (the network's current
//!   estimate), y' = F_net(t, y; QP(t, theta, thetadot)) with, for the zeroing networks, the
//!   QP's time derivative taken along the current motion (theta moving at thetadot, thetadot at
//!   the network's thetaddot).
//!
//! The neural loop's Jacobian combines the network's analytic dF/dy with the QP frozen (where
//! it gives one), the exact arm rows, and, for the arm-state columns (QP data depends on theta
//! nonlinearly through J, f and the bounds) and for the zeroing networks' joint-command columns
//! too (dQP/dt is taken along the command), the chain rule where the network gives its
//! derivative along the QP data ([`NeuralSolver::data_derivative`]): central differences of
//! the QP data (and dQP/dt) times that derivative. Differencing F as a whole (the fallback, and
//! what the other networks get) puts the network's own nonlinearity inside the difference: for
//! kong2019's finite-time network on its finite-time scheme a step of sqrt(eps) in a joint
//! angle whose error sits inside the sign-power's band moves the network error E by ~1e-3,
//! a thousand times the activation's band of 1e-6, and the column came out ~90x too small:
//! Newton then failed on every other step (650,000 steps instead of ~3,000).

use nalgebra::{DMatrix, DVector};
use qp::QpDotScratch;
use schemes::Scheme;
use solvers::neural::NeuralSolver;
use solvers::ode::OdeSystem;
use solvers::{ExactError, Qp};
use solvers::{ExactPath, ExactPathStats};
use spec::Level;

/// Number of arm-state entries of an n-joint arm: n at the velocity level, 2n at the
/// acceleration level.
pub fn arm_dim(n: usize, level: Level) -> usize {
    match level {
        Level::Velocity => n,
        Level::Acceleration => 2 * n,
    }
}

/// (theta, thetadot) of an n-joint arm as slices of a state vector; thetadot = `command` at
/// the velocity level (it is not a state there).
pub fn arm_slices<'y>(
    n: usize,
    level: Level,
    y: &'y [f64],
    command: &'y [f64],
) -> (&'y [f64], &'y [f64]) {
    match level {
        Level::Velocity => (&y[..n], &command[..n]),
        Level::Acceleration => (&y[..n], &y[n..2 * n]),
    }
}

/// Writes the arm part of y' of an n-joint arm given the joint command x[..n].
fn arm_rhs(n: usize, level: Level, y: &[f64], command: &[f64], dy: &mut [f64]) {
    match level {
        Level::Velocity => dy[..n].copy_from_slice(&command[..n]),
        Level::Acceleration => {
            dy[..n].copy_from_slice(&y[n..2 * n]);
            dy[n..2 * n].copy_from_slice(&command[..n]);
        }
    }
}

/// The scheme with its exact optimum in the loop ([`ExactPath`]: the certified active-set
/// solver, Clarabel when it fails and on a sample).
pub struct ExactLoop<'a> {
    /// The scheme whose QP is solved at every evaluation.
    pub scheme: &'a dyn Scheme,
    /// The QP buffer, rebuilt in place at every evaluation.
    pub qp: Qp,
    /// The exact solver, hot-started along the run.
    pub solver: ExactPath,
    /// First failure of the exact solver, with its instant (the run is then reported as
    /// failed with it).
    pub failure: Option<(f64, ExactError)>,
    /// thetadot = 0, the velocity level's unused argument of the scheme.
    zeros: Vec<f64>,
}

impl<'a> ExactLoop<'a> {
    /// The loop of `scheme`, its QP and solver buffers allocated once.
    pub fn new(scheme: &'a dyn Scheme) -> Self {
        let qp = scheme.new_qp();
        Self {
            scheme,
            solver: ExactPath::new(&qp),
            qp,
            failure: None,
            zeros: vec![0.0; scheme.joints()],
        }
    }

    /// x*(t, theta, thetadot) with the QP it solves (both in the loop's buffers: nothing is
    /// allocated), or the solver's error.
    pub fn optimum(
        &mut self,
        t: f64,
        theta: &[f64],
        thetadot: &[f64],
    ) -> Result<(&DVector<f64>, &Qp), ExactError> {
        self.scheme.build(t, theta, thetadot, &mut self.qp);
        let x = self.solver.solve(&self.qp)?;
        Ok((x, &self.qp))
    }

    /// QPs solved, fallbacks and the Clarabel sample so far.
    pub fn stats(&self) -> ExactPathStats {
        self.solver.stats
    }
}

impl OdeSystem for ExactLoop<'_> {
    fn dim(&self) -> usize {
        arm_dim(self.scheme.joints(), self.scheme.level())
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let level = self.scheme.level();
        let n = self.scheme.joints();
        let zeros = std::mem::take(&mut self.zeros);
        let (theta, thetadot) = arm_slices(n, level, y, &zeros);
        let failure = match self.optimum(t, theta, thetadot) {
            Ok((x, _)) => {
                arm_rhs(n, level, y, x.as_slice(), dy);
                None
            }
            Err(e) => {
                dy.fill(f64::NAN);
                Some(e)
            }
        };
        self.zeros = zeros;
        if let (Some(e), None) = (failure, &self.failure) {
            self.failure = Some((t, e));
        }
    }
}

/// The scheme solved by a recurrent network, integrated together with the arm.
pub struct NeuralLoop<'a> {
    /// The scheme whose QP the network solves.
    pub scheme: &'a dyn Scheme,
    /// The network; its state is the part of y after the arm's.
    pub network: Box<dyn NeuralSolver>,
    qp: Qp,
    qp_dot: Qp,
    dot_scratch: QpDotScratch,
    net_dim: usize,
    /// Evaluations of F spent inside [`OdeSystem::jacobian`] (finite-difference columns).
    pub jacobian_rhs_evals: usize,
    jac_net: DMatrix<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    yp: Vec<f64>,
    /// QP data (and dQP/dt) at y -/+ h e_j, then their difference quotient, for the chain rule.
    qp_lo: Qp,
    qp_hi: Qp,
    qp_dot_lo: Qp,
    qp_dot_hi: Qp,
    dcol: Vec<f64>,
    /// The zero thetaddot of the velocity level's dQP/dt.
    zeros: Vec<f64>,
}

/// The QP (and, with `dot`, dQP/dt along the command) at the state y, as [`NeuralLoop`]'s
/// right-hand side builds them.
/// `zeros` holds n zeros (the velocity level's thetaddot).
#[allow(clippy::too_many_arguments)]
fn qp_data_at(
    scheme: &dyn Scheme,
    k: usize,
    t: f64,
    y: &[f64],
    qp: &mut Qp,
    dot: Option<&mut Qp>,
    scratch: &mut QpDotScratch,
    zeros: &[f64],
) {
    let level = scheme.level();
    let n = scheme.joints();
    let (theta, thetadot) = arm_slices(n, level, y, &y[k..]);
    scheme.build(t, theta, thetadot, qp);
    if let Some(qp_dot) = dot {
        let command = &y[k..k + n];
        let (thetadot_m, thetaddot) = match level {
            Level::Velocity => (command, zeros),
            Level::Acceleration => (thetadot, command),
        };
        scheme.build_dot(t, theta, thetadot_m, thetaddot, qp_dot, scratch);
    }
}

/// hi <- (hi - lo) / (2 h) for the data the networks read (P, q, A, b, G, h).
fn central_difference(hi: &mut Qp, lo: &Qp, h: f64) {
    let s = 0.5 / h;
    for (a, b) in [(&mut hi.p, &lo.p), (&mut hi.a, &lo.a), (&mut hi.g, &lo.g)] {
        *a -= b;
        *a *= s;
    }
    for (a, b) in [(&mut hi.q, &lo.q), (&mut hi.b, &lo.b), (&mut hi.h, &lo.h)] {
        *a -= b;
        *a *= s;
    }
}

impl<'a> NeuralLoop<'a> {
    /// The loop of `scheme` and `network`, every buffer sized for the scheme's QP once.
    pub fn new(scheme: &'a dyn Scheme, network: Box<dyn NeuralSolver>) -> Self {
        let net_dim = network.state_dim(scheme.dims());
        let dim = arm_dim(scheme.joints(), scheme.level()) + net_dim;
        Self {
            scheme,
            network,
            qp: scheme.new_qp(),
            qp_dot: scheme.new_qp(),
            dot_scratch: scheme.new_dot_scratch(),
            net_dim,
            jacobian_rhs_evals: 0,
            jac_net: DMatrix::zeros(net_dim, net_dim),
            f0: vec![0.0; dim],
            f1: vec![0.0; dim],
            yp: vec![0.0; dim],
            qp_lo: scheme.new_qp(),
            qp_hi: scheme.new_qp(),
            qp_dot_lo: scheme.new_qp(),
            qp_dot_hi: scheme.new_qp(),
            dcol: vec![0.0; net_dim],
            zeros: vec![0.0; scheme.joints()],
        }
    }

    /// Offset of the network state in the ODE state.
    pub fn net_offset(&self) -> usize {
        arm_dim(self.scheme.joints(), self.scheme.level())
    }

    fn eval(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let k = self.net_offset();
        let level = self.scheme.level();
        let n = self.scheme.joints();
        let dot = self.network.needs_qp_dot();
        qp_data_at(
            self.scheme,
            k,
            t,
            y,
            &mut self.qp,
            dot.then_some(&mut self.qp_dot),
            &mut self.dot_scratch,
            &self.zeros,
        );
        let qp_dot = dot.then_some(&self.qp_dot);
        let (arm, net) = dy.split_at_mut(k);
        self.network.rhs(t, &y[k..], &self.qp, qp_dot, net);
        arm_rhs(n, level, y, &y[k..], arm);
    }
}

impl NeuralLoop<'_> {
    /// The network rows of the first `columns` columns of the Jacobian by the chain rule (module
    /// docs): the network's analytic block (already in `jac`, for the command columns) plus its
    /// derivative along the QP data, differenced centrally with step sqrt(eps) max(|y_j|, 1).
    /// `self.qp` and `self.qp_dot` must hold the data at y. False (and `jac` untouched) when
    /// the network does not give its data derivative.
    fn chain_rule_columns(
        &mut self,
        t: f64,
        y: &[f64],
        columns: usize,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        let k = self.net_offset();
        let scheme = self.scheme;
        let dot = self.network.needs_qp_dot();
        let mut dcol = std::mem::take(&mut self.dcol);
        self.yp.copy_from_slice(y);
        for j in 0..columns {
            let h = f64::EPSILON.sqrt() * y[j].abs().max(1.0);
            self.yp[j] = y[j] + h;
            let hi = self.yp[j];
            qp_data_at(
                scheme,
                k,
                t,
                &self.yp,
                &mut self.qp_hi,
                dot.then_some(&mut self.qp_dot_hi),
                &mut self.dot_scratch,
                &self.zeros,
            );
            self.yp[j] = y[j] - h;
            let lo = self.yp[j];
            qp_data_at(
                scheme,
                k,
                t,
                &self.yp,
                &mut self.qp_lo,
                dot.then_some(&mut self.qp_dot_lo),
                &mut self.dot_scratch,
                &self.zeros,
            );
            self.yp[j] = y[j];
            // The step actually taken (y_j +- h rounded).
            let h = 0.5 * (hi - lo);
            central_difference(&mut self.qp_hi, &self.qp_lo, h);
            if dot {
                central_difference(&mut self.qp_dot_hi, &self.qp_dot_lo, h);
            }
            let ok = self.network.data_derivative(
                t,
                &y[k..],
                &self.qp,
                dot.then_some(&self.qp_dot),
                &self.qp_hi,
                dot.then_some(&self.qp_dot_hi),
                &mut dcol,
            );
            if !ok {
                self.dcol = dcol;
                return false;
            }
            for (i, d) in dcol.iter().enumerate() {
                let analytic = if j >= k {
                    self.jac_net[(i, j - k)]
                } else {
                    0.0
                };
                jac[(k + i, j)] = analytic + d;
            }
        }
        self.dcol = dcol;
        true
    }
}

impl OdeSystem for NeuralLoop<'_> {
    fn dim(&self) -> usize {
        self.net_offset() + self.net_dim
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.eval(t, y, dy);
    }

    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) -> bool {
        let k = self.net_offset();
        let level = self.scheme.level();
        let arm = self.scheme.joints();
        // F at y: the base of the differences below, and it leaves the QP (and, for the
        // zeroing networks, dQP/dt) at this state for the network's analytic block.
        let mut f0 = std::mem::take(&mut self.f0);
        self.eval(t, y, &mut f0);
        self.f0 = f0;
        let qp_dot_needed = self.network.needs_qp_dot();
        let qp_dot = qp_dot_needed.then_some(&self.qp_dot);
        if !self
            .network
            .jacobian(t, &y[k..], &self.qp, qp_dot, &mut self.jac_net)
        {
            self.jacobian_rhs_evals += 1;
            return false;
        }
        let n = self.dim();
        jac.fill(0.0);
        jac.view_mut((k, k), (self.net_dim, self.net_dim))
            .copy_from(&self.jac_net);
        // Arm rows: theta' = x[..n] (velocity) or theta' = thetadot, thetadot' = x[..n].
        match level {
            Level::Velocity => (0..arm).for_each(|i| jac[(i, k + i)] = 1.0),
            Level::Acceleration => (0..arm).for_each(|i| {
                jac[(i, arm + i)] = 1.0;
                jac[(arm + i, k + i)] = 1.0;
            }),
        }
        // Network rows, by forward differences, for the arm-state columns and (for networks fed
        // with dQP/dt) the joint-command columns: dQP/dt is taken along the network's own
        // command, a dependence the frozen-QP block above does not see.
        let fd_columns = if qp_dot_needed { k + arm } else { k };
        if self.chain_rule_columns(t, y, fd_columns, jac) {
            // F at y above (the network's data derivatives are not evaluations of F).
            self.jacobian_rhs_evals += 1;
            return true;
        }
        let f0 = std::mem::take(&mut self.f0);
        let mut f1 = std::mem::take(&mut self.f1);
        self.jacobian_rhs_evals += 1 + fd_columns;
        self.yp.copy_from_slice(y);
        for j in 0..fd_columns {
            let h = f64::EPSILON.sqrt() * y[j].abs().max(1.0);
            self.yp[j] = y[j] + h;
            let yp = std::mem::take(&mut self.yp);
            self.eval(t, &yp, &mut f1);
            self.yp = yp;
            for i in k..n {
                jac[(i, j)] = (f1[i] - f0[i]) / h;
            }
            self.yp[j] = y[j];
        }
        self.f0 = f0;
        self.f1 = f1;
        true
    }
}
