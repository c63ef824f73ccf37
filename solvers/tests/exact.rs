//! The exact reference solver (Clarabel) and the seeded random QPs.

use nalgebra::{dmatrix, dvector, DMatrix, DVector};
use solvers::random_qp::{jia2019, rng_from_seed, zhong2021, VARPI};
use solvers::{cone_sizes, ConeSizes};
use solvers::{
    random_feasible, random_qp, solve_equality_kkt, ExactError, ExactSolver, ExactStatus, Qp,
    QpDims, QpShape,
};

/// Random QPs solved per shape.
const N_RANDOM: u64 = 250;
/// Required accuracy of Clarabel's answers in our own KKT residuals.
const KKT_TOL: f64 = 1e-7;

/// Solves `qp` and asserts the KKT residuals and feasibility; returns the solution's x.
fn solve_checked(solver: &mut ExactSolver, qp: &Qp, what: &str) -> DVector<f64> {
    let sol = solver.solve(qp).unwrap_or_else(|e| panic!("{what}: {e}"));
    assert_eq!(sol.status, ExactStatus::Solved, "{what}");
    let kkt = qp.kkt_residuals(&sol.x, &sol.duals);
    assert_eq!(kkt, sol.kkt, "{what}: reported residuals are not ours");
    assert!(kkt.max() <= KKT_TOL, "{what}: KKT residuals {kkt:?}");
    assert!(
        qp.constraint_violation(&sol.x) <= KKT_TOL,
        "{what}: infeasible"
    );
    assert!(
        (sol.objective - qp.objective(&sol.x)).abs() <= 1e-12 * (1.0 + sol.objective.abs()),
        "{what}"
    );
    sol.x
}

/// Whether a bound is active at x: a finite bound of `qp`, or an inequality row with a single
/// nonzero (a bound written as a row, as in zhong2021).
fn has_active_bound(qp: &Qp, x: &DVector<f64>) -> bool {
    let near = |slack: f64| slack.abs() < 1e-7;
    let rows = (0..qp.h.len())
        .filter(|&r| qp.g.row(r).iter().filter(|v| **v != 0.0).count() == 1)
        .any(|r| near(qp.h[r] - qp.g.row(r).dot(&x.transpose())));
    rows || (0..x.len()).any(|i| near(x[i] - qp.lower[i]) || near(qp.upper[i] - x[i]))
}

#[test]
fn random_qps_of_every_shape_satisfy_kkt() {
    let mut solver = ExactSolver::new();
    for shape in QpShape::ALL {
        let mut worst: f64 = 0.0;
        let mut active = 0usize;
        for seed in 0..N_RANDOM {
            let qp = random_qp(shape, seed);
            let x = solve_checked(&mut solver, &qp, &format!("{shape:?} seed {seed}"));
            worst = worst.max(
                qp.kkt_residuals(&x, &solver.solve(&qp).unwrap().duals)
                    .max(),
            );
            active += usize::from(has_active_bound(&qp, &x));
        }
        eprintln!("{shape:?}: worst KKT residual {worst:.2e}, {active} of {N_RANDOM} with an active bound");
        // Not vacuous: the bounds bind in a good share of the inequality-constrained QPs, not in all.
        if !shape.is_equality_only() {
            assert!(
                active as u64 > N_RANDOM / 10,
                "{shape:?}: only {active} QPs have an active bound"
            );
            assert!(
                (active as u64) < N_RANDOM,
                "{shape:?}: every QP has an active bound"
            );
        }
    }
}

#[test]
fn equality_only_shapes_match_the_kkt_linear_solve() {
    let mut solver = ExactSolver::new();
    for shape in [QpShape::Zhang2018, QpShape::Kong2019] {
        for seed in 0..N_RANDOM {
            let qp = random_qp(shape, seed);
            let x = solve_checked(&mut solver, &qp, &format!("{shape:?} seed {seed}"));
            let x_kkt = solve_equality_kkt(&qp).expect("nonsingular KKT system");
            let err = (&x - &x_kkt).amax();
            assert!(
                err <= 1e-8,
                "{shape:?} seed {seed}: |x_clarabel - x_kkt| = {err:e}"
            );
        }
    }
}

