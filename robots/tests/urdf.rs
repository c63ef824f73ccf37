//! `robots::urdf`: the path from base to tip, fixed joints folded, limits, merged inertials,
//! the tool point, and every refusal (each names the file and never quotes it). Pinocchio
//! checks the numbers on real arms (`tests/pinocchio.rs`).

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use robots::JointKind;
use robots::{
    parse_urdf, read_urdf, ChainEnds, UrdfChainError, MAX_LENGTH, URDF_MAX_DEPTH, URDF_MAX_JOINTS,
    URDF_MAX_LISTED_LINKS,
};
use std::time::{Duration, Instant};

/// A small arm: `world` -fixed-> `base` -revolute j1-> `l1` -fixed-> `l1b` -prismatic j2->
/// `l2` -continuous j3-> `l3` -fixed-> `tcp`; off the path, `sensor` (fixed on `l1`) and
/// `finger` (revolute on `l3`).
fn arm(finger_mass: f64) -> String {
    format!(
        r#"<?xml version="1.0"?>
<robot name="test-arm">
  <link name="world"/>
  <link name="base"/>
  <link name="l1">
    <inertial><origin xyz="0.1 0 0" rpy="0 0 0"/><mass value="2.0"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.04"/></inertial>
  </link>
  <link name="l1b"/>
  <link name="sensor">
    <inertial><origin xyz="0 0.2 0" rpy="0.3 0 0"/><mass value="1.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="l2">
    <inertial><origin xyz="0 0 0.1"/><mass value="1.5"/>
      <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.02" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="l3">
    <inertial><origin xyz="0.05 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <link name="tcp"/>
  <link name="finger">
    <inertial><origin xyz="0 0 0.02"/><mass value="{finger_mass}"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <joint name="mount" type="fixed">
    <parent link="world"/><child link="base"/><origin xyz="0 0 0.5" rpy="0 0 1.0"/>
  </joint>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/><origin xyz="0 0 0.3" rpy="0.1 0.2 0.3"/>
    <axis xyz="0 0 2"/><limit lower="-2" upper="2.5" effort="50" velocity="1.5"/>
  </joint>
  <joint name="flange" type="fixed">
    <parent link="l1"/><child link="l1b"/><origin xyz="0.4 0 0" rpy="0 1.5707963267948966 0"/>
  </joint>
  <joint name="sensor_mount" type="fixed">
    <parent link="l1"/><child link="sensor"/><origin xyz="0.1 0.1 0" rpy="0 0 0.5"/>
  </joint>
  <joint name="j2" type="prismatic">
    <parent link="l1b"/><child link="l2"/><origin xyz="0 0.1 0"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.3" effort="100" velocity="0"/>
  </joint>
  <joint name="j3" type="continuous">
    <parent link="l2"/><child link="l3"/><origin xyz="0 0 0.2" rpy="-0.4 0 0"/>
    <axis xyz="0 1 0"/>
  </joint>
  <joint name="tcp_joint" type="fixed">
    <parent link="l3"/><child link="tcp"/><origin xyz="0.1 0 0" rpy="0 0 0.7"/>
  </joint>
  <joint name="finger_joint" type="revolute">
    <parent link="l3"/><child link="finger"/><origin xyz="0.05 0 0"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>"#
    )
}

fn ends<'a>(base: &'a str, tip: &'a str) -> ChainEnds<'a> {
    ChainEnds {
        base,
        tip,
        tool: Vector3::new(0.01, 0.02, 0.03),
    }
}

