//! The dense active-set solver against Clarabel: cold and hot-started on random QPs of every
//! paper's shape, along slowly varying sequences, on inconsistent warm sets and on infeasible
//! QPs; equality-only QPs, the rows a cold start adds, degenerate vertices, a P that changes
//! along a sequence or is singular (the LU factorisation), and malformed data.

use nalgebra::{DMatrix, DVector};
use rand::Rng;
use solvers::random_qp::rng_from_seed;
use solvers::DEFAULT_CERT_TOL;
use solvers::{
    random_feasible, random_qp, solve_equality_kkt, ActiveSetError, ActiveSetSolution,
    ActiveSetSolver, ActiveSetStart, Constraint, ExactError, ExactSolution, ExactSolver,
    ExactStatus, Qp, QpDims, QpShape, WorkingSet,
};

/// Random QPs per paper shape (4 shapes: 10,000 QPs), each solved cold, warm from its own
/// working set and warm from another QP's working set.
const N_PER_SHAPE: u64 = 2_500;
/// Random QPs of general sizes ([`random_feasible`]).
const N_GENERAL: u64 = 1_000;
/// Required agreement with Clarabel in x (relative to max(1, |x|_inf)) and the objective.
const AGREE_TOL: f64 = 1e-8;

/// The largest sizes of the tests' QPs.
const MAX_DIMS: QpDims = QpDims {
    nx: 9,
    n_eq: 3,
    n_in: 26,
};

/// Worst differences from Clarabel and counts of the starts, over a family of QPs.
#[derive(Default, Debug)]
struct Stats {
    n: usize,
    x: f64,
    objective: f64,
    duals: f64,
    kkt: f64,
    warm: usize,
    warm_primal: usize,
    warm_dual: usize,
    cold: usize,
    max_iterations: u32,
    max_solves: u32,
    /// QPs where Clarabel's x was off by more than [`AGREE_TOL`] and its polished answer was
    /// used, and the largest such |x - x_clarabel|.
    polished: usize,
    x_clarabel: f64,
}

/// Clarabel's answer `x` polished: the rows with slack below 1e-6 (relative) held as
/// equalities, the equality-constrained QP solved by [`solve_equality_kkt`] (nalgebra LU).
fn polish(qp: &Qp, x: &DVector<f64>) -> Option<DVector<f64>> {
    let nx = x.len();
    let near = |slack: f64, rhs: f64| slack <= 1e-6 * (1.0 + rhs.abs());
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    for r in 0..qp.a.nrows() {
        rows.push((qp.a.row(r).iter().copied().collect(), qp.b[r]));
    }
    for r in 0..qp.h.len() {
        let gx = qp.g.row(r).transpose().dot(x);
        if qp.h[r].is_finite() && near(qp.h[r] - gx, qp.h[r]) {
            rows.push((qp.g.row(r).iter().copied().collect(), qp.h[r]));
        }
    }
    for i in 0..nx {
        for (bound, sign) in [(qp.upper[i], 1.0), (qp.lower[i], -1.0)] {
            if bound.is_finite() && near(sign * (bound - x[i]), bound) {
                let mut e = vec![0.0; nx];
                e[i] = 1.0;
                rows.push((e, bound));
            }
        }
    }
    let mut eq = Qp::zeros(QpDims {
        nx,
        n_eq: rows.len(),
        n_in: 0,
    });
    eq.p.copy_from(&qp.p);
    eq.q.copy_from(&qp.q);
    for (r, (row, rhs)) in rows.iter().enumerate() {
        eq.a.row_mut(r).copy_from_slice(row);
        eq.b[r] = *rhs;
    }
    solve_equality_kkt(&eq)
}

