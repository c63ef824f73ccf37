//! One controller run: a scheme's QP solved (or tracked, by a network) at a fixed control
//! period h, the command held over each tick and the arm integrated exactly between ticks
//! (`arm`), over one or more cycles of a closed path.
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
//!
//! With [`Rounding::OneUlp`] ([`LoopSettings::rounding`]) the run is the rounding-noise probe:
//! after step 3 of every tick each joint angle of theta_{k+1} is moved by one ulp (module
//! `rounding`), outside the timed part; with [`Rounding::AsComputed`] nothing is moved.

use crate::arm::advance;
use crate::rounding::Rounding;
use crate::tick::TickSolver;
use nalgebra::DVector;
use qp::QpDotScratch;
use qp::{Qp, QpSolve};
use robots::Robot;
use schemes::paths::Path;
use schemes::Scheme;
use solvers::ExactPath;
use spec::Level;
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
    /// The state as computed, or moved by one ulp after every tick (the rounding-noise probe).
    pub rounding: Rounding,
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
    /// max |x - x*| over the ticks at t >= `SETTLE` (module `control_loop`).
    pub max_dx_settled: f64,
    /// |theta(c T) - theta_0|_2 after each completed cycle c = 1, 2, ...
    pub drift: Vec<f64>,
    /// |theta(c T) - theta((c - 1) T)|_2 for each completed cycle c.
    pub cycle_change: Vec<f64>,
    /// Mean and max per tick of the products [`TickSolver::tick`] reports (None when not
    /// counted).
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
pub fn run_loop(
    robot: &dyn Robot,
    path: &dyn Path,
    scheme: &dyn Scheme,
    solver: &mut dyn TickSolver,
    theta0: &[f64],
    settings: &LoopSettings,
    mut observer: Option<&mut dyn Observer>,
) -> LoopOutcome {
    let h = settings.h;
    let per_cycle = settings.ticks_per_cycle();
    let total = (per_cycle * settings.cycles).min(settings.max_ticks.unwrap_or(usize::MAX));
    let needs_dot = solver.needs_qp_dot() || observer.as_ref().is_some_and(|o| o.needs_qp_dot());
    let theta0 = DVector::from_column_slice(theta0);
    let mut state = LoopState::new(scheme, &theta0, needs_dot);
    let mut reference = ExactPath::new(&state.qp);
    let mut tally = Tally::new(total, settings.cycles);
    let mut cycle_start = theta0.clone();
    let mut moves = settings.rounding.moves();

    for k in 0..total {
        let t = k as f64 * h;
        let timed = match state.tick(solver, t, h) {
            Ok(timed) => timed,
            Err(status) => {
                tally.out.status = status;
                break;
            }
        };
        tally.timed(&timed);
        if let Some(moves) = moves.as_mut() {
            moves.apply(state.theta.as_mut_slice());
        }

        // Scoring (not timed).
        tally.track((robot.position(state.theta_k.as_slice()) - path.at(t).r).norm());
        let x = solver.x();
        match reference.solve(&state.qp) {
            Ok(x_star) => {
                tally.distance(t, joint_distance(scheme.joints(), x, x_star));
                if let Some(o) = observer.as_mut() {
                    let qp_dot = needs_dot.then_some(&state.qp_dot);
                    o.observe(k, t, &state.qp, qp_dot, x_star.as_slice());
                }
            }
            Err(_) => tally.out.score_failures += 1,
        }
        tally.work(timed.cost.products, timed.cost.iterations);
        if (k + 1) % per_cycle == 0 {
            let theta = &state.theta;
            tally.cycle_end((theta - &theta0).norm(), (theta - &cycle_start).norm());
            cycle_start.copy_from(theta);
        }
    }
    tally.finish()
}

/// What a run carries from tick to tick: the tick's QP and dQP/dt (buffers built into, never
/// reallocated), the arm's state and the command held over the tick.
struct LoopState<'a> {
    scheme: &'a dyn Scheme,
    level: Level,
    /// Whether dQP/dt is built (for the solver or the observer).
    needs_dot: bool,
    qp: Qp,
    qp_dot: Qp,
    scratch: QpDotScratch,
    theta: DVector<f64>,
    thetadot: DVector<f64>,
    command: DVector<f64>,
    /// Zero joint rates (the acceleration of the velocity level's motion).
    zeros: DVector<f64>,
    /// The joint angles at t_k of the last tick, before the arm moved.
    theta_k: DVector<f64>,
}

impl<'a> LoopState<'a> {
    /// The arm at rest at `theta0`, no command yet.
    fn new(scheme: &'a dyn Scheme, theta0: &DVector<f64>, needs_dot: bool) -> Self {
        let n = theta0.len();
        LoopState {
            scheme,
            level: scheme.level(),
            needs_dot,
            qp: scheme.new_qp(),
            qp_dot: scheme.new_qp(),
            scratch: scheme.new_dot_scratch(),
            theta: theta0.clone(),
            thetadot: DVector::zeros(n),
            command: DVector::zeros(n),
            zeros: DVector::zeros(n),
            theta_k: theta0.clone(),
        }
    }

