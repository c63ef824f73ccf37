//! What runs at every control tick: a network stepped in discrete time
//! ([`crate::network_tick`]) or a registered QP solver (built by `solvers::registry`, a tick
//! solver as it is), behind one interface, [`TickSolver`] ([`crate::tick`]).

use crate::error::ControlError;
use crate::network_tick::{Discretisation, NetworkTick};
use crate::tick::TickSolver;
use qp::QpDims;
use records::control::Family;
use settings::qp_solver::{QpSolverKey, QpSolverSettings};
use settings::SolverSpec;

/// A registered QP solver (`solvers::registry`) with its settings, solved at every tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Numerical {
    /// The solver.
    pub solver: QpSolverKey,
    /// Its settings as given (the solver's defaults complete them).
    pub settings: QpSolverSettings,
}

impl Numerical {
    /// The built-in solver `id` at its defaults; the PLPE methods to the control experiments'
    /// stopping rule instead, |e(U)|_2 <= 1e-10 within 200000 iterations
    /// ([`solvers::LVI_DEFAULT_TOLERANCE`], [`solvers::LVI_DEFAULT_MAX_ITERATIONS`]).
    fn builtin(info: &'static settings::qp_solver::QpSolverInfo) -> Numerical {
        let plpe = info.tolerance.is_some();
        Numerical {
            solver: info.key(),
            settings: QpSolverSettings {
                tolerance: plpe.then_some(solvers::LVI_DEFAULT_TOLERANCE),
                max_iterations: plpe.then_some(solvers::LVI_DEFAULT_MAX_ITERATIONS),
            },
        }
    }

    /// The solvers of the control experiments: the built-in ones of this build
    /// (`settings::qp_solver::BUILTIN`: the six PLPE methods in robio2018's order, the active
    /// set, Clarabel and, with the `osqp` feature, OSQP) at their defaults, the PLPE methods to
    /// |e(U)|_2 <= 1e-10 within 200000 iterations.
    pub fn all() -> Vec<Numerical> {
        settings::qp_solver::BUILTIN
            .iter()
            .filter_map(|i| solvers::registry::check(i.id, &QpSolverSettings::default()).ok())
            .map(|(info, _)| Numerical::builtin(info))
            .collect()
    }

    /// The hot-started active set.
    pub fn active_set() -> Numerical {
        Numerical::by_id("active-set")
    }

    /// The built-in solver `id` at the settings of [`Numerical::all`].
    fn by_id(id: &str) -> Numerical {
        Numerical::builtin(
            settings::qp_solver::lookup(id).expect("a built-in id is registered from the start"),
        )
    }

    /// Whether it is one of robio2018's six PLPE methods.
    pub fn is_plpe(&self) -> bool {
        settings::qp_solver::PLPE_IDS.contains(&self.solver.id())
    }

    /// Display name (the registry's).
    pub fn name(&self) -> &'static str {
        self.solver.info().name
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
            Method::Numerical(n) => {
                Box::new(solvers::registry::build(n.solver.id(), &n.settings, dims)?)
            }
        })
    }
}
