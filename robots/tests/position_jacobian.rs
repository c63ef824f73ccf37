//! `Robot::position_jacobian` gives, bit for bit, what `Robot::position` and `Robot::jacobian`
//! give separately, for every model the registry names, n-link arms and a mounted arm (tool
//! offset and base transform): the schemes' tracking term calls the shared evaluation, and the
//! results must not depend on which of the two a model implements.

use robots::{nlink_name, robot_by_name, robot_names, Mount, Mounted, Robot};
use std::sync::Arc;

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Checks the shared evaluation against the separate ones at 12 configurations.
pub(crate) fn assert_shared_is_separate(robot: &dyn Robot) {
    let n = robot.dof();
    for k in 0..12 {
        let theta: Vec<f64> = (0..n)
            .map(|i| (0.37 * (k * n + i) as f64).sin() * 2.5 - 0.1 * k as f64)
            .collect();
        let (mut shared, mut alone) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
        let p = robot.position_jacobian(&theta, &mut shared);
        robot.jacobian(&theta, &mut alone);
        let name = robot.name();
        assert_eq!(
            bits(p.as_slice()),
            bits(robot.position(&theta).as_slice()),
            "{name}: p"
        );
        assert_eq!(bits(&shared), bits(&alone), "{name}: J");
    }
}

#[test]
fn every_model_shares_its_evaluation_bit_for_bit() {
    // Other tests of this binary register files of their own, some refused on purpose (a
    // missing URDF): the models are those that build, and the suite's own must be among them.
    let models: Vec<_> = robot_names()
        .iter()
        .cloned()
        .chain([2, 7, 30].map(nlink_name))
        .filter_map(|name| robot_by_name(&name).ok())
        .collect();
    for own in ["jaco2-pen", "katana6m180", "panda", "puma560", "nlink-7"] {
        assert!(models.iter().any(|m| m.name() == own), "{own} missing");
    }
    for model in &models {
        assert_shared_is_separate(model.robot.as_ref());
    }
}

#[test]
fn a_mounted_arm_shares_its_evaluation_bit_for_bit() {
    for name in ["jaco2-pen", "panda", "puma560"] {
        let inner = robot_by_name(name).unwrap().robot;
        for tool in [[0.0; 3], [0.01, -0.02, 0.05]] {
            let mount = Mount::new(tool, [0.1, -0.2, 0.3], [0.2, -0.1, 0.4]).unwrap();
            let mounted = Mounted::new(Arc::clone(&inner), mount).unwrap();
            assert_shared_is_separate(&mounted);
        }
    }
}