    /// Steps 1-3 of the tick at `t`, timed (module docs): QP_k (and dQP/dt where needed),
    /// `solver`'s answer x_k, and the arm moved under its command over [t, t + h]. Why the run
    /// stops instead, if the solver failed or the command diverged.
    fn tick(&mut self, solver: &mut dyn TickSolver, t: f64, h: f64) -> Result<Timed, Status> {
        let start = Instant::now();
        self.scheme.build(
            t,
            self.theta.as_slice(),
            self.thetadot.as_slice(),
            &mut self.qp,
        );
        if self.needs_dot {
            // Velocity level: theta moves at the command; acceleration level: thetadot does.
            let (v, a) = match self.level {
                Level::Velocity => (&self.command, &self.zeros),
                Level::Acceleration => (&self.thetadot, &self.command),
            };
            self.scheme.build_dot(
                t,
                self.theta.as_slice(),
                v.as_slice(),
                a.as_slice(),
                &mut self.qp_dot,
                &mut self.scratch,
            );
        }
        let solve_start = Instant::now();
        let dot = solver.needs_qp_dot().then_some(&self.qp_dot);
        let result = solver.tick(t, &self.qp, dot, h);
        let solve_end = Instant::now();
        let cost = result.map_err(|e| Status::Failed {
            t,
            message: e.to_string(),
        })?;
        let x = solver.x();
        if x.iter().any(|v| !v.is_finite() || v.abs() > DIVERGED) {
            return Err(Status::Diverged { t });
        }
        let n = self.theta.len();
        self.command.copy_from_slice(&x[..n]);
        self.theta_k.copy_from(&self.theta);
        advance(
            self.level,
            h,
            self.theta.as_mut_slice(),
            self.thetadot.as_mut_slice(),
            self.command.as_slice(),
        );
        let end = Instant::now();
        Ok(Timed {
            solve_us: (solve_end - solve_start).as_secs_f64() * 1e6,
            tick_us: (end - start).as_secs_f64() * 1e6,
            cost,
        })
    }
}

/// What the timed part of a tick (steps 1-3 of the module docs) measured.
struct Timed {
    /// Duration of the solve alone (us).
    solve_us: f64,
    /// Duration of the whole tick (us).
    tick_us: f64,
    /// The solver's iterations and products of the tick.
    cost: QpSolve,
}

/// |x[..n] - x*[..n]|_inf / max(1, |x*[..n]|_inf): the joint command's distance from the exact
/// optimum, relative (module docs).
fn joint_distance(n: usize, x: &[f64], x_star: &DVector<f64>) -> f64 {
    let scale = x_star.rows(0, n).amax().max(1.0);
    x[..n]
        .iter()
        .zip(x_star.iter())
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// A run's outcome as its ticks are scored, with the running sums its means are made of.
struct Tally {
    /// The outcome so far (its means are set by [`Tally::finish`]).
    out: LoopOutcome,
    /// Sum of the squared tracking errors.
    sum_track2: f64,
    /// Sum of the squared distances |x - x*| of the ticks scored.
    sum_dx2: f64,
    /// Ticks scored against the exact optimum.
    scored: usize,
    /// Sum of the products per tick.
    sum_products: u64,
    /// Most products in a tick.
    max_products: u64,
    /// Whether the solver counts its products.
    counted: bool,
    /// Sum of the iterations per tick.
    sum_iterations: u64,
}

impl Tally {
    /// No tick yet, room for `total` ticks over `cycles` cycles.
    fn new(total: usize, cycles: usize) -> Self {
        Tally {
            out: LoopOutcome {
                status: Status::Completed,
                ticks: 0,
                solve_us: Vec::with_capacity(total),
                tick_us: Vec::with_capacity(total),
                max_track_err: 0.0,
                rms_track_err: 0.0,
                max_dx: 0.0,
                rms_dx: 0.0,
                max_dx_settled: 0.0,
                drift: Vec::with_capacity(cycles),
                cycle_change: Vec::with_capacity(cycles),
                products_mean: None,
                products_max: None,
                iterations_mean: 0.0,
                iterations_max: 0,
                score_failures: 0,
            },
            sum_track2: 0.0,
            sum_dx2: 0.0,
            scored: 0,
            sum_products: 0,
            max_products: 0,
            counted: false,
            sum_iterations: 0,
        }
    }

    /// A completed tick and its durations.
    fn timed(&mut self, timed: &Timed) {
        self.out.solve_us.push(timed.solve_us);
        self.out.tick_us.push(timed.tick_us);
        self.out.ticks += 1;
    }

    /// The tick's tracking error |f(theta_k) - r*(t_k)|_2.
    fn track(&mut self, err: f64) {
        self.out.max_track_err = self.out.max_track_err.max(err);
        self.sum_track2 += err * err;
    }

    /// The tick's relative distance `dx` from the exact optimum ([`joint_distance`]) at `t`.
    fn distance(&mut self, t: f64, dx: f64) {
        self.out.max_dx = self.out.max_dx.max(dx);
        if t >= SETTLE {
            self.out.max_dx_settled = self.out.max_dx_settled.max(dx);
        }
        self.sum_dx2 += dx * dx;
        self.scored += 1;
    }

    /// The solver's work in the tick: its products (if counted) and iterations.
    fn work(&mut self, products: Option<u64>, iterations: u32) {
        if let Some(p) = products {
            self.counted = true;
            self.sum_products += p;
            self.max_products = self.max_products.max(p);
        }
        self.sum_iterations += iterations as u64;
        self.out.iterations_max = self.out.iterations_max.max(iterations);
    }

    /// The end of a cycle: the drift from the start and the change over the cycle.
    fn cycle_end(&mut self, drift: f64, change: f64) {
        self.out.drift.push(drift);
        self.out.cycle_change.push(change);
    }

    /// The outcome, its means made of the sums.
    fn finish(mut self) -> LoopOutcome {
        let out = &mut self.out;
        let ticks = out.ticks.max(1) as f64;
        out.rms_track_err = (self.sum_track2 / ticks).sqrt();
        out.rms_dx = (self.sum_dx2 / self.scored.max(1) as f64).sqrt();
        out.iterations_mean = self.sum_iterations as f64 / ticks;
        if self.counted {
            out.products_mean = Some(self.sum_products as f64 / ticks);
            out.products_max = Some(self.max_products);
        }
        self.out
    }
}
