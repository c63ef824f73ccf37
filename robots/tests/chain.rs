//! `robots::chain`: the Jacobian and its time derivative against central differences of the
//! forward kinematics, `H` symmetric positive definite, `c` against the Christoffel symbols of
//! finite-difference `dH/dtheta`, `g` against the gradient of the potential, on seeded random
//! chains mixing revolute, continuous and prismatic joints; `Chain::from_dh` against the data
//! robots of every built-in robot file; the Jaco2's file against the Rust model's dynamics.

use nalgebra::{DMatrix, DVector, Matrix3, Rotation3, SVector, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use robots::Frame;
use robots::RigidBody;
use robots::{builtin_files, builtin_models, parse_builtin};
use robots::{Chain, ChainJoint, ChainWorkspace, JointKind, JointRange};
use robots::{DataRobot, Dynamics, Jaco2, Robot};

/// A random rotation (axis-angle with a random axis and angle).
fn random_rotation(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
    let axis = Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    Rotation3::new(axis * rng.gen_range(0.0..3.0)).into_inner()
}

fn random_frame(rng: &mut ChaCha8Rng, reach: f64) -> Frame {
    Frame {
        rot: random_rotation(rng),
        origin: Vector3::from_fn(|_, _| rng.gen_range(-reach..reach)),
    }
}

/// A random positive definite inertia tensor about the centre of mass: `R diag R'` with
/// principal moments obeying the triangle inequality.
fn random_body(rng: &mut ChaCha8Rng) -> RigidBody {
    let (a, b): (f64, f64) = (rng.gen_range(0.01..0.2), rng.gen_range(0.01..0.2));
    let c = rng.gen_range((a - b).abs() + 0.005..a + b);
    let r = random_rotation(rng);
    RigidBody {
        mass: rng.gen_range(0.2..3.0),
        com: Vector3::from_fn(|_, _| rng.gen_range(-0.2..0.2)),
        inertia: r * Matrix3::from_diagonal(&Vector3::new(a, b, c)) * r.transpose(),
    }
}

/// A random chain of `n` joints (every third prismatic, some continuous), base, tool, gravity.
fn random_chain(seed: u64, n: usize) -> Chain {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let joints = (0..n)
        .map(|i| ChainJoint {
            name: format!("j{i}"),
            origin: random_frame(&mut rng, 0.4),
            kind: match i % 3 {
                0 => JointKind::Revolute,
                1 => JointKind::Prismatic,
                _ => JointKind::Continuous,
            },
            axis: Vector3::from_fn(|_, _| rng.gen_range(-1.0..1.0)),
            limits: JointRange::UNLIMITED,
            body: Some(random_body(&mut rng)),
        })
        .collect();
    let tool = random_frame(&mut rng, 0.2);
    let base = random_frame(&mut rng, 0.5);
    let gravity = Vector3::new(0.3, -0.5, -9.81);
    Chain::new(joints, tool)
        .unwrap()
        .with_base(base)
        .with_gravity(gravity)
}

fn random_vector(rng: &mut ChaCha8Rng, n: usize, lim: f64) -> DVector<f64> {
    DVector::from_fn(n, |_, _| rng.gen_range(-lim..lim))
}

/// `|a - b| <= tol max(1, |a|)` entrywise (max norm).
fn close(a: &DMatrix<f64>, b: &DMatrix<f64>, tol: f64) -> bool {
    (a - b).amax() <= tol * a.amax().max(1.0)
}

/// The angular velocity `w` with `Rdot R' = [w]x`, from a central difference of `R`.
fn fd_angular(
    chain: &Chain,
    ws: &mut ChainWorkspace,
    q: &DVector<f64>,
    dq: &DVector<f64>,
    h: f64,
) -> Vector3<f64> {
    let rp = chain.tool_pose(ws, (q + dq * h).as_slice()).rot;
    let rm = chain.tool_pose(ws, (q - dq * h).as_slice()).rot;
    let r = chain.tool_pose(ws, q.as_slice()).rot;
    let w = (rp - rm) / (2.0 * h) * r.transpose();
    Vector3::new(
        w[(2, 1)] - w[(1, 2)],
        w[(0, 2)] - w[(2, 0)],
        w[(1, 0)] - w[(0, 1)],
    ) * 0.5
}

#[test]
fn jacobian_matches_finite_differences_of_the_tool_pose() {
    for (seed, n) in [(1, 1), (2, 2), (3, 5), (4, 9), (5, 20)] {
        let chain = random_chain(seed, n);
        let mut ws = chain.workspace();
        let mut rng = ChaCha8Rng::seed_from_u64(seed + 100);
        let h = 1e-6;
        for _ in 0..10 {
            let q = random_vector(&mut rng, n, 2.0);
            let jac = chain.jacobian(&mut ws, q.as_slice()).clone();
            let mut fd = DMatrix::zeros(6, n);
            for k in 0..n {
                let mut e = DVector::zeros(n);
                e[k] = 1.0;
                let dp = (chain.tool_position(&mut ws, (&q + &e * h).as_slice())
                    - chain.tool_position(&mut ws, (&q - &e * h).as_slice()))
                    / (2.0 * h);
                fd.fixed_view_mut::<3, 1>(0, k).copy_from(&dp);
                let w = fd_angular(&chain, &mut ws, &q, &e, h);
                fd.fixed_view_mut::<3, 1>(3, k).copy_from(&w);
            }
            assert!(close(&fd, &jac, 1e-7), "n = {n}: J\n{jac}\nfd\n{fd}");
            let pj = chain.position_jacobian(&mut ws, q.as_slice()).into_owned();
            assert_eq!(pj, jac.rows(0, 3).into_owned());
        }
    }
}

#[test]
fn jacobian_dot_matches_finite_differences_of_the_jacobian() {
    for (seed, n) in [(11, 1), (12, 3), (13, 6), (14, 10)] {
        let chain = random_chain(seed, n);
        let mut ws = chain.workspace();
        let mut rng = ChaCha8Rng::seed_from_u64(seed + 100);
        let h = 1e-6;
        for _ in 0..10 {
            let q = random_vector(&mut rng, n, 2.0);
            let qd = random_vector(&mut rng, n, 1.0);
            let jdot = chain
                .jacobian_dot(&mut ws, q.as_slice(), qd.as_slice())
                .clone();
            let jp = chain.jacobian(&mut ws, (&q + &qd * h).as_slice()).clone();
            let jm = chain.jacobian(&mut ws, (&q - &qd * h).as_slice()).clone();
            let fd = (jp - jm) / (2.0 * h);
            assert!(close(&fd, &jdot, 1e-7), "n = {n}: Jdot\n{jdot}\nfd\n{fd}");
        }
    }
}

/// The potential `U = -sum m_i g0 . p_ci`.
fn potential(chain: &Chain, ws: &mut ChainWorkspace, q: &DVector<f64>) -> f64 {
    let g0 = chain.gravity();
    let frames = chain.body_frames(ws, q.as_slice()).to_vec();
    chain
        .joints()
        .iter()
        .zip(&frames)
        .map(|(j, f)| {
            let b = j.body.unwrap();
            -b.mass * g0.dot(&f.transform_point(&b.com))
        })
        .sum()
}

#[test]
fn inertia_is_symmetric_positive_definite_and_rnea_is_consistent() {
    for (seed, n) in [(21, 1), (22, 4), (23, 7), (24, 15), (25, 200)] {
        let chain = random_chain(seed, n);
        let mut ws = chain.workspace();
        let mut rng = ChaCha8Rng::seed_from_u64(seed + 100);
        for _ in 0..10 {
            let q = random_vector(&mut rng, n, 2.0);
            let qd = random_vector(&mut rng, n, 1.0);
            let qdd = random_vector(&mut rng, n, 1.0);
            let h = chain.inertia(&mut ws, q.as_slice()).clone();
            assert!(close(&h, &h.transpose(), 1e-13), "H not symmetric\n{h}");
            let eig = h.clone().symmetric_eigenvalues();
            assert!(eig.min() > 0.0, "H not positive definite: {eig}");
            let c = chain.coriolis(&mut ws, q.as_slice(), qd.as_slice()).clone();
            let g = chain.gravity_torques(&mut ws, q.as_slice()).clone();
            let tau = chain
                .inverse_dynamics(&mut ws, q.as_slice(), qd.as_slice(), qdd.as_slice())
                .clone();
            let sum = &h * &qdd + &c + &g;
            assert!(
                close(
                    &DMatrix::from_column_slice(n, 1, tau.as_slice()),
                    &DMatrix::from_column_slice(n, 1, sum.as_slice()),
                    1e-12
                ),
                "tau {tau} vs H qdd + c + g {sum}"
            );
            // H = sum (m Jv' Jv + Jw' I Jw): twice the kinetic energy along qd is qd' H qd.
            let kinetic = kinetic_energy(&chain, &mut ws, &q, &qd);
            let quad = qd.dot(&(&h * &qd)) * 0.5;
            assert!(
                (kinetic - quad).abs() <= 1e-7 * quad.abs().max(1.0),
                "T {kinetic} vs qd'Hqd/2 {quad}"
            );
        }
    }
}

/// The kinetic energy `sum (m |v_c|^2 + w' I w) / 2` from finite-difference body velocities.
fn kinetic_energy(
    chain: &Chain,
    ws: &mut ChainWorkspace,
    q: &DVector<f64>,
    qd: &DVector<f64>,
) -> f64 {
    let h = 1e-6;
    let plus = chain.body_frames(ws, (q + qd * h).as_slice()).to_vec();
    let minus = chain.body_frames(ws, (q - qd * h).as_slice()).to_vec();
    let now = chain.body_frames(ws, q.as_slice()).to_vec();
    chain
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let b = j.body.unwrap();
            let vc =
                (plus[i].transform_point(&b.com) - minus[i].transform_point(&b.com)) / (2.0 * h);
            let w = (plus[i].rot - minus[i].rot) / (2.0 * h) * now[i].rot.transpose();
            let w = Vector3::new(
                w[(2, 1)] - w[(1, 2)],
                w[(0, 2)] - w[(2, 0)],
                w[(1, 0)] - w[(0, 1)],
            ) * 0.5;
            let iw = now[i].rot * b.inertia * now[i].rot.transpose();
            0.5 * (b.mass * vc.norm_squared() + w.dot(&(iw * w)))
        })
        .sum()
}

