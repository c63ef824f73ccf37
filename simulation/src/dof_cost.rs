//! Cost against the number of joints: what one instant and one whole run cost on the n-link arms
//! `nlink-N` of the registry ([`NLINK_SIZES`], N = 3 ... 30), with jia2019's VLTCO scheme on a
//! four-leaf clover and kong2019's ZNN scheme (eq. 22) on a circle, and the growth exponent k of
//! cost ~ c N^k fitted to each quantity ([`fit_power_law`]).
//!
//! # What is measured
//!
//! Each (N, scheme) pair ([`Case`]) first runs the exact column once ([`simulate`] with
//! [`Solver::Exact`]); up to [`Budget::states`] instants of that run's trace, evenly spread, are
//! the states every per-call quantity is timed at, so the costs are those of a real trajectory
//! (active sets, conditioning), not of one hand-picked point. Per state, the quantities
//! ([`Quantity`]) are:
//!
//! - `scheme-build`: [`Scheme::build`], the QP assembly (J, bounds, objective) at the state;
//! - `network-rhs`, `network-jacobian`: one right-hand side and one analytic Jacobian of the
//!   network ([`Case::network`], LVI-PDNN with gamma = 1e7 for both schemes) at a state near the
//!   optimum (x* + 1e-3 sin(i + 1), multipliers 0, as the criterion benches use);
//! - `exact-active-set`: the certified active-set solver ([`ActiveSetSolver`]) hot-started from
//!   the previous sampled instant's optimal working set, what the exact column and the scorer
//!   call at every instant ([`solvers::ExactPath`] adds to it a Clarabel check on every 100th
//!   solve, not timed here);
//! - `exact-clarabel`: one Clarabel solve ([`ExactSolver::solve`]) of the same QP, the reference
//!   of record;
//! - `kkt-floor`: one dense LU solve of the equality-constrained KKT system of the same QP
//!   (`[[P, A'], [A, 0]]`, size nx + n_eq, assembled and factorised by
//!   [`solvers::solve_equality_kkt`], allocation included): what no exact method that factorises
//!   the KKT matrix can beat, the active-set method's cost when its working set is empty.
//!
//! and per whole run ([`simulate`] with the experiment files' defaults: the exact column with
//! [`default_exact_integrator`], the network with [`IntegratorSettings::default`], scored at
//! every accepted step): `run-exact` and `run-network`, wall seconds of the whole call.
//!
//! # How it is timed
//!
//! [`std::time::Instant`] around batches: a per-call quantity is timed as `reps` back-to-back
//! calls on one state (`reps` chosen once per quantity so a batch lasts at least
//! [`Budget::min_batch_us`], so the clock's resolution and overhead do not count), the sample
//! being the batch's time over `reps`; every state gives one sample per pass, over
//! [`Budget::passes`] passes. A run is one sample per repetition ([`Budget::runs`]). Reported
//! are the median and the 95th percentile (nearest rank) of the samples, in microseconds
//! ([`Summary`]). Nothing here asserts a speed: the numbers go to `results/dof-cost.csv` and the
//! report.

use crate::simulate::{simulate, Outcome, Settings, Solver};
use catalog::experiment::{default_exact_integrator, NetworkInit, Scoring};
use catalog::integrator::IntegratorSettings;
use catalog::robot_registry::{nlink_name, robot_by_name, RobotVisitor, NLINK_SIZES};
use catalog::solver_spec::SolverSpec;
use nalgebra::{DMatrix, DVector, SVector};
use robots::{Dynamics, Robot};
use schemes::jia2019::Jia2019;
use schemes::kong2019::Kong2019;
use schemes::paths::{build_path, Path, PathSpec};
use schemes::qp::{Qp, QpDims};
use schemes::scheme::Scheme;
use solvers::neural::{build_solver, NeuralSolver};
use solvers::{solve_equality_kkt, ActiveSetSolution, ActiveSetSolver, ExactSolver, WorkingSet};
use std::sync::Arc;
use std::time::Instant;

/// The schemes measured, by paper id.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SchemeKind {
    /// jia2019 VLTCO (phi = 0.2, tau = 0.4, kappa = 20, Lambda = 20) on a four-leaf clover of
    /// size 0.1 m (5 s): nx = N + 1, n_eq = 3, n_in = 2N, bounds on every variable.
    Jia2019,
    /// kong2019 ZNN scheme (eq. 22, mu = 1, k_p = 1) on a circle of radius 0.05 m (9 s):
    /// nx = N, n_eq = 3, no inequalities.
    Kong2019,
}

