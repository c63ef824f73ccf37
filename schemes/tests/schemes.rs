//! Tests of the papers' schemes on a small planar test arm (see `common/mod.rs`): QP shapes,
//! the data each equation prescribes, the merged joint bounds, the exact optimum's task
//! constraint, zhang2018's weight matrix, kong2019's finite-time term, the QP time derivative,
//! constant sizes along a run, and the experiment-file spec.

use crate::common;

use std::sync::Arc;

use common::{admm, kkt_solve, paper_specs as specs, Circle, FixedRobot, PlanarZ};
use nalgebra::{DMatrix, SVector, Vector3};
use qp::QpDotScratch;
use qp::{Qp, QpDims};
use robots::{Dynamics, JointLimits, Robot};
use schemes::build_scheme;
use schemes::paths::Path;
use schemes::{central_difference, default_step, Scheme};
use schemes::{merged_bound, piecewise_bound};
use spec::Level;
use spec::RmpReading;
use spec::{hl_jdf_name, vltco_name, SchemeError, SchemeSpec};

const N: usize = 6;
type V = SVector<f64, N>;

fn theta0() -> V {
    V::from([0.3, 1.2, -0.8, 0.5, -0.4, 0.2])
}

fn planar() -> PlanarZ {
    PlanarZ::new(N)
}

fn robot() -> Arc<PlanarZ> {
    Arc::new(planar())
}

fn path() -> Arc<Circle> {
    Arc::new(Circle {
        r0: planar().position_n(&theta0()),
        a: 0.05,
        t_end: 5.0,
    })
}

fn make(spec: &SchemeSpec) -> Box<dyn Scheme> {
    let r = robot();
    build_scheme(spec, r.clone(), Some(r), path(), theta0().as_slice()).unwrap()
}

fn expected_dims(spec: &SchemeSpec) -> (QpDims, Level) {
    match spec {
        SchemeSpec::Vltco { .. } => (
            QpDims {
                nx: N + 1,
                n_eq: 3,
                n_in: 2 * N,
            },
            Level::Velocity,
        ),
        SchemeSpec::Cmco { .. } => (
            QpDims {
                nx: N + 1,
                n_eq: 3,
                n_in: 4 * N + 2,
            },
            Level::Velocity,
        ),
        SchemeSpec::HlJdf { .. } => (
            QpDims {
                nx: N,
                n_eq: 3,
                n_in: 0,
            },
            Level::Acceleration,
        ),
        _ => (
            QpDims {
                nx: N,
                n_eq: 3,
                n_in: 0,
            },
            Level::Velocity,
        ),
    }
}

/// A state away from theta0 (and from every kink of the merged bounds).
fn state() -> (V, V, V) {
    let th = theta0() + V::from([0.05, -0.1, 0.07, -0.03, 0.02, 0.04]);
    let thd = V::from([0.3, -0.2, 0.25, 0.1, -0.15, 0.05]);
    let thdd = V::from([1.0, -0.5, 0.3, 0.7, -0.2, 0.4]);
    (th, thd, thdd)
}

#[test]
fn qp_shapes_per_scheme() {
    let (th, thd, _) = state();
    for spec in specs() {
        let s = make(&spec);
        let (dims, level) = expected_dims(&spec);
        assert_eq!(s.dims(), dims, "{}", spec.display_name());
        assert_eq!(s.level(), level, "{}", spec.display_name());
        let mut qp = s.new_qp();
        s.build(1.3, th.as_slice(), thd.as_slice(), &mut qp);
        assert_eq!(qp.dims(), dims);
        // P symmetric; A = [J 0] (first N columns are the Jacobian).
        assert_eq!(qp.p, qp.p.transpose(), "{}", spec.display_name());
        let j = planar().jacobian_n(&th);
        for r in 0..3 {
            for c in 0..N {
                assert_eq!(qp.a[(r, c)], j[(r, c)]);
            }
            if dims.nx == N + 1 {
                assert_eq!(qp.a[(r, N)], 0.0);
            }
        }
        match spec {
            SchemeSpec::Vltco { .. } => {
                // G = [I -1; -I -1], h = 0; bounds x- = [zeta-; 0], x+ = [zeta+; +inf].
                for i in 0..N {
                    for c in 0..=N {
                        let top = if c == i {
                            1.0
                        } else if c == N {
                            -1.0
                        } else {
                            0.0
                        };
                        let bot = if c == i || c == N { -1.0 } else { 0.0 };
                        assert_eq!(qp.g[(i, c)], top);
                        assert_eq!(qp.g[(N + i, c)], bot);
                    }
                }
                assert!(qp.h.iter().all(|&v| v == 0.0));
                assert_eq!(qp.lower[N], 0.0);
                assert_eq!(qp.upper[N], f64::INFINITY);
                assert!(qp.lower.rows(0, N).iter().all(|v| v.is_finite()));
                assert!(qp.upper.rows(0, N).iter().all(|v| v.is_finite()));
            }
            SchemeSpec::Cmco { .. } => {
                // B = [s; E; -E], everything in G/h, no variable bounds.
                let mut b = DMatrix::zeros(4 * N + 2, N + 1);
                for i in 0..N {
                    b[(i, i)] = 1.0;
                    b[(i, N)] = -1.0;
                    b[(N + i, i)] = -1.0;
                    b[(N + i, N)] = -1.0;
                }
                for i in 0..=N {
                    b[(2 * N + i, i)] = 1.0;
                    b[(3 * N + 1 + i, i)] = -1.0;
                }
                assert_eq!(qp.g, b);
                assert!(qp.h.rows(0, 2 * N).iter().all(|&v| v == 0.0));
                assert_eq!(qp.h[3 * N], f64::INFINITY, "k <= varpi");
                assert_eq!(qp.h[4 * N + 1], 0.0, "-k <= -0");
                assert!(qp.lower.iter().all(|&v| v == f64::NEG_INFINITY));
                assert!(qp.upper.iter().all(|&v| v == f64::INFINITY));
            }
            SchemeSpec::VelocityRmp {
                upsilon: Some(_), ..
            } => {
                // Bound conversion on: finite joint bounds with zeta- < zeta+.
                assert!(qp.h.is_empty());
                for i in 0..N {
                    assert!(qp.lower[i].is_finite() && qp.upper[i].is_finite());
                    assert!(qp.lower[i] < qp.upper[i], "{}", spec.display_name());
                }
            }
            _ => {
                assert!(qp.lower.iter().all(|&v| v == f64::NEG_INFINITY));
                assert!(qp.upper.iter().all(|&v| v == f64::INFINITY));
            }
        }
    }
}

