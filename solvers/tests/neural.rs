//! Tests of the papers' neural solvers (solvers::neural): activations, analytic Jacobians,
//! steady states on frozen random QPs against the exact optimum, tracking of time-varying QPs,
//! the reference perturbation, and the experiment-file specifications.

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use settings::projection::{ProjectionErrorForm, ProjectionSpec, Scaling};
use settings::zeroing::GainLaw;
use settings::ReferencePerturbation;
use settings::SolverSpec;
use settings::SIGN_POWER_MIN_ABS;
use settings::{ActivationKind, ActivationSpec};
use settings::{IntegratorSettings, Method};
use solvers::neural::activation::Activation;
use solvers::neural::projection::{primal_dual_dim, LviCore};
use solvers::neural::{build_solver, NeuralSolver, PerturbationTerms, ProjectionNetwork};
use solvers::ode::{integrate, Control, OdeSystem};
use solvers::{random_qp, ExactSolver, Qp, QpDims, QpShape};

// ---------------------------------------------------------------------------------------------
// helpers

/// The projection family's LVI form with scaling `scaling` and constant gain `gamma`, linear:
/// LVI-PDNN (`IPlusMt`) or S-LVI-PDNN (`Identity`).
fn lvi_network(scaling: Scaling, gamma: f64, dims: QpDims) -> ProjectionNetwork {
    let spec = ProjectionSpec {
        name: "LVI",
        error: ProjectionErrorForm::Lvi { scaling },
        gain: GainLaw::Constant { gamma },
        activation: ActivationSpec::of(ActivationKind::Linear),
    };
    ProjectionNetwork::from_spec(&spec, dims).unwrap()
}

/// The projection family's penalty form (p, sigma) with gain law `gain` and activation `act`:
/// VP-RNN-PF with `GainLaw::Exponential`.
fn penalty_network(
    p: f64,
    sigma: f64,
    gain: GainLaw,
    act: ActivationSpec,
    dims: QpDims,
) -> ProjectionNetwork {
    let spec = ProjectionSpec {
        name: "VP-RNN-PF",
        error: ProjectionErrorForm::Penalty { p, sigma },
        gain,
        activation: act,
    };
    ProjectionNetwork::from_spec(&spec, dims).unwrap()
}

/// VP-RNN-PF (zhong2021 (2.30)): the penalty form with gain gamma exp(t).
fn vp_rnn_pf(
    p: f64,
    sigma: f64,
    gamma: f64,
    act: ActivationSpec,
    dims: QpDims,
) -> ProjectionNetwork {
    penalty_network(p, sigma, GainLaw::Exponential { gamma }, act, dims)
}

/// The network of `spec` for QPs of sizes `dims`.
fn built(spec: SolverSpec, dims: QpDims) -> Box<dyn NeuralSolver> {
    build_solver(&spec, dims).unwrap_or_else(|e| panic!("{spec:?}: {e}"))
}

/// A network on a QP that is either frozen (`qp1 = None`) or moves linearly,
/// QP(t) = qp0 + t qp1 (bounds fixed), so that dQP/dt = qp1 exactly.
struct Net<'a> {
    solver: &'a mut dyn NeuralSolver,
    qp0: &'a Qp,
    qp1: Option<&'a Qp>,
    qp: Qp,
    n: usize,
}

impl<'a> Net<'a> {
    fn new(solver: &'a mut dyn NeuralSolver, qp0: &'a Qp, qp1: Option<&'a Qp>) -> Self {
        let n = solver.state_dim(qp0.dims());
        Self {
            solver,
            qp0,
            qp1,
            qp: qp0.clone(),
            n,
        }
    }
    fn update(&mut self, t: f64) {
        if let Some(d) = self.qp1 {
            qp_at(self.qp0, d, t, &mut self.qp);
        }
    }
}

fn qp_at(qp0: &Qp, d: &Qp, t: f64, out: &mut Qp) {
    out.p.copy_from(&(&qp0.p + &d.p * t));
    out.q.copy_from(&(&qp0.q + &d.q * t));
    out.a.copy_from(&(&qp0.a + &d.a * t));
    out.b.copy_from(&(&qp0.b + &d.b * t));
    out.g.copy_from(&(&qp0.g + &d.g * t));
    out.h.copy_from(&(&qp0.h + &d.h * t));
}

impl OdeSystem for Net<'_> {
    fn dim(&self) -> usize {
        self.n
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.update(t);
        self.solver.rhs(t, y, &self.qp, self.qp1, dy);
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) -> bool {
        self.update(t);
        self.solver.jacobian(t, y, &self.qp, self.qp1, jac)
    }
}

fn settings(rtol: f64, atol: f64) -> IntegratorSettings {
    IntegratorSettings {
        method: Method::Bdf,
        rtol,
        atol,
        max_steps: 200_000,
        max_step: None,
        ..IntegratorSettings::default()
    }
}

