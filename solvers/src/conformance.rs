//! The conformance kit: one call, [`check_qp_solver`], runs the same battery of checks on any
//! [`QpSolver`], built-in or outside this crate (a test crate, the Python bindings), so that
//! every solver is held to one standard (the model is diffsol's generic `test_ode_solver` and
//! benchopt's per-solver tests).
//!
//! # The checks
//!
//! For every QP shape the schemes produce ([`QpShape::ALL`], [`mod@crate::random_qp`]) and for
//! random feasible QPs of mixed sizes with finite bounds ([`random_feasible`]; left out for a
//! solver that does not claim bounds, [`Conformance::random_feasible`]), each against Clarabel
//! ([`ExactSolver`], the reference of record):
//!
//! 1. **Agreement, cold:** a fresh solver (or one after [`QpSolver::reset`]) solves the QP;
//!    |x - x*|_inf / max(1, |x*|_inf) <= `x_tolerance`, and the KKT residuals of its own
//!    answer ([`QpSolver::kkt_residuals`]) are at most `kkt_tolerance`.
//! 2. **Agreement, warm:** one solver solves the whole family in sequence, without reset (a
//!    warm start from the previous QP's answer where the method keeps one), to the same
//!    tolerances; solving the same QP again takes no more iterations than the first solve
//!    (where the method promises it, [`Conformance::repeat_no_longer`]).
//! 3. **Failures are statuses, never answers:** an infeasible QP (x_0 = 1 and x_0 = 2) and a
//!    QP with a NaN in q each return a [`QpSolverError`] (any status but [`QpStatus::Solved`];
//!    the infeasible one is also allowed to be refused as singular, iteration limit or numerical
//!    failure, since a method without an infeasibility certificate cannot tell); a QP of other
//!    sizes than the solver was built for is refused as invalid input, or, by a solver with no
//!    fixed sizes, solved right; none panics.
//! 4. **Degenerate input:** a QP whose equality matrix repeats a row (consistent, rank
//!    deficient) is either solved to the tolerances or refused by status.
//! 5. **No allocation per solve** (when an allocation counter is given, [`AllocationCounter`]):
//!    a warm solve of a QP of the solver's sizes allocates nothing.
//!
//! Each failed check is a [`Violation`] naming the check, the QP and the numbers; the kit
//! returns them all rather than stopping at the first.
//!
//! # Networks
//!
//! [`check_network`] holds a network ([`NeuralSolver`], built-in or outside) to the one
//! property every network of the suite is built for: on a fixed QP its equilibrium is the
//! QP's optimum. For every QP shape it claims ([`NetworkConformance::shapes`]) and seed, the
//! network's ODE ydot = F(t, y; QP) (with dQP/dt = 0 where it needs it) is integrated from its
//! initial state over [0, `t_end`] ([`NetworkConformance::t_end`], a few of its time constants)
//! with the integrator it names ([`NetworkConformance::integrator`]), and x = y[..nx] must be within `x_tolerance` of Clarabel's optimum
//! (relative, as above; check `equilibrium`); an integration that fails, or a network that
//! cannot be built for the QP, is a violation too (checks `integration`, `build`). When an
//! allocation counter is given, one more evaluation of F at the final state (after the
//! integration's own) must allocate nothing (check `allocation`): a network keeps its scratch.

use crate::exact::ExactSolver;
use crate::neural::NeuralSolver;
use crate::ode::{integrate, Control, OdeSystem};
use crate::random_qp::{random_feasible, random_qp, QpShape};
use qp::{Qp, QpDims, QpDuals, QpSolver, QpStatus};
use settings::{IntegratorSettings, Method};
use std::fmt;

#[cfg(doc)]
use qp::QpSolverError;

