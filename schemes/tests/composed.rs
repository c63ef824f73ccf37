//! Schemes as term lists: every preset written out as its terms in a file builds the same QP
//! bit for bit (and the same derivative); a composed scheme's sizes follow its terms; the file
//! form's errors name the term, the field and the valid choices.

use crate::common;

use std::sync::Arc;

use common::{paper_specs, Circle, PlanarZ};
use qp::QpDims;
use robots::Robot;
use schemes::build_scheme;
use spec::Level;
use spec::SchemeSpec;

const N: usize = 6;

fn theta0() -> Vec<f64> {
    vec![0.3, 1.2, -0.8, 0.5, -0.4, 0.2]
}

fn build(spec: &SchemeSpec) -> Box<dyn schemes::Scheme> {
    let robot = Arc::new(PlanarZ::new(N));
    let path = Arc::new(Circle {
        r0: robot.position(&theta0()),
        a: 0.05,
        t_end: 5.0,
    });
    build_scheme(spec, robot.clone(), Some(robot), path, &theta0()).unwrap()
}

#[test]
fn every_preset_written_as_its_terms_builds_the_same_qp() {
    let th: Vec<f64> = theta0().iter().map(|v| v + 0.07).collect();
    let thd = vec![0.3, -0.2, 0.25, 0.1, -0.15, 0.05];
    for spec in paper_specs() {
        // The expansion, through the file form and back.
        let text = toml::to_string(&SchemeSpec::Composed(spec.expand())).unwrap();
        let written: SchemeSpec = toml::from_str(&text).unwrap();
        assert!(matches!(written, SchemeSpec::Composed(_)), "{text}");
        let (a, b) = (build(&spec), build(&written));
        assert_eq!(a.dims(), b.dims(), "{}", spec.display_name());
        assert_eq!(a.level(), b.level());
        let (mut qa, mut qb) = (a.new_qp(), b.new_qp());
        a.build(1.1, &th, &thd, &mut qa);
        b.build(1.1, &th, &thd, &mut qb);
        assert_eq!(qa, qb, "{}: QPs differ", spec.display_name());
        let (mut da, mut db) = (a.new_qp(), b.new_qp());
        let (mut sa, mut sb) = (a.new_dot_scratch(), b.new_dot_scratch());
        a.build_dot(1.1, &th, &thd, &thd, &mut da, &mut sa);
        b.build_dot(1.1, &th, &thd, &thd, &mut db, &mut sb);
        assert_eq!(da, db, "{}: derivatives differ", spec.display_name());
        assert_eq!(a.terms(), b.terms());
    }
}

#[test]
fn a_composed_scheme_is_sized_by_its_terms() {
    let [proof, axes, planar]: [SchemeSpec; 3] = common::composed_specs().try_into().unwrap();
    // Joints + s; 3 tracking rows; 2n infinity-norm rows + 2 (n + 1) bound rows.
    let s = build(&proof);
    assert_eq!(
        s.dims(),
        QpDims {
            nx: N + 1,
            n_eq: 3,
            n_in: 2 * N + 2 * (N + 1)
        }
    );
    assert_eq!(s.name(), "own (inf-norm + sign-power + feedback)");
    assert_eq!(s.terms().len(), 7, "{:?}", s.terms());
    assert!(s.terms()[1].contains("variable x[6]"), "{:?}", s.terms());
    // The bounds as rows: no variable bounds left, and h carries u and -l.
    let mut qp = s.new_qp();
    s.build(0.5, &theta0(), &theta0(), &mut qp);
    assert!(qp.lower.iter().all(|v| *v == f64::NEG_INFINITY));
    assert!(qp.upper.iter().all(|v| *v == f64::INFINITY));
    assert_eq!(qp.h[2 * N + N], 10.0, "varpi as the row of s");
    assert_eq!(qp.p[(N, N)], 0.3);
    assert_eq!(qp.p[(0, 0)], 0.5);
    // Two task axes, x and z: the rows of J and of rdot* of those axes.
    let s = build(&axes);
    assert_eq!(s.dims().n_eq, 2);
    let mut qp = s.new_qp();
    s.build(0.5, &theta0(), &theta0(), &mut qp);
    let j = PlanarZ::new(N).jacobian_matrix(&theta0());
    for c in 0..N {
        assert_eq!(qp.a[(0, c)], j[(0, c)]);
        assert_eq!(qp.a[(1, c)], j[(2, c)]);
    }
    assert_eq!(
        qp.p[(0, 0)],
        1.5,
        "velocity norm 1 + squared repetitive 0.5"
    );
    // The linear infinity-norm penalty: q_s = w, P_ss = 0, and s's bounds [0, +inf).
    assert_eq!((qp.q[N], qp.p[(N, N)]), (0.2, 0.0));
    assert_eq!((qp.lower[N], qp.upper[N]), (0.0, f64::INFINITY));
    assert_eq!(s.dims().n_in, 2 * N);
    let s = build(&planar);
    assert_eq!(s.level(), Level::Acceleration);
    assert_eq!(s.dims().n_eq, 2);
}

