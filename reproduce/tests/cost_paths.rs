//! What the harness prepares: the n-link arm of any joint count the registry builds (not one
//! below two joints), both schemes at any N, every quantity of a case (every backend of the
//! dense LUs, whole runs included). No timing.

use records::dof_cost::{Quantity, SchemeKind};
use reproduce::cost::{backends, prepare, Case, CostError};
use solvers::Backend;

#[test]
fn an_arm_the_registry_does_not_build_is_refused() {
    assert!(matches!(
        prepare(&Case::new(SchemeKind::ZnnRmp, 1), 1),
        Err(CostError::NotRegistered(1))
    ));
}

#[test]
fn every_quantity_is_computed_at_100_joints_and_jia2019_runs_at_40() {
    let mut case = prepare(&Case::new(SchemeKind::ZnnRmp, 100), 3).unwrap();
    assert_eq!(case.label(), "znn-rmp nlink-100");
    assert_eq!(case.states(), 3);
    let dims = case.dims();
    assert_eq!((dims.nx, dims.n_eq, dims.n_in), (100, 3, 0));
    for quantity in Quantity::ALL.into_iter().filter(|q| !q.is_run()) {
        assert!(case.supports(quantity), "{quantity:?}");
        for &backend in backends(quantity) {
            for i in 0..case.states() {
                case.call(quantity, backend, i);
            }
        }
    }
    assert!(
        case.last_run().is_some_and(|r| r.completed),
        "the sampling run"
    );
    assert!(case.supports(Quantity::RunExact) && case.supports(Quantity::RunNetwork));
    let vltco = prepare(&Case::new(SchemeKind::Vltco, 40), 2).unwrap();
    let dims = vltco.dims();
    assert_eq!((dims.nx, dims.n_eq, dims.n_in), (41, 3, 80));
}

/// A whole run through the harness is the engine's run: completed, with its steps counted.
#[test]
fn whole_runs_complete_at_5_and_10_joints() {
    for n in [5, 10] {
        let mut case = prepare(&Case::new(SchemeKind::ZnnRmp, n), 2).unwrap();
        for quantity in [Quantity::RunExact, Quantity::RunNetwork] {
            case.call(quantity, Backend::Nalgebra, 0);
            let run = case.last_run().unwrap();
            assert!(
                run.completed && run.steps > 10,
                "nlink-{n} {quantity:?}: {run:?}"
            );
        }
    }
}
