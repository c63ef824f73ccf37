//! Integration of the coupled arm + network ODEs y' = F(t, y) with diffsol.
//!
//! The papers' research group integrated everything with MATLAB's `ode15s` (RelTol 1e-6,
//! AbsTol 1e-8). diffsol's [`Method::Bdf`] is the same family: variable-order BDF with the NDF
//! modification of Shampine & Reichelt (1997), i.e. ode15s's method. For comparison the
//! explicit Dormand-Prince 5(4) pair ([`Method::Dopri5`], MATLAB ode45's method) is run through
//! diffsol's explicit Runge-Kutta driver with the Dormand-Prince tableau (Dormand & Prince 1980,
//! coefficients in [`dopri5_tableau`]); Tsitouras 5(4), TR-BDF2 and ESDIRK3(4) are diffsol's own.
//!
//! Implicit methods need dF/dy. A system gives it densely through [`OdeSystem::jacobian`] when it
//! can (the projection networks are piecewise linear); otherwise it is formed column by column
//! from forward differences of F with step sqrt(eps) max(|y_j|, 1). diffsol asks for the
//! Jacobian as products J v with unit vectors v; the dense matrix is computed once per state and
//! cached, so a product costs a matrix-vector multiply.
//!
//! A largest step ([`IntegratorSettings::max_step`], ode15s's `MaxStep`; the group's code sets
//! 0.05 s) is enforced through diffsol's stop time: before each step the stop time is set to
//! t + max_step, so a method whose proposed step is longer rescales it to land there (BDF through
//! its own step-size change, which rescales the difference array and keeps the order, unlike
//! overwriting h through `state_mut`, which would restart BDF at first order). When less than
//! two maximal steps remain, the rest is split in two equal steps rather than leaving a sliver.
//! Without it (the default) the stop time is t1 once, as before.
//!
//! Every call reports steps, rejected steps, F evaluations (including those spent on
//! finite-difference Jacobians), Jacobian evaluations, LU factorisations of the Newton matrix
//! and wall time.

use diffsol::{
    DiffsolError, NalgebraLU, NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod,
    OdeSolverStopReason, Tableau, TableauMat, TableauVec, VectorCommon,
};
use nalgebra::{DMatrix, DVector};
use settings::{IntegratorSettings, Method};
use std::cell::RefCell;
use std::time::Instant;

/// An ODE y' = F(t, y) of fixed dimension.
pub trait OdeSystem {
    /// The dimension of y.
    fn dim(&self) -> usize;
    /// dy = F(t, y).
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Dense dF/dy at (t, y) into `jac`; false to let the integrator use finite differences.
    fn jacobian(&mut self, _t: f64, _y: &[f64], _jac: &mut DMatrix<f64>) -> bool {
        false
    }
}

/// Cost of one integration.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OdeStats {
    /// Accepted steps.
    pub steps: usize,
    /// Steps rejected by the local error test.
    pub rejected: usize,
    /// Evaluations of F (including those spent on finite-difference Jacobians).
    pub rhs_evals: usize,
    /// Dense Jacobian evaluations (analytic or finite-difference).
    pub jac_evals: usize,
    /// LU factorisations of the Newton matrix I - c J (diffsol's linear-solver setups; 0 for
    /// the explicit methods).
    pub lu_factorisations: usize,
    /// Wall time of the integration (s), the observer's calls included.
    pub wall_seconds: f64,
}

/// Why an integration stopped early.
#[derive(Clone, Debug, PartialEq)]
pub enum OdeError {
    /// diffsol gave up (step size underflow, Newton failure, ...).
    Solver {
        /// The time reached (s).
        t: f64,
        /// diffsol's message (or why the integrator settings were refused).
        message: String,
    },
    /// The state left the finite numbers: the network diverged.
    NonFinite {
        /// The time of the first non-finite state (s).
        t: f64,
    },
    /// More than `max_steps` accepted steps.
    TooManySteps {
        /// The time reached (s).
        t: f64,
        /// The accepted steps taken: the limit `max_steps`.
        steps: usize,
    },
    /// The observer asked to stop.
    Stopped {
        /// The time of the step the observer stopped at (s).
        t: f64,
        /// The observer's reason ([`Control::Stop`]).
        reason: String,
    },
    /// The wall-time budget ran out.
    WallBudget {
        /// The time reached (s).
        t: f64,
        /// The budget (s of wall time, `max_wall_s`).
        seconds: f64,
    },
    /// The right-hand-side evaluation budget ran out (`max_rhs_evals`, scaled from the span:
    /// `IntegratorSettings::rhs_budget`).
    EvalBudget {
        /// The time reached (s).
        t: f64,
        /// The budget (evaluations of F, `max_rhs_evals`).
        evals: usize,
    },
}

