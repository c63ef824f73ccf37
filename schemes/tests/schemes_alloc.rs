//! `build` and the analytic `build_dot` overrides must not allocate: counted with the
//! workspace's counting allocator (crate `alloc-count`: this thread's allocations).

use crate::common;

use std::sync::Arc;

use alloc_count::count;
use common::{Circle, PlanarZ};
use nalgebra::SVector;
use robots::Robot;
use schemes::build_scheme;

#[test]
fn build_and_build_dot_do_not_allocate() {
    const N: usize = 6;
    // The counter itself works.
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    let theta0 = SVector::<f64, N>::from([0.3, 1.2, -0.8, 0.5, -0.4, 0.2]);
    let robot = Arc::new(PlanarZ::new(N));
    let path = Arc::new(Circle {
        r0: robot.position(theta0.as_slice()),
        a: 0.05,
        t_end: 5.0,
    });
    let specs: Vec<_> = common::paper_specs()
        .into_iter()
        .chain(common::composed_specs())
        .collect();
    let th = theta0 + SVector::<f64, N>::repeat(0.05);
    let thd = SVector::<f64, N>::repeat(0.2);
    for spec in &specs {
        let s = build_scheme(
            spec,
            robot.clone(),
            Some(robot.clone()),
            path.clone(),
            theta0.as_slice(),
        )
        .unwrap();
        let mut qp = s.new_qp();
        let mut dot = s.new_qp();
        let mut scratch = s.new_dot_scratch();
        let (th, thd) = (th.as_slice(), thd.as_slice());
        let n = count(|| s.build(1.0, th, thd, &mut qp));
        assert_eq!(n, 0, "{}: build allocated {n} times", spec.display_name());
        let n = count(|| s.build_dot(1.0, th, thd, thd, &mut dot, &mut scratch));
        assert_eq!(
            n,
            0,
            "{}: build_dot allocated {n} times",
            spec.display_name()
        );
    }
}

/// Every velocity-level scheme on an arm of `robot`'s joint count builds without allocating,
/// once the thread has evaluated the arm (a DH chain's frame buffer grows on its first use).
fn velocity_schemes_do_not_allocate(robot: Arc<dyn robots::Robot>, pose: &[f64]) {
    let path = Arc::new(Circle {
        r0: robot.position(pose),
        a: 0.05,
        t_end: 5.0,
    });
    let th: Vec<f64> = pose.iter().map(|v| v + 0.05).collect();
    let thd = vec![0.2; pose.len()];
    let specs = common::paper_specs()
        .into_iter()
        .chain(common::composed_specs());
    for spec in specs.filter(|s| !s.needs_dynamics()) {
        let s = build_scheme(&spec, robot.clone(), None, path.clone(), pose).unwrap();
        let (mut qp, mut dot, mut scratch) = (s.new_qp(), s.new_qp(), s.new_dot_scratch());
        s.build(1.0, &th, &thd, &mut qp);
        let name = spec.display_name();
        assert_eq!(count(|| s.build(1.0, &th, &thd, &mut qp)), 0, "{name}");
        assert_eq!(
            count(|| s.build_dot(1.0, &th, &thd, &thd, &mut dot, &mut scratch)),
            0,
            "{name}"
        );
    }
}

#[test]
fn the_schemes_do_not_allocate_at_200_joints_nor_on_a_dh_chain() {
    let arm = robots::NLink::new(200).unwrap();
    let home = arm.home();
    velocity_schemes_do_not_allocate(Arc::new(arm), home.as_slice());
    let puma = robots::robot_by_name("puma560").unwrap();
    velocity_schemes_do_not_allocate(puma.robot, &puma.stated_pose);
}

#[test]
fn hl_jdf_on_the_jaco2_does_not_allocate() {
    let jaco2 = robots::robot_by_name("jaco2-pen").unwrap();
    let dynamics = jaco2.dynamics.clone().unwrap();
    let pose = jaco2.stated_pose.clone();
    let path = Arc::new(Circle {
        r0: jaco2.robot.position(&pose),
        a: 0.05,
        t_end: 5.0,
    });
    let spec = common::paper_specs()
        .into_iter()
        .find(|s| s.needs_dynamics())
        .unwrap();
    let s = build_scheme(&spec, jaco2.robot, Some(dynamics), path, &pose).unwrap();
    let thd = vec![0.2; 6];
    let (mut qp, mut dot, mut scratch) = (s.new_qp(), s.new_qp(), s.new_dot_scratch());
    let mut tau = vec![0.0; 6];
    s.build(1.0, &pose, &thd, &mut qp);
    assert_eq!(count(|| s.build(1.0, &pose, &thd, &mut qp)), 0);
    assert_eq!(
        count(|| s.build_dot(1.0, &pose, &thd, &thd, &mut dot, &mut scratch)),
        0
    );
    assert_eq!(count(|| assert!(s.torque(&pose, &thd, &thd, &mut tau))), 0);
}