#[test]
fn general_random_qps_satisfy_kkt() {
    let mut solver = ExactSolver::new();
    for seed in 0..N_RANDOM {
        let nx = 1 + (seed % 9) as usize;
        let dims = QpDims {
            nx,
            n_eq: (seed / 9 % 3) as usize % (nx + 1),
            n_in: (seed / 27 % 5) as usize,
        };
        let qp = random_feasible(dims, seed);
        assert_eq!(qp.dims(), dims);
        solve_checked(
            &mut solver,
            &qp,
            &format!("random_feasible {dims:?} seed {seed}"),
        );
    }
}

#[test]
fn equality_kkt_solve_refuses_inequalities_and_bounds() {
    let qp = random_qp(QpShape::Jia2019, 1);
    assert!(solve_equality_kkt(&qp).is_none());
    let mut qp = random_qp(QpShape::Kong2019, 1);
    qp.upper[0] = 10.0;
    assert!(solve_equality_kkt(&qp).is_none());
}

/// Multipliers of one-variable QPs with a single active constraint, against hand-derived
/// values in the convention P x + q + A'lambda + G'mu - z_l + z_u = 0.
#[test]
fn dual_signs_follow_the_qp_convention() {
    let mut solver = ExactSolver::new();
    let one = |q: f64| {
        let mut qp = Qp::zeros(QpDims {
            nx: 1,
            n_eq: 0,
            n_in: 0,
        });
        qp.p[(0, 0)] = 1.0;
        qp.q[0] = q;
        qp
    };
    // min x^2/2 - 2x, x <= 1: x = 1, z_u = 1.
    let mut qp = one(-2.0);
    qp.upper[0] = 1.0;
    let s = solver.solve(&qp).unwrap();
    assert!(
        (s.x[0] - 1.0).abs() < 1e-8 && (s.duals.z_upper[0] - 1.0).abs() < 1e-8,
        "{s:?}"
    );
    assert_eq!(s.duals.z_lower[0], 0.0);
    // min x^2/2 + 2x, x >= -1: x = -1, z_l = 1.
    let mut qp = one(2.0);
    qp.lower[0] = -1.0;
    let s = solver.solve(&qp).unwrap();
    assert!(
        (s.x[0] + 1.0).abs() < 1e-8 && (s.duals.z_lower[0] - 1.0).abs() < 1e-8,
        "{s:?}"
    );
    assert_eq!(s.duals.z_upper[0], 0.0);
    // min x^2/2 - 2x, 2x <= 2: x = 1, mu = 1/2.
    let mut qp = one(-2.0);
    qp.g = dmatrix![2.0];
    qp.h = dvector![2.0];
    let s = solver.solve(&qp).unwrap();
    assert!(
        (s.x[0] - 1.0).abs() < 1e-8 && (s.duals.mu[0] - 0.5).abs() < 1e-8,
        "{s:?}"
    );
    // min x^2/2, 2x = 6: x = 3, lambda = -3/2.
    let mut qp = one(0.0);
    qp.a = dmatrix![2.0];
    qp.b = dvector![6.0];
    let s = solver.solve(&qp).unwrap();
    assert!(
        (s.x[0] - 3.0).abs() < 1e-8 && (s.duals.lambda[0] + 1.5).abs() < 1e-8,
        "{s:?}"
    );
    assert!((s.objective - 4.5).abs() < 1e-8);
}

/// x in R^2, min |x|^2/2.
fn two_var_qp() -> Qp {
    let mut qp = Qp::zeros(QpDims {
        nx: 2,
        n_eq: 0,
        n_in: 0,
    });
    qp.p = DMatrix::identity(2, 2);
    qp
}

#[test]
fn contradictory_equalities_are_primal_infeasible() {
    let mut qp = two_var_qp();
    qp.a = dmatrix![1.0, 1.0; 1.0, 1.0];
    qp.b = dvector![1.0, 2.0];
    let err = ExactSolver::new().solve(&qp).unwrap_err();
    assert!(matches!(err, ExactError::PrimalInfeasible(_)), "{err}");
}

#[test]
fn crossed_bounds_are_primal_infeasible() {
    let mut qp = two_var_qp();
    qp.lower[1] = 1.0;
    qp.upper[1] = -1.0;
    let err = ExactSolver::new().solve(&qp).unwrap_err();
    assert!(matches!(err, ExactError::PrimalInfeasible(_)), "{err}");
    assert!(err.to_string().contains("PrimalInfeasible"), "{err}");
}