impl SchemeKind {
    pub const ALL: [SchemeKind; 2] = [SchemeKind::Jia2019, SchemeKind::Kong2019];

    /// The paper id (`jia2019`, `kong2019`).
    pub fn id(self) -> &'static str {
        match self {
            SchemeKind::Jia2019 => "jia2019",
            SchemeKind::Kong2019 => "kong2019",
        }
    }

    /// The path the scheme is run on, starting at the arm's tip.
    pub fn path(self) -> PathSpec {
        match self {
            SchemeKind::Jia2019 => PathSpec {
                scale: Some(CLOVER_SCALE),
                ..PathSpec::new("four-leaf-clover", 5.0)
            },
            SchemeKind::Kong2019 => PathSpec::new("circle", 9.0),
        }
    }
}

/// Size a of the four-leaf clover (m): 0.1, inside the n-link arms' workspace around
/// `NLink::home` for every N (the suite's default 0.15 m is the Jaco2's).
pub const CLOVER_SCALE: f64 = 0.1;

/// What is timed (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Quantity {
    SchemeBuild,
    NetworkRhs,
    NetworkJacobian,
    ExactActiveSet,
    ExactClarabel,
    KktFloor,
    RunExact,
    RunNetwork,
}

impl Quantity {
    pub const ALL: [Quantity; 8] = [
        Quantity::SchemeBuild,
        Quantity::NetworkRhs,
        Quantity::NetworkJacobian,
        Quantity::ExactActiveSet,
        Quantity::ExactClarabel,
        Quantity::KktFloor,
        Quantity::RunExact,
        Quantity::RunNetwork,
    ];

    /// The name in `results/dof-cost.csv` and in the criterion ids.
    pub fn id(self) -> &'static str {
        match self {
            Quantity::SchemeBuild => "scheme-build",
            Quantity::NetworkRhs => "network-rhs",
            Quantity::NetworkJacobian => "network-jacobian",
            Quantity::ExactActiveSet => "exact-active-set",
            Quantity::ExactClarabel => "exact-clarabel",
            Quantity::KktFloor => "kkt-floor",
            Quantity::RunExact => "run-exact",
            Quantity::RunNetwork => "run-network",
        }
    }

    /// The quantity named `id` ([`Self::id`]).
    pub fn from_id(id: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.id() == id)
    }

    /// Whether it is a whole run (one sample per run) rather than one call at one state.
    pub fn is_run(self) -> bool {
        matches!(self, Quantity::RunExact | Quantity::RunNetwork)
    }
}

/// Median and 95th percentile of a set of samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub median_us: f64,
    pub p95_us: f64,
    pub samples: usize,
}

impl Summary {
    /// The summary of `samples_us` (nearest-rank quantiles; `None` when empty or not finite).
    pub fn of(samples_us: &[f64]) -> Option<Self> {
        if samples_us.is_empty() || samples_us.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let mut s = samples_us.to_vec();
        s.sort_by(f64::total_cmp);
        Some(Summary {
            median_us: quantile(&s, 0.5),
            p95_us: quantile(&s, 0.95),
            samples: s.len(),
        })
    }
}

/// The nearest-rank `p`-quantile of sorted, non-empty `sorted`: the smallest sample with at
/// least a fraction p of the samples at or below it (the median of an even count is the lower
/// middle sample).
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let rank = (p * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

/// A least-squares fit of cost = c N^k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerFit {
    /// The growth exponent k.
    pub k: f64,
    /// The factor c (the cost's unit).
    pub c: f64,
    /// Points fitted.
    pub points: usize,
}