#[test]
fn jia2019_objective_data() {
    let (th, thd, _) = state();
    for (phi, tau) in [(1.0, 0.0), (0.2, 0.0), (0.2, 0.4)] {
        let s = make(&vltco(phi, tau));
        let mut qp = s.new_qp();
        // At theta = theta0 the joint part of q vanishes.
        s.build(0.7, theta0().as_slice(), thd.as_slice(), &mut qp);
        assert!(qp.q.iter().all(|&v| v == 0.0), "{}: q = {}", s.name(), qp.q);
        // D = diag((phi + tau) I, 1 - phi - tau).
        let mut d = DMatrix::zeros(N + 1, N + 1);
        for i in 0..N {
            d[(i, i)] = phi + tau;
        }
        d[(N, N)] = 1.0 - phi - tau;
        assert_eq!(qp.p, d);
        // Elsewhere q = [tau Lambda (theta - theta0); 0].
        s.build(0.7, th.as_slice(), thd.as_slice(), &mut qp);
        for i in 0..N {
            assert!((qp.q[i] - tau * 20.0 * (th[i] - theta0()[i])).abs() < 1e-14);
        }
        assert_eq!(qp.q[N], 0.0);
        // b = rdot* (no position feedback).
        assert_eq!(
            qp.b,
            nalgebra::DVector::from_column_slice(path().at(0.7).rdot.as_slice())
        );
    }
    assert_eq!(vltco_name(1.0, 0.0), "MVN");
    assert_eq!(vltco_name(0.2, 0.0), "MVN-INVM");
    assert_eq!(vltco_name(0.2, 0.4), "VLTCO");
}

#[test]
fn merged_bounds_tighten_near_joint_limits() {
    let s = make(&vltco(0.2, 0.4));
    let z = make(&SchemeSpec::Cmco {
        eta: 0.2,
        delta: 0.4,
        upsilon: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        tau: 10.0,
    });
    let lim = planar().limits().clone();
    let mut qp = s.new_qp();
    let mut zqp = z.new_qp();
    // Joint 2 (index 1): limits [-1, 2.5], velocity +-1.5, kappa = 20 -> switch 0.075 from the limit.
    let mut prev_hi = f64::INFINITY;
    for k in 0..=400 {
        let d = 0.5 * (1.0 - k as f64 / 400.0); // distance to the upper limit: 0.5 -> 0
        let mut th = theta0();
        th[1] = lim.theta_max[1] - d;
        s.build(0.0, th.as_slice(), th.as_slice(), &mut qp);
        let hi = qp.upper[1];
        assert!(hi <= 1.5, "upper bound {hi} exceeds the velocity limit");
        assert!(
            hi <= prev_hi + 1e-15,
            "upper bound grows as the joint nears its limit"
        );
        assert!(
            (hi - (20.0 * d).min(1.5)).abs() < 1e-12,
            "d = {d}: zeta+ = {hi}"
        );
        assert!(
            qp.lower[1] >= -1.5 && qp.lower[1] == -1.5,
            "far from the lower limit"
        );
        prev_hi = hi;
        // zhong2021's rows carry the same bounds: h = [0; zeta+; varpi; -zeta-; 0].
        z.build(0.0, th.as_slice(), th.as_slice(), &mut zqp);
        assert!((zqp.h[2 * N + 1] - hi).abs() < 1e-12);
        assert!((zqp.h[3 * N + 1 + 1] + qp.lower[1]).abs() < 1e-12);
    }
    assert_eq!(prev_hi, 0.0, "zeta+ must be 0 at the limit");
    // Beyond the limit the bound turns negative (pushes back); near the lower limit zeta- -> 0.
    let mut th = theta0();
    th[1] = lim.theta_max[1] + 0.01;
    s.build(0.0, th.as_slice(), th.as_slice(), &mut qp);
    assert!(qp.upper[1] < 0.0);
    for d in [0.5, 0.1, 0.05, 0.01, 0.0] {
        th[1] = lim.theta_min[1] + d;
        s.build(0.0, th.as_slice(), th.as_slice(), &mut qp);
        assert!(qp.lower[1] >= -1.5);
        assert!((qp.lower[1] - (-20.0 * d).max(-1.5)).abs() < 1e-12);
        assert_eq!(qp.upper[1], 1.5);
    }
    assert_eq!(qp.lower[1], 0.0);
}

