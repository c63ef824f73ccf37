//! What runs at every control tick: a network stepped in discrete time
//! ([`crate::network_tick`]) or a numerical QP method ([`crate::numerical_tick`]), built behind
//! one interface, [`TickSolver`] ([`crate::tick`]).

use crate::error::ControlError;
use crate::network_tick::{Discretisation, NetworkTick};
use crate::numerical_tick::QpTick;
use crate::tick::TickSolver;
use qp::QpDims;
use records::control::Family;
use settings::solver_spec::SolverSpec;
use solvers::lvi_numerical::{LviMethod, LviSettings, LviSolver};
#[cfg(feature = "osqp")]
use solvers::osqp_qp::{OsqpQp, OsqpSettings};
use solvers::{ExactSolver, HotActiveSet};

/// A numerical QP method, solved to its tolerance at every tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Numerical {
    /// One of robio2018's six PLPE methods ([`solvers::lvi_numerical`]), warm-started from the
    /// previous tick.
    Lvi(LviMethod, LviSettings),
    /// The dense active-set solver hot-started from the previous tick's working set.
    ActiveSet,
    /// Clarabel (interior point: no warm start).
    Clarabel,
    /// OSQP, data updated in place and warm-started (with the `osqp` feature).
    #[cfg(feature = "osqp")]
    Osqp(OsqpSettings),
}

impl Numerical {
    /// The methods of the control experiments, at their default settings: the six PLPE
    /// methods in robio2018's order, then the active set, Clarabel and (with the `osqp`
    /// feature) OSQP.
    pub fn all() -> Vec<Numerical> {
        let mut all: Vec<Numerical> = LviMethod::ALL
            .map(|m| Numerical::Lvi(m, LviSettings::default()))
            .into();
        all.extend([Numerical::ActiveSet, Numerical::Clarabel]);
        #[cfg(feature = "osqp")]
        all.push(Numerical::Osqp(OsqpSettings::default()));
        all
    }

    /// Display name.
    pub fn name(&self) -> &'static str {
        match self {
            Numerical::Lvi(m, _) => m.name(),
            Numerical::ActiveSet => "active set",
            Numerical::Clarabel => "Clarabel",
            #[cfg(feature = "osqp")]
            Numerical::Osqp(_) => "OSQP",
        }
    }
}

/// What computes the joint command at each tick.
#[derive(Clone, Debug, PartialEq)]
pub enum Method {
    /// A network, `substeps` steps of its discrete form per tick (step h / substeps).
    Network {
        spec: SolverSpec,
        form: Discretisation,
        substeps: u32,
    },
    Numerical(Numerical),
}

impl Method {
    /// The label in results: the method's name, a network's form and its substeps when not 1.
    pub fn label(&self) -> String {
        match self {
            Method::Network {
                spec,
                form,
                substeps,
            } => {
                let sub = if *substeps > 1 {
                    format!(" x{substeps}")
                } else {
                    String::new()
                };
                format!("{} [{}{sub}]", spec.display_name(), form.name())
            }
            Method::Numerical(n) => n.name().to_string(),
        }
    }

    /// Whether the method is a network or a numerical QP method.
    pub fn family(&self) -> Family {
        match self {
            Method::Network { .. } => Family::Network,
            Method::Numerical(_) => Family::Numerical,
        }
    }

    /// The per-tick solver for QPs of sizes `dims`.
    pub fn build(&self, dims: QpDims) -> Result<Box<dyn TickSolver>, ControlError> {
        Ok(match self {
            Method::Network {
                spec,
                form,
                substeps,
            } => Box::new(NetworkTick::new(spec, *form, *substeps, dims)?),
            Method::Numerical(Numerical::Lvi(m, s)) => {
                Box::new(QpTick::new(LviSolver::new(*m, dims, *s)))
            }
            Method::Numerical(Numerical::ActiveSet) => {
                Box::new(QpTick::new(HotActiveSet::new(dims)))
            }
            Method::Numerical(Numerical::Clarabel) => Box::new(QpTick::new(ExactSolver::new())),
            #[cfg(feature = "osqp")]
            Method::Numerical(Numerical::Osqp(s)) => Box::new(QpTick::new(OsqpQp::new(dims, *s))),
        })
    }
}
