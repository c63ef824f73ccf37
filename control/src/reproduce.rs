//! The control experiments end to end: every method on the standard task set at the control
//! period, the period sweep, the networks' stability limits and the many-cycles runs, written to
//! `results/` ([`records::control`]); and the efficiency claim's check runs, returned as
//! measurements for crate `analysis` to judge (this crate decides no claim).
//!
//! Every run of a row of `results/control.csv` and of `results/cycles-trend.csv` runs twice: as
//! computed, and as the rounding-noise probe ([`Rounding::OneUlp`], module `rounding`), whose
//! outcome gives the row's noise floor (`results/control-noise.csv`, module `noise_floor`; the
//! trend's `class_under_noise` and `rate_noise`). The probes double those runs' cost.
//!
//! Cost on 2 cores of a 2020s server CPU at the standard task set's budget
//! (`experiments/control/tasks.toml`): see the report's section
//! "At a robot's control rate" (about two minutes of CPU, a minute with the runs in parallel
//! on both cores, half of it the rounding-noise probes; most of it robio2018's methods
//! iterating to 1e-10 at every tick of the runs at 1 ms, and the 20-cycle runs).

use crate::continuous::{ContinuousCycles, ExactCycles};
use crate::control_loop::{run_loop, LoopOutcome, LoopSettings, Observer, Status};
use crate::error::ControlError;
use crate::latency::Latency;
use crate::method::{Method, Numerical};
use crate::network_tick::{products_per_evaluation, Discretisation};
use crate::noise_floor::{noise_row, relative_change};
use crate::rounding::Rounding;
use crate::stability::{gain, LimitProbe};
use crate::task::{load_tasks, with_task, Task, TaskArm};
use crate::tick::TickSolver;
use crate::trend::classify;
use records::control::{steps_needed, ClaimCheck};
use records::control::{ControlRow, ControlStatus, CycleRow, NoiseRow, StabilityRow, TrendRow};
use settings::projection::ProjectionErrorForm;
use settings::SolverSpec;
use simulation::map_costliest_first;
use solvers::neural::build_solver;
use solvers::HotActiveSet;
use spec::ids::SolverId;
use spec::RunSpec;
use spec::{Budget, TaskSet};
use store::results_dir;

/// The method label of the continuous-time exact column in the many-cycles results.
pub const CONTINUOUS_EXACT: &str = "exact (continuous)";

/// What the reproduction ran: its row counts, and the efficiency claim's check runs, which
/// crate `analysis` judges (`analysis::control_claim::judge`) into `results/control-claim.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    pub control_runs: usize,
    pub cycle_runs: usize,
    /// The claim's measurements, one per task and network checked.
    pub claim_checks: Vec<ClaimCheck>,
}

/// Whether a network is a zeroing network (its Taylor-type discrete form is defined): every
/// network but the projection family's LVI form, whose F does not come from a design formula.
fn is_zeroing(spec: &SolverSpec) -> bool {
    !spec
        .projection()
        .is_some_and(|p| matches!(p.error, ProjectionErrorForm::Lvi { .. }))
}

/// The network forms run on a task: Euler for every network, Taylor for the zeroing ones.
fn network_methods(task: &Task, substeps: u32) -> Vec<Method> {
    let mut out = Vec::new();
    for spec in &task.networks {
        out.push(Method::Network {
            spec: spec.clone(),
            form: Discretisation::Euler,
            substeps,
        });
        if is_zeroing(spec) {
            out.push(Method::Network {
                spec: spec.clone(),
                form: Discretisation::Taylor,
                substeps,
            });
        }
    }
    out
}

/// Runs one method on a task's arm ([`RunMethod::run_on`]).
struct RunMethod<'a> {
    method: &'a Method,
    h: f64,
    cycles: usize,
    max_ticks: Option<usize>,
    rounding: Rounding,
}

impl RunMethod<'_> {
    fn run_on(self, arm: &TaskArm<'_>) -> Result<LoopOutcome, ControlError> {
        let TaskArm {
            robot,
            path,
            scheme,
            theta0,
            period,
        } = *arm;
        let mut solver = self.method.build(scheme.dims())?;
        let settings = LoopSettings {
            h: self.h,
            period,
            cycles: self.cycles,
            max_ticks: self.max_ticks,
            rounding: self.rounding,
        };
        Ok(run_loop(
            robot,
            path,
            scheme,
            solver.as_mut(),
            theta0,
            &settings,
            None,
        ))
    }
}

