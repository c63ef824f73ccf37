//! The diffsol layer against closed-form solutions, for every method, with analytic and
//! finite-difference Jacobians, on a non-stiff and a stiff (gamma = 1e7) problem.

use nalgebra::DMatrix;
use settings::{IntegratorSettings, Method};
use solvers::ode::{integrate, Control, OdeSystem};

/// Harmonic oscillator y'' = -y: y(t) = (cos t, -sin t).
struct Oscillator;

impl OdeSystem for Oscillator {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }
}

/// y' = -gamma (y - sin t), the shape of a gamma = 1e7 network tracking a moving optimum.
/// Solution from y(0) = 0: y(t) = gamma (gamma sin t - cos t + e^{-gamma t}) / (1 + gamma^2).
struct Tracking {
    gamma: f64,
    analytic_jacobian: bool,
}

impl OdeSystem for Tracking {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -self.gamma * (y[0] - t.sin());
    }
    fn jacobian(&mut self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) -> bool {
        jac[(0, 0)] = -self.gamma;
        self.analytic_jacobian
    }
}

fn settings(method: Method, rtol: f64, atol: f64) -> IntegratorSettings {
    IntegratorSettings {
        method,
        rtol,
        atol,
        max_steps: 1_000_000,
        max_step: None,
        ..IntegratorSettings::default()
    }
}

#[test]
fn every_method_follows_the_oscillator() {
    for method in [
        Method::Bdf,
        Method::Esdirk34,
        Method::TrBdf2,
        Method::Dopri5,
        Method::Tsit45,
    ] {
        let mut observed = 0;
        let (y, stats) = integrate(
            &mut Oscillator,
            &[1.0, 0.0],
            0.0,
            5.0,
            &settings(method, 1e-8, 1e-10),
            |_, _| {
                observed += 1;
                Control::Continue
            },
        )
        .unwrap();
        let err = (y[0] - 5f64.cos()).abs().max((y[1] + 5f64.sin()).abs());
        assert!(err < 1e-5, "{method}: error {err:e}");
        assert_eq!(
            observed,
            stats.steps + 1,
            "{method}: observer sees t0 and every accepted step"
        );
        assert!(stats.rhs_evals > stats.steps);
    }
}

#[test]
fn dopri5_is_fifth_order() {
    let run = |rtol: f64| {
        let (y, stats) = integrate(
            &mut Oscillator,
            &[1.0, 0.0],
            0.0,
            10.0,
            &settings(Method::Dopri5, rtol, rtol * 1e-2),
            |_, _| Control::Continue,
        )
        .unwrap();
        ((y[0] - 10f64.cos()).abs(), stats.steps)
    };
    let (e_loose, n_loose) = run(1e-5);
    let (e_tight, n_tight) = run(1e-10);
    assert!(
        e_tight < 1e-8 && e_tight < e_loose,
        "errors {e_loose:e} -> {e_tight:e}"
    );
    // A 5(4) pair: a 1e5 tighter tolerance costs about 1e5^(1/5) = 10x the steps, not 100x as order 2 would.
    let ratio = n_tight as f64 / n_loose as f64;
    assert!(ratio > 3.0 && ratio < 30.0, "step ratio {ratio}");
}

#[test]
fn bdf_handles_gamma_1e7_with_both_jacobians() {
    for analytic in [true, false] {
        let gamma = 1e7;
        let mut sys = Tracking {
            gamma,
            analytic_jacobian: analytic,
        };
        let t1 = 3.0;
        let (y, stats) = integrate(
            &mut sys,
            &[0.0],
            0.0,
            t1,
            &IntegratorSettings::default(),
            |_, _| Control::Continue,
        )
        .unwrap();
        let exact = gamma * (gamma * t1.sin() - t1.cos()) / (1.0 + gamma * gamma);
        assert!(
            (y[0] - exact).abs() < 1e-6,
            "analytic={analytic}: {} vs {exact}",
            y[0]
        );
        assert!(
            stats.steps < 5_000,
            "a stiff method must not be step-limited by gamma: {} steps",
            stats.steps
        );
        assert!(stats.jac_evals >= 1);
    }
}

#[test]
fn explicit_method_is_step_limited_on_the_stiff_problem() {
    let mut sys = Tracking {
        gamma: 1e5,
        analytic_jacobian: true,
    };
    let (_, stats) = integrate(
        &mut sys,
        &[0.0],
        0.0,
        0.1,
        &settings(Method::Dopri5, 1e-6, 1e-8),
        |_, _| Control::Continue,
    )
    .unwrap();
    // Dormand-Prince's stability interval is about 3.3 / gamma.
    assert!(
        stats.steps as f64 > 0.1 * 1e5 / 4.0,
        "only {} steps",
        stats.steps
    );
}

