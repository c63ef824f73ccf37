//! Hostile robot files: each is refused with an error naming the file and the field, and no
//! input panics.

use robots::builtin_files;
use robots::DataRobot;
use robots::{RobotFileError, RobotForm, RobotSpec, RuleError, MAX_LENGTH, ROBOT_FILE_MAX_BYTES};

/// The built-in PUMA 560 file, the base of every mutation here.
fn puma_text() -> &'static str {
    builtin_files()
        .iter()
        .find(|(f, _)| *f == "puma560.toml")
        .map(|(_, t)| *t)
        .unwrap()
}

/// The PUMA file with `from` replaced by `to` (which must occur).
fn mutated(from: &str, to: &str) -> String {
    let text = puma_text();
    assert!(text.contains(from), "{from:?} not in puma560.toml");
    text.replacen(from, to, 1)
}

fn refuse(text: &str) -> RobotFileError {
    let err = RobotSpec::parse("hostile.toml", text).expect_err("the file must be refused");
    let message = err.to_string();
    assert!(message.starts_with("hostile.toml: "), "{message}");
    println!("{message}");
    err
}

#[test]
fn the_unmodified_file_parses() {
    let spec = RobotSpec::parse("puma560.toml", puma_text()).unwrap();
    assert_eq!(spec.name(), "puma560");
    assert_eq!(spec.joints().len(), 6);
    assert_eq!(robots::Robot::dof(&DataRobot::new(&spec)), 6);
}

#[test]
fn nan_is_refused_naming_the_field() {
    let err = refuse(&mutated("a = 0.4318", "a = nan"));
    assert!(
        matches!(&err, RobotFileError::Rule { source: RuleError::NotFinite { field, value, .. }, .. } if field == "joint 2: a" && value.is_nan()),
        "{err:?}"
    );
    let err = refuse(&mutated(
        "tool = [0.0, 0.0, 0.05625]",
        "tool = [0.0, inf, 0.05625]",
    ));
    assert!(
        matches!(&err, RobotFileError::Rule { source: RuleError::NotFinite { field, .. }, .. } if field == "tool[1]")
    );
}

#[test]
fn theta_min_above_theta_max_is_refused() {
    let err = refuse(&mutated("theta_min = -2.7751", "theta_min = 2.8"));
    assert!(
        matches!(
            err,
            RobotFileError::Rule {
                source: RuleError::EmptyRange { joint: 1, .. },
                ..
            }
        ),
        "{err:?}"
    );
}

#[test]
fn unknown_convention_lists_the_valid_ones() {
    let err = refuse(&mutated(
        "convention = \"standard\"",
        "convention = \"craig\"",
    ));
    let message = err.to_string();
    assert!(matches!(err, RobotFileError::Syntax { .. }));
    assert!(
        message.contains("craig") && message.contains("standard") && message.contains("modified")
    );
    let err = refuse(&mutated("convention = \"standard\"\n", ""));
    assert!(err.to_string().contains("convention"), "{err}");
}

