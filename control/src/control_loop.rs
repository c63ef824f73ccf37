//! One controller run: a scheme's QP solved (or tracked, by a network) at a fixed control
//! period h, the command held over each tick and the arm integrated exactly between ticks
//! ([`crate::arm`]), over one or more cycles of a closed path.
//!
//! At tick k (t_k = k h), with the arm at (theta_k, thetadot_k):
//!
//! 1. the scheme builds QP_k = QP(t_k, theta_k, thetadot_k) (and, for the zeroing networks,
//!    dQP/dt along the previous tick's command);
//! 2. the solver computes x_k ([`TickSolver::tick`]);
//! 3. the arm moves under x_k[..N] held over [t_k, t_k + h].
//!
//! Steps 1-3 are the tick, timed as a whole (`tick`), and step 2 alone (`solve`). Then, not
//! timed, the tick is scored: the tracking error |f(theta_k) - r*(t_k)|_2 and the distance of
//! the joint command from the exact optimum x*_k of QP_k (certified active set, Clarabel
//! fallback: [`solvers::ExactPath`]), |x_k[..N] - x*_k[..N]|_inf / max(1, |x*_k[..N]|_inf)
//! (the joint command only: jia2019's auxiliary p is not unique where its weight is zero, as in
//! MVN), overall and after the first [`SETTLE`] seconds (a network starts at zero, away from
//! x*(0) wherever the scheme pulls the arm toward a reference pose). The drift
//! |theta(c T) - theta_0|_2 is recorded at the end of every cycle c.
//!
//! A run whose command stops being finite or exceeds [`DIVERGED`] in magnitude has diverged
//! (the discretised network is unstable at this h): it stops there.

use crate::arm::advance;
use crate::error::ControlError;
use crate::method::TickSolver;
use nalgebra::SVector;
use robots::Robot;
use schemes::paths::Path;
use schemes::qp::Qp;
use schemes::scheme::Scheme;
use solvers::ExactPath;
use std::time::Instant;

/// The start transient left out of [`LoopOutcome::max_dx_settled`] (s).
pub const SETTLE: f64 = 1.0;

/// A command entry beyond this (rad/s or rad/s^2) is a diverged run.
pub const DIVERGED: f64 = 1e4;

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    Completed,
    /// The command blew up at this instant.
    Diverged {
        t: f64,
    },
    /// The solver failed at this instant.
    Failed {
        t: f64,
        message: String,
    },
}

impl Status {
    /// The status column of the run's row.
    pub fn column(&self) -> records::control::ControlStatus {
        use records::control::ControlStatus;
        match self {
            Status::Completed => ControlStatus::Ok,
            Status::Diverged { .. } => ControlStatus::Diverged,
            Status::Failed { .. } => ControlStatus::Failed,
        }
    }

    /// Why the run stopped early, with the instant (none when it completed).
    pub fn failure(&self) -> Option<String> {
        match self {
            Status::Completed => None,
            Status::Diverged { t } => Some(format!("diverged at t = {t}")),
            Status::Failed { t, message } => Some(format!("failed at t = {t}: {message}")),
        }
    }
}

/// The run's setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopSettings {
    /// Control period h (s).
    pub h: f64,
    /// Duration T of one cycle (s).
    pub period: f64,
    /// Cycles K run back to back (the path is repeated K times).
    pub cycles: usize,
    /// Stop after this many ticks (a short check run); all ticks of the K cycles when `None`.
    pub max_ticks: Option<usize>,
}

impl LoopSettings {
    /// Ticks per cycle (T / h, rounded).
    pub fn ticks_per_cycle(&self) -> usize {
        (self.period / self.h).round().max(1.0) as usize
    }
}

/// What a run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct LoopOutcome {
    pub status: Status,
    pub ticks: usize,
    /// Per-tick durations (us) of the solve alone and of the whole tick.
    pub solve_us: Vec<f64>,
    pub tick_us: Vec<f64>,
    pub max_track_err: f64,
    pub rms_track_err: f64,
    pub max_dx: f64,
    pub rms_dx: f64,
    /// max |x - x*| over the ticks at t >= [`SETTLE`].
    pub max_dx_settled: f64,
    /// |theta(c T) - theta_0|_2 after each completed cycle c = 1, 2, ...
    pub drift: Vec<f64>,
    /// |theta(c T) - theta((c - 1) T)|_2 for each completed cycle c.
    pub cycle_change: Vec<f64>,
    /// Mean and max per tick of [`TickSolver::products`] (None when not counted).
    pub products_mean: Option<f64>,
    pub products_max: Option<u64>,
    pub iterations_mean: f64,
    pub iterations_max: u32,
    /// Ticks the exact reference could not score.
    pub score_failures: usize,
}

/// Sees every scored tick of a run (the stability analysis samples the QPs of a run with it).
pub trait Observer {
    /// Whether [`Observer::observe`] needs dQP/dt.
    fn needs_qp_dot(&self) -> bool;
    /// Tick `k` at `t`: its QP, dQP/dt (when asked for) and the exact optimum x*.
    fn observe(&mut self, k: usize, t: f64, qp: &Qp, qp_dot: Option<&Qp>, x_star: &[f64]);
}