#[test]
fn coriolis_matches_the_christoffel_symbols_of_finite_difference_inertia() {
    for (seed, n) in [(31, 2), (32, 5), (33, 8)] {
        let chain = random_chain(seed, n);
        let mut ws = chain.workspace();
        let mut rng = ChaCha8Rng::seed_from_u64(seed + 100);
        let h = 1e-6;
        for _ in 0..5 {
            let q = random_vector(&mut rng, n, 2.0);
            let qd = random_vector(&mut rng, n, 1.0);
            // dH[k] = dH/dq_k by central differences.
            let dh: Vec<DMatrix<f64>> = (0..n)
                .map(|k| {
                    let mut e = DVector::zeros(n);
                    e[k] = h;
                    let hp = chain.inertia(&mut ws, (&q + &e).as_slice()).clone();
                    let hm = chain.inertia(&mut ws, (&q - &e).as_slice()).clone();
                    (hp - hm) / (2.0 * h)
                })
                .collect();
            let christoffel = DVector::from_fn(n, |i, _| {
                let mut s = 0.0;
                for j in 0..n {
                    for k in 0..n {
                        let gamma = 0.5 * (dh[k][(i, j)] + dh[j][(i, k)] - dh[i][(j, k)]);
                        s += gamma * qd[j] * qd[k];
                    }
                }
                s
            });
            let c = chain.coriolis(&mut ws, q.as_slice(), qd.as_slice()).clone();
            assert!(
                (&c - &christoffel).amax() <= 1e-6 * c.amax().max(1.0),
                "n = {n}: c {c} vs Christoffel {christoffel}"
            );
        }
    }
}