#[test]
fn eight_joints_are_an_arm_and_one_is_refused_naming_the_field() {
    let text = format!(
        "{}\n[[joint]]\na = 0.0\nalpha = 0.0\nd = 0.1\n\n[[joint]]\na = 0.0\nalpha = 0.0\nd = 0.1\n",
        puma_text().replace("stated_pose", "# stated_pose")
    );
    let spec = RobotSpec::parse("eight.toml", &text).unwrap();
    assert_eq!(robots::Robot::dof(&DataRobot::new(&spec)), 8);
    let one = puma_text().replace("stated_pose", "# stated_pose");
    let first = one.find("[[joint]]").unwrap();
    let second = first + 1 + one[first + 1..].find("[[joint]]").unwrap();
    let err = refuse(&one[..second]);
    assert!(
        matches!(
            err,
            RobotFileError::Rule {
                source: RuleError::JointCount { joints: 1, .. },
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("field `joint`"), "{err}");
}

#[test]
fn unknown_fields_are_refused() {
    let err = refuse(&mutated("name = ", "colour = \"red\"\nname = "));
    assert!(err.to_string().contains("colour"), "{err}");
    let err = refuse(&mutated(
        "velocity_max = 1.5",
        "velocity_max = 1.5\nvelocity_maximum = 2.0",
    ));
    assert!(err.to_string().contains("velocity_maximum"), "{err}");
}

#[test]
fn oversized_files_are_refused_before_parsing() {
    let big = format!(
        "{}\n#{}\n",
        puma_text(),
        "x".repeat(ROBOT_FILE_MAX_BYTES as usize)
    );
    let err = refuse(&big);
    assert!(
        matches!(
            err,
            RobotFileError::Rule {
                source: RuleError::TooLarge { .. },
                ..
            }
        ),
        "{err:?}"
    );
}

/// Whether an error is the one a case expects.
type Expected = fn(&RobotFileError) -> bool;

#[test]
fn other_invalid_values_are_refused() {
    let cases: [(&str, &str, Expected); 8] = [
        ("name = \"puma560\"", "name = \"Puma 560\"", |e| matches!(e, RobotFileError::Rule { source: RuleError::Name, .. })),
        ("name = \"puma560\"", "name = \"puma--560\"", |e| matches!(e, RobotFileError::Rule { source: RuleError::Name, .. })),
        ("velocity_max = 1.5", "velocity_max = 0.0", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::Limit { field: "velocity_max", joint: 1, .. }, .. })
        }),
        ("velocity_max = 1.5", "velocity_max = 1.5\nvelocity_min = 0.5", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::Limit { field: "velocity_min", .. }, .. })
        }),
        ("velocity_max = 1.5", "velocity_max = 1.5\nacceleration_max = -1.0", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::Limit { field: "acceleration_max", .. }, .. })
        }),
        ("convention = \"standard\"", "convention = \"modified\"", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::Flange { .. }, .. })
        }),
        ("stated_pose = [", "stated_pose = [0.0, ", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::StatedPose { given: 7, joints: 6, .. }, .. })
        }),
        ("velocity_max = 1.5", "velocity_max = 1.5\nlink = { mass = -1.0, center_of_mass = [0.0, 0.0, 0.0], inertia = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0] }", |e| {
            matches!(e, RobotFileError::Rule { source: RuleError::Link { field: "mass", .. }, .. })
        }),
    ];
    for (from, to, expected) in cases {
        let err = refuse(&mutated(from, to));
        assert!(expected(&err), "{to}: {err:?}");
    }
}

#[test]
fn base_rotations_are_validated() {
    let with_base = |base: &str| mutated("\n[[joint]]", &format!("\n[base]\n{base}\n\n[[joint]]"));
    let ok = RobotSpec::parse(
        "base.toml",
        &with_base("translation = [0.1, 0.0, 0.0]\nmatrix = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]"),
    )
    .unwrap();
    let list = RobotSpec::parse(
        "base.toml",
        &with_base("translation = [0.1, 0.0, 0.0]\nrotation = [{ axis = \"z\", angle = 1.5707963267948966 }]"),
    )
    .unwrap();
    assert!((ok.base().rot - list.base().rot).amax() < 1e-15);
    let err = refuse(&with_base(
        "matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]",
    ));
    assert!(
        matches!(err, RobotFileError::NotARotation { .. }),
        "{err:?}"
    );
    let err = refuse(&with_base(
        "matrix = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\nrotation = []",
    ));
    assert!(
        matches!(
            err,
            RobotFileError::Rule {
                source: RuleError::TwoRotations,
                ..
            }
        ),
        "{err:?}"
    );
    let err = refuse(&with_base("rotation = [{ axis = \"w\", angle = 0.1 }]"));
    assert!(err.to_string().contains("`x`"), "{err}");
}

#[test]
fn no_input_panics() {
    let text = puma_text();
    // Every prefix (cut at character boundaries), and every single-character corruption by a
    // few hostile characters.
    for cut in (0..text.len()).filter(|&k| text.is_char_boundary(k)) {
        let _ = RobotSpec::parse("cut.toml", &text[..cut]).map(|s| DataRobot::new(&s));
    }
    for (k, _) in text.char_indices().step_by(3) {
        for c in ["-", "9", "]", "\"", "\n", "e"] {
            let mut t = text.to_string();
            t.replace_range(k..k + t[k..].chars().next().unwrap().len_utf8(), c);
            let _ = RobotSpec::parse("corrupt.toml", &t).map(|s| DataRobot::new(&s));
        }
    }
}