/// A network's Euler limit on a task ([`ProbeLimit::run_on`] runs the exact optimum in the loop
/// with a [`LimitProbe`]): (limit, instant), or `None`.
struct ProbeLimit<'a> {
    spec: &'a SolverSpec,
    h: f64,
}

impl ProbeLimit<'_> {
    fn run_on(self, arm: &TaskArm<'_>) -> Result<Option<(f64, f64)>, ControlError> {
        let TaskArm {
            robot,
            path,
            scheme,
            theta0,
            period,
        } = *arm;
        let dims = scheme.dims();
        let net = build_solver(self.spec, dims).map_err(|error| ControlError::Network {
            task: self.spec.display_name(),
            error,
        })?;
        let dim = net.state_dim(dims);
        let mut probe = LimitProbe::new(net, dim);
        let mut solver = HotActiveSet::new(dims);
        let settings = LoopSettings {
            h: self.h,
            period,
            cycles: 1,
            max_ticks: None,
            rounding: Rounding::AsComputed,
        };
        run_loop(
            robot,
            path,
            scheme,
            &mut solver as &mut dyn TickSolver,
            theta0,
            &settings,
            Some(&mut probe as &mut dyn Observer),
        );
        Ok(probe.limit)
    }
}

/// The row of one run.
fn control_row(task: &Task, method: &Method, h: f64, mut out: LoopOutcome) -> ControlRow {
    let solve = Latency::of(&mut out.solve_us);
    let tick = Latency::of(&mut out.tick_us);
    let stopped_at = match out.status {
        Status::Completed => None,
        Status::Diverged { t } | Status::Failed { t, .. } => Some(t),
    };
    ControlRow {
        task: task.id(),
        paper: task.paper().to_string(),
        scheme: task.scheme(),
        method: method.label(),
        family: method.family(),
        h_ms: h * 1e3,
        substeps: match method {
            Method::Network { substeps, .. } => *substeps,
            Method::Numerical(_) => 1,
        },
        status: out.status.column(),
        stopped_at,
        ticks: out.ticks,
        solve_p50_us: solve.p50_us,
        solve_p99_us: solve.p99_us,
        solve_max_us: solve.max_us,
        tick_p50_us: tick.p50_us,
        tick_p99_us: tick.p99_us,
        tick_max_us: tick.max_us,
        max_track_err: out.max_track_err,
        rms_track_err: out.rms_track_err,
        max_dx: out.max_dx,
        rms_dx: out.rms_dx,
        max_dx_settled: out.max_dx_settled,
        drift: out.drift.first().copied(),
        products_mean: out.products_mean,
        products_max: out.products_max,
        iterations_mean: out.iterations_mean,
        iterations_max: out.iterations_max,
    }
}

/// One controller run of the reproduction: `method` on `task` at the period `h` over `cycles`
/// cycles, stopped after `max_ticks` ticks when given, with the state as computed or moved by
/// one ulp after every tick (`rounding`).
#[derive(Clone, Debug)]
struct LoopRun<'a> {
    task: &'a Task,
    method: Method,
    h: f64,
    cycles: usize,
    max_ticks: Option<usize>,
    rounding: Rounding,
}

impl<'a> LoopRun<'a> {
    /// A run over whole cycles, as computed.
    fn cycles(task: &'a Task, method: Method, h: f64, cycles: usize) -> Self {
        LoopRun {
            task,
            method,
            h,
            cycles,
            max_ticks: None,
            rounding: Rounding::AsComputed,
        }
    }

    /// The same run as the rounding-noise probe.
    fn probe(&self) -> Self {
        LoopRun {
            rounding: Rounding::OneUlp,
            ..self.clone()
        }
    }

    fn run(&self) -> Result<LoopOutcome, ControlError> {
        let method = RunMethod {
            method: &self.method,
            h: self.h,
            cycles: self.cycles,
            max_ticks: self.max_ticks,
            rounding: self.rounding,
        };
        with_task(self.task, self.cycles, |arm| method.run_on(arm))?
    }