/// The URDF pose as an isometry, written independently with nalgebra's Euler angles.
fn iso(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

#[test]
fn the_path_folds_fixed_joints_and_reads_limits() {
    let chain = parse_urdf("arm.urdf", &arm(0.2), &ends("world", "tcp")).unwrap();
    let names: Vec<&str> = chain.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["j1", "j2", "j3"]);
    let kinds: Vec<JointKind> = chain.joints().iter().map(|j| j.kind).collect();
    assert_eq!(
        kinds,
        [
            JointKind::Revolute,
            JointKind::Prismatic,
            JointKind::Continuous
        ]
    );
    let [j1, j2, j3] = [0, 1, 2].map(|i| chain.joints()[i].limits);
    assert_eq!(
        (
            j1.position_min,
            j1.position_max,
            j1.velocity_max,
            j1.effort_max
        ),
        (-2.0, 2.5, 1.5, 50.0)
    );
    assert_eq!(j1.velocity_min, -1.5);
    // velocity="0" and a missing <limit> leave the limit open.
    assert_eq!(
        (j2.position_min, j2.position_max, j2.velocity_max),
        (0.0, 0.3, f64::INFINITY)
    );
    assert_eq!(
        (j3.position_min, j3.position_max),
        (f64::NEG_INFINITY, f64::INFINITY)
    );
    assert_eq!(j3.effort_max, f64::INFINITY);
    assert_eq!(chain.joints()[0].axis, Vector3::z(), "axis normalised");

    let mut ws = chain.workspace();
    let q = [0.7, 0.12, -1.1];
    let expected = iso([0.0, 0.0, 0.5], [0.0, 0.0, 1.0])
        * iso([0.0, 0.0, 0.3], [0.1, 0.2, 0.3])
        * Isometry3::rotation(Vector3::z() * q[0])
        * iso([0.4, 0.0, 0.0], [0.0, std::f64::consts::FRAC_PI_2, 0.0])
        * iso([0.0, 0.1, 0.0], [0.0; 3])
        * Isometry3::translation(0.0, 0.0, q[1])
        * iso([0.0, 0.0, 0.2], [-0.4, 0.0, 0.0])
        * Isometry3::rotation(Vector3::y() * q[2])
        * iso([0.1, 0.0, 0.0], [0.0, 0.0, 0.7])
        * Isometry3::translation(0.01, 0.02, 0.03);
    let pose = chain.tool_pose(&mut ws, &q);
    assert!(
        (pose.origin - expected.translation.vector).amax() < 1e-14,
        "{} vs {}",
        pose.origin,
        expected.translation.vector
    );
    let r: Matrix3<f64> = *expected.rotation.to_rotation_matrix().matrix();
    assert!((pose.rot - r).amax() < 1e-14);
}

#[test]
fn a_body_carries_its_fixed_links_and_not_the_moving_branches() {
    let chain = parse_urdf("arm.urdf", &arm(0.2), &ends("base", "l3")).unwrap();
    // Body 1 is l1 with its sensor (and l1b, massless): masses add, centres average.
    let b1 = chain.joints()[0].body.unwrap();
    assert!((b1.mass - 3.0).abs() < 1e-15);
    let sensor = Vector3::new(0.1, 0.1, 0.0)
        + Rotation3::from_euler_angles(0.0, 0.0, 0.5) * Vector3::new(0.0, 0.2, 0.0);
    let com = (Vector3::new(0.1, 0.0, 0.0) * 2.0 + sensor) / 3.0;
    assert!((b1.com - com).amax() < 1e-15, "{} vs {com}", b1.com);
    // The inertia about the merged centre: trace = sum of traces + parallel-axis terms.
    let d1 = Vector3::new(0.1, 0.0, 0.0) - com;
    let d2 = sensor - com;
    let trace = 0.09 + 0.03 + 2.0 * (2.0 * d1.norm_squared() + d2.norm_squared());
    assert!((b1.inertia.trace() - trace).abs() < 1e-15);
    // The finger hangs on l3 by a moving joint: its mass is not part of the chain.
    let heavy = parse_urdf("arm.urdf", &arm(7.0), &ends("base", "l3")).unwrap();
    let (mut ws, mut ws_heavy) = (chain.workspace(), heavy.workspace());
    let q = [0.3, 0.1, 0.9];
    assert_eq!(chain.inertia(&mut ws, &q), heavy.inertia(&mut ws_heavy, &q));
    assert_eq!(
        chain.gravity_torques(&mut ws, &q),
        heavy.gravity_torques(&mut ws_heavy, &q)
    );
}

fn error(text: &str, base: &str, tip: &str) -> (UrdfChainError, String) {
    let e = parse_urdf("robots/my-arm.urdf", text, &ends(base, tip)).unwrap_err();
    let m = e.to_string();
    assert!(m.starts_with("robots/my-arm.urdf: "), "{m}");
    (e, m)
}