/// What a solver is held to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conformance {
    /// Largest |x - x*|_inf / max(1, |x*|_inf) against Clarabel.
    pub x_tolerance: f64,
    /// Largest KKT residual of the solver's own primal-dual answer.
    pub kkt_tolerance: f64,
    /// Random QPs per shape.
    pub seeds: u64,
    /// The QP shapes the solver claims to solve (a method that needs M invertible, say, leaves
    /// out the shapes with inequality rows).
    pub shapes: &'static [QpShape],
    /// Whether every QP of those shapes must be solved. A method known to fail on some (a
    /// paper's rule as printed that does not converge there) sets it false: a failure is then
    /// allowed as long as it is reported by status, but an answer must still be right.
    pub must_solve: bool,
    /// Whether solving the same QP again, warm from the method's own answer, must take no more
    /// iterations than the first solve (a method that checks termination only every k
    /// iterations and adapts its step, as ADMM does, need not promise it).
    pub repeat_no_longer: bool,
    /// Whether the random feasible family (equalities and finite bounds, mixed sizes) is
    /// checked: a solver of equality-constrained QPs only claims the equality-only shapes and
    /// leaves it out.
    pub random_feasible: bool,
}

impl Default for Conformance {
    /// 1e-6 in x and KKT, 10 QPs per shape, every shape and the random feasible family.
    fn default() -> Self {
        Conformance {
            x_tolerance: 1e-6,
            kkt_tolerance: 1e-6,
            seeds: 10,
            shapes: &QpShape::ALL,
            must_solve: true,
            repeat_no_longer: true,
            random_feasible: true,
        }
    }
}

/// Counts the allocations the current thread makes while a closure runs (a test binary's
/// counting global allocator, which only a binary can install).
pub trait AllocationCounter {
    /// Allocations made while `f` ran.
    fn count(&self, f: &mut dyn FnMut()) -> usize;
}

/// One failed check.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// The solver's id.
    pub solver: String,
    /// Which check (module docs): `cold`, `warm`, `warm-repeat`, `infeasible`, `dimensions`,
    /// `nan`, `degenerate`, `allocation`.
    pub check: &'static str,
    /// The QP (shape and seed) and what was found.
    pub detail: String,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} [{}]: {}", self.solver, self.check, self.detail)
    }
}

/// Builds a solver for QPs of the given sizes.
pub type Factory<'a> = &'a dyn Fn(QpDims) -> Box<dyn QpSolver>;

/// Runs every check of the module docs on the solvers `make` builds; `counter` enables the
/// allocation check. Returns every violation (empty: the solver conforms).
pub fn check_qp_solver(
    make: Factory<'_>,
    spec: &Conformance,
    counter: Option<&dyn AllocationCounter>,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let mut clarabel = ExactSolver::new();
    let families = spec
        .shapes
        .iter()
        .map(|&shape| {
            let qps: Vec<Qp> = (0..spec.seeds).map(|s| random_qp(shape, s)).collect();
            (format!("{shape:?}"), qps)
        })
        .chain(spec.random_feasible.then(|| {
            (
                "random-feasible".to_string(),
                (0..spec.seeds)
                    .map(|s| {
                        let dims = QpDims {
                            nx: 4 + (s as usize % 5),
                            n_eq: 1 + (s as usize % 3),
                            n_in: 0,
                        };
                        random_feasible(dims, s)
                    })
                    .collect(),
            )
        }));
    for (family, qps) in families {
        agreement(make, spec, &mut clarabel, &family, &qps, &mut out);
    }
    failures(make, spec, &mut clarabel, &mut out);
    degenerate(make, spec, &mut clarabel, &mut out);
    if let Some(counter) = counter {
        allocation(make, spec, counter, &mut out);
    }
    out
}