    /// The run's relative cost, to start the longest runs first (scheduling only): its ticks
    /// (at most) times the work of a tick, in network steps: a network's steps per tick; for
    /// a numerical method weights read off the latencies of `results/control.csv` (the PLPE
    /// methods iterate to 1e-10, tens of network steps; Clarabel, OSQP or an outside solver about ten; the
    /// hot-started active set one).
    fn cost(&self) -> f64 {
        let ticks = self.task.job.path.duration * self.cycles as f64 / self.h;
        let ticks = self.max_ticks.map_or(ticks, |m| ticks.min(m as f64));
        ticks
            * match self.method {
                Method::Network { substeps, .. } => f64::from(substeps),
                Method::Numerical(n) if n.is_plpe() => 30.0,
                Method::Numerical(n) if n == Numerical::active_set() => 1.0,
                Method::Numerical(_) => 10.0,
            }
    }
}

/// A check run of the efficiency claim: `spec`'s Euler form on the run's task at h with
/// [`Budget::check_steps_factor`] times the steps per tick its stability limit needs, over the
/// first [`Budget::check_ticks`] ticks, and the numerical method it is compared with.
struct ClaimRun<'a> {
    spec: &'a SolverSpec,
    /// Products with the LVI matrix per evaluation of the network.
    per_step: u64,
    /// The network's Euler limit on the task (s).
    limit: f64,
    /// Euler steps per tick the limit needs.
    needed: u64,
    /// Euler steps per tick of the check run.
    check_steps: u64,
    /// The numerical method's row at h and its mean products per tick.
    numerical: (&'a ControlRow, f64),
    run: LoopRun<'a>,
}

impl<'a> ClaimRun<'a> {
    fn new(
        task: &'a Task,
        spec: &'a SolverSpec,
        per_step: u64,
        limit: f64,
        numerical: (&'a ControlRow, f64),
        budget: &Budget,
    ) -> Self {
        let needed = steps_needed(budget.h, limit);
        let check_steps = budget.check_steps_factor.saturating_mul(needed);
        let method = Method::Network {
            spec: spec.clone(),
            form: Discretisation::Euler,
            substeps: u32::try_from(check_steps).unwrap_or(u32::MAX),
        };
        ClaimRun {
            spec,
            per_step,
            limit,
            needed,
            check_steps,
            numerical,
            run: LoopRun {
                max_ticks: Some(budget.check_ticks),
                ..LoopRun::cycles(task, method, budget.h, 1)
            },
        }
    }

    /// The claim's measurements on the check run's task, from the check run's outcome `out`.
    fn measured(&self, mut out: LoopOutcome) -> Result<ClaimCheck, ControlError> {
        let check_solve = Latency::of(&mut out.solve_us);
        let task = self.run.task;
        let (num, num_mean) = self.numerical;
        Ok(ClaimCheck {
            task: task.id(),
            network: self.spec.display_name(),
            experiment: task.reference.experiment.clone(),
            variant_id: task.reference.variant.clone(),
            solver_id: SolverId::new(self.spec.id())?,
            h_ms: self.run.h * 1e3,
            products_per_step: self.per_step,
            euler_limit_s: self.limit,
            steps_needed: self.needed,
            check_steps: self.check_steps,
            check_ticks: out.ticks,
            check_status: out.status.column(),
            check_max_dx: out.max_dx,
            check_solve_p50_us: check_solve.p50_us,
            numerical: num.method.clone(),
            numerical_products_mean: num_mean,
            numerical_products_max: num.products_max.unwrap_or(0),
            numerical_max_dx: num.max_dx,
            numerical_solve_p50_us: num.solve_p50_us,
        })
    }
}

/// Runs everything (module docs) on the task set `set` (its tasks resolved among `jobs`, every
/// run of the experiment files, at its budget) and writes the result files but the
/// claim's into `results`; `progress` is told what runs. The claim's check runs are returned
/// in the [`Summary`].
///
/// The runs are independent of one another but for what selects them, so they run in parallel
/// (rayon's pool) in two rounds: first every run that needs no other's result (each method at
/// h, the period sweep, the stability probes, the exact optimum's many cycles at h and in
/// continuous time), then those selected by the first round's results (the claim's check runs,
/// on the networks' stability limits; the many cycles of the network forms stable at h). The
/// rows are assembled in the order of the tasks, methods and periods, as a sequential pass
/// would write them.
pub fn reproduce(
    set: &TaskSet,
    jobs: &[RunSpec],
    results: &std::path::Path,
    mut progress: impl FnMut(&str),
) -> Result<Summary, ControlError> {
    let tasks = load_tasks(jobs, &set.tasks)?;
    let budget = &set.budget;
    let h = budget.h;

    // Round 1, then the rows it gives.
    let first = FirstRound::plan(&tasks, budget);
    progress(&first.describe());
    let first_out = first.run();
    let (control, noise) = control_rows(&first.loops[..first.rows], first_out.rows)?;
    let stability = stability_rows(&first.probes, first_out.limits, &control)?;

    // Round 2, selected by those rows, then the rows of both rounds' many cycles.
    let second = SecondRound::plan(&tasks, budget, &control, &stability);
    progress(&second.describe(budget));
    let second_out = second.run();
    let claim_checks = second
        .checks
        .iter()
        .zip(second_out.checks)
        .map(|(check, out)| check.measured(out?))
        .collect::<Result<Vec<ClaimCheck>, ControlError>>()?;
    let cycles = CycleTables::of(
        &tasks,
        h,
        first_out.exact_cycles,
        first_out.continuous,
        &second.network_cycles,
        second_out.network_cycles,
    )?;

    let control: Vec<ControlRow> = control.into_iter().map(|(_, r)| r).collect();
    store::control::write(results, results_dir::CONTROL, &control)?;
    store::control::write(results, results_dir::CONTROL_NOISE, &noise)?;
    store::control::write(results, results_dir::CONTROL_STABILITY, &stability)?;
    store::control::write(results, results_dir::CYCLES, &cycles.cycles)?;
    store::control::write(results, results_dir::CYCLES_TREND, &cycles.trends)?;
    Ok(Summary {
        control_runs: control.len(),
        cycle_runs: cycles.trends.len(),
        claim_checks,
    })
}

/// What a run and its rounding-noise probe returned.
struct Probed<T> {
    /// The run as computed.
    computed: Result<T, ControlError>,
    /// The same run with its state moved by one ulp ([`Rounding::OneUlp`]).
    probe: Result<T, ControlError>,
}

/// The outcomes of runs (`outs`: the runs as computed, then their probes in the same order)
/// paired with their probes'.
fn probed<T>(mut outs: Vec<Result<T, ControlError>>) -> Vec<Probed<T>> {
    let probes = outs.split_off(outs.len() / 2);
    outs.into_iter()
        .zip(probes)
        .map(|(computed, probe)| Probed { computed, probe })
        .collect()
}

/// The first round of [`reproduce`]: every run that needs no other's result.
struct FirstRound<'a> {
    tasks: &'a [Task],
    budget: &'a Budget,
    /// The controller runs: first those of the rows of results/control.csv (per task, every
    /// method at h, then the period sweep), then the exact optimum's many cycles at h (the
    /// active set), per task; each as computed, then all of them again as their rounding-noise
    /// probes, in the same order.
    loops: Vec<LoopRun<'a>>,
    /// How many of `loops` are rows of results/control.csv (as computed).
    rows: usize,
    /// Each network on its task, for its Euler limit.
    probes: Vec<(&'a Task, &'a SolverSpec)>,
}

