//! The harness: one case (jia2019's VLTCO on a four-leaf clover or kong2019's ZNN scheme,
//! eq. 22, on a circle) on the registry's n-link arm `nlink-N` of any N, through the engine's
//! one path: the scheme, the exact column and whole runs are the ones the reproduction runs.
//!
//! [`prepare`] builds the case's robot, path, scheme and network, runs the exact column once
//! ([`simulate`] with [`Solver::Exact`]) and samples up to `states` instants of its trace,
//! evenly spread: every per-call quantity is timed at those states, so the costs are those of
//! a real trajectory (active sets, conditioning), not of one hand-picked point. Besides the
//! per-instant quantities of [`Instants`]:
//!
//! - `scheme-build`: [`Scheme::build`], the QP assembly (J, bounds, objective) at the state;
//! - `run-exact`, `run-network`: one whole [`simulate`] call with the experiment files'
//!   defaults (the exact column with [`default_exact_integrator`], the network with
//!   [`IntegratorSettings::default`], scored at every accepted step), wall time.
//!
//! [`SWEEP_SIZES`] are measured with both schemes, [`LARGE_SIZES`] with kong2019's alone (its
//! QP has no inequality rows, so its cost past N = 30 is the arm's and the dense LUs').

use super::case::{path_of, Case, PreparedCase, KONG2019_KP, KONG2019_MU};
use super::error::CostError;
use super::instants::Instants;
use catalog::default_exact_integrator;
use qp::{Qp, QpDims};
pub use records::dof_cost::SWEEP_SIZES;
use records::dof_cost::{Quantity, RunCounts, SchemeKind};
use robots::Robot;
use robots::{nlink_name, robot_by_name};
use schemes::build_scheme;
use schemes::paths::{build_path, Path};
use schemes::Scheme;
use settings::IntegratorSettings;
use settings::SolverSpec;
use simulation::{simulate, Outcome, Run, Settings, Solver};
use solvers::Backend;
use spec::NetworkInit;
use spec::RmpReading;
use spec::SchemeSpec;
use spec::Scoring;
use std::sync::Arc;

/// The joint counts measured with kong2019's scheme alone, past [`SWEEP_SIZES`].
pub const LARGE_SIZES: [usize; 6] = [40, 50, 70, 100, 140, 200];

/// States sampled at the large sizes (N = 40 ... 200; fewer than the sweep's: the LUs there are
/// slow).
pub const LARGE_STATES: usize = 20;

/// Prepares `case`, sampling up to `states` states of one exact run (see the module docs). An
/// error when there is no n-link arm of N joints, or the exact run does not start or leaves no
/// trace.
pub fn prepare(case: &Case, states: usize) -> Result<Box<dyn PreparedCase>, CostError> {
    let model = robot_by_name(&nlink_name(case.n)).map_err(|_| CostError::NotRegistered(case.n))?;
    Ok(Box::new(Prepared::new(
        case,
        model.robot,
        &model.stated_pose,
        states,
    )?))
}

/// A sampled state (t, theta, thetadot).
type State = (f64, Vec<f64>, Vec<f64>);

/// [`PreparedCase`] for an arm of any joint count.
struct Prepared {
    label: String,
    robot: Arc<dyn Robot>,
    path: Arc<dyn Path>,
    scheme: Box<dyn Scheme>,
    theta0: Vec<f64>,
    network_spec: SolverSpec,
    states: Vec<State>,
    instants: Instants,
    scratch_qp: Qp,
    last_run: Option<RunCounts>,
}

impl Prepared {
    fn new(
        case: &Case,
        robot: Arc<dyn Robot>,
        home: &[f64],
        states: usize,
    ) -> Result<Self, CostError> {
        let label = case.label();
        let theta0 = home.to_vec();
        let path: Arc<dyn Path> = Arc::from(
            build_path(&path_of(case.scheme), robot.position(&theta0)).map_err(|error| {
                CostError::Path {
                    label: label.clone(),
                    error,
                }
            })?,
        );
        let spec = match case.scheme {
            SchemeKind::Vltco => SchemeSpec::Vltco {
                phi: 0.2,
                tau: 0.4,
                kappa: 20.0,
                lambda: 20.0,
                rmp: RmpReading::Printed,
                mu: 5.0,
            },
            SchemeKind::ZnnRmp => SchemeSpec::ZnnRmp {
                mu: KONG2019_MU,
                k_p: KONG2019_KP,
            },
        };
        let scheme: Box<dyn Scheme> =
            build_scheme(&spec, robot.clone(), None, path.clone(), &theta0).map_err(|error| {
                CostError::Scheme {
                    label: label.clone(),
                    error,
                }
            })?;

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
        .map_err(|error| CostError::Run {
            label: label.clone(),
            error,
        })?;
        if let Outcome::Failed { t, error, .. } = &run.outcome {
            eprintln!("{label}: the exact run failed at t = {t}: {error}");
        }
        let trace = &run.trace;
        let count = states.clamp(1, trace.len().max(1));
        let states: Vec<State> = (0..count)
            .filter_map(|i| trace.get(i * trace.len() / count))
            .map(|p| (p.t, p.theta.clone(), p.thetadot.clone()))
            .collect();
        if states.is_empty() {
            return Err(CostError::NoTrace(label));
        }
        let mut qps = Vec::with_capacity(states.len());
        let mut qp_dots = Vec::with_capacity(states.len());
        let mut scratch = scheme.new_dot_scratch();
        for (t, theta, thetadot) in &states {
            let mut qp = scheme.new_qp();
            scheme.build(*t, theta, thetadot, &mut qp);
            qps.push(qp);
            let mut qp_dot = scheme.new_qp();
            let thetaddot = vec![0.0; theta.len()];
            scheme.build_dot(*t, theta, thetadot, &thetaddot, &mut qp_dot, &mut scratch);
            qp_dots.push(qp_dot);
        }
        let ts = states.iter().map(|s| s.0).collect();
        let instants = Instants::new(&label, &case.network, ts, qps, qp_dots)?;
        Ok(Prepared {
            label,
            scratch_qp: scheme.new_qp(),
            robot,
            path,
            scheme,
            theta0,
            network_spec: case.network.clone(),
            states,
            instants,
            last_run: Some(counts(&run)),
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
        self.last_run = run.ok().map(|r| counts(&r));
    }
}

/// The counts of a whole run.
fn counts(run: &Run) -> RunCounts {
    RunCounts {
        steps: run.stats.steps,
        rhs_evals: run.stats.rhs_evals,
        completed: matches!(run.outcome, Outcome::Completed(_)),
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

impl PreparedCase for Prepared {
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
            Quantity::SchemeBuild | Quantity::RunExact | Quantity::RunNetwork => true,
            _ => self.instants.supports(quantity),
        }
    }

    fn call(&mut self, quantity: Quantity, backend: Backend, i: usize) {
        match quantity {
            Quantity::SchemeBuild => {
                let (t, theta, thetadot) = &self.states[i % self.states.len()];
                self.scheme.build(*t, theta, thetadot, &mut self.scratch_qp)
            }
            Quantity::RunExact => self.run(Solver::Exact, &exact_settings()),
            Quantity::RunNetwork => {
                let spec = self.network_spec.clone();
                let (dims, scheme) = (self.scheme.dims(), self.scheme.name());
                let build = move || simulation::build_network(&spec, dims, &scheme);
                self.run(Solver::Network(&build), &network_settings());
            }
            _ => self.instants.call(quantity, backend, i),
        }
    }

    fn last_run(&self) -> Option<RunCounts> {
        self.last_run
    }
}