#[test]
fn observer_can_stop_and_divergence_is_reported() {
    struct Blowup;
    impl OdeSystem for Blowup {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[0] * y[0];
        }
    }
    // y' = y^2, y(0) = 1 blows up at t = 1.
    let r = integrate(
        &mut Blowup,
        &[1.0],
        0.0,
        2.0,
        &settings(Method::Dopri5, 1e-6, 1e-8),
        |_, _| Control::Continue,
    );
    assert!(
        r.is_err(),
        "blow-up must be reported, got {:?}",
        r.map(|x| x.0)
    );
    let r = integrate(
        &mut Oscillator,
        &[1.0, 0.0],
        0.0,
        5.0,
        &settings(Method::Bdf, 1e-6, 1e-8),
        |t, _| {
            if t > 1.0 {
                Control::Stop("enough".into())
            } else {
                Control::Continue
            }
        },
    );
    let failure = r.expect_err("stopped by the observer");
    assert!(matches!(
        failure.error,
        solvers::ode::OdeError::Stopped { .. }
    ));
    assert!(
        failure.stats.steps > 0 && failure.stats.rhs_evals > failure.stats.steps,
        "cost until the stop is kept"
    );
}

/// ode15s's MaxStep (the group's 0.05 s): on the oscillator over [0, 8], which every method
/// would otherwise cross in far fewer steps, no accepted step is longer than 0.05 and the
/// result is still accurate.
#[test]
fn max_step_bounds_every_accepted_step() {
    for method in [
        Method::Bdf,
        Method::Esdirk34,
        Method::TrBdf2,
        Method::Dopri5,
        Method::Tsit45,
    ] {
        // Tolerances loose enough that the method steps beyond 0.05 when unlimited.
        let rtol = if method == Method::TrBdf2 { 1e-3 } else { 1e-5 };
        let (mut last, mut longest_unlimited) = (0.0, 0.0_f64);
        integrate(
            &mut Oscillator,
            &[1.0, 0.0],
            0.0,
            8.0,
            &settings(method, rtol, rtol * 1e-2),
            |t, _| {
                longest_unlimited = longest_unlimited.max(t - last);
                last = t;
                Control::Continue
            },
        )
        .unwrap();
        let mut s = settings(method, rtol, rtol * 1e-2);
        s.max_step = Some(0.05);
        last = 0.0;
        let mut longest: f64 = 0.0;
        let (y, stats) = integrate(&mut Oscillator, &[1.0, 0.0], 0.0, 8.0, &s, |t, _| {
            longest = longest.max(t - last);
            last = t;
            Control::Continue
        })
        .unwrap();
        assert!(
            longest_unlimited > 0.06,
            "{method}: the test needs steps longer than 0.05 when unlimited, longest {longest_unlimited}"
        );
        assert!(stats.steps >= 160, "{method}: {} steps", stats.steps);
        assert!(longest <= 0.05 + 1e-12, "{method}: a step of {longest}");
        assert_eq!(last, 8.0, "{method}: ends at t1");
        let err = (y[0] - 8f64.cos()).abs().max((y[1] + 8f64.sin()).abs());
        assert!(err < 100.0 * rtol, "{method}: error {err:e}");
    }
    // Validation.
    for bad in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let mut s = settings(Method::Bdf, 1e-6, 1e-8);
        s.max_step = Some(bad);
        assert!(s.validate().is_err());
        assert!(
            integrate(&mut Oscillator, &[1.0, 0.0], 0.0, 1.0, &s, |_, _| {
                Control::Continue
            })
            .is_err()
        );
    }
    // TOML: absent means None, present is read.
    let s: IntegratorSettings =
        toml::from_str("method = \"bdf\"\nrtol = 1e-6\natol = 1e-8\nmax_step = 0.05").unwrap();
    assert_eq!(s.max_step, Some(0.05));
    let s: IntegratorSettings =
        toml::from_str("method = \"bdf\"\nrtol = 1e-6\natol = 1e-8").unwrap();
    assert_eq!(s.max_step, None);
}

/// The wall-time budget bounds every integration: past it the run fails with that reason (a
/// budget far below one step's cost trips it after the first step).
#[test]
fn the_wall_time_budget_stops_a_run() {
    let budget = IntegratorSettings {
        max_wall_s: 1e-12,
        ..settings(Method::Dopri5, 1e-10, 1e-12)
    };
    let failure = integrate(&mut Oscillator, &[1.0, 0.0], 0.0, 1e3, &budget, |_, _| {
        Control::Continue
    })
    .unwrap_err();
    assert!(
        matches!(failure.error, solvers::ode::OdeError::WallBudget { .. }),
        "{failure}"
    );
    assert!(failure.to_string().contains("wall-time budget"));
    assert!(IntegratorSettings {
        max_wall_s: 0.0,
        ..IntegratorSettings::default()
    }
    .validate()
    .is_err());
}

/// The evaluation budget bounds every integration the same way, deterministically.
#[test]
fn the_evaluation_budget_stops_a_run() {
    let budget = IntegratorSettings {
        max_rhs_evals: 50,
        ..settings(Method::Dopri5, 1e-10, 1e-12)
    };
    let failure = integrate(&mut Oscillator, &[1.0, 0.0], 0.0, 1e3, &budget, |_, _| {
        Control::Continue
    })
    .unwrap_err();
    assert!(
        failure.to_string().contains("evaluation budget of 50"),
        "{failure}"
    );
    assert!(failure.stats.rhs_evals > 50 && failure.stats.rhs_evals < 100);
}
