//! The dynamic-size path: arms of hundreds of joints (N = [`SIZES`]) with no compile-time
//! instantiation per size. The arm is [`NLinkDyn`] (the n-link kinematics on `DVector` /
//! `Matrix3xX`, the same implementation as `NLink<N>`), and kong2019's ZNN QP (eq. 22, mu = 1,
//! k_p = 1: P = I, q = mu (theta - theta*0), A = J, b = rdot* + k_p (r* - f(theta))) is written
//! by [`fill_qp`], the function the const-generic scheme writes it with.
//!
//! Measured: the per-instant quantities of [`Instants`] (network RHS, Jacobian and its LU, the
//! exact solvers, the KKT floor on both backends). Not measured, and why:
//!
//! - `scheme-build` and whole runs: the [`schemes::scheme::Scheme`] trait, the integrators'
//!   state and `simulation::simulate` are const-generic in N (stack vectors, no allocation
//!   per step at the papers' 5-7 joints), so a run at N = 200 needs `NLink<200>` and every
//!   scheme instantiated for it; registering such sizes in the registry would be one
//!   instantiation per size, which this path exists to avoid. A run would also cost minutes
//!   (jia2019's exact runs already take seconds at N = 30), past the cost mode's budget.
//! - jia2019: its VLTCO QP (bounds from the joint limits, the max-norm rows) is assembled by
//!   the const-generic scheme only; writing it again for dynamic sizes would duplicate it.
//!
//! The states are not from an exact run (there is none here): state s of [`STATES`] is
//! t_s = s T / S on the circle, theta = home + 0.05 sin(k + 1 + s) rad per joint k, near the
//! start where the fixed path's runs also begin. The exact optimum (for the network states)
//! is the active-set solution, as on the fixed path.

use crate::case::{path_of, Case, PreparedCase, KONG2019_KP, KONG2019_MU};
use crate::error::CostError;
use crate::instants::Instants;
use nalgebra::{DVector, Matrix3xX};
use records::dof_cost::{Quantity, RunCounts, SchemeKind};
use robots::NLinkDyn;
use schemes::paths::build_path;
use schemes::qp::{Qp, QpDims};
use schemes::velocity_rmp::fill_qp;
use solvers::Backend;

/// The joint counts of the dynamic path (above the registry's largest, 30).
pub const SIZES: [usize; 6] = [40, 50, 70, 100, 140, 200];

/// States per case (fewer than the fixed path's: each holds an N x N network Jacobian).
pub const STATES: usize = 20;

/// kong2019's scheme name ([`schemes::velocity_rmp::VelocityRmp::name`] of the ZNN variant).
const KONG2019_NAME: &str = "ZNN";

/// Prepares `case` (kong2019, any N >= 3) on the dynamic-size path with up to `states` states.
pub fn prepare(case: &Case, states: usize) -> Result<Box<dyn PreparedCase>, CostError> {
    Ok(Box::new(Dynamic::new(case, states)?))
}

/// [`PreparedCase`] of the dynamic path.
struct Dynamic {
    label: String,
    network_name: String,
    instants: Instants,
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
        let count = states.max(1);
        let dims = QpDims {
            nx: n,
            n_eq: 3,
            n_in: 0,
        };
        let mut jac = Matrix3xX::zeros(n);
        let mut ts = Vec::with_capacity(count);
        let mut qps = Vec::with_capacity(count);
        for s in 0..count {
            let t = s as f64 * path.duration() / count as f64;
            let theta = DVector::from_fn(n, |k, _| home[k] + 0.05 * ((k + 1 + s) as f64).sin());
            arm.jacobian_into(&theta, &mut jac);
            let q = (&theta - &home) * KONG2019_MU;
            let mut qp = Qp::zeros(dims);
            fill_qp(
                &mut qp,
                q.as_slice(),
                jac.as_slice(),
                &arm.position(&theta),
                &path.at(t),
                KONG2019_KP,
            );
            ts.push(t);
            qps.push(qp);
        }
        let instants = Instants::new(&label, &case.network, ts, qps, Vec::new())?;
        Ok(Dynamic {
            label,
            network_name: case.network.display_name(),
            instants,
        })
    }
}

impl PreparedCase for Dynamic {
    fn label(&self) -> String {
        self.label.clone()
    }

    fn scheme_name(&self) -> String {
        KONG2019_NAME.to_string()
    }

    fn network_name(&self) -> String {
        self.network_name.clone()
    }

    fn dims(&self) -> QpDims {
        self.instants.dims()
    }

    fn states(&self) -> usize {
        self.instants.len()
    }

    fn supports(&self, quantity: Quantity) -> bool {
        self.instants.supports(quantity)
    }

    fn call(&mut self, quantity: Quantity, backend: Backend, i: usize) {
        self.instants.call(quantity, backend, i)
    }

    fn last_run(&self) -> Option<RunCounts> {
        None
    }
}