impl std::fmt::Display for OdeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OdeError::Solver { t, message } => {
                write!(f, "integrator failed at t = {t:.6}: {message}")
            }
            OdeError::NonFinite { t } => {
                write!(f, "state became non-finite at t = {t:.6} (diverged)")
            }
            OdeError::TooManySteps { t, steps } => write!(
                f,
                "more than {steps} steps by t = {t:.6} (diverging or too stiff for the method)"
            ),
            OdeError::Stopped { t, reason } => write!(f, "stopped at t = {t:.6}: {reason}"),
            OdeError::WallBudget { t, seconds } => write!(
                f,
                "wall-time budget of {seconds} s used up at t = {t:.6} (max_wall_s)"
            ),
            OdeError::EvalBudget { t, evals } => write!(
                f,
                "stopped at t = {t:.6}: evaluation budget of {evals} right-hand-side evaluations \
                 used up (max_rhs_evals, at most {} per second of the span)",
                settings::RHS_EVALS_PER_SECOND
            ),
        }
    }
}

impl std::error::Error for OdeError {}

/// A failed integration with the cost spent until it stopped.
#[derive(Clone, Debug)]
pub struct OdeFailure {
    /// Why it stopped.
    pub error: OdeError,
    /// The cost spent until it stopped.
    pub stats: OdeStats,
}

impl std::fmt::Display for OdeFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for OdeFailure {}

/// What the observer tells the integrator after an accepted step.
#[derive(Debug, Clone, PartialEq)]
pub enum Control {
    /// Go on integrating.
    Continue,
    /// Stop here, for the reason given (it becomes [`OdeError::Stopped`]).
    Stop(String),
}

/// The Dormand-Prince 5(4) tableau (FSAL, 7 stages), with d = b - b_hat for the error estimate.
pub fn dopri5_tableau() -> Tableau<f64> {
    let c = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
    let b = [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
        0.0,
    ];
    let b_hat = [
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ];
    let rows: [&[f64]; 7] = [
        &[],
        &[1.0 / 5.0],
        &[3.0 / 40.0, 9.0 / 40.0],
        &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
        &b[..6],
    ];
    let mut a = TableauMat::zeros(7, 7);
    for (i, row) in rows.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            a[(i, j)] = *v;
        }
    }
    let d: Vec<f64> = b.iter().zip(b_hat.iter()).map(|(x, y)| x - y).collect();
    Tableau::new(
        a,
        TableauVec::from_slice(&b),
        TableauVec::from_slice(&c),
        TableauVec::from_slice(&d),
        4,
        None,
    )
}

/// The system plus the cached dense Jacobian and the evaluation counters.
struct Counted<'s> {
    sys: &'s mut dyn OdeSystem,
    rhs_evals: usize,
    jac_evals: usize,
    jac: DMatrix<f64>,
    jac_at: DVector<f64>,
    jac_t: f64,
    jac_valid: bool,
    f0: Vec<f64>,
    f1: Vec<f64>,
    yp: Vec<f64>,
}

impl<'s> Counted<'s> {
    /// The counted `sys`, no evaluation done and no Jacobian cached yet.
    fn new(sys: &'s mut dyn OdeSystem) -> Self {
        let n = sys.dim();
        Counted {
            sys,
            rhs_evals: 0,
            jac_evals: 0,
            jac: DMatrix::zeros(n, n),
            jac_at: DVector::zeros(n),
            jac_t: f64::NAN,
            jac_valid: false,
            f0: vec![0.0; n],
            f1: vec![0.0; n],
            yp: vec![0.0; n],
        }
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_evals += 1;
        self.sys.rhs(t, y, dy);
    }

    /// dy = J(t, y) v with J cached per (t, y). diffsol forms its dense Jacobian from products
    /// with the unit vectors e_j: such a product is column j of J, copied (O(n) instead of the
    /// O(n^2) product, bit for bit the same numbers).
    fn jac_mul(&mut self, t: f64, y: &[f64], v: &[f64], out: &mut [f64]) {
        if !(self.jac_valid && self.jac_t == t && self.jac_at.as_slice() == y) {
            self.refresh_jacobian(t, y);
        }
        let n = y.len();
        if let Some(j) = unit_index(v) {
            out.copy_from_slice(self.jac.column(j).as_slice());
            return;
        }
        for (i, o) in out.iter_mut().enumerate() {
            let mut s = 0.0;
            for (j, vj) in v.iter().enumerate().take(n) {
                s += self.jac[(i, j)] * vj;
            }
            *o = s;
        }
    }