impl Stats {
    fn record(&mut self, what: &str, qp: &Qp, sol: &ActiveSetSolution, exact: &ExactSolution) {
        self.n += 1;
        assert!(sol.certified, "{what}: not certified");
        let kkt = sol.kkt.expect("certified answers carry their residuals");
        let scale = 1.0 + qp.q.amax().max(qp.b.amax());
        // The solver computes the residuals itself (summing in another order): they are
        // those of its answer to rounding, and the answer meets the tolerance.
        let recomputed = qp.kkt_residuals(&sol.x, &sol.duals);
        let pairs = [
            (kkt.primal, recomputed.primal),
            (kkt.dual, recomputed.dual),
            (kkt.complementarity, recomputed.complementarity),
        ];
        assert!(
            pairs.iter().all(|(a, b)| (a - b).abs() <= 1e-12 * scale),
            "{what}: residuals {kkt:?}, recomputed {recomputed:?}"
        );
        assert!(
            recomputed.max() <= DEFAULT_CERT_TOL * scale,
            "{what}: {recomputed:?}"
        );
        let mut dx = (&sol.x - &exact.x).amax() / exact.x.amax().max(1.0);
        if dx > AGREE_TOL {
            // Clarabel stops on a complementarity product: where a bound is nearly degenerate
            // (multiplier ~1e-6) its x may sit ~1e-7 inside the bound. Polish its answer
            // independently of the active-set solver: hold the rows Clarabel finds (nearly)
            // active as equalities and solve that KKT system (exact::solve_equality_kkt).
            assert!(dx <= 1e-6, "{what}: |x - x_clarabel| = {dx:e}");
            let polished = polish(qp, &exact.x)
                .unwrap_or_else(|| panic!("{what}: |x - x_clarabel| = {dx:e}, no polish"));
            assert!(
                qp.constraint_violation(&polished) <= 1e-12,
                "{what}: polished Clarabel answer infeasible"
            );
            let dp = (&sol.x - &polished).amax() / polished.amax().max(1.0);
            assert!(
                dp <= AGREE_TOL,
                "{what}: |x - x_clarabel| = {dx:e}, |x - x_polished| = {dp:e}"
            );
            self.polished += 1;
            self.x_clarabel = self.x_clarabel.max(dx);
            dx = dp;
        }
        let dobj = (sol.objective - exact.objective).abs() / exact.objective.abs().max(1.0);
        assert!(dobj <= AGREE_TOL, "{what}: objective differs by {dobj:e}");
        assert!(
            (sol.objective - qp.objective(&sol.x)).abs() <= 1e-12 * (1.0 + sol.objective.abs()),
            "{what}: objective not that of x"
        );
        let d = &sol.duals;
        let e = &exact.duals;
        let dd = [
            (&d.lambda - &e.lambda).amax(),
            (&d.mu - &e.mu).amax(),
            (&d.z_lower - &e.z_lower).amax(),
            (&d.z_upper - &e.z_upper).amax(),
        ]
        .into_iter()
        .fold(0.0, f64::max)
            / scale;
        self.x = self.x.max(dx);
        self.objective = self.objective.max(dobj);
        self.duals = self.duals.max(dd);
        self.kkt = self.kkt.max(kkt.max() / scale);
        match sol.start {
            ActiveSetStart::Warm => self.warm += 1,
            ActiveSetStart::WarmPrimal => self.warm_primal += 1,
            ActiveSetStart::WarmDual => self.warm_dual += 1,
            ActiveSetStart::Cold => self.cold += 1,
        }
        self.max_iterations = self.max_iterations.max(sol.iterations);
        self.max_solves = self.max_solves.max(sol.kkt_solves);
    }
}

fn solve_exact(exact: &mut ExactSolver, qp: &Qp, what: &str) -> ExactSolution {
    exact
        .solve(qp)
        .unwrap_or_else(|e| panic!("{what}: Clarabel: {e}"))
}

/// Cold, warm from its own set and warm from `foreign`, for one QP; returns its working set.
fn check_qp(
    solver: &mut ActiveSetSolver,
    exact: &ExactSolver,
    qp: &Qp,
    foreign: Option<&WorkingSet>,
    what: &str,
    stats: &mut [Stats; 3],
) -> WorkingSet {
    let mut exact = exact.clone();
    let reference = solve_exact(&mut exact, qp, what);
    let cold = solver
        .solve(qp, None)
        .unwrap_or_else(|e| panic!("{what} cold: {e}"));
    assert_eq!(cold.start, ActiveSetStart::Cold, "{what}");
    stats[0].record(&format!("{what} cold"), qp, &cold, &reference);

    let warm = solver
        .solve(qp, Some(&cold.working_set))
        .unwrap_or_else(|e| panic!("{what} warm: {e}"));
    assert_eq!(warm.start, ActiveSetStart::Warm, "{what}");
    assert_eq!(
        warm.kkt_solves, 1,
        "{what}: warm start from the optimal set"
    );
    assert_eq!(warm.iterations, 0, "{what}");
    assert_eq!(warm.working_set, cold.working_set, "{what}");
    stats[1].record(&format!("{what} warm"), qp, &warm, &reference);

    if let Some(ws) = foreign {
        let other = solver
            .solve(qp, Some(ws))
            .unwrap_or_else(|e| panic!("{what} foreign warm {ws:?}: {e}"));
        stats[2].record(&format!("{what} foreign warm"), qp, &other, &reference);
    }
    cold.working_set
}