/// Fits cost = c N^k to `(N, cost)` points by least squares on the logarithms:
/// with u = ln N and v = ln cost, the line v = ln c + k u minimising sum (v_i - ln c - k u_i)^2
/// has
///
/// ```text
/// k = sum (u_i - u_mean)(v_i - v_mean) / sum (u_i - u_mean)^2,   ln c = v_mean - k u_mean.
/// ```
///
/// So a relative error in each cost weighs the same at every N (the measurements' noise is
/// relative). Points with a non-positive or non-finite N or cost are left out; `None` with fewer
/// than two distinct N left.
pub fn fit_power_law(points: &[(f64, f64)]) -> Option<PowerFit> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, y)| n.is_finite() && y.is_finite() && *n > 0.0 && *y > 0.0)
        .map(|(n, y)| (n.ln(), y.ln()))
        .collect();
    let m = logs.len() as f64;
    let u_mean = logs.iter().map(|p| p.0).sum::<f64>() / m;
    let v_mean = logs.iter().map(|p| p.1).sum::<f64>() / m;
    let suu: f64 = logs.iter().map(|(u, _)| (u - u_mean).powi(2)).sum();
    let suv: f64 = logs.iter().map(|(u, v)| (u - u_mean) * (v - v_mean)).sum();
    if logs.len() < 2 || suu <= 0.0 {
        return None;
    }
    let k = suv / suu;
    Some(PowerFit {
        k,
        c: (v_mean - k * u_mean).exp(),
        points: logs.len(),
    })
}

/// How much is measured: the defaults take ~20-40 s for the eight N and both schemes on one
/// core of a 2020s server CPU (most of it the jia2019 runs at N = 20 and 30).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// States sampled from the exact run's trace.
    pub states: usize,
    /// Passes over the states (samples per quantity = states x passes).
    pub passes: usize,
    /// Shortest batch of back-to-back calls (us).
    pub min_batch_us: f64,
    /// Most calls in one batch.
    pub max_reps: usize,
    /// Whole runs per run quantity (one sample each).
    pub runs: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            states: 100,
            passes: 3,
            min_batch_us: 20.0,
            max_reps: 200,
            runs: 5,
        }
    }
}

/// One measured (N, scheme) pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub scheme: SchemeKind,
    pub n: usize,
    /// The network timed (network-rhs, network-jacobian, run-network).
    pub network: SolverSpec,
}

impl Case {
    /// The scheme on `nlink-n` with LVI-PDNN (gamma = 1e7, jia2019's).
    pub fn new(scheme: SchemeKind, n: usize) -> Self {
        Case {
            scheme,
            n,
            network: SolverSpec::LviPdnn { gamma: 1e7 },
        }
    }
}

/// One measured quantity of one [`Case`].
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    pub scheme: SchemeKind,
    /// The scheme's own name (`VLTCO`, `ZNN (eq. 22)`).
    pub scheme_name: String,
    /// The network's display name (`LVI-PDNN`).
    pub network: String,
    pub n: usize,
    pub dims: QpDims,
    pub quantity: Quantity,
    pub summary: Summary,
    /// For runs: accepted steps, RHS evaluations and whether the run completed (of the first
    /// repetition; every repetition is the same deterministic run).
    pub run: Option<RunCounts>,
}

/// Counts of a whole run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunCounts {
    pub steps: usize,
    pub rhs_evals: usize,
    pub completed: bool,
}

/// The machine measured on: the CPU model of `/proc/cpuinfo` and the logical cores the process
/// may use (`"unknown CPU"` where there is no `/proc/cpuinfo`).
pub fn machine() -> (String, usize) {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| {
            let (key, value) = l.split_once(':')?;
            (key.trim() == "model name").then(|| value.split_whitespace().collect::<Vec<_>>())
        })
        .map(|words| words.join(" "))
        .unwrap_or_else(|| "unknown CPU".to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (model, cores)
}

/// Measures every N of [`NLINK_SIZES`] with both schemes, calling `progress` after each case.
pub fn measure_all(budget: &Budget, mut progress: impl FnMut(&Case)) -> Vec<Measurement> {
    let mut out = Vec::new();
    for scheme in SchemeKind::ALL {
        for n in NLINK_SIZES {
            let case = Case::new(scheme, n);
            out.extend(measure(&case, budget));
            progress(&case);
        }
    }
    out
}

/// Measures one case (see the module docs); quantities that cannot be measured (a network
/// without an analytic Jacobian, a failed exact run) are left out, with a message on stderr.
pub fn measure(case: &Case, budget: &Budget) -> Vec<Measurement> {
    let mut prepared = match prepare(case, budget.states) {
        Ok(p) => p,
        Err(e) => {
            eprintln!(
                "{} nlink-{}: {e}; nothing measured",
                case.scheme.id(),
                case.n
            );
            return Vec::new();
        }
    };
    let timer = Timer { budget };
    let mut out = Vec::new();
    for quantity in Quantity::ALL {
        if !prepared.supports(quantity) {
            eprintln!("{}: {} not measured", prepared.label(), quantity.id());
            continue;
        }
        let (samples, run) = if quantity.is_run() {
            let (samples, ()) = repeat_runs(budget.runs, || prepared.call(quantity, 0));
            (samples, prepared.last_run())
        } else {
            let states = prepared.states();
            (timer.samples(states, |i| prepared.call(quantity, i)), None)
        };
        if let Some(summary) = Summary::of(&samples) {
            out.push(Measurement {
                scheme: case.scheme,
                scheme_name: prepared.scheme_name(),
                network: prepared.network_name(),
                n: case.n,
                dims: prepared.dims(),
                quantity,
                summary,
                run,
            });
        }
    }
    out
}

