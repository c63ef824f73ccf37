//! Which path prepares what: the fixed-size path refuses an N the registry has no `NLink<N>`
//! for, the dynamic-size path refuses jia2019 and computes every quantity of kong2019 (every
//! backend of the dense LUs, whole runs included); at an N both paths have, their whole runs
//! are the same runs. No timing.

use cost::{dynamic, fixed, Case, CostError};
use records::dof_cost::{Quantity, SchemeKind};
use solvers::Backend;

#[test]
fn each_path_prepares_its_own_cases() {
    assert!(matches!(
        fixed::prepare(&Case::new(SchemeKind::ZnnRmp, 100), 1),
        Err(CostError::NotRegistered(100))
    ));
    assert!(matches!(
        dynamic::prepare(&Case::new(SchemeKind::Vltco, 100), 1),
        Err(CostError::NoDynamicScheme("vltco"))
    ));
    assert!(matches!(
        dynamic::prepare(&Case::new(SchemeKind::ZnnRmp, 2), 1),
        Err(CostError::TooFewJoints(2))
    ));
}

#[test]
fn the_dynamic_path_computes_every_quantity_at_100_joints() {
    let mut case = dynamic::prepare(&Case::new(SchemeKind::ZnnRmp, 100), 3).unwrap();
    assert_eq!(case.label(), "znn-rmp nlink-100");
    assert_eq!(case.states(), 3);
    let dims = case.dims();
    assert_eq!((dims.nx, dims.n_eq, dims.n_in), (100, 3, 0));
    for quantity in Quantity::ALL.into_iter().filter(|q| !q.is_run()) {
        assert!(case.supports(quantity), "{quantity:?}");
        for &backend in cost::backends(quantity) {
            for i in 0..case.states() {
                case.call(quantity, backend, i);
            }
        }
    }
    assert_eq!(case.last_run(), None);
    assert!(case.supports(Quantity::RunExact) && case.supports(Quantity::RunNetwork));
}

/// The dynamic path's whole runs integrate the same ODE as `simulate` on `NLink<N>`, step for
/// step: same accepted steps and RHS evaluations, both completed.
#[test]
fn both_paths_run_the_same_whole_runs_at_a_shared_joint_count() {
    for n in [5, 10] {
        let case = Case::new(SchemeKind::ZnnRmp, n);
        let mut on_fixed = fixed::prepare(&case, 2).unwrap();
        let mut on_dynamic = dynamic::prepare(&case, 2).unwrap();
        for quantity in [Quantity::RunExact, Quantity::RunNetwork] {
            on_fixed.call(quantity, Backend::Nalgebra, 0);
            on_dynamic.call(quantity, Backend::Nalgebra, 0);
            let (a, b) = (on_fixed.last_run().unwrap(), on_dynamic.last_run().unwrap());
            assert!(a.completed && a.steps > 10, "nlink-{n} {quantity:?}: {a:?}");
            assert_eq!(a, b, "nlink-{n} {quantity:?}");
        }
    }
}