fn report(name: &str, stats: &[Stats; 3]) {
    for (kind, s) in ["cold", "own set", "foreign set"].iter().zip(stats) {
        eprintln!(
            "{name:>10} {kind:>11}: {} QPs, max |dx| {:.1e}, |dobj| {:.1e}, |dduals| {:.1e}, \
             KKT {:.1e}; starts warm/primal/dual/cold {}/{}/{}/{}; max iterations {}, \
             max KKT solves {}; {} polished (max |x - x_clarabel| {:.1e})",
            s.n,
            s.x,
            s.objective,
            s.duals,
            s.kkt,
            s.warm,
            s.warm_primal,
            s.warm_dual,
            s.cold,
            s.max_iterations,
            s.max_solves,
            s.polished,
            s.x_clarabel
        );
    }
}

#[test]
fn agrees_with_clarabel_cold_and_warm_on_every_shape() {
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let exact = ExactSolver::new();
    let mut total = [Stats::default(), Stats::default(), Stats::default()];
    for shape in QpShape::ALL {
        let mut stats = [Stats::default(), Stats::default(), Stats::default()];
        let mut previous: Option<WorkingSet> = None;
        let mut active = 0usize;
        for seed in 0..N_PER_SHAPE {
            let qp = random_qp(shape, seed);
            let ws = check_qp(
                &mut solver,
                &exact,
                &qp,
                previous.as_ref(),
                &format!("{shape:?} seed {seed}"),
                &mut stats,
            );
            active += usize::from(!ws.is_empty());
            previous = Some(ws);
        }
        report(&format!("{shape:?}"), &stats);
        if !shape.is_equality_only() {
            // Not vacuous: inequalities bind in a good share of the QPs, and the foreign warm
            // starts exercise both the primal and the dual continuation.
            assert!(active as u64 > N_PER_SHAPE / 10, "{shape:?}: {active}");
            assert!(stats[2].warm_primal > 0, "{shape:?}: no primal warm path");
            assert!(stats[2].warm_dual > 0, "{shape:?}: no dual warm path");
        }
        for (t, s) in total.iter_mut().zip(&stats) {
            t.n += s.n;
            t.x = t.x.max(s.x);
            t.objective = t.objective.max(s.objective);
            t.duals = t.duals.max(s.duals);
            t.kkt = t.kkt.max(s.kkt);
            t.polished += s.polished;
            t.warm += s.warm;
            t.warm_primal += s.warm_primal;
            t.warm_dual += s.warm_dual;
            t.cold += s.cold;
            t.max_iterations = t.max_iterations.max(s.max_iterations);
            t.max_solves = t.max_solves.max(s.max_solves);
            t.x_clarabel = t.x_clarabel.max(s.x_clarabel);
        }
    }
    assert!(total[0].n >= 10_000);
    report("all", &total);
    // The multipliers are unique (A of full row rank, independent active rows): they agree too.
    assert!(total[0].duals <= 1e-6, "{:?}", total[0]);
}

#[test]
fn agrees_with_clarabel_on_general_random_qps() {
    // Start small: the buffers grow to the largest QP met.
    let mut solver = ActiveSetSolver::new(QpDims {
        nx: 1,
        n_eq: 0,
        n_in: 0,
    });
    let exact = ExactSolver::new();
    let mut stats = [Stats::default(), Stats::default(), Stats::default()];
    let mut previous: Option<WorkingSet> = None;
    for seed in 0..N_GENERAL {
        let nx = 1 + (seed % 9) as usize;
        let dims = QpDims {
            nx,
            n_eq: (seed / 9 % 3) as usize % (nx + 1),
            n_in: (seed / 27 % 7) as usize,
        };
        let qp = random_feasible(dims, seed);
        previous = Some(check_qp(
            &mut solver,
            &exact,
            &qp,
            previous.as_ref(),
            &format!("random_feasible {dims:?} seed {seed}"),
            &mut stats,
        ));
    }
    report("general", &stats);
}