#[test]
fn gravity_is_the_gradient_of_the_potential() {
    for (seed, n) in [(41, 1), (42, 4), (43, 9)] {
        let chain = random_chain(seed, n);
        let mut ws = chain.workspace();
        let mut rng = ChaCha8Rng::seed_from_u64(seed + 100);
        let h = 1e-6;
        for _ in 0..10 {
            let q = random_vector(&mut rng, n, 2.0);
            let g = chain.gravity_torques(&mut ws, q.as_slice()).clone();
            let fd = DVector::from_fn(n, |k, _| {
                let mut e = DVector::zeros(n);
                e[k] = h;
                (potential(&chain, &mut ws, &(&q + &e)) - potential(&chain, &mut ws, &(&q - &e)))
                    / (2.0 * h)
            });
            assert!(
                (&g - &fd).amax() <= 1e-6 * g.amax().max(1.0),
                "g {g} vs dU/dq {fd}"
            );
        }
    }
}

#[test]
fn a_vertical_prismatic_joint_lifts_its_mass() {
    let body = RigidBody {
        mass: 2.0,
        com: Vector3::new(0.1, 0.0, 0.0),
        inertia: Matrix3::identity() * 0.01,
    };
    let chain = Chain::new(
        vec![ChainJoint {
            name: "lift".into(),
            origin: Frame::identity(),
            kind: JointKind::Prismatic,
            axis: Vector3::new(0.0, 0.0, 3.0),
            limits: JointRange::UNLIMITED,
            body: Some(body),
        }],
        Frame::identity(),
    )
    .unwrap();
    let mut ws = chain.workspace();
    assert_eq!(
        chain.tool_position(&mut ws, &[0.5]),
        Vector3::new(0.0, 0.0, 0.5)
    );
    assert!((chain.gravity_torques(&mut ws, &[0.5])[0] - 2.0 * 9.81).abs() < 1e-12);
    assert!((chain.inertia(&mut ws, &[0.5])[(0, 0)] - 2.0).abs() < 1e-12);
    assert_eq!(chain.coriolis(&mut ws, &[0.5], &[3.0])[0], 0.0);
}