/// A case made ready to time (see [`prepare`]): every quantity of [`Quantity`] as one call,
/// without allocation where the code timed does not allocate itself. Object safe, so the
/// criterion benches and [`measure`] drive it without knowing N.
pub trait PreparedCase {
    /// `<scheme> nlink-<N>`.
    fn label(&self) -> String;
    fn scheme_name(&self) -> String;
    fn network_name(&self) -> String;
    fn dims(&self) -> QpDims;
    /// States sampled from the exact run (per-call quantities take an index below this).
    fn states(&self) -> usize;
    /// Whether `quantity` can be timed (the network has an analytic Jacobian, the equality
    /// KKT matrix is regular).
    fn supports(&self, quantity: Quantity) -> bool;
    /// One call of `quantity` at state `i` (a whole run, for the run quantities; `i` unused).
    fn call(&mut self, quantity: Quantity, i: usize);
    /// Counts of the last whole run [`Self::call`] made.
    fn last_run(&self) -> Option<RunCounts>;
}

/// Builds `case`'s robot, path, scheme and network, runs the exact column once and samples up
/// to `states` states of its trace (evenly spread), with the QP, its time derivative, the
/// exact optimum and the previous sampled instant's optimal working set at each. An error when
/// the exact run does not start or leaves no trace.
pub fn prepare(case: &Case, states: usize) -> Result<Box<dyn PreparedCase>, String> {
    let robot = robot_by_name(&nlink_name(case.n))
        .ok_or_else(|| format!("nlink-{} is not in the registry (NLINK_SIZES)", case.n))?;
    let home = robot.stated_pose();
    robot.visit(Prepare {
        case,
        states,
        home: &home,
    })
}

/// [`prepare`] generic in N.
struct Prepare<'a> {
    case: &'a Case,
    states: usize,
    home: &'a [f64],
}

impl RobotVisitor for Prepare<'_> {
    type Output = Result<Box<dyn PreparedCase>, String>;

    fn visit<const N: usize>(
        self,
        robot: Arc<dyn Robot<N>>,
        _: Option<Arc<dyn Dynamics<N>>>,
    ) -> Self::Output {
        Ok(Box::new(Prepared::<N>::new(
            self.case,
            robot,
            self.home,
            self.states,
        )?))
    }
}

/// A state of the arm at an instant: (t, theta, thetadot).
type State<const N: usize> = (f64, SVector<f64, N>, SVector<f64, N>);

/// [`PreparedCase`] for an N-joint arm.
struct Prepared<const N: usize> {
    label: String,
    robot: Arc<dyn Robot<N>>,
    path: Arc<dyn Path>,
    scheme: Box<dyn Scheme<N>>,
    theta0: SVector<f64, N>,
    network_spec: SolverSpec,
    network: Box<dyn NeuralSolver>,
    needs_dot: bool,
    has_jacobian: bool,
    has_kkt: bool,
    states: Vec<State<N>>,
    qps: Vec<Qp>,
    qp_dots: Vec<Qp>,
    /// Network states near the optimum.
    ys: Vec<Vec<f64>>,
    /// The previous sampled instant's optimal working set (the hot start).
    warm: Vec<WorkingSet>,
    /// The equality-constrained QPs of the same P, q, A, b (the KKT floor).
    equality: Vec<Qp>,
    scratch_qp: Qp,
    fast: ActiveSetSolver,
    sol: ActiveSetSolution,
    clarabel: ExactSolver,
    ydot: Vec<f64>,
    jac: DMatrix<f64>,
    last_run: Option<RunCounts>,
}

