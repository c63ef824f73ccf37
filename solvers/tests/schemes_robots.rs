//! The schemes on the papers' robots (Jaco2 `jaco2-pen` with dynamics, Katana 6M180) and paths,
//! with the exact solver (Clarabel) in the loop: the optimum meets the task constraint and the
//! merged bounds, zhang2018's W is SPD with the real inertia, and build_dot matches a
//! higher-order difference on the real kinematics.

use std::f64::consts::PI;
use std::sync::Arc;

use nalgebra::{DVector, Vector3};
use qp::Qp;
use robots::{Dynamics, Jaco2, Katana6m180, Robot};
use schemes::build_scheme;
use schemes::paths::{build_path, Path};
use schemes::{central_difference, Scheme};
use solvers::ExactSolver;
use spec::Level;
use spec::PathSpec;
use spec::RmpReading;
use spec::SchemeSpec;

fn path(name: &str, duration: f64, start: Vector3<f64>) -> Arc<dyn Path> {
    Arc::from(build_path(&PathSpec::new(name, duration), start).unwrap())
}

/// Richardson-extrapolated central difference (O(h^4)) along the motion.
fn reference_dot(s: &dyn Scheme, t: f64, th: &[f64], thd: &[f64], thdd: &[f64], h: f64) -> Qp {
    let mut d1 = s.new_qp();
    let mut d2 = s.new_qp();
    let mut scratch = s.new_dot_scratch();
    central_difference(s, t, th, thd, thdd, h, &mut d1, &mut scratch);
    central_difference(s, t, th, thd, thdd, 2.0 * h, &mut d2, &mut scratch);
    let comb = |o: &mut [f64], t: &[f64]| {
        o.iter_mut()
            .zip(t)
            .for_each(|(a, b)| *a = (4.0 * *a - b) / 3.0)
    };
    comb(d1.p.as_mut_slice(), d2.p.as_slice());
    comb(d1.q.as_mut_slice(), d2.q.as_slice());
    comb(d1.a.as_mut_slice(), d2.a.as_slice());
    comb(d1.b.as_mut_slice(), d2.b.as_slice());
    comb(d1.g.as_mut_slice(), d2.g.as_slice());
    comb(d1.h.as_mut_slice(), d2.h.as_slice());
    comb(d1.lower.as_mut_slice(), d2.lower.as_slice());
    comb(d1.upper.as_mut_slice(), d2.upper.as_slice());
    d1
}

#[test]
fn jaco2_schemes_exact_optimum_and_derivative() {
    let theta0 = DVector::from_column_slice(&[1.675, 2.79, -3.216, 4.187, -1.71, -2.95]);
    let jaco = Arc::new(Jaco2::pen());
    let robot: Arc<dyn Robot> = jaco.clone();
    let dynamics: Arc<dyn Dynamics> = jaco.clone();
    let clover = path("four-leaf-clover", 5.0, robot.position(theta0.as_slice()));
    let butterfly = path("butterfly", 8.0, robot.position(theta0.as_slice()));
    let specs = [
        (
            SchemeSpec::Vltco {
                phi: 1.0,
                tau: 0.0,
                kappa: 20.0,
                lambda: 20.0,
                rmp: RmpReading::Printed,
                mu: 5.0,
            },
            &clover,
        ),
        (
            SchemeSpec::Vltco {
                phi: 0.2,
                tau: 0.0,
                kappa: 20.0,
                lambda: 20.0,
                rmp: RmpReading::Printed,
                mu: 5.0,
            },
            &clover,
        ),
        (
            SchemeSpec::Vltco {
                phi: 0.2,
                tau: 0.4,
                kappa: 20.0,
                lambda: 20.0,
                rmp: RmpReading::Printed,
                mu: 5.0,
            },
            &clover,
        ),
        (
            SchemeSpec::Cmco {
                eta: 0.2,
                delta: 0.4,
                upsilon: 20.0,
                lambda: 20.0,
                rmp: RmpReading::Printed,
                tau: 10.0,
            },
            &clover,
        ),
        (
            SchemeSpec::HlJdf {
                zeta: 0.0,
                alpha: 20.0,
                beta: 20.0,
                rho_v: 20.0,
                rho_p: 20.0,
            },
            &butterfly,
        ),
        (
            SchemeSpec::HlJdf {
                zeta: 0.6,
                alpha: 20.0,
                beta: 20.0,
                rho_v: 20.0,
                rho_p: 20.0,
            },
            &butterfly,
        ),
    ];
    let mut exact = ExactSolver::new();
    let th = &theta0 + DVector::from_column_slice(&[0.02, -0.03, 0.01, 0.04, -0.02, 0.03]);
    let thd = DVector::from_column_slice(&[0.2, -0.1, 0.15, -0.3, 0.25, 0.1]);
    let thdd = DVector::from_column_slice(&[0.5, -0.4, 0.3, 0.2, -0.6, 0.1]);
    for (spec, p) in specs {
        let s = build_scheme(
            &spec,
            robot.clone(),
            Some(dynamics.clone()),
            (*p).clone(),
            theta0.as_slice(),
        )
        .unwrap();
        let mut qp = s.new_qp();
        for t in [0.0, 1.0, 2.3, 3.9] {
            s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
            let sol = exact
                .solve(&qp)
                .unwrap_or_else(|e| panic!("{} t = {t}: {e}", spec.display_name()));
            assert!(
                sol.kkt.max() < 1e-6,
                "{}: {:?}",
                spec.display_name(),
                sol.kkt
            );
            let x = DVector::from_iterator(6, sol.x.iter().take(6).copied());
            let j = robot.jacobian_matrix(th.as_slice());
            let pp = p.at(t);
            let b = if s.level() == Level::Velocity {
                pp.rdot
            } else {
                pp.rddot - robot.jacobian_dot_matrix(th.as_slice(), thd.as_slice()) * &thd
                    + (pp.rdot - &j * &thd) * 20.0
                    + (pp.r - robot.position(th.as_slice())) * 20.0
            };
            assert!(
                (&j * &x - b).norm() < 1e-8,
                "{} t = {t}: |J x - b| = {}",
                spec.display_name(),
                (&j * &x - b).norm()
            );
            if s.level() == Level::Velocity {
                assert!(
                    x.amax() <= 1.5 + 1e-8,
                    "{}: velocity limit",
                    spec.display_name()
                );
            } else {
                let w = qp.p.clone().symmetric_eigenvalues();
                assert!(w.min() > 0.0, "{}: W eigenvalues {w}", spec.display_name());
                let mut tau = [f64::NAN; 6];
                assert!(s.torque(th.as_slice(), thd.as_slice(), x.as_slice(), &mut tau));
                assert!(tau.iter().all(|v| v.is_finite()));
            }
        }
        let mut dot = s.new_qp();
        let mut scratch = s.new_dot_scratch();
        s.build_dot(
            1.7,
            th.as_slice(),
            thd.as_slice(),
            thdd.as_slice(),
            &mut dot,
            &mut scratch,
        );
        let d = dot.max_rel_diff(&reference_dot(
            &*s,
            1.7,
            th.as_slice(),
            thd.as_slice(),
            thdd.as_slice(),
            1e-3,
        ));
        assert!(d < 1e-6, "{}: build_dot off by {d}", spec.display_name());
    }
}