/// What the first round's runs returned, in the order of its runs, each with its probe's.
struct FirstRoundOut {
    /// The runs of the rows of results/control.csv.
    rows: Vec<Probed<LoopOutcome>>,
    /// The exact optimum's many cycles at h, per task.
    exact_cycles: Vec<Probed<LoopOutcome>>,
    /// Each probe's Euler limit: (limit, instant), or `None`.
    limits: Vec<Result<Option<(f64, f64)>, ControlError>>,
    /// The exact column's many cycles in continuous time, per task.
    continuous: Vec<Probed<ContinuousCycles>>,
}

impl<'a> FirstRound<'a> {
    /// The round's runs on `tasks` at `budget`.
    fn plan(tasks: &'a [Task], budget: &'a Budget) -> Self {
        let h = budget.h;
        let mut loops: Vec<LoopRun> = Vec::new();
        for task in tasks {
            let mut methods: Vec<Method> = Numerical::all()
                .into_iter()
                .map(Method::Numerical)
                .collect();
            methods.extend(network_methods(task, 1));
            loops.extend(
                methods
                    .into_iter()
                    .map(|method| LoopRun::cycles(task, method, h, 1)),
            );
            let mut swept = network_methods(task, 1);
            swept.push(Method::Numerical(Numerical::active_set()));
            for &hs in &budget.sweep {
                loops.extend(
                    swept
                        .iter()
                        .map(|method| LoopRun::cycles(task, method.clone(), hs, 1)),
                );
            }
        }
        let rows = loops.len();
        loops.extend(tasks.iter().map(|task| {
            LoopRun::cycles(
                task,
                Method::Numerical(Numerical::active_set()),
                h,
                budget.cycles,
            )
        }));
        let noisy: Vec<LoopRun> = loops.iter().map(LoopRun::probe).collect();
        loops.extend(noisy);
        let probes = tasks
            .iter()
            .flat_map(|task| task.networks.iter().map(move |spec| (task, spec)))
            .collect();
        FirstRound {
            tasks,
            budget,
            loops,
            rows,
            probes,
        }
    }

