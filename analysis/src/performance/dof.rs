//! The cost against the number of joints (`results/dof-cost.csv`): where each fit's
//! measurements start and end, the whole runs per N (seconds, steps, the cost of a step), and
//! the growth exponents of the whole runs past the two-scheme sweep's joint counts, where only
//! kong2019's scheme is measured.

use crate::fits::{fit_power_law, PowerFit};
use records::dof_cost::{DofCostRow, Quantity, NALGEBRA};

/// The measured row of (scheme, N, quantity) on nalgebra (the backend of every quantity; the
/// dense LUs on faer have their own fits).
pub fn find<'a>(
    dof: &'a [DofCostRow],
    scheme: &str,
    n: usize,
    quantity: Quantity,
) -> Option<&'a DofCostRow> {
    dof.iter().find(|r| {
        !r.is_fit()
            && r.scheme == scheme
            && r.n == Some(n)
            && r.quantity == quantity
            && r.backend == NALGEBRA
    })
}

/// The schemes of the measurement, in file order.
pub fn schemes(dof: &[DofCostRow]) -> Vec<&str> {
    records::table::distinct(dof, |r| &r.scheme)
}

/// The largest N measured (0 without a measurement).
pub fn largest_n(dof: &[DofCostRow]) -> usize {
    dof.iter().filter_map(|r| r.n).max().unwrap_or(0)
}

/// One fit row with the measurements it was fitted to: the (N, median) at the smallest and at
/// the largest N measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitExtent<'a> {
    pub fit: &'a DofCostRow,
    pub smallest: Option<(usize, f64)>,
    pub largest: Option<(usize, f64)>,
}

/// Every fit row of `dof`, in file order, with its extent.
pub fn fit_extents(dof: &[DofCostRow]) -> Vec<FitExtent<'_>> {
    dof.iter()
        .filter(|r| r.is_fit())
        .map(|fit| {
            let measured: Vec<(usize, f64)> = dof
                .iter()
                .filter(|r| {
                    !r.is_fit()
                        && r.scheme == fit.scheme
                        && r.quantity == fit.quantity
                        && r.backend == fit.backend
                })
                .filter_map(|r| Some((r.n?, r.median_us?)))
                .collect();
            let at = |pick: fn(usize, usize) -> bool| {
                measured
                    .iter()
                    .copied()
                    .reduce(|a, b| if pick(b.0, a.0) { b } else { a })
            };
            FitExtent {
                fit,
                smallest: at(|a, b| a < b),
                largest: at(|a, b| a > b),
            }
        })
        .collect()
}

/// A whole run of the DOF measurement: its median time, steps and time per step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunCost {
    /// The median over the repetitions (s).
    pub seconds: Option<f64>,
    /// The run failed (its time is until the failure).
    pub failed: bool,
    pub steps: Option<usize>,
    /// The median over the steps (us; a run of no step counts one).
    pub per_step_us: Option<f64>,
}

impl RunCost {
    fn of(r: &DofCostRow) -> Self {
        RunCost {
            seconds: r.median_us.map(|m| m * 1e-6),
            failed: r.completed == Some(false),
            steps: r.steps,
            per_step_us: r.median_us.zip(r.steps).map(|(m, s)| m / s.max(1) as f64),
        }
    }
}

/// The whole runs of one scheme at one N: the exact column's and the network's.
#[derive(Clone, Debug, PartialEq)]
pub struct RunsAtN<'a> {
    pub scheme: &'a str,
    pub n: usize,
    pub exact: Option<RunCost>,
    pub network: Option<RunCost>,
}

/// Per scheme (file order) and N (ascending), the whole runs measured there.
pub fn runs_at_n(dof: &[DofCostRow]) -> Vec<RunsAtN<'_>> {
    let mut out = Vec::new();
    for scheme in schemes(dof) {
        let mut ns: Vec<usize> = dof
            .iter()
            .filter(|r| r.scheme == scheme)
            .filter_map(|r| r.n)
            .collect();
        ns.sort_unstable();
        ns.dedup();
        for n in ns {
            let cost = |q| find(dof, scheme, n, q).map(RunCost::of);
            out.push(RunsAtN {
                scheme,
                n,
                exact: cost(Quantity::RunExact),
                network: cost(Quantity::RunNetwork),
            });
        }
    }
    out
}