    fn refresh_jacobian(&mut self, t: f64, y: &[f64]) {
        self.jac_evals += 1;
        if !self.sys.jacobian(t, y, &mut self.jac) {
            let n = y.len();
            self.rhs_evals += 1;
            self.sys.rhs(t, y, &mut self.f0);
            self.yp.copy_from_slice(y);
            for j in 0..n {
                let h = f64::EPSILON.sqrt() * y[j].abs().max(1.0);
                self.yp[j] = y[j] + h;
                self.rhs_evals += 1;
                self.sys.rhs(t, &self.yp, &mut self.f1);
                for i in 0..n {
                    self.jac[(i, j)] = (self.f1[i] - self.f0[i]) / h;
                }
                self.yp[j] = y[j];
            }
        }
        self.jac_at.as_mut_slice().copy_from_slice(y);
        self.jac_t = t;
        self.jac_valid = true;
    }
}

/// j when v is the unit vector e_j (one entry 1, the others 0), else None.
fn unit_index(v: &[f64]) -> Option<usize> {
    let mut index = None;
    for (j, &vj) in v.iter().enumerate() {
        if vj == 1.0 && index.is_none() {
            index = Some(j);
        } else if vj != 0.0 {
            return None;
        }
    }
    index
}

/// Integrates `sys` from `t0` to `t1` starting at `y0`. `observe(t, y)` is called at t0 and after
/// every accepted step (the last one at t1) and may stop the run. Returns y(t1) and the cost;
/// a failure carries the cost spent until it stopped.
///
/// Generic for the caller's convenience only: the integration itself ([`integrate_dyn`]) takes
/// the system and the observer as trait objects, so diffsol's solvers are compiled once, here,
/// not again in every crate and test binary for every system and observer type (one virtual
/// call per RHS evaluation and per accepted step; the numbers are the same).
pub fn integrate<S: OdeSystem>(
    sys: &mut S,
    y0: &[f64],
    t0: f64,
    t1: f64,
    settings: &IntegratorSettings,
    mut observe: impl FnMut(f64, &[f64]) -> Control,
) -> Result<(Vec<f64>, OdeStats), OdeFailure> {
    integrate_dyn(sys, y0, t0, t1, settings, &mut observe)
}

/// [`integrate`] on trait objects.
pub fn integrate_dyn(
    sys: &mut dyn OdeSystem,
    y0: &[f64],
    t0: f64,
    t1: f64,
    settings: &IntegratorSettings,
    observe: &mut dyn FnMut(f64, &[f64]) -> Control,
) -> Result<(Vec<f64>, OdeStats), OdeFailure> {
    let n = sys.dim();
    assert_eq!(y0.len(), n, "initial state has the wrong dimension");
    let start = Instant::now();
    if let Err(e) = settings.validate() {
        return Err(OdeFailure {
            error: OdeError::Solver {
                t: t0,
                message: e.to_string(),
            },
            stats: OdeStats::default(),
        });
    }
    let counted = RefCell::new(Counted::new(sys));
    let mut steps_done = (0usize, 0usize, 0usize);
    let outcome = solve(&counted, y0, t0, t1, settings, observe, &mut steps_done);
    let c = counted.borrow();
    let stats = OdeStats {
        steps: steps_done.0,
        rejected: steps_done.1,
        rhs_evals: c.rhs_evals,
        jac_evals: c.jac_evals,
        lu_factorisations: steps_done.2,
        wall_seconds: start.elapsed().as_secs_f64(),
    };
    match outcome {
        Ok(y) => Ok((y, stats)),
        Err(error) => Err(OdeFailure { error, stats }),
    }
}