    /// What the round runs, in a line.
    fn describe(&self) -> String {
        format!(
            "control: {} runs on {} tasks at {} ms and over the period sweep, {} stability \
             probes, the exact optimum over {} cycles",
            self.rows,
            self.tasks.len(),
            self.budget.h * 1e3,
            self.probes.len(),
            self.budget.cycles
        )
    }

    /// Runs the round in parallel: the controller runs beside the stability probes and the
    /// continuous-time cycles (as computed, then their rounding-noise probes).
    fn run(&self) -> FirstRoundOut {
        let h = self.budget.h;
        let continuous_runs: Vec<(&Task, Rounding)> = [Rounding::AsComputed, Rounding::OneUlp]
            .into_iter()
            .flat_map(|rounding| self.tasks.iter().map(move |task| (task, rounding)))
            .collect();
        let (loops, (limits, continuous)) = rayon::join(
            || map_costliest_first(&self.loops, LoopRun::cost, LoopRun::run),
            || {
                rayon::join(
                    || {
                        map_costliest_first(
                            &self.probes,
                            |(task, _)| task.job.path.duration,
                            |(task, spec)| {
                                with_task(task, 1, |arm| ProbeLimit { spec, h }.run_on(arm))?
                            },
                        )
                    },
                    || {
                        map_costliest_first(
                            &continuous_runs,
                            |(task, _)| task.job.path.duration,
                            |&(task, rounding)| {
                                let cycles = ExactCycles {
                                    task,
                                    cycles: self.budget.cycles,
                                    rounding,
                                };
                                with_task(task, 1, |arm| cycles.run_on(arm))
                            },
                        )
                    },
                )
            },
        );
        let mut rows = probed(loops);
        let exact_cycles = rows.split_off(self.rows);
        FirstRoundOut {
            rows,
            exact_cycles,
            limits,
            continuous: probed(continuous),
        }
    }
}

/// Controller runs' rows, each beside its method.
type MethodRows = Vec<(Method, ControlRow)>;

/// Each controller run's row beside its method (`runs` and their outcomes `outs`, in order):
/// later passes select runs by method (an identity), never by the row's label; and each row's
/// noise floor, from its probe's outcome (module `noise_floor`).
fn control_rows(
    runs: &[LoopRun],
    outs: Vec<Probed<LoopOutcome>>,
) -> Result<(MethodRows, Vec<NoiseRow>), ControlError> {
    let mut control = Vec::with_capacity(runs.len());
    let mut noise = Vec::with_capacity(runs.len());
    for (run, out) in runs.iter().zip(outs) {
        let row = control_row(run.task, &run.method, run.h, out.computed?);
        let probe = control_row(run.task, &run.method, run.h, out.probe?);
        noise.push(noise_row(&row, &probe));
        control.push((run.method.clone(), row));
    }
    Ok((control, noise))
}

/// Each probed network's row (`probes` and their Euler `limits`, in order): its limit beside its
/// gain and the largest period of the sweep at which its Euler form completed (among the
/// `control` rows).
fn stability_rows(
    probes: &[(&Task, &SolverSpec)],
    limits: Vec<Result<Option<(f64, f64)>, ControlError>>,
    control: &[(Method, ControlRow)],
) -> Result<Vec<StabilityRow>, ControlError> {
    let mut stability = Vec::with_capacity(probes.len());
    for ((task, spec), limit) in probes.iter().zip(limits) {
        let limit = limit?;
        let (gain_name, g) = gain(spec);
        let euler = Method::Network {
            spec: (*spec).clone(),
            form: Discretisation::Euler,
            substeps: 1,
        };
        let largest = control
            .iter()
            .filter(|(m, r)| r.task == task.id() && *m == euler && r.status == ControlStatus::Ok)
            .map(|(_, r)| r.h_ms)
            .reduce(f64::max);
        stability.push(StabilityRow {
            task: task.id(),
            network: spec.display_name(),
            solver_id: SolverId::new(spec.id())?,
            gain_name: gain_name.to_string(),
            gain: g,
            euler_limit_s: limit.map(|l| l.0),
            limit_at_s: limit.map(|l| l.1),
            gain_x_limit: limit.map(|l| l.0 * g),
            largest_stable_h_ms: largest,
        });
    }
    Ok(stability)
}