#[test]
fn katana_kong2019_schemes() {
    let star = DVector::from_column_slice(&[2.0 * PI / 5.0, PI / 2.0, 0.0, -PI / 6.0, PI / 3.0]);
    let robot: Arc<dyn Robot> = Arc::new(Katana6m180::new());
    let circle = path("circle", 9.0, robot.position(star.as_slice()));
    let mut exact = ExactSolver::new();
    let th = &star + DVector::from_column_slice(&[0.0, 0.0, 0.0, 0.0, 0.5]);
    let thd = DVector::from_column_slice(&[0.1, -0.05, 0.08, 0.02, -0.2]);
    for spec in [
        SchemeSpec::FiniteTimeRmp {
            beta_theta: 1.0,
            k_p: 1.0,
            alpha: 0.1,
        },
        SchemeSpec::ZnnRmp { mu: 1.0, k_p: 1.0 },
    ] {
        let s = build_scheme(&spec, robot.clone(), None, circle.clone(), star.as_slice()).unwrap();
        let mut qp = s.new_qp();
        s.build(0.0, star.as_slice(), thd.as_slice(), &mut qp);
        assert!(qp.q.iter().all(|&v| v == 0.0), "q = 0 at theta*0");
        for t in [0.0, 2.0, 4.5, 7.0] {
            s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
            let sol = exact.solve(&qp).unwrap();
            let x = DVector::from_iterator(5, sol.x.iter().copied());
            let pp = circle.at(t);
            let b = pp.rdot + (pp.r - robot.position(th.as_slice())) * 1.0;
            assert!((robot.jacobian_matrix(th.as_slice()) * &x - b).norm() < 1e-8);
            // Joint 5 (wrist roll) does not move the tip: its velocity is the repetitive term alone.
            assert!(
                (x[4] + qp.q[4]).abs() < 1e-7,
                "x5 = {} vs -q5 = {}",
                x[4],
                -qp.q[4]
            );
        }
        // build_dot away from e = 0 (at e_i = 0 the finite-time derivative is floored, see
        // kong2019's module docs, and no difference quotient converges).
        let th2 = &star + DVector::from_column_slice(&[0.03, -0.02, 0.05, 0.01, 0.5]);
        let mut dot = s.new_qp();
        s.build_dot(
            3.0,
            th2.as_slice(),
            thd.as_slice(),
            thd.as_slice(),
            &mut dot,
            &mut s.new_dot_scratch(),
        );
        let d = dot.max_rel_diff(&reference_dot(
            &*s,
            3.0,
            th2.as_slice(),
            thd.as_slice(),
            thd.as_slice(),
            1e-4,
        ));
        assert!(d < 1e-6, "{}: build_dot off by {d}", spec.display_name());
    }
}