/// |x - x*|_inf / max(1, |x*|_inf).
fn rel_dx(x: &[f64], reference: &[f64]) -> f64 {
    if x.len() != reference.len() {
        return f64::INFINITY;
    }
    let scale = reference.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(reference)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Checks 1 and 2 on one family of QPs of equal sizes (a random-feasible family is checked
/// cold only, its sizes vary).
fn agreement(
    make: Factory<'_>,
    spec: &Conformance,
    clarabel: &mut ExactSolver,
    family: &str,
    qps: &[Qp],
    out: &mut Vec<Violation>,
) {
    let same_dims = qps.windows(2).all(|w| w[0].dims() == w[1].dims());
    let mut warm = qps.first().filter(|_| same_dims).map(|qp| make(qp.dims()));
    for (seed, qp) in qps.iter().enumerate() {
        let Ok(exact) = clarabel.solve(qp) else {
            continue;
        };
        let mut cold = make(qp.dims());
        judge(
            cold.as_mut(),
            qp,
            exact.x.as_slice(),
            spec,
            "cold",
            family,
            seed,
            out,
        );
        if let Some(solver) = warm.as_mut() {
            if let Some(first) = judge(
                solver.as_mut(),
                qp,
                exact.x.as_slice(),
                spec,
                "warm",
                family,
                seed,
                out,
            ) {
                if let Ok(again) = solver.solve(qp) {
                    if spec.repeat_no_longer && again.iterations > first {
                        out.push(Violation {
                            solver: solver.id().to_string(),
                            check: "warm-repeat",
                            detail: format!(
                                "{family} seed {seed}: the same QP again took {} iterations, \
                                 the first solve {first}",
                                again.iterations
                            ),
                        });
                    }
                }
            }
        }
    }
}

/// Solves `qp` with `solver` and records a violation of the tolerances; returns the
/// iterations of a successful solve.
#[allow(clippy::too_many_arguments)]
fn judge(
    solver: &mut dyn QpSolver,
    qp: &Qp,
    reference: &[f64],
    spec: &Conformance,
    check: &'static str,
    family: &str,
    seed: usize,
    out: &mut Vec<Violation>,
) -> Option<u32> {
    let id = solver.id().to_string();
    let mut violation = |detail: String| {
        out.push(Violation {
            solver: id.clone(),
            check,
            detail: format!("{family} seed {seed}: {detail}"),
        })
    };
    match solver.solve(qp) {
        Err(e) => {
            if spec.must_solve || e.status == QpStatus::Solved {
                violation(format!("failed with status {}: {e}", e.status));
            }
            None
        }
        Ok(solve) => {
            if solve.status != QpStatus::Solved {
                violation(format!("returned Ok with status {}", solve.status));
            }
            let dx = rel_dx(solver.x(), reference);
            if !(dx <= spec.x_tolerance) {
                violation(format!(
                    "|x - x*| = {dx:.3e} > {:.1e} (relative, against Clarabel)",
                    spec.x_tolerance
                ));
            }
            let mut duals = QpDuals::zeros(qp.dims());
            let kkt = solver.kkt_residuals(qp, &mut duals);
            if !(kkt.max() <= spec.kkt_tolerance) {
                violation(format!(
                    "KKT residuals primal {:.3e}, dual {:.3e}, complementarity {:.3e} > {:.1e}",
                    kkt.primal, kkt.dual, kkt.complementarity, spec.kkt_tolerance
                ));
            }
            Some(solve.iterations)
        }
    }
}

/// A QP with x_0 = 1 and x_0 = 2: infeasible.
fn infeasible_qp() -> Qp {
    let mut qp = Qp::zeros(QpDims {
        nx: 3,
        n_eq: 2,
        n_in: 0,
    });
    qp.p.fill_with_identity();
    qp.a[(0, 0)] = 1.0;
    qp.a[(1, 0)] = 1.0;
    qp.b[0] = 1.0;
    qp.b[1] = 2.0;
    qp
}

/// Check 3: inputs that have no answer end in a failure status, without a panic.
fn failures(
    make: Factory<'_>,
    spec: &Conformance,
    clarabel: &mut ExactSolver,
    out: &mut Vec<Violation>,
) {
    let infeasible = infeasible_qp();
    let mut nan = random_qp(QpShape::Kong2019, 0);
    nan.q[0] = f64::NAN;
    let wrong_size = random_qp(QpShape::Jia2019, 0);
    let cases: [(&'static str, QpDims, &Qp); 3] = [
        ("infeasible", infeasible.dims(), &infeasible),
        ("nan", nan.dims(), &nan),
        ("dimensions", nan.dims(), &wrong_size),
    ];
    for (check, dims, qp) in cases {
        let mut solver = make(dims);
        let id = solver.id().to_string();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solver.solve(qp)));
        let detail = match result {
            Err(_) => Some("panicked".to_string()),
            Ok(Ok(_)) if check == "dimensions" => {
                let dx = clarabel
                    .solve(qp)
                    .map_or(f64::INFINITY, |e| rel_dx(solver.x(), e.x.as_slice()));
                (!(dx <= spec.x_tolerance))
                    .then(|| format!("answered a QP of other sizes with |x - x*| = {dx:.3e}"))
            }
            Ok(Ok(s)) => Some(format!(
                "returned an answer (status {}) for a QP that has none",
                s.status
            )),
            Ok(Err(e)) if e.status == QpStatus::Solved => {
                Some("failed with status solved".to_string())
            }
            Ok(Err(e)) if check == "dimensions" && e.status != QpStatus::InvalidInput => Some(
                format!("refused with status {}, expected invalid-input", e.status),
            ),
            Ok(Err(_)) => None,
        };
        if let Some(detail) = detail {
            out.push(Violation {
                solver: id,
                check,
                detail,
            });
        }
    }
}

/// Check 4: a repeated (consistent) equality row is solved or refused by status.
fn degenerate(
    make: Factory<'_>,
    spec: &Conformance,
    clarabel: &mut ExactSolver,
    out: &mut Vec<Violation>,
) {
    let base = random_qp(QpShape::Kong2019, 1);
    let QpDims { nx, n_eq, .. } = base.dims();
    let mut qp = Qp::zeros(QpDims {
        nx,
        n_eq: n_eq + 1,
        n_in: 0,
    });
    qp.p.copy_from(&base.p);
    qp.q.copy_from(&base.q);
    qp.a.rows_mut(0, n_eq).copy_from(&base.a);
    qp.a.row_mut(n_eq).copy_from(&base.a.row(0));
    qp.b.rows_mut(0, n_eq).copy_from(&base.b);
    qp.b[n_eq] = base.b[0];
    qp.lower.copy_from(&base.lower);
    qp.upper.copy_from(&base.upper);
    let Ok(exact) = clarabel.solve(&qp) else {
        return;
    };
    let mut solver = make(qp.dims());
    let id = solver.id().to_string();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solver.solve(&qp)));
    match result {
        Err(_) => out.push(Violation {
            solver: id,
            check: "degenerate",
            detail: "panicked on a repeated equality row".to_string(),
        }),
        Ok(Err(_)) => {}
        Ok(Ok(_)) => {
            let dx = rel_dx(solver.x(), exact.x.as_slice());
            if !(dx <= spec.x_tolerance) {
                out.push(Violation {
                    solver: id,
                    check: "degenerate",
                    detail: format!(
                        "answered a repeated equality row with |x - x*| = {dx:.3e} > {:.1e}",
                        spec.x_tolerance
                    ),
                });
            }
        }
    }
}