/// The second round of [`reproduce`]: the runs selected by the first round's results.
struct SecondRound<'a> {
    /// The efficiency claim's check runs.
    checks: Vec<ClaimRun<'a>>,
    /// Per task, the many cycles of every network form that was stable at h.
    network_cycles: Vec<Vec<LoopRun<'a>>>,
}

impl<'a> SecondRound<'a> {
    /// The round's runs on `tasks` at `budget`, selected by the first round's `control` and
    /// `stability` rows.
    fn plan(
        tasks: &'a [Task],
        budget: &Budget,
        control: &'a [(Method, ControlRow)],
        stability: &[StabilityRow],
    ) -> Self {
        let h = budget.h;
        let checks = claim_checks(tasks, control, stability, budget);
        let network_cycles = tasks
            .iter()
            .map(|task| {
                network_methods(task, 1)
                    .into_iter()
                    .filter(|m| stable_at(control, task, m, h))
                    .map(|m| LoopRun::cycles(task, m, h, budget.cycles))
                    .collect()
            })
            .collect();
        SecondRound {
            checks,
            network_cycles,
        }
    }

    /// What the round runs, in a line.
    fn describe(&self, budget: &Budget) -> String {
        format!(
            "control: {} claim check runs, {} network runs over {} cycles",
            self.checks.len(),
            self.network_cycles.iter().map(Vec::len).sum::<usize>(),
            budget.cycles
        )
    }

    /// Runs the round in parallel: the check runs beside the many cycles (as computed, then
    /// their rounding-noise probes).
    fn run(&self) -> SecondRoundOut {
        let computed = self.network_cycles.iter().flatten();
        let noisy: Vec<LoopRun> = computed.clone().map(LoopRun::probe).collect();
        let flat_cycle_runs: Vec<&LoopRun> = computed.chain(&noisy).collect();
        let (checks, network_cycles) = rayon::join(
            || map_costliest_first(&self.checks, |c| c.run.cost(), |c| c.run.run()),
            || map_costliest_first(&flat_cycle_runs, |r| r.cost(), |r| r.run()),
        );
        SecondRoundOut {
            checks,
            network_cycles: probed(network_cycles),
        }
    }
}

/// What the second round's runs returned, in the order of its runs.
struct SecondRoundOut {
    /// The claim's check runs.
    checks: Vec<Result<LoopOutcome, ControlError>>,
    /// The networks' many cycles, task by task, each with its probe's.
    network_cycles: Vec<Probed<LoopOutcome>>,
}

/// The efficiency claim's check runs, on the tasks run by a network built on the LVI whose
/// Euler limit was found (among the `stability` rows), each with its comparator among the
/// `control` rows at the budget's period.
fn claim_checks<'a>(
    tasks: &'a [Task],
    control: &'a [(Method, ControlRow)],
    stability: &[StabilityRow],
    budget: &Budget,
) -> Vec<ClaimRun<'a>> {
    let h = budget.h;
    let mut checks = Vec::new();
    for task in tasks {
        for spec in &task.networks {
            let Some(per_step) = products_per_evaluation(spec) else {
                continue;
            };
            let Some(limit) = stability
                .iter()
                .find(|s| s.task == task.id() && s.solver_id == spec.id())
                .and_then(|s| s.euler_limit_s)
            else {
                continue;
            };
            // Without a comparator the claim has nothing to compare with on this task.
            let Some(numerical) = comparator(control, task, h) else {
                continue;
            };
            checks.push(ClaimRun::new(
                task, spec, per_step, limit, numerical, budget,
            ));
        }
    }
    checks
}