impl<const N: usize> Prepared<N> {
    fn new(
        case: &Case,
        robot: Arc<dyn Robot<N>>,
        home: &[f64],
        states: usize,
    ) -> Result<Self, String> {
        let label = format!("{} nlink-{N}", case.scheme.id());
        let theta0 = SVector::<f64, N>::from_column_slice(home);
        let path: Arc<dyn Path> = Arc::from(
            build_path(&case.scheme.path(), robot.position(&theta0))
                .map_err(|e| format!("{label}: {e}"))?,
        );
        let scheme: Box<dyn Scheme<N>> = match case.scheme {
            SchemeKind::Jia2019 => Box::new(Jia2019::new(
                robot.clone(),
                path.clone(),
                theta0,
                0.2,
                0.4,
                20.0,
                20.0,
            )),
            SchemeKind::Kong2019 => {
                Box::new(Kong2019::znn(robot.clone(), path.clone(), theta0, 1.0, 1.0))
            }
        };
        let dims = scheme.dims();
        let mut network = build_solver(&case.network, dims).map_err(|e| format!("{label}: {e}"))?;
        let needs_dot = network.needs_qp_dot();

        // The states: evenly spread trace points of one exact run.
        let run = simulate(
            robot.as_ref(),
            path.as_ref(),
            scheme.as_ref(),
            Solver::Exact,
            &theta0,
            &theta0,
            &exact_settings(),
        )
        .map_err(|e| format!("{label}: the exact run does not start: {e}"))?;
        if let Outcome::Failed { t, error, .. } = &run.outcome {
            eprintln!("{label}: the exact run failed at t = {t}: {error}");
        }
        let trace = &run.trace;
        let count = states.clamp(1, trace.len().max(1));
        let states: Vec<State<N>> = (0..count)
            .filter_map(|i| trace.get(i * trace.len() / count))
            .map(|p| {
                (
                    p.t,
                    SVector::from_column_slice(&p.theta),
                    SVector::from_column_slice(&p.thetadot),
                )
            })
            .collect();
        if states.is_empty() {
            return Err(format!("{label}: the exact run left no trace"));
        }
        let mut qps = Vec::with_capacity(states.len());
        let mut qp_dots = Vec::with_capacity(states.len());
        let mut scratch = scheme.new_dot_scratch();
        for (t, theta, thetadot) in &states {
            let mut qp = scheme.new_qp();
            scheme.build(*t, theta, thetadot, &mut qp);
            qps.push(qp);
            let mut qp_dot = scheme.new_qp();
            let thetaddot = SVector::zeros();
            scheme.build_dot(*t, theta, thetadot, &thetaddot, &mut qp_dot, &mut scratch);
            qp_dots.push(qp_dot);
        }

        // Exact optima and optimal working sets along the sampled states.
        let mut fast = ActiveSetSolver::new(dims);
        let mut sol = ActiveSetSolution::zeros(dims);
        let mut clarabel = ExactSolver::new();
        let mut x_star: Vec<DVector<f64>> = Vec::with_capacity(qps.len());
        let mut optimal: Vec<WorkingSet> = Vec::with_capacity(qps.len());
        let mut uncertified = 0usize;
        for qp in &qps {
            match fast.solve_into(qp, optimal.last(), &mut sol) {
                Ok(()) => {
                    x_star.push(sol.x.clone());
                    optimal.push(sol.working_set.clone());
                }
                Err(_) => {
                    uncertified += 1;
                    let x = clarabel
                        .solve(qp)
                        .map(|s| s.x)
                        .unwrap_or_else(|_| DVector::zeros(dims.nx));
                    x_star.push(x);
                    optimal.push(optimal.last().cloned().unwrap_or_default());
                }
            }
        }
        if uncertified > 0 {
            eprintln!(
                "{label}: {uncertified} of {} sampled QPs not certified by the active-set solver",
                qps.len()
            );
        }
        let warm: Vec<WorkingSet> = (0..qps.len())
            .map(|i| optimal[i.saturating_sub(1)].clone())
            .collect();

        // Network states near the optimum: x* + 1e-3 sin(i + 1), multipliers 0.
        let dim = network.state_dim(dims);
        let ys: Vec<Vec<f64>> = x_star
            .iter()
            .map(|x| {
                let mut y = vec![0.0; dim];
                for (i, xi) in x.iter().enumerate() {
                    y[i] = xi + 1e-3 * ((i + 1) as f64).sin();
                }
                y
            })
            .collect();
        let mut jac = DMatrix::zeros(dim, dim);
        let has_jacobian = network.jacobian(
            states[0].0,
            &ys[0],
            &qps[0],
            needs_dot.then_some(&qp_dots[0]),
            &mut jac,
        );

        let equality: Vec<Qp> = qps
            .iter()
            .map(|qp| {
                let mut e = Qp::zeros(QpDims {
                    nx: dims.nx,
                    n_eq: dims.n_eq,
                    n_in: 0,
                });
                e.p.copy_from(&qp.p);
                e.q.copy_from(&qp.q);
                e.a.copy_from(&qp.a);
                e.b.copy_from(&qp.b);
                e.lower.fill(f64::NEG_INFINITY);
                e.upper.fill(f64::INFINITY);
                e
            })
            .collect();
        let has_kkt = solve_equality_kkt(&equality[0]).is_some();
        Ok(Prepared {
            label,
            scratch_qp: scheme.new_qp(),
            robot,
            path,
            scheme,
            theta0,
            network_spec: case.network.clone(),
            network,
            needs_dot,
            has_jacobian,
            has_kkt,
            states,
            qps,
            qp_dots,
            ys,
            warm,
            equality,
            fast,
            sol,
            clarabel,
            ydot: vec![0.0; dim],
            jac,
            last_run: Some(RunCounts::of(&run)),
        })
    }