/// Perturbs q and b of `qp` by uniform steps of relative size `step`.
fn perturb<R: Rng>(qp: &mut Qp, rng: &mut R, step: f64) {
    for v in qp.q.iter_mut() {
        *v += step * rng.gen_range(-1.0..1.0);
    }
    for v in qp.b.iter_mut() {
        *v += step * rng.gen_range(-1.0..1.0);
    }
}

#[test]
fn slowly_varying_sequences_mostly_take_one_solve() {
    const SEQUENCES: u64 = 40;
    const STEPS: usize = 150;
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    for shape in QpShape::ALL {
        let mut stats = Stats::default();
        let mut one_solve = 0usize;
        let mut changes = 0usize;
        for s in 0..SEQUENCES {
            let mut qp = random_qp(shape, 1_000_000 + s);
            let mut rng = rng_from_seed(2_000_000 + s);
            let mut ws: Option<WorkingSet> = None;
            for step in 0..STEPS {
                let what = format!("{shape:?} sequence {s} step {step}");
                let sol = solver
                    .solve(&qp, ws.as_ref())
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                let reference = solve_exact(&mut exact, &qp, &what);
                stats.record(&what, &qp, &sol, &reference);
                if step > 0 {
                    one_solve += usize::from(sol.kkt_solves == 1);
                    changes += usize::from(ws.as_ref() != Some(&sol.working_set));
                }
                ws = Some(sol.working_set);
                perturb(&mut qp, &mut rng, 2e-3);
            }
        }
        let n = (SEQUENCES as usize) * (STEPS - 1);
        eprintln!(
            "{shape:?}: {one_solve} of {n} hot starts took one KKT solve, {changes} changed \
             the working set; max |dx| {:.1e}, |dobj| {:.1e}, max KKT solves {}; {} polished \
             (max |x - x_clarabel| {:.1e})",
            stats.x, stats.objective, stats.max_solves, stats.polished, stats.x_clarabel
        );
        assert!(
            one_solve as f64 > 0.9 * n as f64,
            "{shape:?}: only {one_solve} of {n}"
        );
        if !shape.is_equality_only() {
            assert!(changes > 0, "{shape:?}: the working set never changed");
        }
    }
}

#[test]
fn inconsistent_warm_sets_fall_back_to_a_cold_start() {
    let qp = random_qp(QpShape::Jia2019, 7);
    let mut solver = ActiveSetSolver::new(qp.dims());
    let mut exact = ExactSolver::new();
    let reference = solve_exact(&mut exact, &qp, "jia2019 seed 7");
    let bad: Vec<WorkingSet> = vec![
        [Constraint::Inequality(12)].into_iter().collect(),
        [Constraint::Upper(7)].into_iter().collect(),
        [Constraint::Upper(0), Constraint::Upper(0)]
            .into_iter()
            .collect(),
        // x_0 at both bounds: dependent rows, singular KKT matrix.
        [Constraint::Upper(0), Constraint::Lower(0)]
            .into_iter()
            .collect(),
        // More rows than variables.
        (0..5).map(Constraint::Inequality).collect(),
    ];
    for ws in &bad {
        let sol = solver
            .solve(&qp, Some(ws))
            .unwrap_or_else(|e| panic!("{ws:?}: {e}"));
        assert_eq!(sol.start, ActiveSetStart::Cold, "{ws:?}");
        let mut stats = Stats::default();
        stats.record(&format!("{ws:?}"), &qp, &sol, &reference);
    }
    // An infinite right-hand side (the absent bound on p when varpi = +inf).
    let mut qp = qp;
    qp.upper[6] = f64::INFINITY;
    let reference = solve_exact(&mut exact, &qp, "varpi = inf");
    let ws: WorkingSet = [Constraint::Upper(6)].into_iter().collect();
    let sol = solver.solve(&qp, Some(&ws)).unwrap();
    assert_eq!(sol.start, ActiveSetStart::Cold);
    Stats::default().record("varpi = inf", &qp, &sol, &reference);
}