/// Check 5: a warm solve allocates nothing.
fn allocation(
    make: Factory<'_>,
    spec: &Conformance,
    counter: &dyn AllocationCounter,
    out: &mut Vec<Violation>,
) {
    for &shape in spec.shapes {
        let first = random_qp(shape, 0);
        let second = random_qp(shape, 1);
        let mut solver = make(first.dims());
        if solver.solve(&first).is_err() {
            continue;
        }
        let n = counter.count(&mut || {
            let _ = solver.solve(&second);
        });
        if n > 0 {
            out.push(Violation {
                solver: solver.id().to_string(),
                check: "allocation",
                detail: format!("{shape:?}: a warm solve made {n} allocations"),
            });
        }
    }
}

/// What a network is held to ([`check_network`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NetworkConformance {
    /// Largest |x - x*|_inf / max(1, |x*|_inf) against Clarabel at t_end.
    pub x_tolerance: f64,
    /// Random QPs per shape.
    pub seeds: u64,
    /// The QP shapes the network claims (an equality-only network: the equality-only ones).
    pub shapes: &'static [QpShape],
    /// How long the network runs on each QP (s): several of its time constants.
    pub t_end: f64,
    /// The integrator (an explicit one for the projection networks, whose right-hand side is
    /// only piecewise smooth; a stiff one for a finite-time network).
    pub integrator: IntegratorSettings,
}