/// Integrate the network on the frozen QP from y(0) over chunks of length chunk, 2 chunk,
/// 4 chunk, ... until `done(y)` (at most `max_chunks`).
fn steady_state(
    solver: &mut dyn NeuralSolver,
    qp: &Qp,
    chunk: f64,
    max_chunks: usize,
    s: &IntegratorSettings,
    mut done: impl FnMut(&mut dyn NeuralSolver, f64, &[f64]) -> bool,
) -> Vec<f64> {
    let n = solver.state_dim(qp.dims());
    let mut y = vec![0.0; n];
    solver.initial_state(qp.dims(), &mut y);
    let mut t = 0.0;
    let mut len = chunk;
    for _ in 0..max_chunks {
        let mut net = Net::new(&mut *solver, qp, None);
        let (y1, _) = integrate(&mut net, &y, t, t + len, s, |_, _| Control::Continue)
            .expect("integration failed");
        y = y1;
        t += len;
        len *= 2.0;
        if done(solver, t, &y) {
            break;
        }
    }
    y
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn x_err(y: &[f64], xs: &DVector<f64>) -> f64 {
    xs.iter()
        .zip(y)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
}

/// A random derivative of a QP (same shapes; bounds' derivatives zero where bounds are absent).
fn random_qp_dot(qp: &Qp, rng: &mut ChaCha8Rng, scale: f64) -> Qp {
    let mut d = Qp::zeros(qp.dims());
    let QpDims { nx, n_eq, n_in } = qp.dims();
    let mut r = |_: usize, _: usize| rng.gen_range(-scale..scale);
    let ps = DMatrix::from_fn(nx, nx, &mut r);
    d.p = (&ps + ps.transpose()) * 0.5;
    d.q = DVector::from_fn(nx, &mut r);
    d.a = DMatrix::from_fn(n_eq, nx, &mut r);
    d.b = DVector::from_fn(n_eq, &mut r);
    d.g = DMatrix::from_fn(n_in, nx, &mut r);
    d.h = DVector::from_fn(n_in, &mut r);
    for j in 0..nx {
        d.lower[j] = if qp.lower[j].is_finite() {
            r(0, 0)
        } else {
            0.0
        };
        d.upper[j] = if qp.upper[j].is_finite() {
            r(0, 0)
        } else {
            0.0
        };
    }
    d
}

/// Central-difference dF/dy of the solver's rhs.
fn fd_jacobian(
    solver: &mut dyn NeuralSolver,
    t: f64,
    y: &[f64],
    qp: &Qp,
    qp_dot: Option<&Qp>,
) -> DMatrix<f64> {
    let n = y.len();
    let mut jac = DMatrix::zeros(n, n);
    let mut yp = y.to_vec();
    let mut fp = vec![0.0; n];
    let mut fm = vec![0.0; n];
    for j in 0..n {
        let h = 1e-6 * y[j].abs().max(1.0);
        yp[j] = y[j] + h;
        solver.rhs(t, &yp, qp, qp_dot, &mut fp);
        yp[j] = y[j] - h;
        solver.rhs(t, &yp, qp, qp_dot, &mut fm);
        yp[j] = y[j];
        for i in 0..n {
            jac[(i, j)] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    jac
}

/// Max |J - J_fd| relative to max(1, |J|_max).
fn jacobian_mismatch(
    solver: &mut dyn NeuralSolver,
    t: f64,
    y: &[f64],
    qp: &Qp,
    qp_dot: Option<&Qp>,
) -> f64 {
    let n = y.len();
    let mut jac = DMatrix::from_element(n, n, f64::NAN);
    assert!(
        solver.jacobian(t, y, qp, qp_dot, &mut jac),
        "{} gives no analytic Jacobian",
        solver.name()
    );
    let fd = fd_jacobian(solver, t, y, qp, qp_dot);
    let scale = jac.amax().max(1.0);
    (&jac - &fd).amax() / scale
}

fn exact(qp: &Qp) -> solvers::ExactSolution {
    ExactSolver::new()
        .solve(qp)
        .expect("exact solver failed on a feasible random QP")
}

const N_QPS: u64 = 1000;

// ---------------------------------------------------------------------------------------------
// activations

fn all_activations() -> Vec<Activation> {
    vec![
        Activation::Linear,
        Activation::Sinh,
        Activation::power_sigmoid_default(),
        Activation::PowerSigmoid {
            alpha: 2.0,
            chi: 5.0,
        },
        Activation::SignPower {
            r: 0.1,
            smoothing: 0.0,
        },
        Activation::SignPower {
            r: 0.5,
            smoothing: 0.0,
        },
        Activation::GroupPowerSigmoid { xi: 1.0, p: 1.0 },
        Activation::GroupPowerSigmoid { xi: 1.0, p: 3.0 },
        Activation::GroupPowerSigmoid { xi: 4.0, p: 3.0 },
    ]
}

#[test]
fn group_power_sigmoid_is_afmpowersigmoid() {
    // AFMpowersigmoid(e, xi, p) transcribed: e^p where |e| >= 1, else the sigmoid, on e itself.
    let afm = |e: f64, xi: f64, p: i32| {
        if e.abs() >= 1.0 {
            e.powi(p)
        } else {
            ((1.0 + (-xi).exp()) / (1.0 - (-xi).exp())) * (1.0 - (-xi * e).exp())
                / (1.0 + (-xi * e).exp())
        }
    };
    for (xi, p) in [(1.0, 1), (1.0, 3), (2.5, 3)] {
        let act = Activation::GroupPowerSigmoid { xi, p: p as f64 };
        assert!(act.validate().is_ok());
        for e in [
            -3.0, -1.0, -0.999, -0.4, -1e-3, 0.0, 1e-3, 0.3, 0.999, 1.0, 1.2, 4.0,
        ] {
            let (got, want) = (act.value(e), afm(e, xi, p));
            assert!(
                (got - want).abs() <= 1e-14 * want.abs().max(1.0),
                "xi={xi} p={p} at {e}: {got} vs {want}"
            );
            // Odd, exactly.
            assert_eq!(act.value(-e), -act.value(e));
        }
        // Continuous at |e| = 1: both branches give +-1.
        for s in [1.0, -1.0] {
            let inside = act.value(s * (1.0 - 1e-12));
            let outside = act.value(s * (1.0 + 1e-12));
            assert!((inside - s).abs() < 1e-10 && (outside - s).abs() < 1e-10);
            assert!((act.value(s) - s).abs() < 1e-15);
        }
        // The power branch owns |e| = 1: its derivative is p there, the sigmoid's xi/sinh(xi)
        // just inside.
        assert_eq!(act.derivative(1.0), p as f64);
        let inner = act.derivative(1.0 - 1e-12);
        assert!((inner - xi / xi.sinh()).abs() < 1e-9, "{inner}");
    }
    // Same family as zhong2021's eq. 2.29: alpha = xi, chi = p, equal away from |e| = 1.
    let g = Activation::GroupPowerSigmoid { xi: 4.0, p: 3.0 };
    let z = Activation::PowerSigmoid {
        alpha: 4.0,
        chi: 3.0,
    };
    for e in [-2.0, -0.7, 0.2, 0.9, 1.5] {
        assert_eq!(g.value(e), z.value(e));
        assert_eq!(g.derivative(e), z.derivative(e));
    }
    for bad in [
        (0.0, 1.0),
        (-1.0, 1.0),
        (1.0, 0.5),
        (f64::NAN, 1.0),
        (1.0, f64::INFINITY),
    ] {
        assert!(Activation::GroupPowerSigmoid {
            xi: bad.0,
            p: bad.1
        }
        .validate()
        .is_err());
    }
}

#[test]
fn activations_are_odd_and_increasing() {
    let pts: Vec<f64> = (-400..=400).map(|i| i as f64 * 0.01).collect();
    for act in all_activations() {
        for &e in &pts {
            assert_eq!(act.value(-e), -act.value(e), "{act:?} not odd at {e}");
        }
        for w in pts.windows(2) {
            assert!(
                act.value(w[1]) > act.value(w[0]),
                "{act:?} not increasing on [{}, {}]",
                w[0],
                w[1]
            );
        }
        assert_eq!(act.value(0.0), 0.0);
    }
}

#[test]
fn activations_have_the_papers_forms() {
    // Linear (zhong2021 eq. 2.27), sinh (2.28).
    for e in [-3.0, -0.5, 0.2, 1.7] {
        assert_eq!(Activation::Linear.value(e), e);
        assert!((Activation::Sinh.value(e) - (e.exp() - (-e).exp()) / 2.0).abs() < 1e-14);
    }
    // Power-sigmoid (2.29) with alpha = 4, chi = 3.
    let ps = Activation::power_sigmoid_default();
    let a: f64 = 4.0;
    let sig = |e: f64| {
        (1.0 + (-a).exp()) * (1.0 - (-a * e).exp()) / ((1.0 - (-a).exp()) * (1.0 + (-a * e).exp()))
    };
    for e in [0.1, 0.5, 0.9, 1.0] {
        assert!(
            (ps.value(e) - sig(e)).abs() < 1e-14,
            "sigmoid branch at {e}"
        );
    }
    for e in [1.5, 2.0, 3.0] {
        assert!(
            (ps.value(e) - e.powi(3)).abs() < 1e-12,
            "power branch at {e}"
        );
        assert!((ps.value(-e) + e.powi(3)).abs() < 1e-12);
    }
    // Continuous at |e| = 1 (both branches give 1).
    assert!((ps.value(1.0) - 1.0).abs() < 1e-14);
    assert!((ps.value(1.0 + 1e-12) - 1.0).abs() < 1e-10);
    // Sign-power (kong2019 eq. 6): |e|^r sgn(e).
    let sp = Activation::SignPower {
        r: 0.1,
        smoothing: 0.0,
    };
    for e in [-2.0_f64, -1e-3, 1e-6, 0.3, 5.0] {
        assert!((sp.value(e) - e.abs().powf(0.1) * e.signum()).abs() < 1e-14);
    }
}

#[test]
fn activation_derivatives_match_finite_differences() {
    let pts = [-3.2, -1.3, -0.7, -0.05, 0.05, 0.4, 0.95, 1.05, 2.5];
    for act in all_activations() {
        for &e in &pts {
            let h = 1e-6;
            let fd = (act.value(e + h) - act.value(e - h)) / (2.0 * h);
            let d = act.derivative(e);
            assert!(
                (d - fd).abs() <= 1e-6 * d.abs().max(1.0),
                "{act:?} at {e}: analytic {d}, fd {fd}"
            );
            assert!(d > 0.0);
        }
    }
    // Sign-power slope is finite at 0 (floored) and huge.
    let d0 = Activation::SignPower {
        r: 0.1,
        smoothing: 0.0,
    }
    .derivative(0.0);
    assert!(d0.is_finite() && d0 >= 0.1 * SIGN_POWER_MIN_ABS.powf(-0.9) * 0.999);
}

// ---------------------------------------------------------------------------------------------
// analytic Jacobians

#[test]
fn projection_jacobians_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (shape, seeds) in [
        (QpShape::Jia2019, 0..20u64),
        (QpShape::Zhong2021, 100..120u64),
    ] {
        for seed in seeds {
            let qp = random_qp(shape, seed);
            let dims = qp.dims();
            let n = primal_dual_dim(dims);
            for _ in 0..3 {
                let y: Vec<f64> = (0..n).map(|_| rng.gen_range(-2.0..2.0)).collect();
                let mut lvi = lvi_network(Scaling::IPlusMt, 1e7, dims);
                let m1 = jacobian_mismatch(&mut lvi, 0.3, &y, &qp, None);
                let mut slvi = lvi_network(Scaling::Identity, 1e7, dims);
                let m2 = jacobian_mismatch(&mut slvi, 0.3, &y, &qp, None);
                assert!(
                    m1 < 1e-7 && m2 < 1e-7,
                    "{shape:?} seed {seed}: LVI {m1:e}, S-LVI {m2:e}"
                );
                // Points of the vocabulary: a power-type gain and the sinh activation, whose
                // slope enters as diag(Phi'(e)).
                for scaling in [Scaling::IPlusMt, Scaling::Identity] {
                    let spec = ProjectionSpec {
                        name: "projection",
                        error: ProjectionErrorForm::Lvi { scaling },
                        gain: GainLaw::Power { gamma: 1e3, p: 2.0 },
                        activation: ActivationSpec::of(ActivationKind::Sinh),
                    };
                    let mut net = ProjectionNetwork::from_spec(&spec, dims).unwrap();
                    let m = jacobian_mismatch(&mut net, 0.3, &y, &qp, None);
                    assert!(m < 1e-6, "{shape:?} seed {seed}: {scaling:?}, sinh {m:e}");
                }
            }
        }
    }
}

#[test]
fn zeroing_jacobians_match_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for seed in 0..20u64 {
        for shape in [QpShape::Zhang2018, QpShape::Kong2019] {
            let qp = random_qp(shape, seed);
            let dims = qp.dims();
            let qp_dot = random_qp_dot(&qp, &mut rng, 1.0);
            let n = dims.nx + dims.n_eq;
            let y: Vec<f64> = (0..n).map(|_| rng.gen_range(-2.0..2.0)).collect();
            let t = rng.gen_range(0.0..2.0);
            let mut nets: Vec<Box<dyn NeuralSolver>> = vec![
                built(
                    SolverSpec::FpCdnn {
                        gamma: 200.0,
                        activation: ActivationSpec::of(ActivationKind::Linear),
                        perturbation: None,
                    },
                    dims,
                ),
                built(
                    SolverSpec::VpCdnn {
                        gamma: 2.0,
                        activation: ActivationSpec::of(ActivationKind::Sinh),
                        perturbation: None,
                    },
                    dims,
                ),
                built(
                    SolverSpec::VpCdnn {
                        gamma: 2.0,
                        activation: ActivationSpec::of(ActivationKind::PowerSigmoid),
                        perturbation: None,
                    },
                    dims,
                ),
                built(
                    SolverSpec::FiniteTime {
                        beta: 1.0,
                        alpha: 0.1,
                        smoothing: 1e-8,
                    },
                    dims,
                ),
                built(SolverSpec::Znn { gamma: 1.0 }, dims),
            ];
            if n == 9 {
                nets.push(built(
                    SolverSpec::FpCdnn {
                        gamma: 200.0,
                        activation: ActivationSpec::of(ActivationKind::Linear),
                        perturbation: Some(ReferencePerturbation::reference(8.0)),
                    },
                    dims,
                ));
                nets.push(built(
                    SolverSpec::VpCdnn {
                        gamma: 200.0,
                        activation: ActivationSpec::of(ActivationKind::Linear),
                        perturbation: Some(ReferencePerturbation::reference(8.0)),
                    },
                    dims,
                ));
                nets.push(built(
                    SolverSpec::GroupZnn {
                        gamma: 500.0,
                        nu: 2500.0,
                        activation: ActivationSpec {
                            xi: 1.0,
                            power: 1.0,
                            ..ActivationSpec::of(ActivationKind::GroupPowerSigmoid)
                        },
                        perturbation: Some(ReferencePerturbation::reference(8.0)),
                        udot_rmp: false,
                    },
                    dims,
                ));
            }
            nets.push(built(
                SolverSpec::GroupZnn {
                    gamma: 500.0,
                    nu: 2500.0,
                    activation: ActivationSpec {
                        xi: 1.0,
                        power: 3.0,
                        ..ActivationSpec::of(ActivationKind::GroupPowerSigmoid)
                    },
                    perturbation: None,
                    udot_rmp: true,
                },
                dims,
            ));
            for net in nets.iter_mut() {
                for qd in [None, Some(&qp_dot)] {
                    let m = jacobian_mismatch(net.as_mut(), t, &y, &qp, qd);
                    assert!(
                        m < 1e-6,
                        "{} on {shape:?} seed {seed}: mismatch {m:e}",
                        net.name()
                    );
                }
            }
        }
    }
}

#[test]
fn vp_rnn_pf_jacobian_matches_finite_differences() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    for seed in 0..20u64 {
        for shape in [QpShape::Zhong2021, QpShape::Jia2019] {
            let qp = random_qp(shape, seed);
            let dims = qp.dims();
            let xs = exact(&qp).x;
            let qp_dot = random_qp_dot(&qp, &mut rng, 1.0);
            for (p, sigma) in [(1e-4, 400.0), (0.1, 5.0)] {
                for act in [
                    ActivationKind::Linear,
                    ActivationKind::Sinh,
                    ActivationKind::PowerSigmoid,
                ]
                .map(ActivationSpec::of)
                {
                    let mut net = vp_rnn_pf(p, sigma, 2.0, act, dims);
                    // Near the optimum (the penalty's scale is 1/sigma), multipliers of order 1.
                    let y: Vec<f64> = (0..dims.nx + dims.n_eq)
                        .map(|i| {
                            if i < dims.nx {
                                xs[i] + rng.gen_range(-1.0..1.0) / sigma
                            } else {
                                rng.gen_range(-1.0..1.0)
                            }
                        })
                        .collect();
                    let t = rng.gen_range(0.0..1.0);
                    for qd in [None, Some(&qp_dot)] {
                        let m = jacobian_mismatch(&mut net, t, &y, &qp, qd);
                        assert!(m < 1e-6, "VP-RNN-PF {act:?} p={p} sigma={sigma} on {shape:?} seed {seed}: mismatch {m:e}");
                    }
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// steady states on frozen QPs

/// Primal-dual point of the LVI (jia2019 eq. 2.21) from the exact solution: u = -lambda, v = mu.
fn lvi_point(qp: &Qp, sol: &solvers::ExactSolution) -> Vec<f64> {
    let dims = qp.dims();
    let mut y = vec![0.0; primal_dual_dim(dims)];
    y[..dims.nx].copy_from_slice(sol.x.as_slice());
    for k in 0..dims.n_eq {
        y[dims.nx + k] = -sol.duals.lambda[k];
    }
    for k in 0..dims.n_in {
        y[dims.nx + dims.n_eq + k] = sol.duals.mu[k];
    }
    y
}

fn projection_equilibria(
    shape: QpShape,
    seeds: std::ops::Range<u64>,
    lvi: bool,
) -> (f64, f64, usize) {
    let s = settings(1e-10, 1e-13);
    let (mut worst, mut worst_fixed, mut count) = (0.0_f64, 0.0_f64, 0);
    for seed in seeds {
        let qp = random_qp(shape, seed);
        let dims = qp.dims();
        let sol = exact(&qp);
        // Complement: the exact primal-dual point is a fixed point of the projection (eq. 2.22).
        let mut core = LviCore::new(dims);
        let fixed = inf_norm(core.residual(&qp, &lvi_point(&qp, &sol)));
        worst_fixed = worst_fixed.max(fixed);
        // The network itself, gain scaled to 1 (the equilibrium does not depend on it).
        let scaling = if lvi {
            Scaling::IPlusMt
        } else {
            Scaling::Identity
        };
        let mut net: Box<dyn NeuralSolver> = Box::new(lvi_network(scaling, 1.0, dims));
        let mut probe = LviCore::new(dims);
        // Stop at residual 1e-11, or once the residual is below 1e-7 and stalls (no halving over
        // a doubled horizon): S-LVI-PDNN can slide along a kink of P_Omega (an equilibrium on a
        // weakly active constraint), where the integrator holds the residual at ~1e-9 with one
        // step per time unit forever (1e-9..5e-8 seen), x already within ~1e-7 of x*.
        let mut prev = f64::INFINITY;
        let y = steady_state(net.as_mut(), &qp, 50.0, 16, &s, |_, _, y| {
            let r = inf_norm(probe.residual(&qp, y));
            let stop = r < 1e-11 || (r < 1e-7 && r > 0.5 * prev);
            prev = r;
            stop
        });
        let res = inf_norm(probe.residual(&qp, &y));
        let err = x_err(&y, &sol.x);
        assert!(
            err <= 1e-6,
            "{} on {shape:?} seed {seed}: |x - x*|_inf = {err:e} (residual {res:e})",
            net.name()
        );
        worst = worst.max(err);
        count += 1;
    }
    assert!(
        worst_fixed < 1e-6,
        "exact optimum is not a fixed point of P_Omega: {worst_fixed:e}"
    );
    (worst, worst_fixed, count)
}

#[test]
fn lvi_pdnn_steady_state_is_the_exact_optimum() {
    let (w, f, n) = projection_equilibria(QpShape::Jia2019, 0..N_QPS, true);
    let (w2, f2, n2) = projection_equilibria(QpShape::Zhong2021, 5000..5100, true);
    eprintln!("LVI-PDNN: {n} jia2019 QPs worst |x-x*|_inf {w:.2e} (fixed-point residual at x* {f:.2e}); {n2} zhong2021 QPs worst {w2:.2e} ({f2:.2e})");
}

#[test]
fn s_lvi_pdnn_steady_state_is_the_exact_optimum() {
    let (w, f, n) = projection_equilibria(QpShape::Zhong2021, 0..N_QPS, false);
    let (w2, f2, n2) = projection_equilibria(QpShape::Jia2019, 5000..5100, false);
    eprintln!("S-LVI-PDNN: {n} zhong2021 QPs worst |x-x*|_inf {w:.2e} (fixed-point residual at x* {f:.2e}); {n2} jia2019 QPs worst {w2:.2e} ({f2:.2e})");
}

fn zeroing_equilibria(
    shape: QpShape,
    make: impl Fn(QpDims) -> Box<dyn NeuralSolver>,
    t_end: f64,
) -> (f64, f64) {
    zeroing_equilibria_over(shape, N_QPS, make, t_end)
}

/// [`zeroing_equilibria`] over the first `seeds` random QPs.
fn zeroing_equilibria_over(
    shape: QpShape,
    seeds: u64,
    make: impl Fn(QpDims) -> Box<dyn NeuralSolver>,
    t_end: f64,
) -> (f64, f64) {
    let s = settings(1e-10, 1e-13);
    let (mut worst_x, mut worst_l) = (0.0_f64, 0.0_f64);
    for seed in 0..seeds {
        let qp = random_qp(shape, seed);
        let dims = qp.dims();
        let sol = exact(&qp);
        let mut net = make(dims);
        let y = steady_state(net.as_mut(), &qp, t_end, 1, &s, |_, _, _| true);
        let err = x_err(&y, &sol.x);
        let lerr = (0..dims.n_eq).fold(0.0_f64, |m, k| {
            m.max((y[dims.nx + k] - sol.duals.lambda[k]).abs())
        });
        assert!(
            err <= 1e-6,
            "{} on {shape:?} seed {seed}: |x - x*|_inf = {err:e}",
            net.name()
        );
        assert!(
            lerr <= 1e-5,
            "{} on {shape:?} seed {seed}: |lambda - lambda*|_inf = {lerr:e}",
            net.name()
        );
        worst_x = worst_x.max(err);
        worst_l = worst_l.max(lerr);
    }
    (worst_x, worst_l)
}

#[test]
fn cdnn_steady_states_are_the_exact_optimum() {
    let (a, al) = zeroing_equilibria(
        QpShape::Zhang2018,
        |d| {
            built(
                SolverSpec::FpCdnn {
                    gamma: 200.0,
                    activation: ActivationSpec::of(ActivationKind::Linear),
                    perturbation: None,
                },
                d,
            )
        },
        1.0,
    );
    let (b, bl) = zeroing_equilibria(
        QpShape::Zhang2018,
        |d| {
            built(
                SolverSpec::VpCdnn {
                    gamma: 2.0,
                    activation: ActivationSpec::of(ActivationKind::Linear),
                    perturbation: None,
                },
                d,
            )
        },
        3.0,
    );
    eprintln!("{N_QPS} zhang2018 QPs: FP-CDNN worst |x-x*| {a:.2e} (lambda {al:.2e}); VP-CDNN {b:.2e} ({bl:.2e})");
}

/// A network of the literature entered as data, not as Rust: a varying-parameter zeroing
/// network with a power-type gain g(t) = gamma (p + t^p) and the sign-bi-power activation (no
/// preset combines them) reaches the KKT solution of every QP, as the presets do.
#[test]
fn a_power_type_network_entered_as_data_reaches_the_optimum() {
    let spec = parse(
        "solver = { kind = \"zeroing\", gain = { law = \"power\", gamma = 2.0, p = 2.0 }, \
         activation = \"sign-bi-power\", exponent = 0.5 }",
    )
    .unwrap();
    assert_eq!(spec.id(), "zeroing-power-gamma-2-p-2-sign-bi-power-r-0.5");
    assert_eq!(
        spec.display_name(),
        "ZNN (power(gamma=2,p=2), sign-bi-power(r=0.5))"
    );
    for shape in [QpShape::Kong2019, QpShape::Zhang2018] {
        let (x, l) = zeroing_equilibria_over(shape, 100, |d| built(spec.clone(), d), 6.0);
        eprintln!("power-type zeroing network on {shape:?}: worst |x-x*| {x:.2e} (lambda {l:.2e})");
    }
    // A gain law that is not positive is refused when the network is built, naming the law.
    let bad =
        parse("solver = { kind = \"zeroing\", gain = { law = \"power\", gamma = 2.0, p = -1.0 } }")
            .unwrap();
    let e = build_solver(&bad, random_qp(QpShape::Kong2019, 0).dims())
        .err()
        .expect("p = -1 refused")
        .to_string();
    assert!(e.contains("power") && e.contains("p > 0"), "{e}");
    // An unknown law names the valid ones.
    let e = parse("solver = { kind = \"zeroing\", gain = { law = \"cubic\", gamma = 1.0 } }")
        .unwrap_err();
    assert!(e.contains("constant") && e.contains("power"), "{e}");
}

#[test]
fn kong2019_networks_reach_the_kkt_solution() {
    // FTNN: by eq. 11 each error component vanishes by t_s = |E_i(0)|^0.9 / 0.9 <= ~8 for |E(0)| <= 5.
    let (a, al) = zeroing_equilibria(
        QpShape::Kong2019,
        |d| {
            built(
                SolverSpec::FiniteTime {
                    beta: 1.0,
                    alpha: 0.1,
                    smoothing: 1e-8,
                },
                d,
            )
        },
        12.0,
    );
    let (b, bl) = zeroing_equilibria(
        QpShape::Kong2019,
        |d| built(SolverSpec::Znn { gamma: 1.0 }, d),
        40.0,
    );
    eprintln!(
        "{N_QPS} kong2019 QPs: FTNN worst |x-x*| {a:.2e} (lambda {al:.2e}); ZNN {b:.2e} ({bl:.2e})"
    );
}

/// lambda_min of a symmetric matrix.
fn lambda_min(p: &DMatrix<f64>) -> f64 {
    p.clone().symmetric_eigen().eigenvalues.min()
}

#[test]
fn vp_rnn_pf_steady_state_is_within_the_penalty_bound() {
    // Bound of the penalty form's docs (`solvers/src/neural/penalty.rs`):
    //   lambda_min(P) |x_p - x*|_2^2 <= m p / e + sum_i mu*_i max(0, -N_i(x_p)).
    let s = settings(1e-10, 1e-13);
    let (p, sigma, gamma) = (1e-4, 400.0, 2.0);
    let acts = [
        ActivationKind::Linear,
        ActivationKind::Sinh,
        ActivationKind::PowerSigmoid,
    ]
    .map(ActivationSpec::of);
    let (mut worst_err, mut worst_ratio, mut worst_grad) = (0.0_f64, 0.0_f64, 0.0_f64);
    for seed in 0..N_QPS {
        // Every QP with the linear activation, one in five also with sinh and power-sigmoid.
        let act_list: &[ActivationSpec] = if seed % 5 == 0 { &acts } else { &acts[..1] };
        let qp = random_qp(QpShape::Zhong2021, seed);
        let dims = qp.dims();
        let sol = exact(&qp);
        for &act in act_list {
            let mut net = vp_rnn_pf(p, sigma, gamma, act, dims);
            let y = steady_state(&mut net, &qp, 8.0, 1, &s, |_, _, _| true);
            let x = DVector::from_column_slice(&y[..dims.nx]);
            let lam = DVector::from_column_slice(&y[dims.nx..]);
            // Independent check that x is the penalised problem's KKT point.
            let slack = &qp.h - &qp.g * &x;
            let c = slack.map(|n| p * sigma * (-sigma * n).exp());
            let grad = &qp.p * &x + &qp.q + qp.a.tr_mul(&lam) + qp.g.tr_mul(&c);
            let feas = &qp.a * &x - &qp.b;
            let g = grad.amax().max(feas.amax());
            assert!(
                g < 1e-7,
                "VP-RNN-PF {act:?} seed {seed}: penalised KKT residual {g:e}"
            );
            worst_grad = worst_grad.max(g);
            // The penalty bound.
            let d = &x - &sol.x;
            let lhs = lambda_min(&qp.p) * d.norm_squared();
            let m = qp.h.len() as f64;
            let viol: f64 = (0..qp.h.len())
                .map(|i| sol.duals.mu[i].max(0.0) * (-slack[i]).max(0.0))
                .sum();
            let rhs = m * p / std::f64::consts::E + viol;
            assert!(
                lhs <= rhs * (1.0 + 1e-6) + 1e-10,
                "VP-RNN-PF {act:?} seed {seed}: {lhs:e} > bound {rhs:e}"
            );
            worst_ratio = worst_ratio.max(lhs / rhs);
            worst_err = worst_err.max(d.amax());
        }
    }
    eprintln!(
        "VP-RNN-PF (p={p}, sigma={sigma}) on {N_QPS} zhong2021 QPs: worst |x-x*|_inf {worst_err:.2e}, \
         worst lhs/bound {worst_ratio:.3}, worst penalised KKT residual {worst_grad:.1e}"
    );
}

// ---------------------------------------------------------------------------------------------
// time-varying QPs: the error follows its design formula exactly

fn qp_error_cdnn(qp: &Qp, y: &[f64]) -> DVector<f64> {
    let nx = qp.q.len();
    let x = DVector::from_column_slice(&y[..nx]);
    let l = DVector::from_column_slice(&y[nx..]);
    let top = &qp.p * &x + qp.a.tr_mul(&l) + &qp.q;
    let bot = &qp.a * &x - &qp.b;
    DVector::from_iterator(y.len(), top.iter().chain(bot.iter()).copied())
}

#[test]
fn zeroing_error_follows_its_design_formula_on_moving_qps() {
    // Linear activation: E(t) = E(0) exp(-gamma t) (FP) and E(0) exp(-gamma (e^t - 1)) (VP).
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let s = settings(1e-11, 1e-13);
    for seed in 0..20u64 {
        for shape in [QpShape::Zhang2018, QpShape::Kong2019] {
            let qp0 = random_qp(shape, seed);
            let mut qp1 = random_qp_dot(&qp0, &mut rng, 0.3);
            qp1.p = qp1.p.clone() * 0.0 + DMatrix::identity(qp0.q.len(), qp0.q.len()) * 0.2; // keep P PD
            let dims = qp0.dims();
            for (vp, gamma, t1) in [(false, 3.0, 1.0), (true, 1.0, 0.7)] {
                let mut net = if vp {
                    built(
                        SolverSpec::VpCdnn {
                            gamma,
                            activation: ActivationSpec::of(ActivationKind::Linear),
                            perturbation: None,
                        },
                        dims,
                    )
                } else {
                    built(
                        SolverSpec::FpCdnn {
                            gamma,
                            activation: ActivationSpec::of(ActivationKind::Linear),
                            perturbation: None,
                        },
                        dims,
                    )
                };
                let y0 = vec![0.0; dims.nx + dims.n_eq];
                let mut sys = Net::new(&mut *net, &qp0, Some(&qp1));
                let (y1, _) =
                    integrate(&mut sys, &y0, 0.0, t1, &s, |_, _| Control::Continue).unwrap();
                let mut qpt = qp0.clone();
                qp_at(&qp0, &qp1, t1, &mut qpt);
                let e0 = qp_error_cdnn(&qp0, &y0);
                let e1 = qp_error_cdnn(&qpt, &y1);
                let decay = if vp {
                    (-gamma * (t1.exp() - 1.0)).exp()
                } else {
                    (-gamma * t1).exp()
                };
                let dev = (&e1 - &e0 * decay).amax() / e0.amax();
                assert!(
                    dev < 1e-6,
                    "{shape:?} seed {seed} vp={vp}: E(t) off its design formula by {dev:e}"
                );
            }
        }
    }
}

#[test]
fn vp_rnn_pf_error_follows_its_design_formula_on_moving_qps() {
    // Linear activation: phi(t) = phi(0) exp(-gamma (e^t - 1)), with G, h, P, q, A, b all moving.
    let mut rng = ChaCha8Rng::seed_from_u64(22);
    let s = settings(1e-11, 1e-13);
    let (p, sigma, gamma, t1) = (0.1, 5.0, 1.0, 0.5);
    for seed in 0..20u64 {
        for shape in [QpShape::Zhong2021, QpShape::Jia2019] {
            let qp0 = random_qp(shape, seed);
            let mut qp1 = random_qp_dot(&qp0, &mut rng, 0.3);
            qp1.p = DMatrix::identity(qp0.q.len(), qp0.q.len()) * 0.2;
            qp1.lower.fill(0.0);
            qp1.upper.fill(0.0);
            let dims = qp0.dims();
            let mut net = vp_rnn_pf(p, sigma, gamma, ActivationSpec::default(), dims);
            let y0 = vec![0.0; dims.nx + dims.n_eq];
            let mut f = vec![0.0; y0.len()];
            net.rhs(0.0, &y0, &qp0, Some(&qp1), &mut f);
            let phi0 = DVector::from_column_slice(net.error());
            let mut sys = Net::new(&mut net, &qp0, Some(&qp1));
            let (y1, _) = integrate(&mut sys, &y0, 0.0, t1, &s, |_, _| Control::Continue).unwrap();
            let mut qpt = qp0.clone();
            qp_at(&qp0, &qp1, t1, &mut qpt);
            net.rhs(t1, &y1, &qpt, Some(&qp1), &mut f);
            let phi1 = DVector::from_column_slice(net.error());
            let decay = (-gamma * (t1.exp() - 1.0)).exp();
            let dev = (&phi1 - &phi0 * decay).amax() / phi0.amax();
            assert!(
                dev < 1e-6,
                "{shape:?} seed {seed}: phi(t) off its design formula by {dev:e}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// the reference perturbation (zhang2018 eq. 3.1-3.2, docs/experiments.md)

#[test]
fn reference_perturbation_matches_experiments_md_and_enters_as_eq_3_1() {
    let pert = ReferencePerturbation::reference(8.0);
    // t = T/2: w = pi/2, sin w = 1, cos w = 0, sin 2w = 0, cos 2w = -1, sin 3w = -1, cos 3w = 0,
    // sin 4w = 0, cos 4w = 1, sin 5w = 1, cos 5w = 0.
    let mut dd = DMatrix::zeros(9, 9);
    pert.delta_d(4.0, &mut dd);
    let row2 = [-1.0, -1.0, -1.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0];
    let row3 = [-1.0, 0.0, 0.0, 0.0, 1.0, -1.0, -1.0, -1.0, 0.0];
    let row9 = [0.0, -1.0, -1.0, 0.0, -1.0, -1.0, 0.0, 0.0, -1.0];
    for j in 0..9 {
        assert!((dd[(1, j)] - row2[j]).abs() < 1e-12, "row 2 col {j}");
        assert!((dd[(2, j)] - row3[j]).abs() < 1e-12, "row 3 col {j}");
        assert!((dd[(8, j)] - row9[j]).abs() < 1e-12, "row 9 col {j}");
    }
    let mut ds = [0.0; 9];
    pert.delta_s(4.0, &mut ds);
    let want = [3.0, -6.0, 7.5, 0.0, 1.5, 0.0, -1.5, 0.0, 0.0];
    for i in 0..9 {
        assert!(
            (ds[i] - want[i]).abs() < 1e-12,
            "Delta s entry {i}: {} vs {}",
            ds[i],
            want[i]
        );
    }
    // t = 0: D0 = [sin 0, cos 0, ...]; row 1 = [0, 1, 0, 1, 0, 1, 0, 1, 0]; amplitudes scale.
    let p2 = ReferencePerturbation {
        a_d: 2.5,
        a_s: 0.0,
        task_duration: 8.0,
    };
    p2.delta_d(0.0, &mut dd);
    let row1 = [0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
    for j in 0..9 {
        assert!((dd[(0, j)] - 2.5 * row1[j]).abs() < 1e-12);
    }
    p2.delta_s(1.0, &mut ds);
    assert!(ds.iter().all(|v| *v == 0.0));

    // Eq. 3.1: Q ydot = -(Qdot + DeltaD) y - gamma exp(t) Phi(Q y - u) + udot + Delta s.
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let qp = random_qp(QpShape::Zhang2018, 3);
    let qd = random_qp_dot(&qp, &mut rng, 1.0);
    let dims = qp.dims();
    let t = 2.7;
    let y = DVector::from_fn(9, |_, _| rng.gen_range(-1.0..1.0));
    for vp in [false, true] {
        let mut net = if vp {
            built(
                SolverSpec::VpCdnn {
                    gamma: 200.0,
                    activation: ActivationSpec::of(ActivationKind::Linear),
                    perturbation: Some(pert),
                },
                dims,
            )
        } else {
            built(
                SolverSpec::FpCdnn {
                    gamma: 200.0,
                    activation: ActivationSpec::of(ActivationKind::Linear),
                    perturbation: Some(pert),
                },
                dims,
            )
        };
        let mut ydot = vec![0.0; 9];
        net.rhs(t, y.as_slice(), &qp, Some(&qd), &mut ydot);
        let kkt = |q: &Qp| {
            let mut m = DMatrix::zeros(9, 9);
            m.view_mut((0, 0), (6, 6)).copy_from(&q.p);
            m.view_mut((0, 6), (6, 3)).copy_from(&q.a.transpose());
            m.view_mut((6, 0), (3, 6)).copy_from(&q.a);
            m
        };
        let rhs_vec =
            |q: &Qp| DVector::from_iterator(9, q.q.iter().map(|v| -v).chain(q.b.iter().copied()));
        let (qm, qdm, u, ud) = (kkt(&qp), kkt(&qd), rhs_vec(&qp), rhs_vec(&qd));
        let mut dd = DMatrix::zeros(9, 9);
        pert.delta_d(t, &mut dd);
        let mut ds = [0.0; 9];
        pert.delta_s(t, &mut ds);
        let g = if vp { 200.0 * t.exp() } else { 200.0 };
        let want = -(&qdm + &dd) * &y - (&qm * &y - &u) * g + ud + DVector::from_column_slice(&ds);
        let got = &qm * DVector::from_column_slice(&ydot);
        let dev = (&got - &want).amax() / want.amax();
        assert!(
            dev < 1e-10,
            "vp={vp}: Q ydot deviates from eq. 3.1/3.2 by {dev:e}"
        );
    }
}

/// The group's network is Q ydot = -Qdot y - gamma Phi(E) + udot - nu t E + Delta_s(t)
/// (docs/group-code.md), with udot = [-qdot; bdot] or, with udot_rmp = false, [0; bdot], and no DeltaD.
#[test]
fn group_znn_is_the_groups_equation() {
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    let qp = random_qp(QpShape::Zhang2018, 4);
    let qd = random_qp_dot(&qp, &mut rng, 1.0);
    let dims = qp.dims();
    let t = 1.9;
    let y = DVector::from_fn(9, |_, _| rng.gen_range(-1.0..1.0));
    let pert = ReferencePerturbation {
        a_d: 3.0, // ignored by the group's network
        a_s: 1.5,
        task_duration: 8.0,
    };
    let act = Activation::GroupPowerSigmoid { xi: 1.0, p: 1.0 };
    let act_spec = ActivationSpec::of(ActivationKind::GroupPowerSigmoid);
    let kkt = |q: &Qp| {
        let mut m = DMatrix::zeros(9, 9);
        m.view_mut((0, 0), (6, 6)).copy_from(&q.p);
        m.view_mut((0, 6), (6, 3)).copy_from(&q.a.transpose());
        m.view_mut((6, 0), (3, 6)).copy_from(&q.a);
        m
    };
    let rhs_vec =
        |q: &Qp| DVector::from_iterator(9, q.q.iter().map(|v| -v).chain(q.b.iter().copied()));
    let (qm, qdm, u) = (kkt(&qp), kkt(&qd), rhs_vec(&qp));
    let e = &qm * &y - &u;
    let phi = e.map(|v| act.value(v));
    // Delta_s written out from docs/group-code.md, w = pi t / T.
    let w = std::f64::consts::PI * t / 8.0;
    let ds = DVector::from_vec(vec![
        2.0 * w.sin(),
        4.0 * (2.0 * w).cos(),
        -5.0 * (3.0 * w).sin(),
        (3.0 * w).cos(),
        -(3.0 * w).sin(),
        3.0 * w.cos(),
        -w.sin(),
        -(2.0 * w).sin(),
        w.cos(),
    ]) * 1.5;
    for (perturbed, udot_rmp) in [(true, true), (true, false), (false, true)] {
        let mut ud = rhs_vec(&qd);
        if !udot_rmp {
            ud.rows_mut(0, 6).fill(0.0);
        }
        let mut net = built(
            SolverSpec::GroupZnn {
                gamma: 500.0,
                nu: 2500.0,
                activation: act_spec,
                perturbation: perturbed.then_some(pert),
                udot_rmp,
            },
            dims,
        );
        let mut ydot = vec![0.0; 9];
        net.rhs(t, y.as_slice(), &qp, Some(&qd), &mut ydot);
        let mut want = -&qdm * &y - &phi * 500.0 + ud - &e * (2500.0 * t);
        if perturbed {
            want += &ds;
        }
        let got = &qm * DVector::from_column_slice(&ydot);
        let dev = (&got - &want).amax() / want.amax();
        assert!(
            dev < 1e-10,
            "perturbed={perturbed} udot_rmp={udot_rmp}: deviates by {dev:e}"
        );
    }
    // nu = 0, linear, no perturbation, udot_rmp: exactly FP-CDNN (the same core, bit for bit).
    let mut g = built(
        SolverSpec::GroupZnn {
            gamma: 200.0,
            nu: 0.0,
            activation: ActivationSpec::of(ActivationKind::Linear),
            perturbation: None,
            udot_rmp: true,
        },
        dims,
    );
    let mut f = built(
        SolverSpec::FpCdnn {
            gamma: 200.0,
            activation: ActivationSpec::of(ActivationKind::Linear),
            perturbation: None,
        },
        dims,
    );
    let (mut a, mut b) = (vec![0.0; 9], vec![0.0; 9]);
    g.rhs(t, y.as_slice(), &qp, Some(&qd), &mut a);
    f.rhs(t, y.as_slice(), &qp, Some(&qd), &mut b);
    assert_eq!(a, b);
    assert!(build_solver(
        &SolverSpec::GroupZnn {
            gamma: 500.0,
            nu: -1.0,
            activation: act_spec,
            perturbation: None,
            udot_rmp: true
        },
        dims
    )
    .is_err());
}

// ---------------------------------------------------------------------------------------------
// specifications

#[derive(serde::Deserialize)]
struct File {
    solver: SolverSpec,
}

fn parse(s: &str) -> Result<SolverSpec, String> {
    toml::from_str::<File>(s)
        .map(|f| f.solver)
        .map_err(|e| e.to_string())
}

#[test]
fn solver_specs_parse_build_and_reject_mistakes() {
    let cases = [
        ("solver = { kind = \"lvi-pdnn\", gamma = 1e7 }", "LVI-PDNN", QpShape::Jia2019),
        ("solver = { kind = \"s-lvi-pdnn\", beta = 1e7 }", "S-LVI-PDNN", QpShape::Zhong2021),
        ("solver = { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0 }", "VP-RNN-PF (linear)", QpShape::Zhong2021),
        (
            "solver = { kind = \"vp-rnn-pf\", p = 1e-5, sigma = 200.0, gamma = 2.0, activation = \"power-sigmoid\", alpha = 4.0, chi = 3.0 }",
            "VP-RNN-PF (power-sigmoid)",
            QpShape::Zhong2021,
        ),
        ("solver = { kind = \"fp-cdnn\", gamma = 200.0 }", "FP-CDNN", QpShape::Zhang2018),
        (
            "solver = { kind = \"vp-cdnn\", gamma = 200.0, perturbation = { a_d = 1.0, a_s = 1.5, task_duration = 8.0 } }",
            "VP-CDNN (perturbed A_D=1, A_s=1.5)",
            QpShape::Zhang2018,
        ),
        ("solver = { kind = \"finite-time\", beta = 1.0, alpha = 0.1 }", "FTNN", QpShape::Kong2019),
        ("solver = { kind = \"znn\", gamma = 1.0 }", "ZNN", QpShape::Kong2019),
        ("solver = { kind = \"group-znn\" }", "group ZNN (gamma=500, nu=2500)", QpShape::Zhang2018),
        (
            "solver = { kind = \"group-znn\", gamma = 500.0, nu = 2500.0, activation = \"group-power-sigmoid\", xi = 1.0, power = 1.0, perturbation = { a_s = 1.5, task_duration = 8.0 }, udot_rmp = false }",
            "group ZNN (gamma=500, nu=2500, perturbed A_s=1.5, udot without -qdot)",
            QpShape::Zhang2018,
        ),
        (
            "solver = { kind = \"group-znn\", nu = 0.0, activation = \"linear\" }",
            "group ZNN (gamma=500, nu=0, linear)",
            QpShape::Kong2019,
        ),
        (
            "solver = { kind = \"group-znn\", power = 3.0 }",
            "group ZNN (gamma=500, nu=2500, group-power-sigmoid(xi=1,p=3))",
            QpShape::Zhang2018,
        ),
        (
            "solver = { kind = \"fp-cdnn\", gamma = 200.0, activation = \"group-power-sigmoid\" }",
            "FP-CDNN (group-power-sigmoid)",
            QpShape::Zhang2018,
        ),
        (
            "solver = { kind = \"vp-cdnn\", gamma = 2.0, activation = \"power-sigmoid\", alpha = 2.0 }",
            "VP-CDNN (power-sigmoid(alpha=2,chi=3))",
            QpShape::Zhang2018,
        ),
        (
            "solver = { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0, activation = \"group-power-sigmoid\", xi = 2.0, power = 3.0 }",
            "VP-RNN-PF (group-power-sigmoid(xi=2,p=3))",
            QpShape::Zhong2021,
        ),
    ];
    for (text, name, shape) in cases {
        let spec = parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(spec.display_name(), name);
        let qp = random_qp(shape, 1);
        let mut net = build_solver(&spec, qp.dims()).unwrap();
        let n = net.state_dim(qp.dims());
        let mut y = vec![1.0; n];
        net.initial_state(qp.dims(), &mut y);
        assert!(y.iter().all(|v| *v == 0.0));
        let mut dy = vec![0.0; n];
        let zero = Qp::zeros(qp.dims());
        net.rhs(0.1, &y, &qp, Some(&zero), &mut dy);
        assert!(dy.iter().all(|v| v.is_finite()), "{name}: non-finite rhs");
        assert_eq!(net.needs_qp_dot(), spec.needs_qp_dot());
    }
    // Defaults: vp-rnn-pf's power-sigmoid parameters, perturbation amplitudes.
    let spec = parse(
        "solver = { kind = \"fp-cdnn\", gamma = 200.0, perturbation = { task_duration = 8.0 } }",
    )
    .unwrap();
    match spec {
        SolverSpec::FpCdnn {
            perturbation: Some(p),
            ..
        } => assert_eq!((p.a_d, p.a_s), (1.0, 1.5)),
        other => panic!("{other:?}"),
    }
    // Mistakes.
    for bad in [
        "solver = { kind = \"lvi-pdnn\", gama = 1e7 }",
        "solver = { kind = \"lvi-pdnn\", gamma = 1e7, beta = 1.0 }",
        "solver = { kind = \"lvi\", gamma = 1e7 }",
        "solver = { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 400.0, gamma = 2.0, activation = \"tanh\" }",
        "solver = { kind = \"fp-cdnn\", gamma = 200.0, perturbation = { a_d = 1.0, amplitude = 2.0, task_duration = 8.0 } }",
        "solver = { kind = \"group-znn\", mu = 1.0 }",
        "solver = { kind = \"group-znn\", udot_rmp = 1 }",
    ] {
        assert!(parse(bad).is_err(), "accepted: {bad}");
    }
    // Builder errors: zeroing networks on inequality QPs, perturbation of the wrong size, bad gains.
    let jia = random_qp(QpShape::Jia2019, 2).dims();
    assert!(build_solver(
        &parse("solver = { kind = \"znn\", gamma = 1.0 }").unwrap(),
        jia
    )
    .is_err());
    let kong = random_qp(QpShape::Kong2019, 2).dims();
    let pert = parse(
        "solver = { kind = \"vp-cdnn\", gamma = 2.0, perturbation = { task_duration = 9.0 } }",
    )
    .unwrap();
    assert!(build_solver(&pert, kong).is_err());
    assert!(build_solver(
        &parse("solver = { kind = \"lvi-pdnn\", gamma = -1.0 }").unwrap(),
        jia
    )
    .is_err());
    assert!(build_solver(
        &parse("solver = { kind = \"finite-time\", beta = 1.0, alpha = 1.5 }").unwrap(),
        kong
    )
    .is_err());
    for bad in [
        "solver = { kind = \"group-znn\", nu = -1.0 }",
        "solver = { kind = \"group-znn\", gamma = 0.0 }",
        "solver = { kind = \"group-znn\", xi = 0.0 }",
        "solver = { kind = \"fp-cdnn\", gamma = 1.0, activation = \"group-power-sigmoid\", power = 0.5 }",
    ] {
        assert!(build_solver(&parse(bad).unwrap(), kong).is_err(), "built: {bad}");
    }
    // A projection point out of range is refused naming the parameter and its range.
    for (bad, named) in [
        ("solver = { kind = \"projection\", error = { form = \"penalty\", p = 1e-4, sigma = 0.0 }, gain = { law = \"exponential\", gamma = 2.0 } }", "sigma > 0"),
        ("solver = { kind = \"projection\", error = { form = \"penalty\", p = -1.0, sigma = 4.0 }, gain = { law = \"exponential\", gamma = 2.0 } }", "p >= 0"),
        ("solver = { kind = \"projection\", error = { form = \"lvi\", scaling = \"identity\" }, gain = { law = \"power\", gamma = 1.0, p = 0.0 } }", "p > 0"),
        ("solver = { kind = \"projection\", error = { form = \"lvi\", scaling = \"i-plus-mt\" }, gain = { law = \"constant\", gamma = 1.0 }, activation = \"power-sigmoid\", alpha = -1.0 }", "alpha > 0"),
    ] {
        let e = build_solver(&parse(bad).unwrap(), jia).err().unwrap_or_else(|| panic!("built: {bad}"));
        assert!(e.to_string().contains(named), "{bad}: {e}");
    }
}

#[test]
fn zeroing_network_with_gain_variants_and_fixed_gain_vp_rnn_pf() {
    // Gain schedule values.
    assert_eq!(GainLaw::Constant { gamma: 3.0 }.at(5.0), 3.0);
    assert!((GainLaw::Exponential { gamma: 2.0 }.at(1.0) - 2.0 * 1f64.exp()).abs() < 1e-14);
    // The penalty form with a constant gain shares the steady state of the paper's exp(t) gain.
    let qp = random_qp(QpShape::Zhong2021, 77);
    let dims = qp.dims();
    let s = settings(1e-10, 1e-13);
    let mut a = vp_rnn_pf(1e-4, 400.0, 2.0, ActivationSpec::default(), dims);
    let mut b = penalty_network(
        1e-4,
        400.0,
        GainLaw::Constant { gamma: 2.0 },
        ActivationSpec::default(),
        dims,
    );
    let ya = steady_state(&mut a, &qp, 8.0, 1, &s, |_, _, _| true);
    let yb = steady_state(&mut b, &qp, 30.0, 1, &s, |_, _, _| true);
    let d = ya
        .iter()
        .zip(&yb)
        .take(dims.nx)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(
        d < 1e-7,
        "fixed and varying gain steady states differ by {d:e}"
    );
}