#[test]
fn invalid_chains_are_refused_with_the_joint_named() {
    let joint = |axis: Vector3<f64>, limits: JointRange, kind: JointKind| ChainJoint {
        name: "elbow".into(),
        origin: Frame::identity(),
        kind,
        axis,
        limits,
        body: None,
    };
    let z = Vector3::z();
    let bad = [
        (vec![], "at least one"),
        (
            vec![joint(
                Vector3::zeros(),
                JointRange::UNLIMITED,
                JointKind::Revolute,
            )],
            "zero length",
        ),
        (
            vec![joint(
                z,
                JointRange {
                    position_min: 1.0,
                    position_max: 1.0,
                    ..JointRange::UNLIMITED
                },
                JointKind::Revolute,
            )],
            "not below",
        ),
        (
            vec![joint(
                z,
                JointRange {
                    position_min: -1.0,
                    position_max: 1.0,
                    ..JointRange::UNLIMITED
                },
                JointKind::Continuous,
            )],
            "continuous",
        ),
        (
            vec![joint(
                z,
                JointRange {
                    velocity_max: 0.0,
                    ..JointRange::UNLIMITED
                },
                JointKind::Revolute,
            )],
            "velocity",
        ),
        (
            vec![joint(
                Vector3::new(f64::NAN, 0.0, 1.0),
                JointRange::UNLIMITED,
                JointKind::Revolute,
            )],
            "axis is not finite",
        ),
    ];
    for (joints, needle) in bad {
        let err = Chain::new(joints, Frame::identity())
            .unwrap_err()
            .to_string();
        assert!(err.contains(needle), "{err:?} lacks {needle:?}");
    }
    let mut negative = joint(z, JointRange::UNLIMITED, JointKind::Revolute);
    negative.body = Some(RigidBody {
        mass: 1.0,
        com: Vector3::zeros(),
        inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0)),
    });
    let err = Chain::new(vec![negative], Frame::identity())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("joint 1 (\"elbow\")") && err.contains("positive semi-definite"),
        "{err}"
    );
}

/// Compares a built-in data robot with the chain of the same file at random poses.
fn same_as_chain(robot: &DataRobot, chain: &Chain) {
    let n = robot.dof();
    let mut ws = chain.workspace();
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    for _ in 0..100 {
        let theta: Vec<f64> = (0..n).map(|_| rng.gen_range(-3.0..3.0)).collect();
        let p = robot.position(&theta);
        let pc = chain.tool_position(&mut ws, &theta);
        assert!(
            (p - pc).amax() <= 1e-12 * p.amax().max(1.0),
            "{}: {p} vs {pc}",
            robot.name()
        );
        let j = DMatrix::from_column_slice(3, n, robot.jacobian_matrix(&theta).as_slice());
        let jc = chain
            .position_jacobian(&mut ws, &theta)
            .clone_owned()
            .resize(3, n, 0.0);
        assert!(
            close(&j, &jc, 1e-12),
            "{}: J\n{j}\nchain\n{jc}",
            robot.name()
        );
    }
}

#[test]
fn from_dh_equals_every_builtin_data_robot() {
    let models = builtin_models();
    assert_eq!(models.len(), builtin_files().len());
    for ((file, text), model) in builtin_files().iter().zip(models) {
        let spec = parse_builtin(file, text).unwrap();
        let chain = Chain::from_dh(&spec).unwrap();
        assert_eq!(
            chain.dof(),
            model.1.as_ref().expect("a valid built-in file").dof()
        );
        for (j, row) in chain.joints().iter().zip(spec.joints()) {
            assert_eq!(
                (j.limits.position_min, j.limits.position_max),
                (row.theta_min, row.theta_max)
            );
            assert_eq!(
                (j.limits.velocity_min, j.limits.velocity_max),
                (row.velocity_min, row.velocity_max)
            );
            assert_eq!(j.body.is_some(), row.link.is_some(), "{file}");
        }
        let (_, model) = model;
        same_as_chain(model.as_ref().expect("a valid built-in file"), &chain);
    }
}

