//! The dynamic-size path: arms of hundreds of joints (N = [`SIZES`]) with no compile-time
//! instantiation per size. The arm is [`NLinkDyn`] (the n-link kinematics on slices, the same
//! implementation as `NLink<N>`), and the scheme is kong2019's ZNN scheme (kong2019 (22),
//! mu = 1, k_p = 1: P = I, q = mu (theta - theta*0), A = J, b = rdot* + k_p (r* - f(theta)))
//! written for any N ([`NLinkZnn`], a [`SliceScheme`]).
//!
//! Measured: `scheme-build`, the per-instant quantities of [`Instants`] (network RHS, Jacobian
//! and its LU, the exact solvers, the KKT floor on both backends), and whole runs:
//!
//! - `run-exact`: the arm with the exact optimum in the loop, integrated by
//!   [`simulation::coupled::ExactLoop`] with the experiment files' exact integrator, the
//!   optimum solved again at every accepted step (what `simulate` does to observe it);
//! - `run-network`: the arm with LVI-PDNN, integrated by [`simulation::coupled::NeuralLoop`]
//!   with the network's integrator (BDF, as ode15s), scored against the exact optimum and the
//!   network's own error read at every accepted step.
//!
//! These are the coupled ODE, integrator and per-step solves that `simulation::simulate` runs
//! on the fixed path, through the same code; what `simulate` does besides (the metrics' O(N)
//! bookkeeping and the thinned trace) is left out, as it is written on const-generic vectors.
//! At a joint count both paths have, the two runs take the same accepted steps and RHS
//! evaluations (tested), so the whole-run curve continues past N = 30 on the same runs.
//!
//! jia2019 is not on this path: its VLTCO QP (bounds from the joint limits, the max-norm rows)
//! is assembled by the const-generic scheme only; writing it again for dynamic sizes would
//! duplicate it.
//!
//! The per-instant states are not from an exact run: state s of [`STATES`] is t_s = s T / S
//! on the circle, theta = home + 0.05 sin(k + 1 + s) rad per joint k, near the start where
//! the runs also begin. The exact optimum (for the network states) is the active-set
//! solution, as on the fixed path.

use crate::case::{path_of, Case, PreparedCase, KONG2019_KP, KONG2019_MU};
use crate::error::CostError;
use crate::fixed::{exact_settings, network_settings};
use crate::instants::Instants;
use records::dof_cost::{Quantity, RunCounts, SchemeKind};
use robots::NLinkDyn;
use schemes::paths::build_path;
use schemes::qp::{Qp, QpDims};
use schemes::slice_scheme::SliceScheme;
use schemes::velocity_rmp_dyn::NLinkZnn;
use settings::solver_spec::SolverSpec;
use simulation::coupled::{ExactLoop, NeuralLoop};
use solvers::ode::{integrate, Control, OdeFailure, OdeStats, OdeSystem};
use solvers::Backend;
use std::sync::Arc;

/// The joint counts of the dynamic path (above the registry's largest, 30).
pub const SIZES: [usize; 6] = [40, 50, 70, 100, 140, 200];

/// States per case (fewer than the fixed path's: each holds an N x N network Jacobian).
pub const STATES: usize = 20;

/// Prepares `case` (kong2019, any N >= 3) on the dynamic-size path with up to `states` states.
pub fn prepare(case: &Case, states: usize) -> Result<Box<dyn PreparedCase>, CostError> {
    Ok(Box::new(Dynamic::new(case, states)?))
}

/// [`PreparedCase`] of the dynamic path.
struct Dynamic {
    label: String,
    network: SolverSpec,
    scheme: NLinkZnn,
    home: Vec<f64>,
    duration: f64,
    /// (t, theta) of the per-instant states.
    states: Vec<(f64, Vec<f64>)>,
    instants: Instants,
    scratch_qp: Qp,
    last_run: Option<RunCounts>,
}

