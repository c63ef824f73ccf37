//! `build` and the analytic `build_dot` overrides must not allocate: counted with a global
//! allocator that counts allocations made by the current thread while a flag is set.

use crate::common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;

use common::{Circle, PlanarZ};
use nalgebra::SVector;
use robots::Robot;
use schemes::spec::build_scheme;

struct Counting;

thread_local! {
    static ON: Cell<bool> = const { Cell::new(false) };
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if ON.with(|o| o.get()) {
            COUNT.with(|c| c.set(c.get() + 1));
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<F: FnOnce()>(f: F) -> usize {
    COUNT.with(|c| c.set(0));
    ON.with(|o| o.set(true));
    f();
    ON.with(|o| o.set(false));
    COUNT.with(|c| c.get())
}

#[test]
fn build_and_build_dot_do_not_allocate() {
    const N: usize = 6;
    // The counter itself works.
    assert!(count(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    let theta0 = SVector::<f64, N>::from([0.3, 1.2, -0.8, 0.5, -0.4, 0.2]);
    let robot = Arc::new(PlanarZ::<N>);
    let path = Arc::new(Circle {
        r0: robot.position(&theta0),
        a: 0.05,
        t_end: 5.0,
    });
    let specs = common::paper_specs();
    let th = theta0 + SVector::<f64, N>::repeat(0.05);
    let thd = SVector::<f64, N>::repeat(0.2);
    for spec in &specs {
        let s = build_scheme::<N>(
            spec,
            robot.clone(),
            Some(robot.clone()),
            path.clone(),
            theta0,
        )
        .unwrap();
        let mut qp = s.new_qp();
        let mut dot = s.new_qp();
        let mut scratch = s.new_dot_scratch();
        let n = count(|| s.build(1.0, &th, &thd, &mut qp));
        assert_eq!(n, 0, "{}: build allocated {n} times", spec.display_name());
        let n = count(|| s.build_dot(1.0, &th, &thd, &thd, &mut dot, &mut scratch));
        assert_eq!(
            n,
            0,
            "{}: build_dot allocated {n} times",
            spec.display_name()
        );
    }
}

#[test]
fn the_dynamic_size_znn_scheme_does_not_allocate_at_200_joints() {
    use schemes::slice_scheme::SliceScheme;
    let arm = robots::NLinkDyn::new(200).unwrap();
    let home = arm.home();
    let path = Arc::new(Circle {
        r0: arm.position(&home),
        a: 0.05,
        t_end: 5.0,
    });
    let s = schemes::velocity_rmp_dyn::NLinkZnn::new(arm, path, home.as_slice(), 1.0, 1.0).unwrap();
    let th: Vec<f64> = home.iter().map(|v| v + 0.05).collect();
    let thd = vec![0.2; 200];
    let (mut qp, mut dot, mut scratch) = (s.new_qp(), s.new_qp(), s.new_dot_scratch());
    assert_eq!(count(|| s.build(1.0, &th, &thd, &mut qp)), 0);
    assert_eq!(
        count(|| s.build_dot(1.0, &th, &thd, &thd, &mut dot, &mut scratch)),
        0
    );
}