#[test]
fn unbounded_objective_is_dual_infeasible() {
    let mut qp = two_var_qp();
    qp.p = DMatrix::zeros(2, 2);
    qp.q = dvector![1.0, 0.0];
    qp.upper[0] = 1.0;
    let err = ExactSolver::new().solve(&qp).unwrap_err();
    assert!(matches!(err, ExactError::DualInfeasible(_)), "{err}");
    assert!(err.to_string().contains("DualInfeasible"), "{err}");
}

#[test]
fn iteration_limit_is_reported_as_failure() {
    // Both attempts (see CLARABEL_TOLS) stop after one iteration.
    let mut solver = ExactSolver::new().with_max_iterations(1);
    let err = solver.solve(&random_qp(QpShape::Jia2019, 3)).unwrap_err();
    assert_eq!(
        err,
        ExactError::Failed {
            status: ExactStatus::MaxIterations,
            iterations: 2
        }
    );
    assert!(err.to_string().contains("MaxIterations"), "{err}");
}

#[test]
fn residuals_above_tolerance_are_inaccurate() {
    let mut solver = ExactSolver::new().with_kkt_tolerance(1e-300);
    match solver.solve(&random_qp(QpShape::Jia2019, 4)) {
        Err(ExactError::Inaccurate {
            status,
            kkt,
            tolerance,
        }) => {
            assert_eq!(status, ExactStatus::Solved);
            assert!(kkt.max() > tolerance);
        }
        other => panic!("expected Inaccurate, got {other:?}"),
    }
}

#[test]
fn malformed_data_is_rejected() {
    let mut solver = ExactSolver::new();
    let mut qp = two_var_qp();
    qp.q[0] = f64::NAN;
    assert!(matches!(solver.solve(&qp), Err(ExactError::InvalidData(_))));
    let mut qp = two_var_qp();
    qp.lower[0] = f64::INFINITY;
    assert!(matches!(solver.solve(&qp), Err(ExactError::InvalidData(_))));
    let mut qp = two_var_qp();
    qp.a = DMatrix::zeros(1, 3);
    qp.b = dvector![0.0];
    assert!(matches!(solver.solve(&qp), Err(ExactError::InvalidData(_))));
}

#[test]
fn infinite_bounds_and_rows_get_no_cone_rows() {
    // jia2019: 12 inequality rows, 6 + 1 lower bounds, 6 upper bounds on thetadot, and the
    // upper bound on p only when varpi is finite.
    let mut rng = rng_from_seed(7);
    let finite = jia2019(&mut rng, VARPI);
    assert_eq!(
        cone_sizes(&finite).unwrap(),
        ConeSizes {
            zero: 3,
            nonnegative: 26
        }
    );
    let infinite = jia2019(&mut rng, f64::INFINITY);
    assert_eq!(
        cone_sizes(&infinite).unwrap(),
        ConeSizes {
            zero: 3,
            nonnegative: 25
        }
    );
    // zhong2021: 26 inequality rows, no bounds.
    assert_eq!(
        cone_sizes(&zhong2021(&mut rng)).unwrap(),
        ConeSizes {
            zero: 3,
            nonnegative: 26
        }
    );
    // Equality-only shapes: no nonnegative rows at all.
    for shape in [QpShape::Zhang2018, QpShape::Kong2019] {
        assert_eq!(
            cone_sizes(&random_qp(shape, 1)).unwrap(),
            ConeSizes {
                zero: 3,
                nonnegative: 0
            }
        );
    }
    // An inequality with h = +inf is dropped too, and the solution is unchanged.
    let mut with_inf_row = finite.clone();
    with_inf_row.g = with_inf_row.g.insert_row(0, 1.0);
    with_inf_row.h = with_inf_row.h.insert_row(0, f64::INFINITY);
    assert_eq!(
        cone_sizes(&with_inf_row).unwrap(),
        ConeSizes {
            zero: 3,
            nonnegative: 26
        }
    );
    let mut solver = ExactSolver::new();
    let a = solver.solve(&finite).unwrap();
    let b = solver.solve(&with_inf_row).unwrap();
    assert!((&a.x - &b.x).amax() < 1e-9);
    assert_eq!(b.duals.mu[0], 0.0);
    // random_feasible: one row per finite bound.
    for seed in 0..20 {
        let qp = random_feasible(
            QpDims {
                nx: 6,
                n_eq: 2,
                n_in: 3,
            },
            seed,
        );
        let finite_bounds = qp
            .lower
            .iter()
            .chain(qp.upper.iter())
            .filter(|v| v.is_finite())
            .count();
        assert_eq!(
            cone_sizes(&qp).unwrap(),
            ConeSizes {
                zero: 2,
                nonnegative: 3 + finite_bounds
            }
        );
    }
}

