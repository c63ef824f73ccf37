//! The integrator allocates nothing per step: a BDF integration (analytic and
//! finite-difference Jacobian, with and without a largest step) over a long interval makes
//! only [`PER_JACOBIAN`] allocations per extra Jacobian more than over a short one, though it
//! takes more steps and LU factorisations. Those are diffsol's: its default dense Jacobian
//! (`_default_jacobian_inplace`) allocates the unit vector and the column it forms the
//! Jacobian with at every evaluation, which the closures diffsol is given cannot avoid.
//! Counted with the allocation tests' global allocator.

use alloc_count::count;
use nalgebra::DMatrix;
use settings::{IntegratorSettings, Method};
use solvers::ode::{integrate, Control, OdeStats, OdeSystem};

/// Allocations of one dense Jacobian evaluation inside diffsol (module docs).
const PER_JACOBIAN: usize = 2;

/// y' = -K (y - s(t)) with K = gamma I + a ring coupling and s_i(t) = sin(t + i): stiff,
/// forced, so the step size and order keep changing and the Newton matrix is refactored.
struct Forced {
    n: usize,
    gamma: f64,
    analytic_jacobian: bool,
}

impl OdeSystem for Forced {
    fn dim(&self) -> usize {
        self.n
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let e = |k: usize| y[k] - (t + k as f64).sin();
        for (i, d) in dy.iter_mut().enumerate() {
            *d = -self.gamma * e(i) - (e(i) - e((i + 1) % n));
        }
    }
    fn jacobian(&mut self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) -> bool {
        let n = self.n;
        jac.fill(0.0);
        for i in 0..n {
            jac[(i, i)] = -self.gamma - 1.0;
            jac[(i, (i + 1) % n)] += 1.0;
        }
        self.analytic_jacobian
    }
}

/// Allocations of one integration over [0, t1] and its cost.
fn allocations(analytic_jacobian: bool, max_step: Option<f64>, t1: f64) -> (usize, OdeStats) {
    let mut sys = Forced {
        n: 8,
        gamma: 1e4,
        analytic_jacobian,
    };
    let settings = IntegratorSettings {
        method: Method::Bdf,
        max_step,
        ..IntegratorSettings::default()
    };
    let y0 = vec![0.0; 8];
    let mut stats = None;
    let n = count(|| {
        let (_, s) = integrate(&mut sys, &y0, 0.0, t1, &settings, |_, _| Control::Continue)
            .expect("the forced system integrates");
        stats = Some(s);
    });
    (n, stats.unwrap())
}

#[test]
fn bdf_steps_allocate_nothing_but_diffsols_jacobian_vectors() {
    for analytic_jacobian in [true, false] {
        for max_step in [None, Some(0.05)] {
            let (short, s) = allocations(analytic_jacobian, max_step, 2.0);
            let (long, l) = allocations(analytic_jacobian, max_step, 8.0);
            let case = format!("analytic Jacobian {analytic_jacobian}, max_step {max_step:?}");
            assert!(
                l.steps >= s.steps + 50 && l.lu_factorisations > s.lu_factorisations,
                "{case}: the long run must take more steps ({s:?} vs {l:?})"
            );
            assert!(l.jac_evals > s.jac_evals, "{case}: {s:?} vs {l:?}");
            assert_eq!(
                long - short,
                PER_JACOBIAN * (l.jac_evals - s.jac_evals),
                "{case}: allocations grow with the steps ({} steps: {short}, {} steps: {long})",
                s.steps,
                l.steps
            );
        }
    }
}