impl Dynamic {
    fn new(case: &Case, states: usize) -> Result<Self, CostError> {
        if case.scheme != SchemeKind::ZnnRmp {
            return Err(CostError::NoDynamicScheme(case.scheme.id()));
        }
        let label = case.label();
        let arm = NLinkDyn::new(case.n).ok_or(CostError::TooFewJoints(case.n))?;
        let n = arm.joints();
        let home = arm.home();
        let path = build_path(&path_of(case.scheme), arm.position(&home)).map_err(|error| {
            CostError::Path {
                label: label.clone(),
                error,
            }
        })?;
        let path: Arc<dyn schemes::paths::Path> = Arc::from(path);
        let duration = path.duration();
        let scheme = NLinkZnn::new(arm, path, home.as_slice(), KONG2019_MU, KONG2019_KP)
            .ok_or(CostError::TooFewJoints(n))?;
        let count = states.max(1);
        let zeros = vec![0.0; n];
        let mut scratch = scheme.new_dot_scratch();
        let mut ts = Vec::with_capacity(count);
        let mut qps = Vec::with_capacity(count);
        let mut qp_dots = Vec::with_capacity(count);
        let mut sampled = Vec::with_capacity(count);
        for s in 0..count {
            let t = s as f64 * duration / count as f64;
            let theta: Vec<f64> = (0..n)
                .map(|k| home[k] + 0.05 * ((k + 1 + s) as f64).sin())
                .collect();
            let mut qp = scheme.new_qp();
            scheme.build(t, &theta, &zeros, &mut qp);
            let mut qp_dot = scheme.new_qp();
            scheme.build_dot(t, &theta, &zeros, &zeros, &mut qp_dot, &mut scratch);
            ts.push(t);
            qps.push(qp);
            qp_dots.push(qp_dot);
            sampled.push((t, theta));
        }
        let instants = Instants::new(&label, &case.network, ts, qps, qp_dots)?;
        Ok(Dynamic {
            label,
            network: case.network.clone(),
            scratch_qp: scheme.new_qp(),
            scheme,
            home: home.as_slice().to_vec(),
            duration,
            states: sampled,
            instants,
            last_run: None,
        })
    }

    /// One whole exact run (module docs).
    fn run_exact(&self) -> RunCounts {
        let n = self.scheme.joints();
        let mut sys = ExactLoop::new(&self.scheme);
        let mut probe = ExactLoop::new(&self.scheme);
        let zeros = vec![0.0; n];
        let result = integrate(
            &mut sys,
            &self.home,
            0.0,
            self.duration,
            &exact_settings().integrator,
            |t, y| match probe.optimum(t, &y[..n], &zeros) {
                Ok(_) => Control::Continue,
                Err(e) => Control::Stop(format!("exact QP at t = {t:.6}: {e}")),
            },
        );
        counts(result, 0, sys.failure.is_none())
    }

    /// One whole network run (module docs); `None` when the network cannot be built.
    fn run_network(&self) -> Option<RunCounts> {
        let n = self.scheme.joints();
        let dims = self.scheme.dims();
        let name = self.scheme.name();
        let network = simulation::run::build_network(&self.network, dims, &name).ok()?;
        let mut probe = simulation::run::build_network(&self.network, dims, &name).ok()?;
        let mut sys = NeuralLoop::new(&self.scheme, network);
        let k = sys.net_offset();
        let mut y0 = vec![0.0; sys.dim()];
        y0[..n].copy_from_slice(&self.home);
        let mut scorer = ExactLoop::new(&self.scheme);
        let result = integrate(
            &mut sys,
            &y0,
            0.0,
            self.duration,
            &network_settings().integrator,
            |t, y| {
                // What `simulate` computes to score the step: |x - x*|_inf and the network's
                // own error (their values are not kept here; black_box keeps the work).
                let command = &y[k..k + n];
                if let Ok(x_star) = scorer.optimum(t, &y[..n], command) {
                    let dx = command
                        .iter()
                        .zip(x_star.iter())
                        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
                    std::hint::black_box(dx);
                }
                std::hint::black_box(probe.error_norm(&scorer.qp, &y[k..]));
                Control::Continue
            },
        );
        Some(counts(result, sys.jacobian_rhs_evals, true))
    }
}

/// The counts of a whole run: accepted steps, RHS evaluations (with `extra_rhs`, those spent in
/// finite-difference Jacobian columns) and whether it completed.
fn counts(
    result: Result<(Vec<f64>, OdeStats), OdeFailure>,
    extra_rhs: usize,
    solved: bool,
) -> RunCounts {
    let (stats, completed) = match result {
        Ok((_, stats)) => (stats, solved),
        Err(failure) => (failure.stats, false),
    };
    RunCounts {
        steps: stats.steps,
        rhs_evals: stats.rhs_evals + extra_rhs,
        completed,
    }
}

impl PreparedCase for Dynamic {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn scheme_name(&self) -> String {
        self.scheme.name()
    }

    fn network_name(&self) -> String {
        self.network.display_name()
    }

    fn dims(&self) -> QpDims {
        self.instants.dims()
    }

    fn states(&self) -> usize {
        self.instants.len()
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
                let (t, theta) = &self.states[i % self.states.len()];
                self.scheme.build(*t, theta, theta, &mut self.scratch_qp)
            }
            Quantity::RunExact => self.last_run = Some(self.run_exact()),
            Quantity::RunNetwork => self.last_run = self.run_network(),
            _ => self.instants.call(quantity, backend, i),
        }
    }

    fn last_run(&self) -> Option<RunCounts> {
        self.last_run
    }
}