/// The shared rules (`file_rules`, which the build script also runs) name the file and the
/// field of a bad built-in file and never quote its text (here a canary in `source`).
#[test]
fn the_shared_rules_name_file_and_field_without_quoting_the_file() {
    let canary = "CANARY_SECRET_41";
    let text = mutated("source = \"", &format!("source = \"{canary} "));
    let bad = [
        (
            text.replacen("theta_max = 2.7751", "theta_max = -3.0", 1),
            "joint 1: theta_min",
        ),
        (
            text.replacen("d = 0.15005", "d = inf", 1),
            "joint 3: d = inf",
        ),
        (
            text.replacen("name = \"puma560\"", "name = \"puma\"", 1),
            "field `name`",
        ),
    ];
    for (text, field) in bad {
        let err = robots::parse_builtin("puma560.toml", &text).unwrap_err();
        let message = err.to_string();
        assert!(matches!(err, RobotFileError::Rule { .. }), "{err:?}");
        assert!(
            message.starts_with("robots/data/puma560.toml: "),
            "{message}"
        );
        assert!(message.contains(field), "{message}");
        assert!(!message.contains(canary), "{message}");
    }
}

/// Lengths are finite and within `MAX_LENGTH`: a huge finite number (`1e308`) passed as finite
/// and only failed the run (an infeasible QP, `sigma(J) = inf`); it is refused when the file is
/// read, naming the file, the field and the bound, without printing 300 digits.
#[test]
fn lengths_beyond_the_bound_are_refused_naming_the_field() {
    assert_eq!(MAX_LENGTH, robots::MAX_OFFSET, "one bound for every length");
    let with_base = |base: &str| mutated("\n[[joint]]", &format!("\n[base]\n{base}\n\n[[joint]]"));
    let link = "velocity_max = 1.5\nlink = { mass = 1.0, center_of_mass = [0.0, 0.0, -20.0], \
                inertia = [1.0, 1.0, 1.0, 0.0, 0.0, 0.0] }";
    let cases = [
        (
            with_base("translation = [1e308, 1e308, 1e308]"),
            "base.translation[0]",
        ),
        (
            mutated("tool = [0.0, 0.0, 0.05625]", "tool = [1e308, 0, 0]"),
            "tool[0]",
        ),
        (
            mutated("tool = [0.0, 0.0, 0.05625]", "tool = [0.0, 0.0, -10.5]"),
            "tool[2]",
        ),
        (mutated("a = 0.4318", "a = 431.8"), "joint 2: a"),
        (mutated("d = 0.15005", "d = -1e300"), "joint 3: d"),
        (
            mutated("velocity_max = 1.5", link),
            "joint 1: link.center_of_mass[2]",
        ),
    ];
    for (text, field) in cases {
        let err = refuse(&text);
        assert!(
            matches!(&err, RobotFileError::Rule { source: RuleError::TooLong { field: f, .. }, .. } if f == field),
            "{field}: {err:?}"
        );
        let message = err.to_string();
        assert!(
            message.contains("[-10, 10] m") && message.len() < 200,
            "{message}"
        );
    }
    // The bound itself is a length; NaN is still refused as not finite.
    RobotSpec::parse("edge.toml", &with_base("translation = [10.0, -10.0, 0.0]")).unwrap();
    let err = refuse(&with_base("translation = [nan, 0.0, 0.0]"));
    assert!(matches!(
        err,
        RobotFileError::Rule {
            source: RuleError::NotFinite { .. },
            ..
        }
    ));
    // A modified table's flange row, and the URDF form's tool.
    let panda = builtin_files()
        .iter()
        .find(|(f, _)| *f == "panda.toml")
        .unwrap()
        .1
        .replace("d = 0.107 }", "d = 1e308 }");
    let err = RobotSpec::parse("panda.toml", &panda).unwrap_err();
    assert!(
        matches!(&err, RobotFileError::Rule { source: RuleError::TooLong { field, .. }, .. } if field == "flange.d"),
        "{err:?}"
    );
    let urdf_form =
        "name = \"arm\"\nsource = \"s\"\nurdf = \"arm.urdf\"\nbase = \"b\"\ntip = \"t\"\n\
                     tool = [0.0, 1e308, 0.0]\n";
    let err = RobotForm::parse_named("arm.toml", "arm", urdf_form).unwrap_err();
    assert!(
        matches!(&err, RobotFileError::Rule { source: RuleError::TooLong { field, .. }, .. } if field == "tool[1]"),
        "{err:?}"
    );
}
