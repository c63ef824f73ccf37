//! zhong2021 §1: "compared with numerical methods \[26\], \[27\] (E47, 94LVI), neural network
//! methods can process information in parallel and have higher computational efficiency \[28\]".
//! Decided here as a claim about the cost per control tick of reaching a stated accuracy: the
//! rule and its thresholds, computed from numbers alone, shared by the control experiments
//! (crate `control`, which run it and write [`records::control::ClaimRow`]) and the report.
//!
//! # The common unit
//!
//! robio2018's six LVI methods (94LVI and E47, the claim's refs. \[26\] and \[27\], and M3-M6),
//! LVI-PDNN and S-LVI-PDNN all work on jia2019's LVI (2.21) of the same QP and
//! spend their time in the same operation: a product of the LVI matrix M (or M') with a vector
//! (dense, (nx + n_eq + n_in)^2 multiply-adds at most); everything else per step or iteration is
//! O(dim). So the cost per tick is counted in products with M: a network's forward-Euler step
//! costs `control::network_tick::products_per_evaluation` (LVI-PDNN 2, S-LVI-PDNN 1), an LVI
//! method's iteration 2 (`solvers::lvi_numerical::PRODUCTS_PER_ITERATION`). The counts are the
//! same on every machine and under any load, so the verdict does not depend on either; the
//! latencies are reported beside them for the record.
//!
//! # The comparison (per task, at the control period h, [`records::control::MAIN_H`] = 1 ms)
//!
//! - A network needs at least n = ceil(h / s_max) Euler steps per tick to be stable at all
//!   (s_max its Euler stability limit on the task, `control::stability`): at least
//!   n x (products per step) per tick, whatever its accuracy. A check run at 2n steps per tick
//!   over the first [`CHECK_TICKS`] ticks measures the accuracy it then reaches.
//! - The six LVI methods are run over the whole task at h, warm-started, to their tolerance;
//!   their mean products per tick, and their largest |x - x*| (which must meet [`ACCURACY`]).
//!
//! Verdict against the cheapest of them that solves the task at every tick (E47 and 94LVI as
//! robio2018 prints them fail at the first tick on jia2019's and zhong2021's QPs, so the claim
//! is tested against their family at its cheapest; the row names the method):
//! - **FAIL** when the network's lower bound exceeds the numerical method's mean cost (the
//!   network cannot be cheaper, even before accuracy is asked for);
//! - **PASS** when the network's checked cost is at most the numerical method's mean and the
//!   check run meets [`ACCURACY`];
//! - **UNDECIDED** otherwise.

/// The accuracy asked for: |x - x*|_inf / max(1, |x*|_inf) at every tick.
pub const ACCURACY: f64 = 1e-6;
/// Ticks of a network's check run.
pub const CHECK_TICKS: usize = 20;

use records::control::Verdict;

/// Euler steps per tick a network needs to be stable: ceil(h / limit).
pub fn steps_needed(h: f64, limit: f64) -> u64 {
    (h / limit).ceil().max(1.0) as u64
}

/// The verdict (module docs) from the network's lower bound and checked cost (products per
/// tick), the check run's accuracy and the numerical method's mean products per tick.
pub fn decide(
    network_lower_bound: f64,
    network_checked: f64,
    check_max_dx: f64,
    numerical_mean: f64,
) -> Verdict {
    if network_lower_bound > numerical_mean {
        Verdict::Fail
    } else if network_checked <= numerical_mean && check_max_dx <= ACCURACY {
        Verdict::Pass
    } else {
        Verdict::Undecided
    }
}

/// The overall verdict of the per-task verdicts: PASS or FAIL when they all agree,
/// UNDECIDED otherwise (or when there are none).
pub fn overall(verdicts: &[Verdict]) -> Verdict {
    match verdicts.first() {
        Some(&v) if verdicts.iter().all(|&w| w == v) => v,
        _ => Verdict::Undecided,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts() {
        assert_eq!(decide(1e5, 2e5, 1e-9, 40.0), Verdict::Fail);
        assert_eq!(decide(10.0, 20.0, 1e-8, 40.0), Verdict::Pass);
        assert_eq!(decide(10.0, 20.0, 1e-3, 40.0), Verdict::Undecided);
        assert_eq!(steps_needed(1e-3, 3e-7), 3334);
        assert_eq!(overall(&[Verdict::Fail, Verdict::Fail]), Verdict::Fail);
        assert_eq!(overall(&[Verdict::Fail, Verdict::Pass]), Verdict::Undecided);
    }
}