#[test]
fn unknown_links_are_named_with_a_bounded_list_of_the_valid_ones() {
    let (e, m) = error(&arm(0.2), "base", "hand");
    assert!(
        matches!(e, UrdfChainError::UnknownLink { end: "tip", .. }),
        "{m}"
    );
    assert!(
        m.contains("\"hand\"") && m.contains("\"l1b\"") && m.contains("\"finger\""),
        "{m}"
    );
    let links: String = (0..50)
        .map(|i| format!("<link name=\"link{i}\"/>"))
        .collect();
    let (_, m) = error(
        &format!("<robot name=\"r\">{links}</robot>"),
        "nowhere",
        "link1",
    );
    assert!(
        m.contains(&format!("and {} more", 50 - URDF_MAX_LISTED_LINKS)),
        "{m}"
    );
    assert!(!m.contains("link49"), "{m}");
}

#[test]
fn a_tip_not_below_the_base_is_refused() {
    let (e, m) = error(&arm(0.2), "l2", "sensor");
    assert!(matches!(e, UrdfChainError::NotBelow { .. }), "{m}");
    assert!(
        m.contains("\"l1\"") && m.contains("\"world\""),
        "ancestors listed: {m}"
    );
    let (e, _) = error(&arm(0.2), "l3", "l3");
    assert!(matches!(e, UrdfChainError::Chain { .. }), "no moving joint");
}