/// Equivalent formulations of one QP must give the same x. Up to ~1e-8 rather than 1e-12:
/// where a constraint is weakly active an interior-point x is accurate to about the square
/// root of the duality gap (see the module docs of `exact`).
const SAME_QP_TOL: f64 = 1e-7;

#[test]
fn jia2019_with_infinite_varpi_matches_large_varpi() {
    // p = |thetadot|_inf at the optimum is far below VARPI, so the bound is inactive.
    let mut solver = ExactSolver::new();
    for seed in 0..N_RANDOM {
        let finite = jia2019(&mut rng_from_seed(seed), VARPI);
        let infinite = jia2019(&mut rng_from_seed(seed), f64::INFINITY);
        let (a, b) = (
            solver.solve(&finite).unwrap(),
            solver.solve(&infinite).unwrap(),
        );
        let err = (&a.x - &b.x).amax();
        assert!(err < SAME_QP_TOL, "seed {seed}: {err:e}");
    }
}

#[test]
fn zhong2021_rows_match_jia2019_bounds() {
    // zhong2021 draws the jia2019 data (varpi = VARPI) first and rewrites the bounds as rows
    // 12..19 (upper) and 19..26 (lower): same optimum, same multipliers.
    let mut solver = ExactSolver::new();
    for seed in 0..N_RANDOM {
        let bounded = jia2019(&mut rng_from_seed(seed), VARPI);
        let rows = zhong2021(&mut rng_from_seed(seed));
        assert_eq!(rows.p, bounded.p);
        let (a, b) = (
            solver.solve(&bounded).unwrap(),
            solver.solve(&rows).unwrap(),
        );
        let err = (&a.x - &b.x).amax();
        assert!(err < SAME_QP_TOL, "seed {seed}: x differs by {err:e}");
        let mu = &b.duals.mu;
        let dual_err = (&a.duals.mu - mu.rows(0, 12))
            .amax()
            .max((&a.duals.z_upper - mu.rows(12, 7)).amax())
            .max((&a.duals.z_lower - mu.rows(19, 7)).amax())
            .max((&a.duals.lambda - &b.duals.lambda).amax());
        assert!(
            dual_err < 1e-5,
            "seed {seed}: multipliers differ by {dual_err:e}"
        );
    }
}

#[test]
fn random_qps_are_reproducible_and_well_formed() {
    for shape in QpShape::ALL {
        for seed in 0..N_RANDOM {
            let qp = random_qp(shape, seed);
            assert_eq!(qp, random_qp(shape, seed), "{shape:?} seed {seed}");
            assert_ne!(qp, random_qp(shape, seed + 1), "{shape:?} seed {seed}");
            assert!(
                qp.p.clone().cholesky().is_some(),
                "{shape:?} seed {seed}: P not positive definite"
            );
            assert_eq!(
                qp.p,
                qp.p.transpose(),
                "{shape:?} seed {seed}: P not symmetric"
            );
            assert!(
                qp.a.singular_values().min() > 0.0,
                "{shape:?} seed {seed}: A rank deficient"
            );
            let nx = match shape {
                QpShape::Kong2019 => 5,
                QpShape::Zhang2018 => 6,
                QpShape::Jia2019 | QpShape::Zhong2021 => 7,
            };
            assert_eq!(qp.dims().nx, nx);
            assert_eq!(
                shape.is_equality_only(),
                qp.h.is_empty() && solve_equality_kkt(&qp).is_some()
            );
        }
    }
    let dims = QpDims {
        nx: 5,
        n_eq: 2,
        n_in: 4,
    };
    assert_eq!(random_feasible(dims, 9), random_feasible(dims, 9));
    assert_ne!(random_feasible(dims, 9), random_feasible(dims, 10));
}