#[test]
fn piecewise_bounds_equal_max_min_form() {
    let mut lim: JointLimits = planar().limits().clone();
    lim.theta_min[4] = f64::NEG_INFINITY;
    lim.theta_max[4] = f64::INFINITY;
    lim.thetadot_max[5] = 0.8;
    for k in 0..=2000 {
        let x = -4.0 + 8.0 * k as f64 / 2000.0;
        let th = V::repeat(x);
        for gain in [20.0, 2.0, 100.0] {
            let (mut lo, mut hi, mut plo, mut phi) =
                (V::zeros(), V::zeros(), V::zeros(), V::zeros());
            for i in 0..N {
                (lo[i], hi[i]) = merged_bound(&lim, i, th[i], gain);
                (plo[i], phi[i]) = piecewise_bound(&lim, i, th[i], gain);
            }
            for i in 0..N {
                assert!(
                    (lo[i] - plo[i]).abs() < 1e-12,
                    "x = {x}, joint {i}: {} vs {}",
                    lo[i],
                    plo[i]
                );
                assert!(
                    (hi[i] - phi[i]).abs() < 1e-12,
                    "x = {x}, joint {i}: {} vs {}",
                    hi[i],
                    phi[i]
                );
                assert!(hi[i] <= lim.thetadot_max[i] && lo[i] >= lim.thetadot_min[i]);
            }
            assert_eq!(
                (lo[4], hi[4]),
                (-1.5, 1.5),
                "unlimited joint keeps the velocity limits"
            );
        }
    }
}