    /// A whole run with `solver` and `settings`; records its counts.
    fn run(&mut self, solver: Solver<'_>, settings: &Settings) {
        let run = simulate(
            self.robot.as_ref(),
            self.path.as_ref(),
            self.scheme.as_ref(),
            solver,
            &self.theta0,
            &self.theta0,
            settings,
        );
        self.last_run = run.ok().map(|r| RunCounts::of(&r));
    }
}

impl RunCounts {
    fn of(run: &crate::simulate::Run) -> Self {
        RunCounts {
            steps: run.stats.steps,
            rhs_evals: run.stats.rhs_evals,
            completed: matches!(run.outcome, Outcome::Completed(_)),
        }
    }
}

/// The experiment files' default settings of an exact column: [`default_exact_integrator`],
/// scored (the exact column has nothing to score), network at zero.
pub fn exact_settings() -> Settings {
    Settings {
        integrator: default_exact_integrator(),
        scoring: Scoring::EveryStep,
        network_init: NetworkInit::Zero,
    }
}

/// The experiment files' default settings of a network run: [`IntegratorSettings::default`]
/// (BDF, RelTol 1e-6, AbsTol 1e-8, as ode15s), scored against the exact optimum at every
/// accepted step, network state starting at zero.
pub fn network_settings() -> Settings {
    Settings {
        integrator: IntegratorSettings::default(),
        ..exact_settings()
    }
}

impl<const N: usize> PreparedCase for Prepared<N> {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn scheme_name(&self) -> String {
        self.scheme.name()
    }

    fn network_name(&self) -> String {
        self.network_spec.display_name()
    }

    fn dims(&self) -> QpDims {
        self.scheme.dims()
    }

    fn states(&self) -> usize {
        self.states.len()
    }

    fn supports(&self, quantity: Quantity) -> bool {
        match quantity {
            Quantity::NetworkJacobian => self.has_jacobian,
            Quantity::KktFloor => self.has_kkt,
            _ => true,
        }
    }

    fn call(&mut self, quantity: Quantity, i: usize) {
        let i = i % self.states.len();
        let (t, theta, thetadot) = &self.states[i];
        let dot = self.needs_dot.then_some(&self.qp_dots[i]);
        match quantity {
            Quantity::SchemeBuild => self.scheme.build(*t, theta, thetadot, &mut self.scratch_qp),
            Quantity::NetworkRhs => {
                self.network
                    .rhs(*t, &self.ys[i], &self.qps[i], dot, &mut self.ydot)
            }
            Quantity::NetworkJacobian => {
                self.network
                    .jacobian(*t, &self.ys[i], &self.qps[i], dot, &mut self.jac);
            }
            Quantity::ExactActiveSet => {
                let _ = self
                    .fast
                    .solve_into(&self.qps[i], Some(&self.warm[i]), &mut self.sol);
            }
            Quantity::ExactClarabel => {
                let _ = self.clarabel.solve(&self.qps[i]);
            }
            Quantity::KktFloor => {
                let _ = solve_equality_kkt(&self.equality[i]);
            }
            Quantity::RunExact => self.run(Solver::Exact, &exact_settings()),
            Quantity::RunNetwork => {
                let spec = self.network_spec.clone();
                let (dims, scheme) = (self.scheme.dims(), self.scheme.name());
                let build = move || crate::run::build_network(&spec, dims, &scheme);
                self.run(Solver::Network(&build), &network_settings());
            }
        }
    }