/// QPs with inconsistent constraints, each with a reason.
fn infeasible_qps() -> Vec<(String, Qp)> {
    let mut out = Vec::new();
    for seed in 0..50 {
        // Equalities asking for joint velocities beyond the bounds (|thetadot_i| <= 1.5).
        let mut qp = random_qp(QpShape::Jia2019, seed);
        let far = DVector::from_element(6, 10.0);
        let j = qp.a.columns(0, 6).into_owned();
        qp.b = &j * far;
        out.push((format!("jia2019 seed {seed}, b out of reach"), qp));

        let mut qp = random_qp(QpShape::Zhong2021, seed);
        let j = qp.a.columns(0, 6).into_owned();
        qp.b = &j * DVector::from_element(6, -10.0);
        out.push((format!("zhong2021 seed {seed}, b out of reach"), qp));

        // Crossed bounds.
        let mut qp = random_qp(QpShape::Jia2019, seed);
        let i = (seed % 6) as usize;
        qp.lower[i] = 0.5;
        qp.upper[i] = 0.4;
        out.push((format!("jia2019 seed {seed}, crossed bounds"), qp));

        // Two contradictory rows of G: x_0 <= -1 and -x_0 <= -1.
        let mut qp = random_feasible(
            QpDims {
                nx: 4,
                n_eq: 1,
                n_in: 3,
            },
            seed,
        );
        qp.g = DMatrix::zeros(3, 4);
        qp.g[(0, 0)] = 1.0;
        qp.g[(1, 0)] = -1.0;
        qp.g[(2, 1)] = 1.0;
        qp.h = DVector::from_vec(vec![-1.0, -1.0, 10.0]);
        out.push((
            format!("random_feasible seed {seed}, x_0 <= -1 <= ... >= 1"),
            qp,
        ));
    }
    out
}

#[test]
fn infeasible_qps_return_an_error() {
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    let mut proved = 0usize;
    let cases = infeasible_qps();
    for (what, qp) in &cases {
        assert!(
            matches!(exact.solve(qp), Err(ExactError::PrimalInfeasible(_))),
            "{what}: Clarabel does not call it infeasible"
        );
        let cold = solver.solve(qp, None);
        assert!(cold.is_err(), "{what}: cold answer {cold:?}");
        proved += usize::from(cold == Err(ActiveSetError::Infeasible));
        // Warm starts from various sets, consistent or not, also end in an error.
        let n_in = qp.h.len();
        let warm_sets: Vec<WorkingSet> = vec![
            WorkingSet::new(),
            [Constraint::Upper(0)].into_iter().collect(),
            [Constraint::Lower(1)].into_iter().collect(),
            (0..n_in.min(2)).map(Constraint::Inequality).collect(),
        ];
        for ws in &warm_sets {
            let warm = solver.solve(qp, Some(ws));
            assert!(warm.is_err(), "{what}: warm from {ws:?} answered {warm:?}");
        }
    }
    eprintln!(
        "{} infeasible QPs: {proved} proved infeasible by the dual iterations, the others \
         refused otherwise",
        cases.len()
    );
    assert_eq!(proved, cases.len());
}

#[test]
fn invalid_data_is_refused() {
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut qp = random_qp(QpShape::Kong2019, 3);
    qp.q[0] = f64::NAN;
    assert!(matches!(
        solver.solve(&qp, None),
        Err(ActiveSetError::InvalidData(_))
    ));
    let mut qp = random_qp(QpShape::Jia2019, 3);
    qp.lower[0] = f64::INFINITY;
    assert!(matches!(
        solver.solve(&qp, None),
        Err(ActiveSetError::InvalidData(_))
    ));
    // Rank-deficient equalities: a singular KKT matrix, never an answer.
    let mut qp = random_qp(QpShape::Kong2019, 3);
    let row = qp.a.row(0).into_owned();
    qp.a.row_mut(1).copy_from(&row);
    assert_eq!(solver.solve(&qp, None), Err(ActiveSetError::Singular));
}

#[test]
fn solve_into_matches_solve_and_reuses_its_output() {
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut out = ActiveSetSolution::zeros(QpDims {
        nx: 1,
        n_eq: 0,
        n_in: 0,
    });
    let mut prev = WorkingSet::with_capacity(MAX_DIMS.nx);
    for seed in 0..200 {
        let shape = QpShape::ALL[(seed % 4) as usize];
        let qp = random_qp(shape, seed);
        let warm = (seed % 8 >= 4).then_some(&prev);
        solver.solve_into(&qp, warm, &mut out).unwrap();
        let again = solver.solve(&qp, warm).unwrap();
        assert_eq!(out, again, "{shape:?} seed {seed}");
        prev.clone_from(&out.working_set);
    }
}