#[test]
fn the_jaco2_file_has_the_rust_models_dynamics() {
    let (file, text) = builtin_files()
        .iter()
        .find(|(f, _)| *f == "jaco2.toml")
        .unwrap();
    let chain = Chain::from_dh(&parse_builtin(file, text).unwrap()).unwrap();
    let rust = Jaco2::kinova();
    let mut ws = chain.workspace();
    let mut rng = ChaCha8Rng::seed_from_u64(38);
    let column = |f: &dyn Fn(&mut [f64])| {
        let mut v = DMatrix::zeros(6, 1);
        f(v.as_mut_slice());
        v
    };
    for _ in 0..200 {
        let q = SVector::<f64, 6>::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let qd = SVector::<f64, 6>::from_fn(|_, _| rng.gen_range(-1.5..1.5));
        let h = chain.inertia(&mut ws, q.as_slice()).clone();
        let (qs, qds) = (q.as_slice(), qd.as_slice());
        assert!(close(&rust.inertia_matrix(qs), &h, 1e-12), "H at {q}");
        let c = DMatrix::from_column_slice(
            6,
            1,
            chain
                .coriolis(&mut ws, q.as_slice(), qd.as_slice())
                .as_slice(),
        );
        assert!(
            close(&column(&|c| rust.coriolis(qs, qds, c)), &c, 1e-12),
            "c at {q}, {qd}"
        );
        let g = DMatrix::from_column_slice(
            6,
            1,
            chain.gravity_torques(&mut ws, q.as_slice()).as_slice(),
        );
        assert!(
            close(&column(&|g| rust.gravity(qs, g)), &g, 1e-12),
            "g at {q}"
        );
    }
}

#[test]
fn a_workspace_gives_the_same_results_on_reuse() {
    let chain = random_chain(51, 6);
    let mut ws = chain.workspace();
    let q = [0.1, -0.4, 0.7, 1.1, -2.0, 0.3];
    let first = chain.inertia(&mut ws, &q).clone();
    chain.jacobian_dot(&mut ws, &[0.0; 6], &[1.0; 6]);
    chain.coriolis(&mut ws, &[0.5; 6], &[1.0; 6]);
    assert_eq!(&first, chain.inertia(&mut ws, &q));
    assert_eq!(&first, chain.inertia(&mut chain.workspace(), &q));
    // A new tool frame moves the tool pose by that frame in the last body's frame.
    let last = chain.body_frames(&mut ws, &q)[5];
    let x = Frame {
        rot: Rotation3::new(Vector3::new(0.1, 0.2, 0.3)).into_inner(),
        origin: Vector3::new(0.0, 0.0, 0.2),
    };
    let moved = chain.clone().with_tool(x);
    let pose = moved.tool_pose(&mut moved.workspace(), &q);
    let expected = last.compose(&x);
    assert!(
        (pose.origin - expected.origin).amax() < 1e-15 && (pose.rot - expected.rot).amax() < 1e-15
    );
}

#[test]
fn evaluations_into_a_workspace_do_not_allocate() {
    let chain = random_chain(61, 12);
    let mut ws = chain.workspace();
    let q = vec![0.3; 12];
    let qd = vec![-0.7; 12];
    let mut sink = 0.0;
    let allocations = alloc_count::count(|| {
        for _ in 0..10 {
            sink += chain.tool_pose(&mut ws, &q).origin.x;
            sink += chain.jacobian(&mut ws, &q)[(0, 0)];
            sink += chain.position_jacobian(&mut ws, &q)[(1, 1)];
            sink += chain.jacobian_dot(&mut ws, &q, &qd)[(2, 2)];
            sink += chain.inertia(&mut ws, &q)[(3, 3)];
            sink += chain.coriolis(&mut ws, &q, &qd)[4];
            sink += chain.gravity_torques(&mut ws, &q)[5];
            sink += chain.inverse_dynamics(&mut ws, &q, &qd, &qd)[6];
        }
    });
    assert!(sink.is_finite());
    assert_eq!(allocations, 0, "allocations in the evaluations");
    // The counter sees allocations (the test can fail).
    assert_eq!(
        alloc_count::count(|| drop(std::hint::black_box(vec![0.0; 3]))),
        1
    );
}