#[test]
fn exact_optimum_tracks_the_task_velocity() {
    let (th_off, thd, _) = state();
    for spec in specs() {
        let s = make(&spec);
        let mut qp = s.new_qp();
        for (t, th) in [
            (0.0, theta0()),
            (1.1, th_off),
            (2.6, th_off),
            (4.2, theta0()),
        ] {
            s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
            let (x, duals) = admm(&qp, 20_000);
            let kkt = qp.kkt_residuals(&x, &duals);
            assert!(
                kkt.max() < 1e-7,
                "{} t = {t}: ADMM not converged: {kkt:?}",
                spec.display_name()
            );
            let j = planar().jacobian_n(&th);
            let xd = V::from_iterator(x.iter().take(N).copied());
            let pp = path().at(t);
            let expected = match spec {
                SchemeSpec::Vltco { .. } | SchemeSpec::Cmco { .. } => pp.rdot,
                SchemeSpec::FiniteTimeRmp { k_p, .. }
                | SchemeSpec::ZnnRmp { k_p, .. }
                | SchemeSpec::VelocityRmp { k_p, .. } => {
                    pp.rdot + (pp.r - planar().position_n(&th)) * k_p
                }
                SchemeSpec::HlJdf { rho_v, rho_p, .. } => {
                    pp.rddot - planar().jacobian_dot_n(&th, &thd) * thd
                        + (pp.rdot - j * thd) * rho_v
                        + (pp.r - planar().position_n(&th)) * rho_p
                }
                SchemeSpec::Composed(_) => unreachable!("the papers' specs are presets"),
            };
            let res: Vector3<f64> = j * xd - expected;
            assert!(
                res.norm() < 1e-7,
                "{} t = {t}: |J x - b*| = {}",
                spec.display_name(),
                res.norm()
            );
            // Equality-only QPs: the KKT linear system gives the same optimum.
            if qp.h.is_empty() {
                let xk = kkt_solve(&qp);
                assert!(
                    (&xk - &x).amax() < 1e-6,
                    "{}: ADMM vs KKT {}",
                    spec.display_name(),
                    (&xk - &x).amax()
                );
            }
            // Velocity-level schemes with bounds: the optimum respects the merged limits.
            if matches!(spec, SchemeSpec::Vltco { .. }) {
                let lim = planar().limits().clone();
                for i in 0..N {
                    assert!(
                        x[i] <= lim.thetadot_max[i] + 1e-8 && x[i] >= lim.thetadot_min[i] - 1e-8
                    );
                }
                // p = |thetadot|_inf when the INVM term has weight.
                if let SchemeSpec::Vltco { phi, tau, .. } = spec {
                    if phi + tau < 1.0 {
                        assert!(
                            (x[N] - xd.amax()).abs() < 1e-6,
                            "p = {} vs {}",
                            x[N],
                            xd.amax()
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn mvn_optimum_is_the_minimum_norm_solution() {
    // MVN with inactive bounds: thetadot = J^+ rdot*.
    let s = make(&SchemeSpec::Vltco {
        phi: 1.0,
        tau: 0.0,
        kappa: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        mu: 5.0,
    });
    let mut qp = s.new_qp();
    let t = 1.7;
    s.build(t, theta0().as_slice(), theta0().as_slice(), &mut qp);
    let (x, _) = admm(&qp, 20_000);
    let j = planar().jacobian_n(&theta0());
    let pinv = j.transpose() * (j * j.transpose()).try_inverse().unwrap();
    let want = pinv * path().at(t).rdot;
    for i in 0..N {
        assert!((x[i] - want[i]).abs() < 1e-6, "{} vs {}", x[i], want[i]);
    }
}

#[test]
fn zhang2018_weight_is_spd_and_torque_is_the_dynamics() {
    let (th, thd, thdd) = state();
    for zeta in [0.0, 0.6, 0.8, 1.0] {
        let s = make(&SchemeSpec::HlJdf {
            zeta,
            alpha: 20.0,
            beta: 20.0,
            rho_v: 20.0,
            rho_p: 20.0,
        });
        let mut qp = s.new_qp();
        s.build(2.0, th.as_slice(), thd.as_slice(), &mut qp);
        assert_eq!(qp.p, qp.p.transpose());
        let eig = qp.p.clone().symmetric_eigenvalues();
        assert!(eig.min() > 1e-3, "zeta = {zeta}: eigenvalues {eig}");
        let h = planar().inertia_n(&th);
        let want_w = nalgebra::SMatrix::<f64, N, N>::identity() * zeta + h * h * (1.0 - zeta);
        assert!((&qp.p - want_w).amax() < 1e-12);
        // eta = zeta sigma + (1 - zeta) H'(c + g).
        let sigma = thd * 40.0 + (th - theta0()) * 400.0;
        let cg = planar().coriolis_n(&th, &thd) + planar().gravity_n(&th);
        let eta = sigma * zeta + h.transpose() * cg * (1.0 - zeta);
        for i in 0..N {
            assert!((qp.q[i] - eta[i]).abs() < 1e-12);
        }
        let mut tau = V::zeros();
        assert!(s.torque(
            th.as_slice(),
            thd.as_slice(),
            thdd.as_slice(),
            tau.as_mut_slice()
        ));
        assert!((tau - (h * thdd + cg)).amax() < 1e-14);
    }
    assert_eq!(hl_jdf_name(0.0), "MTN");
    assert_eq!(hl_jdf_name(0.6), "HL-JDF");
    // Schemes without dynamics report no torque.
    let k = make(&SchemeSpec::ZnnRmp { mu: 1.0, k_p: 1.0 });
    let mut tau = V::repeat(7.0);
    assert!(!k.torque(
        th.as_slice(),
        thd.as_slice(),
        thdd.as_slice(),
        tau.as_mut_slice()
    ));
    assert_eq!(tau, V::repeat(7.0));
}

/// kong2019's c = |e|^alpha sgn(e) elementwise, e = theta - theta*0, smoothed over |e| ~ delta:
/// the sign-power term of the finite-time scheme.
fn finite_time_c(theta: &V, star: &V, alpha: f64, delta: f64) -> V {
    (theta - star).map(|e| settings::sign_power(e, alpha, delta))
}

#[test]
fn kong2019_smoothed_c_is_odd_monotone_and_close_to_the_sign_power() {
    let star = theta0();
    let (alpha, delta) = (0.1, 1e-6);
    let c = |e: f64| finite_time_c(&(star + V::repeat(e)), &star, alpha, delta)[0];
    let mut prev = f64::NEG_INFINITY;
    for k in -400..=400 {
        let e = (k as f64 / 40.0).powi(9).copysign(k as f64) * 1e-9;
        let v = c(e);
        assert!((v + c(-e)).abs() <= 1e-15 * v.abs().max(1.0), "odd at {e}");
        assert!(v >= prev, "monotone at {e}");
        prev = v;
        if e.abs() >= 10.0 * delta {
            let exact = e.abs().powf(alpha).copysign(e);
            assert!(
                ((v - exact) / exact).abs() < 5e-3,
                "within 0.5 % of |e|^alpha at {e}"
            );
        }
    }
    // Slope at 0 is delta^(alpha - 1): finite, so integrators can step through e = 0.
    let h = 1e-12;
    let slope = (c(h) - c(-h)) / (2.0 * h);
    assert!(
        (slope / delta.powf(alpha - 1.0) - 1.0).abs() < 1e-3,
        "slope {slope}"
    );
}

#[test]
fn kong2019_c_is_odd_and_zero_at_the_reference() {
    let star = theta0();
    let alpha = 0.1;
    assert_eq!(finite_time_c(&star, &star, alpha, 0.0), V::zeros());
    for e in [
        V::from([0.3, -0.2, 1e-9, -2.0, 0.5, 1e-3]),
        V::from([-1.0, 0.7, 0.01, 0.0, -3e-5, 2.5]),
    ] {
        let cp = finite_time_c(&(star + e), &star, alpha, 0.0);
        let cm = finite_time_c(&(star - e), &star, alpha, 0.0);
        assert!((cp + cm).amax() < 1e-15, "c not odd");
        let e = (star + e) - star; // the difference the scheme actually sees
        for i in 0..N {
            assert!((cp[i].abs() - e[i].abs().powf(alpha)).abs() < 1e-15);
            assert!(cp[i] * e[i] >= 0.0, "c has the sign of e");
        }
    }
    // make() takes theta0() = star as the reference.
    let ft = make(&SchemeSpec::FiniteTimeRmp {
        beta_theta: 1.0,
        k_p: 1.0,
        alpha,
    });
    let znn = make(&SchemeSpec::ZnnRmp { mu: 2.0, k_p: 1.0 });
    let mut qp = ft.new_qp();
    for s in [ft.as_ref(), znn.as_ref()] {
        s.build(0.5, star.as_slice(), star.as_slice(), &mut qp);
        assert!(qp.q.iter().all(|&v| v == 0.0));
        assert_eq!(qp.p, DMatrix::identity(N, N));
    }
    let th = star + V::from([0.1, 0.0, 0.0, 0.0, 0.0, -0.5]);
    znn.build(0.5, th.as_slice(), th.as_slice(), &mut qp);
    assert!((qp.q[5] + 1.0).abs() < 1e-14 && (qp.q[0] - 0.2).abs() < 1e-14);
    ft.build(0.5, th.as_slice(), th.as_slice(), &mut qp);
    // The smoothing (delta = 1e-6) changes c by a relative ~0.45 (delta/e)^2 = 2e-12 at e = 0.5.
    assert!((qp.q[5] + 0.5_f64.powf(0.1)).abs() < 1e-11);
    // build_dot is finite at e = 0 (slope delta^(alpha - 1) of the smoothed c) and exact away from it.
    let thd = V::repeat(0.3);
    let mut dot = ft.new_qp();
    ft.build_dot(
        0.5,
        star.as_slice(),
        thd.as_slice(),
        thd.as_slice(),
        &mut dot,
        &mut ft.new_dot_scratch(),
    );
    assert!(dot.q.iter().all(|v| v.is_finite()));
    assert!((dot.q[0] - 1e-6_f64.powf(-0.9) * 0.3).abs() < 1e-6 * dot.q[0].abs());
}

/// dQP/dt by the five-point stencil (error O(h^4)) along the same motion.
fn stencil_dot(s: &dyn Scheme, t: f64, th: &V, thd: &V, thdd: &V, h: f64) -> Qp {
    let accel = s.level() == Level::Acceleration;
    let at = |k: f64| {
        let mut qp = s.new_qp();
        let th_k = th + thd * (k * h);
        let thd_k = if accel { thd + thdd * (k * h) } else { *thd };
        s.build(t + k * h, th_k.as_slice(), thd_k.as_slice(), &mut qp);
        qp
    };
    let (m2, m1, p1, p2) = (at(-2.0), at(-1.0), at(1.0), at(2.0));
    let mut out = s.new_qp();
    let mut tmp = s.new_qp();
    // (-f(2) + 8 f(1) - 8 f(-1) + f(-2)) / 12h = [8 (f1 - f-1)/2 - (f2 - f-2)/4 ] ... via two quotients.
    qp::difference_quotient(&p1, &m1, 2.0 * h, &mut out);
    qp::difference_quotient(&p2, &m2, 4.0 * h, &mut tmp);
    let comb = |o: &mut [f64], t: &[f64]| {
        for (a, b) in o.iter_mut().zip(t) {
            *a = (4.0 * *a - *b) / 3.0;
        }
    };
    comb(out.p.as_mut_slice(), tmp.p.as_slice());
    comb(out.q.as_mut_slice(), tmp.q.as_slice());
    comb(out.a.as_mut_slice(), tmp.a.as_slice());
    comb(out.b.as_mut_slice(), tmp.b.as_slice());
    comb(out.g.as_mut_slice(), tmp.g.as_slice());
    comb(out.h.as_mut_slice(), tmp.h.as_slice());
    comb(out.lower.as_mut_slice(), tmp.lower.as_slice());
    comb(out.upper.as_mut_slice(), tmp.upper.as_slice());
    out
}

#[test]
fn build_dot_matches_a_higher_order_difference() {
    let (th, thd, thdd) = state();
    // A second state where joint 2 sits on the kappa branch of its upper bound (2.45: 20 * 0.05
    // = 1.0 < 1.5), so the bound's derivative is -kappa thetadot_2, not 0.
    let mut th_near = th;
    th_near[1] = 2.45;
    for spec in specs().into_iter().chain(common::composed_specs()) {
        let s = make(&spec);
        for (t, th) in [(1.3, th), (3.7, th_near)] {
            let mut dot = s.new_qp();
            let mut scratch = s.new_dot_scratch();
            s.build_dot(
                t,
                th.as_slice(),
                thd.as_slice(),
                thdd.as_slice(),
                &mut dot,
                &mut scratch,
            );
            let reference = stencil_dot(&*s, t, &th, &thd, &thdd, 1e-3);
            let d = dot.max_rel_diff(&reference);
            assert!(
                d < 1e-6,
                "{} t = {t}: build_dot off by {d}",
                spec.display_name()
            );
            // The derivative is not trivially zero.
            assert!(dot.b.amax() > 0.0);
            if t == 3.7 && matches!(spec, SchemeSpec::Vltco { .. }) {
                assert!(
                    (dot.upper[1] + 20.0 * thd[1]).abs() < 1e-12,
                    "zeta+ dot = {}",
                    dot.upper[1]
                );
            }
            if t == 3.7 && matches!(spec, SchemeSpec::Cmco { .. }) {
                assert!((dot.h[2 * N + 1] + 20.0 * thd[1]).abs() < 1e-12);
            }
            // The default central difference agrees with the analytic overrides too.
            let mut fd = s.new_qp();
            let h = default_step(s.level(), thd.as_slice(), thdd.as_slice());
            central_difference(
                &*s,
                t,
                th.as_slice(),
                thd.as_slice(),
                thdd.as_slice(),
                h,
                &mut fd,
                &mut scratch,
            );
            let d = fd.max_rel_diff(&reference);
            assert!(
                d < 1e-6,
                "{} t = {t}: central difference off by {d}",
                spec.display_name()
            );
        }
    }
}

#[test]
fn infinite_entries_have_zero_derivative() {
    let s = make(&SchemeSpec::Cmco {
        eta: 0.2,
        delta: 0.4,
        upsilon: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        tau: 10.0,
    });
    let (th, thd, thdd) = state();
    let mut fd = s.new_qp();
    let mut scratch = QpDotScratch::new(s.dims(), N);
    central_difference(
        &*s,
        1.0,
        th.as_slice(),
        thd.as_slice(),
        thdd.as_slice(),
        1e-5,
        &mut fd,
        &mut scratch,
    );
    assert_eq!(fd.h[3 * N], 0.0);
    assert!(fd.lower.iter().chain(fd.upper.iter()).all(|&v| v == 0.0));
    assert!(fd.h.iter().all(|v| v.is_finite()));
}

/// The tracking term keeps f(theta), J and the path point of its last evaluation with their
/// instant (an observer asks for the QP again at the instant a right-hand side just built it):
/// a QP asked again at one instant, after its derivative there and after another instant, is
/// bit for bit the QP of a scheme that never saw the instant.
#[test]
fn a_qp_asked_again_at_one_instant_is_a_fresh_ones() {
    let (th, thd, thdd) = state();
    let t = 1.3;
    for spec in specs() {
        let name = spec.display_name();
        let fresh = {
            let s = make(&spec);
            let mut qp = s.new_qp();
            s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
            qp
        };
        let s = make(&spec);
        let mut scratch = s.new_dot_scratch();
        let (mut qp, mut dot) = (s.new_qp(), s.new_qp());
        s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
        let again = |qp: &mut Qp| s.build(t, th.as_slice(), thd.as_slice(), qp);
        let mut after_dot = s.new_qp();
        s.build_dot(
            t,
            th.as_slice(),
            thd.as_slice(),
            thdd.as_slice(),
            &mut dot,
            &mut scratch,
        );
        again(&mut after_dot);
        let mut after_another = s.new_qp();
        s.build(t + 0.1, (th * 1.01).as_slice(), thd.as_slice(), &mut qp);
        again(&mut after_another);
        for (when, other) in [
            ("after its derivative", &after_dot),
            ("after another instant", &after_another),
        ] {
            for (what, a, b) in [
                ("P", fresh.p.as_slice(), other.p.as_slice()),
                ("q", fresh.q.as_slice(), other.q.as_slice()),
                ("A", fresh.a.as_slice(), other.a.as_slice()),
                ("b", fresh.b.as_slice(), other.b.as_slice()),
            ] {
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(a), bits(b), "{name}: {what} {when}");
            }
        }
    }
}

#[test]
fn dims_constant_along_a_run() {
    let (_, thd, _) = state();
    for spec in specs() {
        let s = make(&spec);
        let dims = s.dims();
        let mut qp = s.new_qp();
        let mut dot = s.new_qp();
        let mut scratch = s.new_dot_scratch();
        let mut th = theta0();
        for k in 0..=50 {
            let t = path().duration() * k as f64 / 50.0;
            s.build(t, th.as_slice(), thd.as_slice(), &mut qp);
            s.build_dot(
                t,
                th.as_slice(),
                thd.as_slice(),
                thd.as_slice(),
                &mut dot,
                &mut scratch,
            );
            assert_eq!(qp.dims(), dims);
            assert_eq!(s.dims(), dims);
            assert_eq!(dot.dims(), dims);
            for v in
                qp.p.iter()
                    .chain(qp.q.iter())
                    .chain(qp.a.iter())
                    .chain(qp.b.iter())
                    .chain(qp.g.iter())
            {
                assert!(v.is_finite(), "{}", spec.display_name());
            }
            assert!(qp
                .h
                .iter()
                .chain(qp.lower.iter())
                .chain(qp.upper.iter())
                .all(|v| !v.is_nan()));
            for v in dot
                .p
                .iter()
                .chain(dot.q.iter())
                .chain(dot.b.iter())
                .chain(dot.h.iter())
            {
                assert!(v.is_finite(), "{}", spec.display_name());
            }
            th += thd * 0.02;
        }
    }
}

// ---- the experiment-file spec ----

#[test]
fn spec_parses_every_kind() {
    let cases = [
        ("kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0", "VLTCO (phi=0.2, tau=0.4)"),
        ("kind = \"jia2019\"\nphi = 1.0\ntau = 0.0\nkappa = 20.0\nlambda = 20.0", "MVN (phi=1, tau=0)"),
        ("kind = \"jia2019\"\nphi = 0.2\ntau = 0.0\nkappa = 20.0\nlambda = 20.0", "MVN-INVM (phi=0.2, tau=0)"),
        ("kind = \"zhong2021\"\neta = 0.1\ndelta = 0.8\nupsilon = 20.0", "CMCO (eta=0.1, delta=0.8)"),
        ("kind = \"zhang2018\"\nzeta = 0.0\nalpha = 20.0\nbeta = 20.0\nrho_v = 20.0\nrho_p = 20.0", "MTN (zeta=0)"),
        ("kind = \"zhang2018\"\nzeta = 0.6\nalpha = 20.0\nbeta = 20.0\nrho_v = 20.0\nrho_p = 20.0", "HL-JDF (zeta=0.6)"),
        ("kind = \"kong2019-finite-time\"\nbeta_theta = 1.0\nk_p = 1.0\nalpha = 0.1", "finite-time (beta_theta=1, alpha=0.1)"),
        ("kind = \"kong2019-znn\"\nmu = 1.0\nk_p = 1.0", "ZNN (mu=1)"),
    ];
    for (text, name) in cases {
        let spec: SchemeSpec = toml::from_str(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(spec.display_name(), name);
        // Round trip.
        let back: SchemeSpec = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
        assert_eq!(back, spec);
        assert!(make(&spec).name().len() > 1);
    }
    let z: SchemeSpec =
        toml::from_str("kind = \"zhong2021\"\neta = 0.1\ndelta = 0.8\nupsilon = 20.0").unwrap();
    assert_eq!(
        z,
        SchemeSpec::Cmco {
            eta: 0.1,
            delta: 0.8,
            upsilon: 20.0,
            lambda: 20.0,
            rmp: RmpReading::Printed,
            tau: 10.0
        }
    );
}

#[test]
fn spec_rejects_unknown_and_missing_fields() {
    assert!(toml::from_str::<SchemeSpec>(
        "kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0\nupsilon = 5.0"
    )
    .is_err());
    assert!(
        toml::from_str::<SchemeSpec>("kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0")
            .is_err()
    );
    assert!(toml::from_str::<SchemeSpec>("kind = \"kong2019\"\nmu = 1.0\nk_p = 1.0").is_err());
}

#[test]
fn build_scheme_reports_clear_errors() {
    let r = robot();
    let zhang = SchemeSpec::HlJdf {
        zeta: 0.6,
        alpha: 20.0,
        beta: 20.0,
        rho_v: 20.0,
        rho_p: 20.0,
    };
    let err = build_scheme(&zhang, r.clone(), None, path(), theta0().as_slice())
        .err()
        .unwrap();
    assert_eq!(err, SchemeError::MissingDynamics { scheme: "hl-jdf" });
    assert!(err.to_string().contains("dynamics"), "{err}");
    let _: &dyn std::error::Error = &err;

    let bad = SchemeSpec::Vltco {
        phi: 0.8,
        tau: 0.4,
        kappa: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        mu: 5.0,
    };
    let err = build_scheme(&bad, r.clone(), None, path(), theta0().as_slice())
        .err()
        .unwrap();
    assert!(err.to_string().contains("'tau'"), "{err}");
    let bad = SchemeSpec::Cmco {
        eta: 0.2,
        delta: 0.4,
        upsilon: -1.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        tau: 10.0,
    };
    let err = build_scheme(&bad, r.clone(), None, path(), theta0().as_slice())
        .err()
        .unwrap();
    assert!(err.to_string().contains("'upsilon'"), "{err}");
    let bad = SchemeSpec::FiniteTimeRmp {
        beta_theta: 1.0,
        k_p: f64::NAN,
        alpha: 0.1,
    };
    let err = build_scheme(&bad, r.clone(), None, path(), theta0().as_slice())
        .err()
        .unwrap();
    assert!(err.to_string().contains("'k_p'"), "{err}");
    let bad = SchemeSpec::HlJdf {
        zeta: 1.5,
        alpha: 20.0,
        beta: 20.0,
        rho_v: 20.0,
        rho_p: 20.0,
    };
    let dynamics: Arc<dyn Dynamics> = r.clone();
    let err = build_scheme(&bad, r.clone(), Some(dynamics), path(), theta0().as_slice())
        .err()
        .unwrap();
    assert!(err.to_string().contains("'zeta'"), "{err}");

    // Non-dynamics schemes do not need dynamics.
    for spec in specs()
        .into_iter()
        .filter(|s| !matches!(s, SchemeSpec::HlJdf { .. }))
    {
        assert!(build_scheme(&spec, r.clone(), None, path(), theta0().as_slice()).is_ok());
    }
}

/// A random state theta near theta0 (deterministic LCG).
fn random_theta(seed: u64) -> V {
    let mut x = seed;
    V::from_fn(|i, _| {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        theta0()[i] + ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5)
    })
}

fn vltco(phi: f64, tau: f64) -> SchemeSpec {
    SchemeSpec::Vltco {
        phi,
        tau,
        kappa: 20.0,
        lambda: 20.0,
        rmp: RmpReading::Printed,
        mu: 5.0,
    }
}

fn jia(tau: f64, rmp: RmpReading, mu: f64) -> SchemeSpec {
    SchemeSpec::Vltco {
        phi: 0.2,
        tau,
        kappa: 20.0,
        lambda: 20.0,
        rmp,
        mu,
    }
}

fn zhong(delta: f64, rmp: RmpReading, tau: f64) -> SchemeSpec {
    SchemeSpec::Cmco {
        eta: 0.1,
        delta,
        upsilon: 20.0,
        lambda: 20.0,
        rmp,
        tau,
    }
}

#[test]
fn rmp_readings_set_the_linear_term_as_the_expansion_predicts() {
    let readings = [
        RmpReading::Printed,
        RmpReading::Expansion,
        RmpReading::TextGain,
    ];
    // At Lambda = 20 and mu = 5: 20, 10 and 5 (times the weight).
    let want_k = [20.0, 10.0, 5.0];
    for (reading, &k) in readings.iter().zip(&want_k) {
        assert_eq!(reading.coefficient(20.0, 5.0), k, "{reading:?}");
    }
    for seed in 1..4u64 {
        let theta = random_theta(seed);
        let t = 0.9 + seed as f64;
        for (&reading, &k) in readings.iter().zip(&want_k) {
            // jia2019: g = [tau k (theta - theta0); 0].
            let tau = 0.4;
            let s = make(&jia(tau, reading, 5.0));
            let mut qp = s.new_qp();
            s.build(t, theta.as_slice(), theta.as_slice(), &mut qp);
            for i in 0..N {
                let want = tau * k * (theta[i] - theta0()[i]);
                assert!(
                    (qp.q[i] - want).abs() <= 1e-15 * want.abs().max(1.0),
                    "jia2019 {reading:?}: g[{i}] = {} vs {want}",
                    qp.q[i]
                );
            }
            assert_eq!(qp.q[N], 0.0);
            // zhong2021 with tau = 5 for the text reading: g = [delta k (theta - theta0); 0].
            let delta = 0.8;
            let s = make(&zhong(delta, reading, 5.0));
            let mut qp = s.new_qp();
            s.build(t, theta.as_slice(), theta.as_slice(), &mut qp);
            for i in 0..N {
                let want = delta * k * (theta[i] - theta0()[i]);
                assert!(
                    (qp.q[i] - want).abs() <= 1e-15 * want.abs().max(1.0),
                    "zhong2021 {reading:?}: g[{i}] = {} vs {want}",
                    qp.q[i]
                );
            }
            assert_eq!(qp.q[N], 0.0);
        }
    }
    // The default reading is the printed one, bit for bit, and the weight-free parts agree.
    let theta = random_theta(7);
    let mut a = make(&jia(0.4, RmpReading::Printed, 5.0)).new_qp();
    let mut b = a.clone();
    make(&jia(0.4, RmpReading::Printed, 5.0)).build(
        2.0,
        theta.as_slice(),
        theta.as_slice(),
        &mut a,
    );
    let file = "kind = \"vltco\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0";
    let direct = make(&toml::from_str::<SchemeSpec>(file).unwrap());
    direct.build(2.0, theta.as_slice(), theta.as_slice(), &mut b);
    assert_eq!(a.q, b.q);
    assert_eq!(a.p, b.p);
    let mut c = a.clone();
    make(&jia(0.4, RmpReading::Expansion, 5.0)).build(
        2.0,
        theta.as_slice(),
        theta.as_slice(),
        &mut c,
    );
    assert_eq!(a.p, c.p);
    assert_eq!(a.a, c.a);
    assert_ne!(a.q, c.q);
}

#[test]
fn rmp_reading_fields_read_display_and_validate() {
    // Existing files (no rmp, no mu) read as the printed reading with the defaults.
    let old: SchemeSpec =
        toml::from_str("kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0")
            .unwrap();
    assert_eq!(old, jia(0.4, RmpReading::Printed, 5.0));
    assert_eq!(old.display_name(), "VLTCO (phi=0.2, tau=0.4)");
    // Defaults are left out when written.
    let text = toml::to_string(&old).unwrap();
    assert!(!text.contains("rmp") && !text.contains("mu"), "{text}");
    let z: SchemeSpec =
        toml::from_str("kind = \"zhong2021\"\neta = 0.1\ndelta = 0.8\nupsilon = 20.0").unwrap();
    assert_eq!(z, zhong(0.8, RmpReading::Printed, 10.0));
    assert_eq!(z.display_name(), "CMCO (eta=0.1, delta=0.8)");
    assert!(!toml::to_string(&z).unwrap().contains("tau"));

    let e: SchemeSpec = toml::from_str(
        "kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0\nrmp = \"expansion\"",
    )
    .unwrap();
    assert_eq!(e, jia(0.4, RmpReading::Expansion, 5.0));
    assert_eq!(e.display_name(), "VLTCO (phi=0.2, tau=0.4, rmp=expansion)");
    let m: SchemeSpec = toml::from_str(
        "kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0\nrmp = \"text-mu\"\nmu = 4.0",
    )
    .unwrap();
    assert_eq!(m, jia(0.4, RmpReading::TextGain, 4.0));
    assert_eq!(
        m.display_name(),
        "VLTCO (phi=0.2, tau=0.4, rmp=text-mu, mu=4)"
    );
    let zt: SchemeSpec = toml::from_str(
        "kind = \"zhong2021\"\neta = 0.1\ndelta = 0.8\nupsilon = 20.0\nrmp = \"text-tau\"\ntau = 5.0",
    )
    .unwrap();
    assert_eq!(zt, zhong(0.8, RmpReading::TextGain, 5.0));
    assert_eq!(
        zt.display_name(),
        "CMCO (eta=0.1, delta=0.8, rmp=text-tau, tau=5)"
    );
    for spec in [e, m, zt] {
        let back: SchemeSpec = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
        assert_eq!(back, spec);
    }
    assert!(toml::from_str::<SchemeSpec>(
        "kind = \"jia2019\"\nphi = 0.2\ntau = 0.4\nkappa = 20.0\nlambda = 20.0\nrmp = \"halved\""
    )
    .is_err());

    let r = robot();
    for mu in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = build_scheme(
            &jia(0.4, RmpReading::TextGain, mu),
            r.clone(),
            None,
            path(),
            theta0().as_slice(),
        )
        .err()
        .unwrap();
        assert!(err.to_string().contains("'mu'"), "{err}");
        let err = build_scheme(
            &zhong(0.8, RmpReading::TextGain, mu),
            r.clone(),
            None,
            path(),
            theta0().as_slice(),
        )
        .err()
        .unwrap();
        assert!(err.to_string().contains("'tau'"), "{err}");
    }
}