/// A QP with P = I (n x n), q, the equalities `a` x = `b` (rows of `a`), the inequalities
/// `g` x <= `h` and no bounds.
fn small_qp(q: &[f64], a: &[&[f64]], b: &[f64], g: &[&[f64]], h: &[f64]) -> Qp {
    let nx = q.len();
    let mut qp = Qp::zeros(QpDims {
        nx,
        n_eq: a.len(),
        n_in: g.len(),
    });
    qp.p = DMatrix::identity(nx, nx);
    qp.q.copy_from_slice(q);
    for (r, row) in a.iter().enumerate() {
        qp.a.row_mut(r).copy_from_slice(row);
    }
    qp.b.copy_from_slice(b);
    for (r, row) in g.iter().enumerate() {
        qp.g.row_mut(r).copy_from_slice(row);
    }
    qp.h.copy_from_slice(h);
    qp
}

#[test]
fn equality_only_qps_take_one_kkt_solve_cold_and_warm() {
    // Both equality-only shapes (kong2019: P = I; zhang2018: a dense P) and general sizes with
    // no inequality and no bound: the answer is the KKT solution of A alone, cold or warm.
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    let mut qps: Vec<(String, Qp)> = Vec::new();
    for seed in 0..300 {
        for shape in [QpShape::Kong2019, QpShape::Zhang2018] {
            qps.push((format!("{shape:?} seed {seed}"), random_qp(shape, seed)));
        }
        let nx = 1 + (seed % 9) as usize;
        let dims = QpDims {
            nx,
            n_eq: (seed % 4) as usize % (nx + 1),
            n_in: 0,
        };
        let mut qp = random_feasible(dims, seed);
        qp.lower.fill(f64::NEG_INFINITY);
        qp.upper.fill(f64::INFINITY);
        qps.push((format!("random_feasible {dims:?} seed {seed}"), qp));
    }
    let mut stats = Stats::default();
    for (what, qp) in &qps {
        let reference = solve_exact(&mut exact, qp, what);
        for warm in [None, Some(&WorkingSet::new())] {
            let sol = solver
                .solve(qp, warm)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let start = if warm.is_some() {
                ActiveSetStart::Warm
            } else {
                ActiveSetStart::Cold
            };
            assert_eq!(sol.start, start, "{what}");
            assert_eq!((sol.kkt_solves, sol.iterations), (1, 0), "{what}");
            assert!(sol.working_set.is_empty(), "{what}");
            stats.record(what, qp, &sol, &reference);
        }
    }
    eprintln!(
        "{} equality-only solves: max |dx| {:.1e}, |dobj| {:.1e}, KKT {:.1e}",
        stats.n, stats.x, stats.objective, stats.kkt
    );
}

#[test]
fn dependent_equalities_are_refused_cold_and_warm() {
    // x0 + x1 + x2 = 1 twice (consistent) or = 1 and = 2 (inconsistent): the KKT matrix is
    // singular either way; no answer, whatever the start.
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let row: &[f64] = &[1.0, 1.0, 1.0];
    for b in [[1.0, 1.0], [1.0, 2.0]] {
        let qp = small_qp(&[0.5, -1.0, 0.0], &[row, row], &b, &[], &[]);
        for warm in [None, Some(&WorkingSet::new())] {
            assert_eq!(
                solver.solve(&qp, warm),
                Err(ActiveSetError::Singular),
                "b = {b:?}"
            );
        }
    }
    let qp = small_qp(&[0.5, -1.0, 0.0], &[row, row], &[1.0, 2.0], &[], &[]);
    assert!(matches!(
        ExactSolver::new().solve(&qp),
        Err(ExactError::PrimalInfeasible(_))
    ));
}