/// The growth exponent of one whole-run quantity of a scheme over the N past the registry's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LargeNFit<'a> {
    pub scheme: &'a str,
    pub quantity: Quantity,
    /// The scheme's network (its name in the quantity's label).
    pub network: &'a str,
    pub fit: PowerFit,
}

/// The cost harness's largest swept joint count (`records::dof_cost::SWEEP_SIZES`): past it
/// only kong2019's scheme is measured, at the large sizes.
pub fn largest_registry_n() -> usize {
    records::dof_cost::SWEEP_SIZES
        .iter()
        .copied()
        .max()
        .unwrap_or(0)
}

/// The growth exponents of the whole runs over N > [`largest_registry_n`] alone, where the
/// per-step cost is past its small-N floor: median ~ c N^k ([`fit_power_law`]) per scheme and
/// run quantity with at least two such N.
pub fn large_n_fits(dof: &[DofCostRow]) -> Vec<LargeNFit<'_>> {
    let largest_fixed = largest_registry_n();
    let mut out = Vec::new();
    for scheme in schemes(dof) {
        for quantity in [Quantity::RunExact, Quantity::RunNetwork] {
            let points: Vec<(f64, f64)> = dof
                .iter()
                .filter(|r| {
                    !r.is_fit()
                        && r.scheme == scheme
                        && r.quantity == quantity
                        && r.n.is_some_and(|n| n > largest_fixed)
                })
                .filter_map(|r| Some((r.n? as f64, r.median_us?)))
                .collect();
            if let Some(fit) = fit_power_law(&points) {
                let network = dof
                    .iter()
                    .find(|r| r.scheme == scheme)
                    .map_or("", |r| r.network.as_str());
                out.push(LargeNFit {
                    scheme,
                    quantity,
                    network,
                    fit,
                });
            }
        }
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A synthetic dof-cost.csv: a scheme `demo` (VLTCO) at N = 3, 6, 12 with cost = N^2 us
    /// (network RHS) and 3 N^2 (active set), half of it for the KKT floor (faer's: slower than
    /// nalgebra's below N = 12, faster there), whole exact runs of 1e4 N us over 1000 steps,
    /// plus the fits.
    pub(crate) fn synthetic() -> Vec<DofCostRow> {
        let rows = fixtures::dof_cost("demo");
        let fits = crate::fits::fit_rows(&rows);
        rows.into_iter().chain(fits).collect()
    }

    #[test]
    fn fits_extend_over_the_measured_n() {
        let dof = synthetic();
        assert_eq!(largest_n(&dof), 12);
        let rhs = fit_extents(&dof)
            .into_iter()
            .find(|e| e.fit.quantity == Quantity::NetworkRhs)
            .unwrap();
        assert_eq!(rhs.smallest, Some((3, 9.0)));
        assert_eq!(rhs.largest, Some((12, 144.0)));
    }

    #[test]
    fn whole_runs_are_priced_per_step() {
        let dof = synthetic();
        let at6 = runs_at_n(&dof).into_iter().find(|r| r.n == 6).unwrap();
        // 6e4 us = 6e-2 s over 1000 steps = 60 us a step; no network run measured.
        let exact = at6.exact.unwrap();
        assert_eq!(exact.seconds, Some(6e4 * 1e-6));
        assert_eq!((exact.steps, exact.per_step_us), (Some(1000), Some(60.0)));
        assert!(!exact.failed && at6.network.is_none());
    }

    #[test]
    fn large_n_fits_need_two_n_past_the_registry() {
        // Every synthetic N is within the registry's sizes: no fit.
        assert!(large_n_fits(&synthetic()).is_empty());
        assert_eq!(largest_registry_n(), 30);
    }
}
