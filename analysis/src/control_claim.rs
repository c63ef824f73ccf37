//! zhong2021 §1: "compared with numerical methods \[26\], \[27\] (E47, 94LVI), neural network
//! methods can process information in parallel and have higher computational efficiency \[28\]".
//! Decided here as a claim about the cost per control tick of reaching a stated accuracy: the
//! rule and its thresholds, computed from numbers alone. The control experiments (crate
//! `control`) measure each task's check run ([`records::control::ClaimCheck`]); [`judge`] turns
//! it into the row of `results/control-claim.csv` ([`records::control::ClaimRow`]), and the
//! report reads that row back.
//!
//! # The common unit
//!
//! robio2018's six LVI methods (94LVI and E47, the claim's refs. \[26\] and \[27\], and M3-M6),
//! LVI-PDNN and S-LVI-PDNN all work on jia2019's LVI (2.21) of the same QP and
//! spend their time in the same operation: a product of the LVI matrix M (or M') with a vector
//! (dense, (nx + n_eq + n_in)^2 multiply-adds at most); everything else per step or iteration is
//! O(dim). So the cost per tick is counted in products with M: a network's forward-Euler step
//! costs `control::network_tick::products_per_evaluation` (LVI-PDNN 2, S-LVI-PDNN 1), an LVI
//! method's iteration 2 (`solvers::PRODUCTS_PER_ITERATION`). The counts are the
//! same on every machine and under any load, so the verdict does not depend on either; the
//! latencies are reported beside them for the record.
//!
//! # The comparison (per task, at the control period h, [`spec::MAIN_H`] = 1 ms)
//!
//! - A network needs at least n = ceil(h / s_max) Euler steps per tick to be stable at all
//!   (s_max its Euler stability limit on the task, `control::stability`;
//!   [`records::control::steps_needed`]): at least n x (products per step) per tick, whatever
//!   its accuracy. A check run at a multiple of n steps per tick over the first ticks (both
//!   declared in `experiments/control/tasks.toml`, table `[budget]`) measures the accuracy it
//!   then reaches.
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

use records::control::{ClaimCheck, ClaimRow, Verdict};

/// The claim's row on one task from its measured `check`: the network's lower bound
/// n x (products per step) (`network_products`), its checked cost (check steps x products per
/// step), their verdict against the numerical method's mean ([`decide`]), and the lower bound
/// over that mean (`cost_ratio`).
pub fn judge(check: ClaimCheck) -> ClaimRow {
    let lower = (check.steps_needed * check.products_per_step) as f64;
    let checked = (check.check_steps * check.products_per_step) as f64;
    let verdict = decide(
        lower,
        checked,
        check.check_max_dx,
        check.numerical_products_mean,
    );
    ClaimRow {
        cost_ratio: lower / check.numerical_products_mean,
        task: check.task,
        network: check.network,
        experiment: check.experiment,
        variant_id: check.variant_id,
        solver_id: check.solver_id,
        h_ms: check.h_ms,
        accuracy: ACCURACY,
        products_per_step: check.products_per_step,
        euler_limit_s: check.euler_limit_s,
        steps_needed: check.steps_needed,
        network_products: lower,
        check_steps: check.check_steps,
        check_ticks: check.check_ticks,
        check_status: check.check_status,
        check_max_dx: check.check_max_dx,
        check_solve_p50_us: check.check_solve_p50_us,
        numerical: check.numerical,
        numerical_products_mean: check.numerical_products_mean,
        numerical_products_max: check.numerical_products_max,
        numerical_max_dx: check.numerical_max_dx,
        numerical_solve_p50_us: check.numerical_solve_p50_us,
        verdict,
    }
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
pub(crate) mod tests {
    use super::*;
    use records::control::ControlStatus;

    /// A check of 10 products per step, n = 4 steps needed, checked at `check_steps`, reaching
    /// `max_dx`, against a method of 50 products per tick.
    pub(crate) fn check(check_steps: u64, max_dx: f64) -> ClaimCheck {
        ClaimCheck {
            task: "e / v".to_string(),
            network: "LVI-PDNN".to_string(),
            experiment: "e".parse().unwrap(),
            variant_id: "v".parse().unwrap(),
            solver_id: "lvi-pdnn".parse().unwrap(),
            h_ms: 1.0,
            products_per_step: 10,
            euler_limit_s: 2.5e-4,
            steps_needed: 4,
            check_steps,
            check_ticks: 20,
            check_status: ControlStatus::Ok,
            check_max_dx: max_dx,
            check_solve_p50_us: 1.0,
            numerical: "E47".to_string(),
            numerical_products_mean: 50.0,
            numerical_products_max: 60,
            numerical_max_dx: 1e-9,
            numerical_solve_p50_us: 2.0,
        }
    }

    #[test]
    fn a_check_is_judged_on_its_counts() {
        // Lower bound 40 <= 50, checked 40 <= 50, accurate: PASS, ratio 0.8.
        let row = judge(check(4, 1e-8));
        assert_eq!((row.verdict, row.network_products), (Verdict::Pass, 40.0));
        assert_eq!((row.cost_ratio, row.accuracy), (0.8, ACCURACY));
        // Checked 80 > 50: UNDECIDED; inaccurate: UNDECIDED.
        assert_eq!(judge(check(8, 1e-8)).verdict, Verdict::Undecided);
        assert_eq!(judge(check(4, 1e-3)).verdict, Verdict::Undecided);
        // Lower bound 10 x 6 = 60 > 50: FAIL whatever the check.
        let fail = ClaimCheck {
            steps_needed: 6,
            ..check(12, 1e-9)
        };
        assert_eq!(judge(fail).verdict, Verdict::Fail);
    }

    #[test]
    fn verdicts() {
        assert_eq!(decide(1e5, 2e5, 1e-9, 40.0), Verdict::Fail);
        assert_eq!(decide(10.0, 20.0, 1e-8, 40.0), Verdict::Pass);
        assert_eq!(decide(10.0, 20.0, 1e-3, 40.0), Verdict::Undecided);
        assert_eq!(records::control::steps_needed(1e-3, 3e-7), 3334);
        assert_eq!(overall(&[Verdict::Fail, Verdict::Fail]), Verdict::Fail);
        assert_eq!(overall(&[Verdict::Fail, Verdict::Pass]), Verdict::Undecided);
    }
}