impl NetworkConformance {
    /// Dormand-Prince 5(4) at RelTol 1e-10, AbsTol 1e-12.
    pub fn dopri5() -> IntegratorSettings {
        IntegratorSettings {
            method: Method::Dopri5,
            rtol: 1e-10,
            atol: 1e-12,
            ..IntegratorSettings::default()
        }
    }
}

/// y' = F(t, y; QP) on a fixed QP (dQP/dt = 0).
struct FixedQp<'a> {
    net: &'a mut dyn NeuralSolver,
    qp: &'a Qp,
    zero_dot: Option<Qp>,
    dim: usize,
}

impl OdeSystem for FixedQp<'_> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.net.rhs(t, y, self.qp, self.zero_dot.as_ref(), dy);
    }
}

/// A network built for QPs of the given sizes, or its own build error (an open type, so an
/// outside network brings its own).
pub type NetworkFactory<'a> =
    &'a dyn Fn(QpDims) -> Result<Box<dyn NeuralSolver>, Box<dyn std::error::Error + Send + Sync>>;

/// Runs the network checks of the module docs on the networks `make` builds; `counter` enables
/// the allocation check. Returns every violation (empty: the network conforms).
pub fn check_network(
    make: NetworkFactory<'_>,
    spec: &NetworkConformance,
    counter: Option<&dyn AllocationCounter>,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let mut clarabel = ExactSolver::new();
    let settings = spec.integrator;
    for &shape in spec.shapes {
        for seed in 0..spec.seeds {
            let qp = random_qp(shape, seed);
            let Ok(exact) = clarabel.solve(&qp) else {
                continue;
            };
            let mut violation = |solver: String, check, detail: String| {
                out.push(Violation {
                    solver,
                    check,
                    detail: format!("{shape:?} seed {seed}: {detail}"),
                })
            };
            let mut net = match make(qp.dims()) {
                Ok(net) => net,
                Err(e) => {
                    violation("?".to_string(), "build", e.to_string());
                    continue;
                }
            };
            let name = net.name();
            let dim = net.state_dim(qp.dims());
            let mut y0 = vec![0.0; dim];
            net.initial_state(qp.dims(), &mut y0);
            let zero_dot = net.needs_qp_dot().then(|| Qp::zeros(qp.dims()));
            let mut sys = FixedQp {
                net: net.as_mut(),
                qp: &qp,
                zero_dot,
                dim,
            };
            match integrate(&mut sys, &y0, 0.0, spec.t_end, &settings, |_, _| {
                Control::Continue
            }) {
                Err(e) => violation(name, "integration", e.error.to_string()),
                Ok((y, _)) => {
                    if let Some(counter) = counter {
                        let mut dy = vec![0.0; dim];
                        let n = counter.count(&mut || sys.rhs(spec.t_end, &y, &mut dy));
                        if n > 0 {
                            violation(
                                name.clone(),
                                "allocation",
                                format!("an evaluation of F made {n} allocations"),
                            );
                        }
                    }
                    let nx = qp.dims().nx;
                    let dx = rel_dx(&y[..nx], exact.x.as_slice());
                    if !(dx <= spec.x_tolerance) {
                        violation(
                            name,
                            "equilibrium",
                            format!(
                                "at t = {} |x - x*| = {dx:.3e} > {:.1e} (relative, against Clarabel)",
                                spec.t_end, spec.x_tolerance
                            ),
                        );
                    }
                }
            }
        }
    }
    out
}
