//! kong2019's ZNN scheme on the dynamic-size n-link arm equals the const-generic scheme on
//! `NLink<N>`: the QP to the last bit, dQP/dt to rounding (J thetadot summed in another
//! order), at random states; and dQP/dt is the derivative of the QP (central differences).

use nalgebra::SVector;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use robots::{NLink, NLinkDyn, Robot};
use schemes::paths::{build_path, Path, PathSpec};
use schemes::scheme::Scheme;
use schemes::slice_scheme::{Fixed, SliceScheme};
use schemes::velocity_rmp::VelocityRmp;
use schemes::velocity_rmp_dyn::NLinkZnn;
use schemes::Qp;
use std::sync::Arc;

const N: usize = 10;

fn fields(qp: &Qp) -> Vec<f64> {
    [&qp.p, &qp.a, &qp.g]
        .iter()
        .flat_map(|m| m.iter().copied())
        .chain(
            [&qp.q, &qp.b, &qp.h, &qp.lower, &qp.upper]
                .iter()
                .flat_map(|v| v.iter().copied()),
        )
        .collect()
}

#[test]
fn the_dynamic_size_scheme_is_the_const_generic_one() {
    let robot = Arc::new(NLink::<N>::new());
    let home = NLink::<N>::home();
    let spec: PathSpec = toml::from_str("name = \"circle\"\nduration = 9.0").unwrap();
    let path: Arc<dyn Path> = Arc::from(build_path(&spec, robot.position(&home)).unwrap());
    let (mu, k_p) = (0.7, 1.3);
    let fixed = VelocityRmp::znn(robot, path.clone(), home, mu, k_p);
    let fixed = Fixed(&fixed as &dyn Scheme<N>);
    let arm = NLinkDyn::new(N).unwrap();
    let dynamic = NLinkZnn::new(arm, path, home.as_slice(), mu, k_p).unwrap();
    assert!(NLinkZnn::new(arm, fixed_path(), &[0.0; 3], mu, k_p).is_none());
    assert_eq!(fixed.dims(), dynamic.dims());
    assert_eq!((fixed.joints(), dynamic.joints()), (N, N));
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut a, mut b) = (fixed.new_qp(), dynamic.new_qp());
    let (mut da, mut db) = (fixed.new_qp(), dynamic.new_qp());
    let (mut sa, mut sb) = (fixed.new_dot_scratch(), dynamic.new_dot_scratch());
    for _ in 0..20 {
        let t = rng.gen_range(0.0..9.0);
        let th: Vec<f64> = home.iter().map(|v| v + rng.gen_range(-0.5..0.5)).collect();
        let thd: Vec<f64> = (0..N).map(|_| rng.gen_range(-1.0..1.0)).collect();
        fixed.build(t, &th, &thd, &mut a);
        dynamic.build(t, &th, &thd, &mut b);
        assert_eq!(fields(&a), fields(&b), "QP at t = {t}");
        fixed.build_dot(t, &th, &thd, &thd, &mut da, &mut sa);
        dynamic.build_dot(t, &th, &thd, &thd, &mut db, &mut sb);
        for (x, y) in fields(&da).iter().zip(fields(&db)) {
            assert!(
                (x - y).abs() <= 1e-13 * x.abs().max(1.0),
                "dQP/dt: {x} vs {y}"
            );
        }
        // dQP/dt against a central difference of the QP along the motion.
        let h = 1e-6;
        let step = |s: f64| -> Vec<f64> {
            let th: Vec<f64> = th.iter().zip(&thd).map(|(p, v)| p + s * v).collect();
            let mut qp = dynamic.new_qp();
            dynamic.build(t + s, &th, &thd, &mut qp);
            fields(&qp)
        };
        let (plus, minus) = (step(h), step(-h));
        for ((p, m), d) in plus.iter().zip(&minus).zip(fields(&db)) {
            if p.is_finite() {
                let fd = (p - m) / (2.0 * h);
                assert!((fd - d).abs() <= 1e-6 * d.abs().max(1.0), "{fd} vs {d}");
            }
        }
    }
}

fn fixed_path() -> Arc<dyn Path> {
    let spec: PathSpec = toml::from_str("name = \"circle\"\nduration = 9.0").unwrap();
    Arc::from(build_path(&spec, SVector::<f64, 3>::new(0.3, 0.0, 0.4)).unwrap())
}
