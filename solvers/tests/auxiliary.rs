//! MVN's QP (the max-norm variable p unweighted, a singular P) through [`ExactPath`]: solved in
//! reduced form by the active set without a Clarabel fallback, certified, and equal to Clarabel
//! in thetadot and the objective; p* = |thetadot*|_inf, the smallest feasible p.

use nalgebra::DVector;
use solvers::{random_qp, AuxiliaryElimination, ExactPath, ExactSolver, Qp, QpShape};

/// Random MVN-shaped QPs per shape.
const N_QPS: u64 = 2_000;
/// Required agreement with Clarabel in thetadot (relative to max(1, |thetadot|_inf)) and the
/// objective (relative to 1 + |f|).
const AGREE_TOL: f64 = 1e-8;

/// A random QP of `shape` (jia2019: bounds on p; zhong2021: every bound a row of G) with p's
/// weight set to zero: P = diag(w I_6, 0), w in [0.05, 0.9), positive definite on thetadot.
fn mvn_qp(shape: QpShape, seed: u64) -> Qp {
    let mut qp = random_qp(shape, seed);
    let p = qp.q.len() - 1;
    qp.p[(p, p)] = 0.0;
    qp
}

/// The smallest p with |thetadot_i| <= p and p >= 0.
fn smallest_p(thetadot: &[f64]) -> f64 {
    thetadot.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

#[test]
fn mvn_qps_are_solved_reduced_certified_and_agree_with_clarabel() {
    for shape in [QpShape::Jia2019, QpShape::Zhong2021] {
        let (mut worst_x, mut worst_obj) = (0.0f64, 0.0f64);
        for seed in 0..N_QPS {
            let qp = mvn_qp(shape, seed);
            let what = format!("{shape:?} seed {seed}");
            let n = qp.q.len() - 1;
            let elimination = AuxiliaryElimination::recognise(&qp)
                .unwrap_or_else(|| panic!("{what}: p not recognised"));
            assert_eq!(elimination.variable(), n, "{what}");
            // The reduced P (thetadot's block) is positive definite: the active set's KKT
            // matrices are regular.
            assert!(
                elimination.reduced().p.clone().cholesky().is_some(),
                "{what}"
            );

            let mut path = ExactPath::new(&qp);
            let x = path.solve(&qp).expect("solved").clone();
            assert_eq!(path.stats.fallbacks, 0, "{what}: fell back to Clarabel");
            let reference = ExactSolver::new().solve(&qp).expect("Clarabel");
            let theta = x.rows(0, n);
            let theta_ref = reference.x.rows(0, n);
            let dx = (theta - theta_ref).amax() / theta_ref.amax().max(1.0);
            let (f, f_ref) = (qp.objective(&x), qp.objective(&reference.x));
            let dobj = (f - f_ref).abs() / (1.0 + f_ref.abs());
            assert!(dx <= AGREE_TOL, "{what}: |dthetadot| {dx:.2e}");
            assert!(dobj <= AGREE_TOL, "{what}: |dobj| {dobj:.2e}");
            assert!(qp.constraint_violation(&x) <= 1e-12, "{what}: infeasible");
            assert_eq!(x[n], smallest_p(theta.as_slice()), "{what}: p*");
            worst_x = worst_x.max(dx);
            worst_obj = worst_obj.max(dobj);
        }
        eprintln!("{shape:?}: max |dthetadot| {worst_x:.1e}, |dobj| {worst_obj:.1e}");
    }
}

#[test]
fn slowly_varying_mvn_qps_stay_on_the_active_set() {
    let mut qp = mvn_qp(QpShape::Jia2019, 7);
    let mut path = ExactPath::new(&qp);
    for k in 0..500 {
        let s = 1e-3 * k as f64;
        qp.b.iter_mut()
            .enumerate()
            .for_each(|(i, b)| *b += 1e-3 * (s + i as f64).sin());
        path.solve(&qp).expect("solved");
    }
    assert_eq!(path.stats.fallbacks, 0);
    assert!(path.stats.checks > 0);
    assert!(path.stats.check_max_dx <= AGREE_TOL, "{:?}", path.stats);
}

#[test]
fn weighted_or_coupled_variables_are_not_eliminated() {
    // p weighted (MVN-INVM, VLTCO): no elimination.
    let qp = random_qp(QpShape::Jia2019, 3);
    assert!(AuxiliaryElimination::recognise(&qp).is_none());
    // p unweighted but in an equality: no elimination.
    let mut qp = mvn_qp(QpShape::Jia2019, 3);
    let n = qp.q.len() - 1;
    qp.a[(0, n)] = 1.0;
    assert!(AuxiliaryElimination::recognise(&qp).is_none());
    // p unweighted with a positive coefficient in a coupled row (an upper limit that depends
    // on thetadot): no elimination.
    let mut qp = mvn_qp(QpShape::Jia2019, 3);
    qp.g[(0, n)] = 1.0;
    assert!(AuxiliaryElimination::recognise(&qp).is_none());
}

#[test]
fn a_finite_upper_bound_on_p_becomes_a_box_on_thetadot() {
    // varpi small enough to bind: |thetadot_i| <= varpi in the reduced QP, p* = varpi.
    let mut qp = mvn_qp(QpShape::Jia2019, 11);
    let n = qp.q.len() - 1;
    let free = ExactPath::new(&qp).solve(&qp).expect("solved").clone();
    let varpi = 0.9 * free[n];
    qp.upper[n] = varpi;
    let mut path = ExactPath::new(&qp);
    let x: DVector<f64> = path.solve(&qp).expect("solved").clone();
    assert_eq!(path.stats.fallbacks, 0);
    assert!((x[n] - varpi).abs() <= 1e-12);
    assert!(smallest_p(&x.as_slice()[..n]) <= varpi * (1.0 + 1e-12));
    let reference = ExactSolver::new().solve(&qp).expect("Clarabel");
    let dx = (x.rows(0, n) - reference.x.rows(0, n)).amax();
    assert!(dx <= AGREE_TOL, "|dthetadot| {dx:.2e}");
}
