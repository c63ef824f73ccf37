//! Which path prepares what: the fixed-size path refuses an N the registry has no `NLink<N>`
//! for, the dynamic-size path refuses jia2019 and computes kong2019's per-instant quantities
//! (every backend of the dense LUs) but no scheme build or run. No timing.

use cost::{dynamic, fixed, Case, CostError};
use records::dof_cost::{Quantity, SchemeKind};

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
fn the_dynamic_path_computes_the_per_instant_quantities_at_100_joints() {
    let mut case = dynamic::prepare(&Case::new(SchemeKind::ZnnRmp, 100), 3).unwrap();
    assert_eq!(case.label(), "znn-rmp nlink-100");
    assert_eq!(case.states(), 3);
    let dims = case.dims();
    assert_eq!((dims.nx, dims.n_eq, dims.n_in), (100, 3, 0));
    for quantity in Quantity::ALL {
        let per_instant = !quantity.is_run() && quantity != Quantity::SchemeBuild;
        assert_eq!(case.supports(quantity), per_instant, "{quantity:?}");
        if per_instant {
            for &backend in cost::backends(quantity) {
                for i in 0..case.states() {
                    case.call(quantity, backend, i);
                }
            }
        }
    }
    assert_eq!(case.last_run(), None);
}