#[test]
fn the_cold_start_adds_only_the_rows_the_equality_minimiser_violates() {
    // min |x|^2/2 s.t. x0 + x1 + x2 = 1: the equality-constrained minimiser is (1/3, 1/3, 1/3).
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    let ones: &[f64] = &[1.0, 1.0, 1.0];
    let (e0, e1): (&[f64], &[f64]) = (&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]);
    // x0 <= 0.5 and x1 <= 10 hold there: no row enters, one KKT solve.
    let qp = small_qp(&[0.0; 3], &[ones], &[1.0], &[e0, e1], &[0.5, 10.0]);
    let sol = solver.solve(&qp, None).unwrap();
    assert_eq!((sol.kkt_solves, sol.iterations), (1, 0));
    assert!(sol.working_set.is_empty());
    for v in sol.x.iter() {
        assert!((v - 1.0 / 3.0).abs() < 1e-15, "{}", sol.x);
    }
    Stats::default().record(
        "feasible",
        &qp,
        &sol,
        &solve_exact(&mut exact, &qp, "feasible"),
    );
    // x0 <= 0.2 is violated and binds: it alone enters (one dual step, two factorisations);
    // x1 <= 10 never does. The optimum is (0.2, 0.4, 0.4).
    let qp = small_qp(&[0.0; 3], &[ones], &[1.0], &[e0, e1], &[0.2, 10.0]);
    let sol = solver.solve(&qp, None).unwrap();
    assert_eq!((sol.kkt_solves, sol.iterations), (2, 1));
    assert_eq!(sol.working_set.as_slice(), [Constraint::Inequality(0)]);
    for (v, want) in sol.x.iter().zip([0.2, 0.4, 0.4]) {
        assert!((v - want).abs() < 1e-15, "{}", sol.x);
    }
    Stats::default().record(
        "one row",
        &qp,
        &sol,
        &solve_exact(&mut exact, &qp, "one row"),
    );
}

#[test]
fn degenerate_and_duplicate_rows_agree_with_clarabel() {
    // min |x - (2, 2)|^2/2 with x0 <= 1, x1 <= 1, x0 + x1 <= 2 and x0 <= 1 again: four rows
    // through the optimum (1, 1), any two of the first three independent. Cold and from every
    // warm set of one or two rows, the answer is (1, 1) with nonnegative multipliers.
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    let rows: [&[f64]; 4] = [&[1.0, 0.0], &[0.0, 1.0], &[1.0, 1.0], &[1.0, 0.0]];
    let qp = small_qp(&[-2.0, -2.0], &[], &[], &rows, &[1.0, 1.0, 2.0, 1.0]);
    let reference = solve_exact(&mut exact, &qp, "degenerate");
    let mut warm_sets: Vec<WorkingSet> = vec![WorkingSet::new()];
    for i in 0..4 {
        warm_sets.push([Constraint::Inequality(i)].into_iter().collect());
        for j in i + 1..4 {
            warm_sets.push(
                [Constraint::Inequality(i), Constraint::Inequality(j)]
                    .into_iter()
                    .collect(),
            );
        }
    }
    let starts = std::iter::once(None).chain(warm_sets.iter().map(Some));
    for warm in starts {
        let what = format!("degenerate, warm {warm:?}");
        let sol = solver
            .solve(&qp, warm)
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        for v in sol.x.iter() {
            assert!((v - 1.0).abs() < 1e-14, "{what}: {}", sol.x);
        }
        Stats::default().record(&what, &qp, &sol, &reference_or_polished(&qp, &reference));
    }
}

/// Clarabel's answer with its x replaced by the KKT solution on the rows it finds active
/// ([`polish`]) when that is feasible: at a degenerate vertex the multipliers are not unique,
/// and Clarabel's interior point stops ~1e-8 inside.
fn reference_or_polished(qp: &Qp, reference: &ExactSolution) -> ExactSolution {
    let mut r = reference.clone();
    if let Some(x) = polish(qp, &reference.x).filter(|x| qp.constraint_violation(x) <= 1e-12) {
        r.objective = qp.objective(&x);
        r.x = x;
    }
    r
}