    fn last_run(&self) -> Option<RunCounts> {
        self.last_run
    }
}

/// Wall times (us) of `times` (at least one) calls of `run`, and the first call's result.
fn repeat_runs<R>(times: usize, mut run: impl FnMut() -> R) -> (Vec<f64>, R) {
    let mut samples = Vec::new();
    let mut first = None;
    for _ in 0..times.max(1) {
        let started = Instant::now();
        let r = run();
        samples.push(started.elapsed().as_secs_f64() * 1e6);
        first.get_or_insert(r);
    }
    (samples, first.expect("at least one call"))
}

/// Times per-call quantities (see the module docs, "How it is timed").
struct Timer<'a> {
    budget: &'a Budget,
}

impl Timer<'_> {
    /// Per-call times (us) of `op(i)` for every state i = 0..states, over the passes.
    fn samples(&self, states: usize, mut op: impl FnMut(usize)) -> Vec<f64> {
        if states == 0 {
            return Vec::new();
        }
        // Calibration: one call (and a warm-up of caches and lazily grown buffers).
        op(0);
        let started = Instant::now();
        op(0);
        let once_us = started.elapsed().as_secs_f64() * 1e6;
        let reps = ((self.budget.min_batch_us / once_us.max(1e-3)).ceil() as usize)
            .clamp(1, self.budget.max_reps.max(1));
        let mut out = Vec::with_capacity(states * self.budget.passes);
        for _ in 0..self.budget.passes.max(1) {
            for i in 0..states {
                let started = Instant::now();
                for _ in 0..reps {
                    op(std::hint::black_box(i));
                }
                out.push(started.elapsed().as_secs_f64() * 1e6 / reps as f64);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_recovers_an_exact_power_law() {
        let points: Vec<(f64, f64)> = NLINK_SIZES
            .iter()
            .map(|&n| (n as f64, 3.0 * (n as f64).powi(2)))
            .collect();
        let fit = fit_power_law(&points).unwrap();
        assert!((fit.k - 2.0).abs() < 1e-12, "{fit:?}");
        assert!((fit.c - 3.0).abs() < 1e-10, "{fit:?}");
        assert_eq!(fit.points, NLINK_SIZES.len());
    }

    #[test]
    fn the_fit_of_noisy_data_is_within_tolerance() {
        // cost = 0.5 N^1.5 with a deterministic relative noise of up to +-10 %.
        let points: Vec<(f64, f64)> = NLINK_SIZES
            .iter()
            .enumerate()
            .map(|(i, &n)| {
                let noise = 1.0 + 0.1 * ((i as f64) * 2.3).sin();
                (n as f64, 0.5 * (n as f64).powf(1.5) * noise)
            })
            .collect();
        let fit = fit_power_law(&points).unwrap();
        assert!((fit.k - 1.5).abs() < 0.1, "{fit:?}");
    }

    #[test]
    fn the_fit_needs_two_distinct_positive_points() {
        assert!(fit_power_law(&[]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (3.0, 2.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (6.0, 0.0), (f64::NAN, 1.0)]).is_none());
        let fit = fit_power_law(&[(3.0, 1.0), (6.0, 2.0), (9.0, -1.0)]).unwrap();
        assert_eq!(fit.points, 2);
        assert!((fit.k - 1.0).abs() < 1e-12);
    }

    #[test]
    fn quantiles_are_nearest_rank() {
        let s: Vec<f64> = (1..=20).map(f64::from).collect();
        assert_eq!(quantile(&s, 0.5), 10.0);
        assert_eq!(quantile(&s, 0.95), 19.0);
        assert_eq!(quantile(&[7.0], 0.95), 7.0);
        let sum = Summary::of(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!((sum.median_us, sum.p95_us, sum.samples), (2.0, 3.0, 3));
        assert!(Summary::of(&[]).is_none());
    }

    #[test]
    fn quantity_ids_round_trip() {
        for q in Quantity::ALL {
            assert_eq!(Quantity::from_id(q.id()), Some(q));
        }
        assert_eq!(Quantity::from_id("fit"), None);
    }
}
