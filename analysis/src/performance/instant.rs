//! Per instant at the Jaco2's size (N = [`JACO2_N`], `results/dof-cost.csv`): each per-call
//! quantity's median against the network's right-hand side and the dense KKT floor, and the
//! hot-started active set against the target on the 7-variable QP.

use super::dof::find;
use records::dof_cost::{DofCostRow, Quantity};

/// The joint count the per-instant table is shown at: the Jaco2's.
pub const JACO2_N: usize = 6;

/// The target: the exact path per instant within this many network RHS evaluations
/// (on the 7-variable QPs).
pub const TARGET_EXACT_OVER_RHS: f64 = 5.0;

/// One per-call quantity of a scheme at N = [`JACO2_N`], with its median as a multiple of the
/// network RHS's median and of the KKT floor's (where both are measured).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstantCost<'a> {
    pub quantity: Quantity,
    pub row: &'a DofCostRow,
    /// median / the network RHS's median.
    pub over_rhs: Option<f64>,
    /// median / the KKT floor's median.
    pub over_floor: Option<f64>,
}

/// The per-call quantities of `scheme` measured at N = [`JACO2_N`], in [`Quantity::ALL`]'s
/// order.
pub fn per_instant<'a>(dof: &'a [DofCostRow], scheme: &str) -> Vec<InstantCost<'a>> {
    let median = |q| find(dof, scheme, JACO2_N, q).and_then(|r| r.median_us);
    let (rhs, floor) = (median(Quantity::NetworkRhs), median(Quantity::KktFloor));
    Quantity::ALL
        .into_iter()
        .filter(|q| !q.is_run())
        .filter_map(|quantity| {
            let row = find(dof, scheme, JACO2_N, quantity)?;
            Some(InstantCost {
                quantity,
                row,
                over_rhs: row.median_us.zip(rhs).map(|(m, d)| m / d),
                over_floor: row.median_us.zip(floor).map(|(m, d)| m / d),
            })
        })
        .collect()
}

/// The hot-started active set against one network RHS evaluation on a 7-variable QP
/// (jia2019's at N = 6, nx = N + 1): the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactOverRhs<'a> {
    pub active_set: &'a DofCostRow,
    pub rhs: &'a DofCostRow,
    /// The active set's median / the RHS's.
    pub ratio: f64,
    /// `ratio` <= [`TARGET_EXACT_OVER_RHS`].
    pub met: bool,
}

/// [`ExactOverRhs`] of `scheme`, where its QP at N = [`JACO2_N`] has 7 variables and both
/// medians are measured.
pub fn exact_over_rhs<'a>(dof: &'a [DofCostRow], scheme: &str) -> Option<ExactOverRhs<'a>> {
    let active_set = find(dof, scheme, JACO2_N, Quantity::ExactActiveSet)?;
    let rhs = find(dof, scheme, JACO2_N, Quantity::NetworkRhs)?;
    if active_set.nx != Some(7) {
        return None;
    }
    let ratio = active_set.median_us? / rhs.median_us?;
    Some(ExactOverRhs {
        active_set,
        rhs,
        ratio,
        met: ratio <= TARGET_EXACT_OVER_RHS,
    })
}

/// What the hot solve would cost without its certification, in RHS evaluations: `ratio` (the
/// whole solve's) times the share outside the certification, 1 - `certification`.
pub fn uncertified_over_rhs(ratio: f64, certification: f64) -> f64 {
    ratio * (1.0 - certification)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::performance::dof::tests::synthetic;

    #[test]
    fn medians_are_taken_over_the_rhs_and_the_floor() {
        let dof = synthetic();
        let costs = per_instant(&dof, "demo");
        // N = 6: the RHS 36 us, the active set 3x that, the floor half of it.
        let active = costs
            .iter()
            .find(|c| c.quantity == Quantity::ExactActiveSet)
            .unwrap();
        assert_eq!(active.over_rhs, Some(3.0));
        assert_eq!(active.over_floor, Some(6.0));
        let target = exact_over_rhs(&dof, "demo").unwrap();
        assert_eq!((target.ratio, target.met), (3.0, true));
        assert_eq!(uncertified_over_rhs(3.0, 0.25), 2.25);
        assert!(exact_over_rhs(&dof, "other").is_none());
    }
}