/// The claim's comparator on `task`: the cheapest LVI method that solved the task at every tick
/// at `h` (`analysis::control_claim`: E47 and 94LVI as printed fail on some tasks), its row
/// among `control` and its mean products per tick.
fn comparator<'a>(
    control: &'a [(Method, ControlRow)],
    task: &Task,
    h: f64,
) -> Option<(&'a ControlRow, f64)> {
    control
        .iter()
        .filter(|(m, r)| {
            matches!(m, Method::Numerical(n) if n.is_plpe())
                && r.task == task.id()
                && r.h_ms == h * 1e3
                && r.status == ControlStatus::Ok
        })
        .filter_map(|(_, r)| r.products_mean.map(|p| (r, p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The many-cycles rows: per cycle (results/cycles.csv) and per run, its trend
/// (results/cycles-trend.csv) and its probe's.
struct CycleTables {
    cycles: Vec<CycleRow>,
    trends: Vec<TrendRow>,
}

impl CycleTables {
    /// The rows per task: the exact optimum at `h` (the first round's `exact_cycles`, per
    /// task), every network form stable at `h` (the second round's `runs` per task, their
    /// outcomes `outs` in order), the exact column in continuous time (`continuous`, per task);
    /// each run's trend beside its probe's.
    fn of(
        tasks: &[Task],
        h: f64,
        exact_cycles: Vec<Probed<LoopOutcome>>,
        continuous: Vec<Probed<ContinuousCycles>>,
        runs: &[Vec<LoopRun>],
        outs: Vec<Probed<LoopOutcome>>,
    ) -> Result<Self, ControlError> {
        let mut tables = CycleTables {
            cycles: Vec::new(),
            trends: Vec::new(),
        };
        let mut network_cycles = outs.into_iter();
        for (((task, exact_at_h), continuous), runs) in
            tasks.iter().zip(exact_cycles).zip(continuous).zip(runs)
        {
            let mut at_h = vec![(
                Method::Numerical(Numerical::active_set()).label(),
                exact_at_h,
            )];
            for (run, out) in runs.iter().zip(network_cycles.by_ref()) {
                at_h.push((run.method.label(), out));
            }
            for (label, out) in at_h {
                let (out, probe) = (out.computed?, out.probe?);
                tables.record(
                    task,
                    label,
                    Some(h * 1e3),
                    (out.status.column(), out.status.failure()),
                    (&out.drift, &out.cycle_change),
                    (&probe.drift, &probe.cycle_change),
                );
            }
            let (continuous, probe) = (continuous.computed?, continuous.probe?);
            tables.record(
                task,
                CONTINUOUS_EXACT.to_string(),
                None,
                continuous.end(),
                (&continuous.drift, &continuous.change),
                (&probe.drift, &probe.change),
            );
        }
        Ok(tables)
    }

    /// The rows of one many-cycles run of `method` on `task` (at the period `h_ms`, none in
    /// continuous time) that ended with `end` (status, failure): its (drift, change) after each
    /// cycle and their trend, beside the trend of its rounding-noise probe's `(drift, change)`.
    fn record(
        &mut self,
        task: &Task,
        method: String,
        h_ms: Option<f64>,
        end: (ControlStatus, Option<String>),
        (drift, change): (&[f64], &[f64]),
        probe: (&[f64], &[f64]),
    ) {
        for (c, (d, ch)) in drift.iter().zip(change).enumerate() {
            self.cycles.push(CycleRow {
                task: task.id(),
                scheme: task.scheme(),
                method: method.clone(),
                h_ms,
                cycle: c + 1,
                drift: *d,
                change: *ch,
            });
        }
        let trend = classify(drift, change);
        let probe = classify(probe.0, probe.1);
        self.trends.push(TrendRow {
            task: task.id(),
            scheme: task.scheme(),
            method,
            h_ms,
            status: end.0,
            failure: end.1,
            cycles: drift.len(),
            drift_first: drift.first().copied(),
            drift_last: drift.last().copied(),
            rate: trend.map(|t| t.rate),
            class: trend.map(|t| t.class),
            class_under_noise: probe.map(|t| t.class),
            rate_noise: relative_change(trend.map(|t| t.rate), probe.map(|t| t.rate)),
        });
    }
}

/// Whether `method`'s run on `task` at the period `h` among the `control` rows completed.
fn stable_at(control: &[(Method, ControlRow)], task: &Task, method: &Method, h: f64) -> bool {
    control.iter().any(|(m, r)| {
        r.task == task.id() && m == method && r.h_ms == h * 1e3 && r.status == ControlStatus::Ok
    })
}