/// The error of a composed scheme's file text.
fn error(text: &str) -> String {
    let head = "kind = \"composed\"\nlevel = \"velocity\"\n";
    match toml::from_str::<SchemeSpec>(&format!("{head}{text}")) {
        Err(e) => e.to_string(),
        Ok(spec) => spec.validate().unwrap_err().to_string(),
    }
}

#[test]
fn composed_file_errors_name_the_term_the_field_and_the_choices() {
    let e = error("[[terms]]\nkind = \"velocity-nrom\"\n");
    assert!(
        e.contains("velocity-nrom") && e.contains("infinity-norm"),
        "{e}"
    );
    let e = error("[[terms]]\nkind = \"infinity-norm\"\nw_inf = 1.0\n");
    assert!(e.contains("w_inf") && e.contains("varpi"), "{e}");
    let e = error("[[terms]]\nkind = \"torque-norm\"\n");
    assert!(
        e.contains("terms[0] (torque-norm)") && e.contains("velocity level"),
        "{e}"
    );
    let e = error("[[terms]]\nkind = \"repetitive\"\nlambda = 1.0\nform = \"sign-power\"\n");
    assert!(e.contains("'alpha'") && e.contains("(0, 1]"), "{e}");
    let e = error("[[terms]]\nkind = \"tracking\"\ntask = \"planar\"\naxes = [\"x\"]\n");
    assert!(e.contains("'axes'") && e.contains("not both"), "{e}");
    let e = error("[[terms]]\nkind = \"tracking\"\naxes = [\"x\", \"x\"]\n");
    assert!(e.contains("distinct"), "{e}");
    let e = error("[[terms]]\nkind = \"tracking\"\naxes = [\"w\"]\n");
    assert!(e.contains("`x`, `y`"), "{e}");
    let e = error("[[terms]]\nkind = \"tracking\"\nrho_v = 1.0\n");
    assert!(e.contains("'rho_v'") && e.contains("k_p"), "{e}");
    let e = error("terms = []\n");
    assert!(e.contains("'terms' is empty"), "{e}");
    let e = error("name = \"a,b\"\n[[terms]]\nkind = \"velocity-norm\"\n");
    assert!(e.contains("'name'"), "{e}");
    let e = error("[[terms]]\nkind = \"bound-conversion\"\ngain = -1.0\n");
    assert!(
        e.contains("terms[0] (bound-conversion)") && e.contains("'gain'"),
        "{e}"
    );
}