#[test]
fn an_unchanged_p_keeps_its_factor_and_a_changed_one_is_refactorised() {
    // One solver along a sequence whose P changes (dense, diagonal, dense again) and stays put
    // in between, against a fresh solver for every QP: the same answers, bit for bit.
    let mut kept = ActiveSetSolver::new(MAX_DIMS);
    let mut prev: Option<WorkingSet> = None;
    for seed in 0..60u64 {
        let shape =
            [QpShape::Zhang2018, QpShape::Jia2019, QpShape::Zhong2021][(seed / 5 % 3) as usize];
        let mut qp = random_qp(shape, seed / 5);
        qp.q[0] += 1e-3 * (seed % 5) as f64;
        let warm = prev.as_ref().filter(|w| {
            w.iter().all(|c| match c {
                Constraint::Inequality(i) => i < qp.h.len(),
                _ => true,
            })
        });
        let got = kept.solve(&qp, warm).unwrap();
        let fresh = ActiveSetSolver::new(qp.dims()).solve(&qp, warm).unwrap();
        assert_eq!(got, fresh, "{shape:?} seed {seed}");
        prev = Some(got.working_set);
    }
}

#[test]
fn invalid_entries_are_refused_with_the_validation_error() {
    // Every field that must be finite (or one-sided), spoilt in turn, certified or not, cold or
    // warm: the error is InvalidData with what Qp::validate says.
    let base = random_qp(QpShape::Jia2019, 11);
    let ws = ActiveSetSolver::new(base.dims())
        .solve(&base, None)
        .unwrap()
        .working_set;
    type Spoil = fn(&mut Qp);
    let spoils: [(&str, Spoil); 12] = [
        ("P NaN", |qp| qp.p[(1, 2)] = f64::NAN),
        ("P inf", |qp| qp.p[(3, 3)] = f64::INFINITY),
        ("q NaN", |qp| qp.q[2] = f64::NAN),
        ("q inf", |qp| qp.q[0] = f64::NEG_INFINITY),
        ("A inf", |qp| qp.a[(1, 4)] = f64::INFINITY),
        ("A NaN, zero column", |qp| qp.a[(0, 6)] = f64::NAN),
        ("b NaN", |qp| qp.b[2] = f64::NAN),
        ("G inf", |qp| qp.g[(5, 0)] = f64::INFINITY),
        ("h NaN", |qp| qp.h[7] = f64::NAN),
        ("h -inf", |qp| qp.h[1] = f64::NEG_INFINITY),
        ("lower +inf", |qp| qp.lower[2] = f64::INFINITY),
        ("upper NaN", |qp| qp.upper[4] = f64::NAN),
    ];
    for (what, spoil) in spoils {
        let mut qp = base.clone();
        spoil(&mut qp);
        let want = ActiveSetError::InvalidData(qp.validate().expect_err(what));
        for certify in [true, false] {
            let mut solver = ActiveSetSolver::new(qp.dims()).with_certification(certify);
            // The valid QP first, so that P's factor is kept from it when P is unchanged.
            solver.solve(&base, None).unwrap();
            for warm in [None, Some(&ws)] {
                assert_eq!(
                    solver.solve(&qp, warm).as_ref().err(),
                    Some(&want),
                    "{what}, certify {certify}, warm {}",
                    warm.is_some()
                );
            }
        }
    }
}

#[test]
fn a_singular_p_goes_through_the_lu_factorisation() {
    // P with a zero last row and column, the last variable tied to the others by an equality:
    // P is not positive definite (no Schur complement) but every KKT matrix is nonsingular.
    // Cold and warm, the answers agree with Clarabel.
    let mut solver = ActiveSetSolver::new(MAX_DIMS);
    let mut exact = ExactSolver::new();
    let mut stats = [Stats::default(), Stats::default(), Stats::default()];
    let mut previous: Option<WorkingSet> = None;
    for seed in 0..300 {
        let dims = QpDims {
            nx: 4,
            n_eq: 1,
            n_in: 3,
        };
        let mut qp = random_feasible(dims, seed);
        for i in 0..4 {
            qp.p[(3, i)] = 0.0;
            qp.p[(i, 3)] = 0.0;
        }
        qp.a[(0, 3)] = 1.0;
        qp.b[0] = 0.5;
        qp.lower[3] = -10.0;
        qp.upper[3] = 10.0;
        if !matches!(exact.solve(&qp), Ok(ref s) if s.status == ExactStatus::Solved) {
            continue;
        }
        previous = Some(check_qp(
            &mut solver,
            &exact,
            &qp,
            previous.as_ref(),
            &format!("singular P seed {seed}"),
            &mut stats,
        ));
    }
    report("singular P", &stats);
    assert!(stats[0].n > 200, "{}", stats[0].n);
}