/// Runs `solver` on `scheme` along `path` (already repeated `settings.cycles` times) from
/// `theta0` at rest (module docs), showing every scored tick to `observer`.
pub fn run_loop<const N: usize>(
    robot: &dyn Robot<N>,
    path: &dyn Path,
    scheme: &dyn Scheme<N>,
    solver: &mut dyn TickSolver,
    theta0: &SVector<f64, N>,
    settings: &LoopSettings,
    mut observer: Option<&mut dyn Observer>,
) -> LoopOutcome {
    let h = settings.h;
    let per_cycle = settings.ticks_per_cycle();
    let total = (per_cycle * settings.cycles).min(settings.max_ticks.unwrap_or(usize::MAX));
    let level = scheme.level();
    let mut qp = scheme.new_qp();
    let mut qp_dot = scheme.new_qp();
    let mut scratch = scheme.new_dot_scratch();
    let mut reference = ExactPath::new(&qp);
    let (mut theta, mut thetadot) = (*theta0, SVector::<f64, N>::zeros());
    let mut command = SVector::<f64, N>::zeros();
    let mut cycle_start = *theta0;
    let needs_dot = solver.needs_qp_dot() || observer.as_ref().is_some_and(|o| o.needs_qp_dot());

    let mut out = LoopOutcome {
        status: Status::Completed,
        ticks: 0,
        solve_us: Vec::with_capacity(total),
        tick_us: Vec::with_capacity(total),
        max_track_err: 0.0,
        rms_track_err: 0.0,
        max_dx: 0.0,
        rms_dx: 0.0,
        max_dx_settled: 0.0,
        drift: Vec::with_capacity(settings.cycles),
        cycle_change: Vec::with_capacity(settings.cycles),
        products_mean: None,
        products_max: None,
        iterations_mean: 0.0,
        iterations_max: 0,
        score_failures: 0,
    };
    let (mut sum_track2, mut sum_dx2, mut scored) = (0.0, 0.0, 0usize);
    let (mut sum_products, mut max_products, mut counted) = (0u64, 0u64, false);
    let mut sum_iterations = 0u64;

    for k in 0..total {
        let t = k as f64 * h;
        let start = Instant::now();
        scheme.build(t, &theta, &thetadot, &mut qp);
        if needs_dot {
            // Velocity level: theta moves at the command; acceleration level: thetadot does.
            let (v, a) = match level {
                schemes::scheme::Level::Velocity => (command, SVector::zeros()),
                schemes::scheme::Level::Acceleration => (thetadot, command),
            };
            scheme.build_dot(t, &theta, &v, &a, &mut qp_dot, &mut scratch);
        }
        let solve_start = Instant::now();
        let dot = solver.needs_qp_dot().then_some(&qp_dot);
        let result = solver.tick(t, &qp, dot, h);
        let solve_end = Instant::now();
        if let Err(e) = result {
            out.status = Status::Failed {
                t,
                message: e.to_string(),
            };
            break;
        }
        let x = solver.x();
        if x.iter().any(|v| !v.is_finite() || v.abs() > DIVERGED) {
            out.status = Status::Diverged { t };
            break;
        }
        command.copy_from_slice(&x[..N]);
        let theta_k = theta;
        advance(level, h, &mut theta, &mut thetadot, command.as_slice());
        let end = Instant::now();
        out.solve_us
            .push((solve_end - solve_start).as_secs_f64() * 1e6);
        out.tick_us.push((end - start).as_secs_f64() * 1e6);
        out.ticks += 1;

        // Scoring (not timed).
        let track = (robot.position(&theta_k) - path.at(t).r).norm();
        out.max_track_err = out.max_track_err.max(track);
        sum_track2 += track * track;
        match reference.solve(&qp) {
            Ok(x_star) => {
                let scale = x_star.rows(0, N).amax().max(1.0);
                let dx = x[..N]
                    .iter()
                    .zip(x_star.iter())
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                    / scale;
                out.max_dx = out.max_dx.max(dx);
                if t >= SETTLE {
                    out.max_dx_settled = out.max_dx_settled.max(dx);
                }
                sum_dx2 += dx * dx;
                scored += 1;
                if let Some(o) = observer.as_mut() {
                    o.observe(k, t, &qp, needs_dot.then_some(&qp_dot), x_star.as_slice());
                }
            }
            Err(_) => out.score_failures += 1,
        }
        if let Some(p) = solver.products() {
            counted = true;
            sum_products += p;
            max_products = max_products.max(p);
        }
        let it = solver.iterations();
        sum_iterations += it as u64;
        out.iterations_max = out.iterations_max.max(it);
        if (k + 1) % per_cycle == 0 {
            out.drift.push((theta - theta0).norm());
            out.cycle_change.push((theta - cycle_start).norm());
            cycle_start = theta;
        }
    }
    let ticks = out.ticks.max(1) as f64;
    out.rms_track_err = (sum_track2 / ticks).sqrt();
    out.rms_dx = (sum_dx2 / scored.max(1) as f64).sqrt();
    out.iterations_mean = sum_iterations as f64 / ticks;
    if counted {
        out.products_mean = Some(sum_products as f64 / ticks);
        out.products_max = Some(max_products);
    }
    out
}

/// A failed setup as a [`ControlError`] for the task `task`.
pub fn setup_error(task: &str, message: impl ToString) -> ControlError {
    ControlError::Setup {
        task: task.to_string(),
        message: message.to_string(),
    }
}