/// The integration proper: diffsol's problem over the counted system from `y0` at `t0`,
/// `observe` called at t0 and after every accepted step (and stopping the run once the RHS
/// evaluations pass `settings.max_rhs_evals`), driven to `t1` by `settings.method`. Leaves the
/// steps, rejected steps and LU factorisations in `steps_done`; returns y(t1).
fn solve(
    counted: &RefCell<Counted<'_>>,
    y0: &[f64],
    t0: f64,
    t1: f64,
    settings: &IntegratorSettings,
    observe: &mut dyn FnMut(f64, &[f64]) -> Control,
    steps_done: &mut (usize, usize, usize),
) -> Result<Vec<f64>, OdeError> {
    let n = y0.len();
    let y0v = y0.to_vec();
    let mut problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .t0(t0)
        .rtol(settings.rtol)
        .atol([settings.atol])
        .rhs_implicit(
            |y, _p, t, dy| counted.borrow_mut().rhs(t, y, dy),
            |y, _p, t, v, out| counted.borrow_mut().jac_mul(t, y, v, out),
        )
        .init(move |_p, _t, y| y.copy_from_slice(&y0v), n)
        .build()
        .map_err(|e| solver_error(t0, e))?;
    // diffsol counts Newton failures over the whole run, not per step: on networks with kinks
    // (projections, sign-power) a long run collects many harmless ones, each answered by a
    // smaller step. A stuck run is caught by the minimum step size and `max_steps` instead.
    problem.ode_options.max_nonlinear_solver_failures = usize::MAX / 2;
    if let Control::Stop(reason) = observe(t0, y0) {
        return Err(OdeError::Stopped { t: t0, reason });
    }
    let solver_err = |e| solver_error(t0, e);
    // The evaluation budget (scaled from the span), checked at every accepted step.
    let max_evals = settings.rhs_budget(t1 - t0);
    let budget_hit = std::cell::Cell::new(false);
    let mut observe = |t: f64, y: &[f64]| {
        if counted.borrow().rhs_evals > max_evals {
            budget_hit.set(true);
            return Control::Stop(String::new());
        }
        observe(t, y)
    };
    let driven = match settings.method {
        Method::Bdf => drive(
            problem.bdf::<NalgebraLU<f64>>().map_err(solver_err)?,
            t1,
            settings,
            &mut observe,
        )?,
        Method::Esdirk34 => drive(
            problem.esdirk34::<NalgebraLU<f64>>().map_err(solver_err)?,
            t1,
            settings,
            &mut observe,
        )?,
        Method::TrBdf2 => drive(
            problem.tr_bdf2::<NalgebraLU<f64>>().map_err(solver_err)?,
            t1,
            settings,
            &mut observe,
        )?,
        Method::Tsit45 => drive(
            problem.tsit45().map_err(solver_err)?,
            t1,
            settings,
            &mut observe,
        )?,
        Method::Dopri5 => {
            let tableau = dopri5_tableau();
            let state = problem.rk_state(&tableau).map_err(solver_err)?;
            drive(
                problem
                    .explicit_rk_solver(state, tableau)
                    .map_err(solver_err)?,
                t1,
                settings,
                &mut observe,
            )?
        }
    };
    let Driven {
        y,
        steps,
        rejected,
        lu_factorisations,
        error,
    } = driven;
    *steps_done = (steps, rejected, lu_factorisations);
    match error {
        Some(OdeError::Stopped { t, .. }) if budget_hit.get() => Err(OdeError::EvalBudget {
            t,
            evals: max_evals,
        }),
        Some(e) => Err(e),
        None => Ok(y),
    }
}

/// When [`drive`] reads the clock for the wall-time budget: at the first accepted step, then
/// after as many steps as the steps so far took on average to fill [`WallCheck::INTERVAL`]
/// (at least 1, at most [`WallCheck::MAX_STRIDE`]). A clock read (some 40 ns) costs about a
/// hundredth of a small arm's step, so reading it at every step was about 1 % of a short run.
/// While the steps keep the pace of the steps so far, the budget is overrun by about one
/// interval plus one step, for slow steps as for fast ones; where they slow down, by at most
/// [`WallCheck::MAX_STRIDE`] steps.
#[derive(Default)]
struct WallCheck {
    /// The accepted step at which the clock is read next.
    next: usize,
}

impl WallCheck {
    /// The wall time aimed at between two reads (s).
    const INTERVAL: f64 = 1e-3;
    /// The most steps between two reads.
    const MAX_STRIDE: usize = 64;

    /// Whether the clock is read after `steps` accepted steps.
    fn due(&self, steps: usize) -> bool {
        steps >= self.next
    }

    /// The wall time since `started` (s), scheduling the next read.
    fn read(&mut self, started: std::time::Instant, steps: usize) -> f64 {
        let elapsed = started.elapsed().as_secs_f64();
        self.schedule(elapsed, steps);
        elapsed
    }

    /// Schedules the next read from `elapsed` seconds over `steps` accepted steps.
    fn schedule(&mut self, elapsed: f64, steps: usize) {
        let per_step = elapsed / steps.max(1) as f64;
        let stride = (Self::INTERVAL / per_step).clamp(1.0, Self::MAX_STRIDE as f64);
        self.next = steps + stride as usize;
    }
}

