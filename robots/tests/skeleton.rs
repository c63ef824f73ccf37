//! The arm's drawing skeleton: it starts at the base, ends at the task point, and its segments
//! have the models' constant link lengths.

use crate::common;

use common::*;
use nalgebra::{SVector, Vector3};
use robots::{Jaco2, Katana6m180, Robot};

const TOL: f64 = 1e-12;

fn close(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    (a - b).norm() <= TOL
}

#[test]
fn jaco2_skeleton_runs_from_the_base_through_the_frame_origins_to_the_task_point() {
    for robot in [Jaco2::pen(), Jaco2::kinova(), Jaco2::hand()] {
        let params = robot.chain().params();
        for theta in random_vectors::<6>(11, 50, 3.0) {
            let points = robot.skeleton_n(&theta);
            assert_eq!(
                points.len(),
                8,
                "{}: origins 0..=6 and the tip",
                robot.name()
            );
            assert!(close(&points[0], &Vector3::zeros()), "{}", robot.name());
            assert!(
                close(&points[7], &robot.position_n(&theta)),
                "{}",
                robot.name()
            );
            // Classical DH: o_i - o_{i-1} = d_i z_{i-1} + a_i x_i, two orthogonal pieces.
            for (i, p) in params.iter().enumerate() {
                let length = (points[i + 1] - points[i]).norm();
                assert!(
                    (length - p.a.hypot(p.d)).abs() <= TOL,
                    "{} link {}: {length} vs {}",
                    robot.name(),
                    i + 1,
                    p.a.hypot(p.d)
                );
            }
            let tip = (points[7] - points[6]).norm();
            assert!((tip - robot.tip().norm()).abs() <= TOL, "{}", robot.name());
        }
    }
}

#[test]
fn katana_skeleton_has_the_link_lengths_of_eq_2_and_ends_at_the_task_point() {
    let robot = Katana6m180::new();
    let lengths = [robot.l1, robot.l2, robot.l3, robot.l4 + robot.l5];
    for theta in random_vectors::<5>(12, 50, 3.0) {
        let points = robot.skeleton_n(&theta);
        assert_eq!(points.len(), 5, "base, shoulder, elbow, wrist, tip");
        assert!(close(&points[0], &Vector3::zeros()));
        assert!(close(&points[4], &robot.position_n(&theta)));
        for (k, l) in lengths.iter().enumerate() {
            let length = (points[k + 1] - points[k]).norm();
            assert!((length - l).abs() <= TOL, "segment {k}: {length} vs {l}");
        }
    }
}

#[test]
fn katana_skeleton_with_the_upper_arm_upright_matches_eq_2_by_hand() {
    let robot = Katana6m180::new();
    let theta = SVector::from([0.3, std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.7]);
    let points = robot.skeleton_n(&theta);
    let top = robot.l1 + robot.l2 + robot.l3;
    assert!(close(&points[3], &Vector3::new(0.0, 0.0, top)));
    // Upper arm and forearm upright; theta2 + theta3 + theta4 = pi/2 turns the wrist horizontal.
    let reach = robot.l4 + robot.l5;
    assert!(close(
        &points[4],
        &Vector3::new(0.3f64.cos() * reach, 0.3f64.sin() * reach, top)
    ));
}