#[test]
fn unsupported_joints_and_non_trees_are_refused() {
    let floating = arm(0.2).replace(
        r#"name="j2" type="prismatic""#,
        r#"name="j2" type="floating""#,
    );
    let (e, m) = error(&floating, "base", "tcp");
    assert!(
        matches!(
            e,
            UrdfChainError::Unsupported {
                kind: "floating",
                ..
            }
        ) && m.contains("\"j2\""),
        "{m}"
    );
    let planar = arm(0.2).replace(
        r#"name="j3" type="continuous""#,
        r#"name="j3" type="planar""#,
    );
    assert!(matches!(
        error(&planar, "base", "tcp").0,
        UrdfChainError::Unsupported { kind: "planar", .. }
    ));
    // A floating joint off the path does not matter.
    let off = arm(0.2).replace(
        r#"name="finger_joint" type="revolute""#,
        r#"name="finger_joint" type="floating""#,
    );
    assert!(parse_urdf("x.urdf", &off, &ends("base", "tcp")).is_ok());
    let mimic = arm(0.2).replace(
        r#"<axis xyz="0 1 0"/>"#,
        r#"<axis xyz="0 1 0"/><mimic joint="j1"/>"#,
    );
    assert!(matches!(
        error(&mimic, "base", "tcp").0,
        UrdfChainError::Unsupported {
            kind: "a mimic joint",
            ..
        }
    ));
    let two_parents = arm(0.2).replace(
        r#"<parent link="l3"/><child link="finger"/>"#,
        r#"<parent link="l3"/><child link="l2"/>"#,
    );
    assert!(matches!(
        error(&two_parents, "base", "tcp").0,
        UrdfChainError::TwoParents { .. }
    ));
    let undeclared = arm(0.2).replace(r#"<link name="tcp"/>"#, "");
    let (e, m) = error(&undeclared, "base", "l3");
    assert!(
        matches!(e, UrdfChainError::UndeclaredLink { .. }) && m.contains("\"tcp_joint\""),
        "{m}"
    );
    let cycle = r#"<robot name="c"><link name="a"/><link name="b"/>
        <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
        <joint name="ba" type="revolute"><parent link="b"/><child link="a"/>
        <limit lower="-1" upper="1" velocity="1" effort="1"/></joint></robot>"#;
    assert!(matches!(
        error(cycle, "a", "b").0,
        UrdfChainError::Cycle { .. }
    ));
}

#[test]
fn bad_limits_and_inertials_name_the_joint() {
    let empty = arm(0.2).replace(r#"lower="-2" upper="2.5""#, r#"lower="2" upper="-2""#);
    let (e, m) = error(&empty, "base", "tcp");
    assert!(
        matches!(e, UrdfChainError::Chain { .. })
            && m.contains("joint 1 (\"j1\")")
            && m.contains("lower position limit"),
        "{m}"
    );
    let negative = arm(-1.0);
    let (_, m) = error(&negative, "base", "finger");
    assert!(
        m.contains("(\"finger_joint\")") && m.contains("mass is negative"),
        "{m}"
    );
    let zero_axis = arm(0.2).replace(r#"<axis xyz="0 1 0"/>"#, r#"<axis xyz="0 0 0"/>"#);
    assert!(error(&zero_axis, "base", "tcp").1.contains("zero length"));
}

#[test]
fn parse_errors_and_oversized_files_quote_nothing() {
    let secret = "SECRET-7f3a";
    for text in [
        format!("<robot name=\"x\"><link name=\"a\">{secret}"),
        format!("<robot name=\"x\"><link name=\"a\"/><joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"{secret} 0 0\"/></joint></robot>"),
        format!("<robot name=\"x\"><link name=\"a\"/><joint name=\"j\" type=\"{secret}\"><parent link=\"a\"/><child link=\"b\"/></joint></robot>"),
    ] {
        let (e, m) = error(&text, "a", "b");
        assert!(matches!(e, UrdfChainError::Syntax { .. }), "{m}");
        assert!(!m.contains(secret), "{m}");
    }
    let joints: String = (0..=URDF_MAX_JOINTS)
        .map(|i| format!("<joint name=\"j{i}\" type=\"fixed\"><parent link=\"a\"/><child link=\"l{i}\"/></joint>"))
        .collect();
    let (e, _) = error(
        &format!("<robot name=\"x\"><link name=\"a\"/>{joints}</robot>"),
        "a",
        "l0",
    );
    assert!(matches!(e, UrdfChainError::TooManyJoints { .. }));
}

#[test]
fn read_goes_through_the_input_reader() {
    let dir = inputs::Scratch::dir("robots-urdf-test");
    let inner = dir.join("papers");
    std::fs::create_dir_all(&inner).unwrap();
    let file = dir.join("arm.urdf");
    std::fs::write(&file, arm(0.2)).unwrap();
    let chain = read_urdf(&file, inputs::Origin::Named, &ends("base", "tcp")).unwrap();
    assert_eq!(chain.dof(), 3);
    // A link that leads out of the directory it is found in is refused, naming the path.
    let link = inner.join("arm.urdf");
    std::os::unix::fs::symlink(&file, &link).unwrap();
    let e = read_urdf(&link, inputs::Origin::Named, &ends("base", "tcp")).unwrap_err();
    assert!(
        matches!(e, UrdfChainError::Input(_)) && e.to_string().contains("papers/arm.urdf"),
        "{e}"
    );
    let missing = read_urdf(
        &dir.join("none.urdf"),
        inputs::Origin::Named,
        &ends("base", "tcp"),
    )
    .unwrap_err();
    assert!(missing.to_string().contains("none.urdf"), "{missing}");
}

#[test]
fn a_two_hundred_joint_urdf_is_one_chain() {
    let n = 200;
    let links: String = (0..=n)
        .map(|i| format!("<link name=\"l{i}\"><inertial><mass value=\"0.1\"/><inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial></link>"))
        .collect();
    let joints: String = (0..n)
        .map(|i| {
            format!(
                "<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{i}\"/><child link=\"l{}\"/>\
                 <origin xyz=\"0 0 0.01\" rpy=\"0 {} 0\"/><axis xyz=\"{}\"/>\
                 <limit lower=\"-3\" upper=\"3\" velocity=\"1\" effort=\"10\"/></joint>",
                i + 1,
                0.01 * i as f64,
                if i % 2 == 0 { "0 0 1" } else { "0 1 0" }
            )
        })
        .collect();
    let text = format!("<robot name=\"long\">{links}{joints}</robot>");
    let chain = parse_urdf("long.urdf", &text, &ends("l0", &format!("l{n}"))).unwrap();
    assert_eq!(chain.dof(), n);
    let mut ws = chain.workspace();
    let q: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let h = chain.inertia(&mut ws, &q).clone();
    assert!((&h - h.transpose()).amax() <= 1e-12 * h.amax());
    assert!(
        h.clone().cholesky().is_some(),
        "H positive definite at 200 joints"
    );
    assert_eq!(chain.jacobian(&mut ws, &q).ncols(), n);
}

/// The test arm with `extra` just before `</robot>`.
fn arm_with(extra: &str) -> String {
    arm(0.2).replace("</robot>", &format!("{extra}\n</robot>"))
}

/// `levels` nested `<a>` elements (self-closing innermost none), with `inner` in the deepest.
fn nested(levels: usize, inner: &str) -> String {
    format!("{}{inner}{}", "<a>".repeat(levels), "</a>".repeat(levels))
}

#[test]
fn deep_nesting_is_refused_before_the_parser_sees_it() {
    // Ten thousand levels inside an ignored <gazebo> (the parser recursed per level and
    // overflowed the stack, aborting the process, whether or not the robot was used); two
    // hundred thousand must end as fast.
    for levels in [10_000, 200_000] {
        let text = arm_with(&format!(
            "<gazebo>{}</gazebo>",
            nested(levels, "SECRET-d33p")
        ));
        let started = Instant::now();
        let (e, m) = error(&text, "base", "tcp");
        assert!(
            started.elapsed() < Duration::from_secs(2),
            "{levels} levels"
        );
        assert!(
            matches!(e, UrdfChainError::TooDeep { limit, .. } if limit == URDF_MAX_DEPTH),
            "{m}"
        );
        assert!(m.contains(&URDF_MAX_DEPTH.to_string()), "{m}");
        assert!(!m.contains("SECRET"), "{m}");
    }
    // <robot> is level 1 and <gazebo> level 2, a self-closing leaf a level too: the limit
    // itself is read, one more is not.
    let at_limit = |extra: usize| {
        arm_with(&format!(
            "<gazebo>{}</gazebo>",
            nested(URDF_MAX_DEPTH - 3 + extra, "<leaf/>")
        ))
    };
    assert_eq!(
        parse_urdf("x.urdf", &at_limit(0), &ends("base", "tcp"))
            .unwrap()
            .dof(),
        3
    );
    let (e, _) = error(&at_limit(1), "base", "tcp");
    assert!(matches!(e, UrdfChainError::TooDeep { .. }));
    // What is not an element opens no level: comments, CDATA, processing instructions, a
    // DOCTYPE, quoted attribute values (which may hold `>` and `<`); self-closing elements side
    // by side are one level.
    let deep_text = "<a>".repeat(3 * URDF_MAX_DEPTH);
    let not_elements = format!(
        "<!-- {deep_text} --><![CDATA[{deep_text}]]><?pi {deep_text} ?>\
         <note text=\"a > b {deep_text}\" other='{deep_text}>'/>{}",
        "<leaf/>".repeat(3 * URDF_MAX_DEPTH)
    );
    let text = arm_with(&format!(
        "<gazebo>{}</gazebo>",
        nested(URDF_MAX_DEPTH - 3, &not_elements)
    ))
    .replace(
        "<?xml version=\"1.0\"?>",
        "<?xml version=\"1.0\"?>\n<!DOCTYPE robot>",
    );
    assert_eq!(
        parse_urdf("x.urdf", &text, &ends("base", "tcp"))
            .map_err(|e| e.to_string())
            .unwrap()
            .dof(),
        3
    );
}

#[test]
fn two_links_or_joints_of_one_name_are_refused_by_position() {
    // <link> elements: world 1, base 2, l1 3, l1b 4, sensor 5, l2 6, ..., finger 9; a second
    // "l2" is the tenth.
    let (e, m) = error(&arm_with("<link name=\"l2\"/>"), "base", "tcp");
    assert!(
        matches!(
            e,
            UrdfChainError::Duplicate {
                element: "link",
                first: 6,
                second: 10,
                ..
            }
        ),
        "{m}"
    );
    assert!(m.contains("\"l2\"") && m.contains("unique"), "{m}");
    // <joint> elements: mount 1, j1 2, ..., finger_joint 8; a second "j1" is the ninth.
    let (e, m) = error(
        &arm_with(
            "<link name=\"extra\"/><joint name=\"j1\" type=\"fixed\"><parent link=\"tcp\"/>\
             <child link=\"extra\"/></joint>",
        ),
        "base",
        "tcp",
    );
    assert!(
        matches!(
            e,
            UrdfChainError::Duplicate {
                element: "joint",
                first: 2,
                second: 9,
                ..
            }
        ),
        "{m}"
    );
    // A long name is shown cut.
    let long = "n".repeat(500);
    let (_, m) = error(
        &arm_with(&format!("<link name=\"{long}\"/><link name=\"{long}\"/>")),
        "base",
        "tcp",
    );
    assert!(m.len() < 400 && m.contains("..."), "{m}");
}

#[test]
fn huge_or_non_finite_origins_are_refused_and_huge_axes_normalised() {
    let on_j1 = r#"<origin xyz="0 0 0.3" rpy="0.1 0.2 0.3"/>"#;
    // On the path, off it (the finger, a moving branch), in an inertial.
    for (from, to, owner) in [
        (
            on_j1,
            r#"<origin xyz="1e308 0 0.3" rpy="0.1 0.2 0.3"/>"#,
            "joint \"j1\"",
        ),
        (
            r#"<origin xyz="0.05 0 0"/>
    <axis xyz="1 0 0"/>"#,
            r#"<origin xyz="0.05 0 -11"/>
    <axis xyz="1 0 0"/>"#,
            "joint \"finger_joint\"",
        ),
        (
            r#"<origin xyz="0.1 0 0" rpy="0 0 0"/><mass value="2.0"/>"#,
            r#"<origin xyz="0.1 -1e300 0" rpy="0 0 0"/><mass value="2.0"/>"#,
            "link \"l1\" <inertial>",
        ),
    ] {
        let text = arm(0.2);
        assert!(text.contains(from), "{from}");
        let (e, m) = error(&text.replacen(from, to, 1), "base", "tcp");
        assert!(
            matches!(e, UrdfChainError::TooLong { limit, .. } if limit == MAX_LENGTH),
            "{m}"
        );
        assert!(
            m.contains(owner) && m.contains("<origin xyz>") && m.contains("[-10, 10] m"),
            "{m}"
        );
        assert!(m.len() < 300, "no 300-digit number: {m}");
    }
    let nan_rpy = arm(0.2).replacen(on_j1, r#"<origin xyz="0 0 0.3" rpy="0.1 nan 0.3"/>"#, 1);
    let (e, m) = error(&nan_rpy, "base", "tcp");
    assert!(
        matches!(
            e,
            UrdfChainError::OriginNotFinite {
                field: "rpy",
                index: 1,
                ..
            }
        ),
        "{m}"
    );
    let inf_xyz = arm(0.2).replacen(on_j1, r#"<origin xyz="0 1e999 0.3"/>"#, 1);
    assert!(matches!(
        error(&inf_xyz, "base", "tcp").0,
        UrdfChainError::OriginNotFinite { field: "xyz", .. }
    ));
    // The bound itself is a length.
    let at_bound = arm(0.2).replacen(on_j1, r#"<origin xyz="10 -10 0.3"/>"#, 1);
    assert!(parse_urdf("x.urdf", &at_bound, &ends("base", "tcp")).is_ok());
    // An axis is scaled by its largest entry before it is normalised: a huge one (whose
    // squares overflow) and a tiny one (whose squares underflow) keep their direction.
    for (axis, unit) in [
        ("1e308 1e308 0", Vector3::new(1.0, 1.0, 0.0) / 2f64.sqrt()),
        ("0 -1e-200 0", -Vector3::y()),
    ] {
        let text = arm(0.2).replacen(
            r#"<axis xyz="0 1 0"/>"#,
            &format!(r#"<axis xyz="{axis}"/>"#),
            1,
        );
        let chain = parse_urdf("x.urdf", &text, &ends("base", "tcp")).unwrap();
        let a = chain.joints()[2].axis;
        assert!((a - unit).amax() < 1e-15, "{axis}: {a}");
        let mut ws = chain.workspace();
        assert!(chain
            .jacobian(&mut ws, &[0.1, 0.1, 0.1])
            .iter()
            .all(|x| x.is_finite()));
    }
}
