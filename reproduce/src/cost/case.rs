//! What is measured: a (scheme, N) [`Case`] with its network, and a case made ready to time
//! ([`PreparedCase`]), as [`super::harness`] prepared it.

use qp::QpDims;
use records::dof_cost::{Quantity, RunCounts, SchemeKind};
use settings::SolverSpec;
use solvers::Backend;
use spec::PathSpec;

/// Size a of the four-leaf clover (m): 0.1, inside the n-link arms' workspace around
/// `NLink::home` for every N (the suite's default 0.15 m is the Jaco2's).
pub const CLOVER_SCALE: f64 = 0.1;

/// The path a scheme is run on, starting at the arm's tip: jia2019 a four-leaf clover of size
/// [`CLOVER_SCALE`] (5 s), kong2019 a circle of radius 0.05 m (9 s).
pub fn path_of(scheme: SchemeKind) -> PathSpec {
    match scheme {
        SchemeKind::Vltco => PathSpec {
            scale: Some(CLOVER_SCALE),
            ..PathSpec::new("four-leaf-clover", 5.0)
        },
        SchemeKind::ZnnRmp => PathSpec::new("circle", 9.0),
    }
}

/// The backends `quantity` is measured on: both [`Backend`]s for the dense LU quantities,
/// nalgebra alone for the rest (the schemes, networks and exact solvers are written on
/// nalgebra). Each is written as its id ([`Backend::id`]) in `results/dof-cost.csv`.
pub fn backends(quantity: Quantity) -> &'static [Backend] {
    match quantity {
        Quantity::NetworkLu | Quantity::KktFloor => &Backend::ALL,
        _ => &[Backend::Nalgebra],
    }
}

/// kong2019's ZNN gains: mu = 1, k_p = 1.
pub const KONG2019_MU: f64 = 1.0;
pub const KONG2019_KP: f64 = 1.0;

/// One measured (N, scheme) pair.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub scheme: SchemeKind,
    pub n: usize,
    /// The network timed (network-rhs, network-jacobian, network-lu, run-network).
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

    /// `<scheme> nlink-<N>`.
    pub fn label(&self) -> String {
        format!("{} nlink-{}", self.scheme.id(), self.n)
    }
}

/// A case made ready to time: every quantity it supports as one call, without allocation
/// where the code timed does not allocate itself. Object safe, so the criterion benches and
/// `reproduce cost`'s timing drive it without knowing N or the path.
pub trait PreparedCase {
    /// `<scheme> nlink-<N>`.
    fn label(&self) -> String;
    fn scheme_name(&self) -> String;
    fn network_name(&self) -> String;
    fn dims(&self) -> QpDims;
    /// States sampled (per-call quantities take an index below this).
    fn states(&self) -> usize;
    /// Whether `quantity` can be timed (the path computes it, the network has an analytic
    /// Jacobian, the equality KKT matrix is regular).
    fn supports(&self, quantity: Quantity) -> bool;
    /// One call of `quantity` on `backend` (one of [`backends`]) at state `i` (a
    /// whole run, for the run quantities; `i` unused).
    fn call(&mut self, quantity: Quantity, backend: Backend, i: usize);
    /// Counts of the last whole run [`Self::call`] made.
    fn last_run(&self) -> Option<RunCounts>;
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::dof_cost::{FAER, NALGEBRA};

    #[test]
    fn the_dense_lu_quantities_are_measured_on_every_backend_under_the_ids_records_reads() {
        assert_eq!(Backend::ALL.map(Backend::id), [NALGEBRA, FAER]);
        assert_eq!(backends(Quantity::KktFloor), &Backend::ALL);
        assert_eq!(backends(Quantity::NetworkLu), &Backend::ALL);
        assert_eq!(backends(Quantity::NetworkRhs), &[Backend::Nalgebra]);
    }
}