/// The tracking term reuses J and the path point from the last QP build for the derivative
/// only at the same (t, theta): a derivative at another instant or state, after a build, is
/// that of a scheme that never built anything (bit for bit).
#[test]
fn the_derivative_after_a_build_elsewhere_is_a_fresh_one() {
    let thd = vec![0.3, -0.2, 0.25, 0.1, -0.15, 0.05];
    let zeros = vec![0.0; N];
    let th: Vec<f64> = theta0().iter().map(|v| v + 0.07).collect();
    for spec in paper_specs() {
        let (used, fresh) = (build(&spec), build(&spec));
        if used.level() != Level::Velocity {
            continue;
        }
        let mut qp = used.new_qp();
        let (mut dot_used, mut dot_fresh) = (used.new_qp(), fresh.new_qp());
        let (mut s1, mut s2) = (used.new_dot_scratch(), fresh.new_dot_scratch());
        // A build at (t, theta0), then derivatives at (t, th), (t + 0.1, theta0), and at the
        // build's own instant: each the same as the fresh scheme's.
        for (t, theta) in [(1.0, &th), (1.1, &theta0()), (1.0, &theta0())] {
            used.build(1.0, &theta0(), &thd, &mut qp);
            used.build_dot(t, theta, &thd, &zeros, &mut dot_used, &mut s1);
            fresh.build_dot(t, theta, &thd, &zeros, &mut dot_fresh, &mut s2);
            assert_eq!(dot_used.a, dot_fresh.a, "{spec:?} at t = {t}");
            assert_eq!(dot_used.b, dot_fresh.b, "{spec:?} at t = {t}");
        }
    }
}

#[test]
fn acceleration_limits_clamp_the_converted_velocity_limits_and_their_derivative_is_exact() {
    let text = "kind = \"composed\"\nlevel = \"acceleration\"\n\
                [[terms]]\nkind = \"acceleration-norm\"\n\
                [[terms]]\nkind = \"acceleration-limits\"\na_max = 2.0\nvelocity_gain = 4.0\n";
    let spec: SchemeSpec = toml::from_str(text).unwrap();
    let s = build(&spec);
    assert_eq!(s.dims().n_eq, 0);
    // Velocity limits +-1.5: joint 0 at 1.1 (upper branch 4 (1.5 - 1.1) = 1.6 inside, lower
    // 4 (-2.6) = -10.4 clamped to -2), joint 1 at 1.9 beyond the limit (upper 4 (1.5 - 1.9) = -1.6 < 0:
    // decelerated), joint 2 at -1.45 (lower 4 (-1.5 + 1.45) = -0.2).
    let th = theta0();
    let thd = vec![1.1, 1.9, -1.45, 0.0, 0.3, -0.3];
    let thdd = vec![0.5, -0.7, 0.9, 0.2, -0.4, 0.1];
    let mut qp = s.new_qp();
    s.build(0.2, &th, &thd, &mut qp);
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    assert!(
        close(qp.upper[0], 1.6) && close(qp.lower[0], -2.0),
        "{qp:?}"
    );
    assert!(close(qp.upper[1], -1.6) && close(qp.lower[1], -2.0));
    assert!(close(qp.lower[2], -0.2) && close(qp.upper[2], 2.0));
    for i in 0..N {
        assert!(qp.lower[i] <= qp.upper[i]);
    }
    // dl/dt, du/dt along (thetadot, thetaddot): -mu thetaddot_i on the velocity branch.
    let mut dot = s.new_qp();
    let mut scratch = s.new_dot_scratch();
    s.build_dot(0.2, &th, &thd, &thdd, &mut dot, &mut scratch);
    let h = 1e-7;
    let at = |sign: f64| {
        let th: Vec<f64> = th.iter().zip(&thd).map(|(a, v)| a + sign * h * v).collect();
        let thd: Vec<f64> = thd
            .iter()
            .zip(&thdd)
            .map(|(a, v)| a + sign * h * v)
            .collect();
        let mut qp = s.new_qp();
        s.build(0.2 + sign * h, &th, &thd, &mut qp);
        qp
    };
    let (plus, minus) = (at(1.0), at(-1.0));
    for i in 0..N {
        let dl = (plus.lower[i] - minus.lower[i]) / (2.0 * h);
        let du = (plus.upper[i] - minus.upper[i]) / (2.0 * h);
        assert!(
            (dl - dot.lower[i]).abs() < 1e-6,
            "joint {i}: dl {dl} vs {}",
            dot.lower[i]
        );
        assert!(
            (du - dot.upper[i]).abs() < 1e-6,
            "joint {i}: du {du} vs {}",
            dot.upper[i]
        );
    }
    assert!(close(dot.upper[1], -4.0 * thdd[1]));
}