/// What [`drive`] returns: the last state, the step counts, and the error that stopped it early.
struct Driven {
    y: Vec<f64>,
    steps: usize,
    rejected: usize,
    lu_factorisations: usize,
    error: Option<OdeError>,
}

fn solver_error(t: f64, e: DiffsolError) -> OdeError {
    OdeError::Solver {
        t,
        message: e.to_string(),
    }
}

/// The next stop time from `t` towards `t1` with steps of at most `h` (module docs): t1 when
/// within one step, the midpoint when within two, else t + h.
fn next_stop(t: f64, t1: f64, h: f64) -> f64 {
    let rest = t1 - t;
    if rest <= h {
        t1
    } else if rest < 2.0 * h {
        t + 0.5 * rest
    } else {
        t + h
    }
}

/// Steps `solver` to `t1`, observing every accepted step (steps of at most
/// `settings.max_step` where given).
fn drive<'a, Eqn, M>(
    mut solver: M,
    t1: f64,
    settings: &IntegratorSettings,
    observe: &mut dyn FnMut(f64, &[f64]) -> Control,
) -> Result<Driven, OdeError>
where
    Eqn: OdeEquations<T = f64, V = diffsol::NalgebraVec<f64>> + 'a,
    M: OdeSolverMethod<'a, Eqn>,
{
    let max_steps = settings.max_steps;
    let started = std::time::Instant::now();
    let mut wall = WallCheck::default();
    // The stop time in force (t1 unless a maximal step is enforced).
    let mut stop_at = match settings.max_step {
        Some(h) => next_stop(solver.state().t, t1, h),
        None => t1,
    };
    solver
        .set_stop_time(stop_at)
        .map_err(|e| solver_error(solver.state().t, e))?;
    let mut steps = 0usize;
    let stop = |solver: &M, steps: usize, error: OdeError| Driven {
        y: solver.state().y.inner().as_slice().to_vec(),
        steps,
        rejected: solver.get_statistics().number_of_error_test_failures,
        lu_factorisations: solver.get_statistics().number_of_linear_solver_setups,
        error: Some(error),
    };
    loop {
        if let Some(h) = settings.max_step {
            if steps > 0 {
                let t = solver.state().t;
                stop_at = next_stop(t, t1, h);
                if let Err(e) = solver.set_stop_time(stop_at) {
                    return Ok(stop(&solver, steps, solver_error(t, e)));
                }
            }
        }
        let reason = match solver.step() {
            Ok(r) => r,
            Err(e) => {
                let err = solver_error(solver.state().t, e);
                return Ok(stop(&solver, steps, err));
            }
        };
        steps += 1;
        let state = solver.state();
        let t = state.t;
        let y = state.y.inner().as_slice();
        if y.iter().any(|v| !v.is_finite()) {
            return Ok(stop(&solver, steps, OdeError::NonFinite { t }));
        }
        if let Control::Stop(reason) = observe(t, y) {
            return Ok(stop(&solver, steps, OdeError::Stopped { t, reason }));
        }
        match reason {
            OdeSolverStopReason::TstopReached if stop_at == t1 => {
                let statistics = solver.get_statistics();
                return Ok(Driven {
                    y: y.to_vec(),
                    steps,
                    rejected: statistics.number_of_error_test_failures,
                    lu_factorisations: statistics.number_of_linear_solver_setups,
                    error: None,
                });
            }
            _ if steps >= max_steps => {
                return Ok(stop(&solver, steps, OdeError::TooManySteps { t, steps }))
            }
            _ if wall.due(steps) && wall.read(started, steps) > settings.max_wall_s => {
                let seconds = settings.max_wall_s;
                return Ok(stop(&solver, steps, OdeError::WallBudget { t, seconds }));
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::WallCheck;

    #[test]
    fn the_clock_is_read_about_once_a_millisecond_of_steps() {
        let mut w = WallCheck::default();
        assert!(w.due(1));
        // 4 us a step: every 64th step (250 would fill the interval).
        w.schedule(4e-3, 1000);
        assert_eq!(w.next, 1064);
        assert!(!w.due(1063) && w.due(1064));
        // 0.1 ms a step: every 10th.
        w.schedule(1.0, 10_000);
        assert_eq!(w.next, 10_010);
        // Slower than the interval, or no time measured at all: every step, and the largest
        // stride.
        w.schedule(5.0, 100);
        assert_eq!(w.next, 101);
        w.schedule(0.0, 7);
        assert_eq!(w.next, 71);
    }
}
