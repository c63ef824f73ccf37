//! A paper's own robot files (`papers/<paper>/robots/*.toml`), read at run time: an invalid
//! file or a link out of the folder fails only the commands that use that robot, with exit 2
//! and a message naming the file (and the field), never a panic and never the file's content;
//! the other robots and commands still work. A file named like a built-in model is refused,
//! naming the file.

use crate::common;
use common::{copy_tree, reproduce};
use std::path::Path;

/// A project root with the workspace's experiments and papers, the robot files `robots` in
/// `papers/kong2019/robots/`, and `experiments/own.toml` of one run per robot of `uses`;
/// removed when dropped.
fn project(tag: &str, robots: &[(&str, String)], uses: &[&str]) -> inputs::Scratch {
    let root = inputs::Scratch::unmade(&format!("robot-files-{tag}"));
    let repo = common::repo_root();
    copy_tree(&repo.join("papers"), &root.join("papers"));
    std::fs::create_dir_all(root.join("experiments")).unwrap();
    let dir = root.join("papers/kong2019/robots");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in robots {
        std::fs::write(dir.join(format!("{name}.toml")), text).unwrap();
    }
    let mut toml = String::from("paper = \"kong2019\"\ntitle = \"own arms\"\n");
    for robot in uses {
        toml.push_str(&format!(
            r#"
[[experiment]]
id = "kong2019-own-{robot}"
paper_output = "none"
robot = "{robot}"
path = {{ name = "circle", duration = 1.0 }}
theta0 = [0.0, -0.7853981633974483, 0.0, 1.5707963267948966, -0.7853981633974483, 0.0]
[[experiment.variant]]
label = "ZNN (eq. 22)"
scheme = {{ kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }}
"#
        ));
    }
    std::fs::write(root.join("experiments/own.toml"), toml).unwrap();
    root
}

/// The PUMA 560's robot file renamed `name`, with `edit` applied.
fn puma(name: &str, edit: impl Fn(String) -> String) -> String {
    let text =
        std::fs::read_to_string(common::repo_root().join("robots/data/puma560.toml")).unwrap();
    edit(text.replace("name = \"puma560\"", &format!("name = \"{name}\"")))
}

/// `reproduce --root root ARGS`: (exit code, stdout, stderr).
fn run(root: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = reproduce()
        .arg("--root")
        .arg(root)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn an_invalid_robot_file_fails_only_the_commands_that_use_it() {
    let good = puma("own-arm", |t| t);
    let bad = puma("bad-arm", |t| {
        t.replacen("theta_max = 2.7751", "theta_max = -9.0", 1)
    });
    let robots = [("own-arm", good), ("bad-arm", bad)];
    // A run of the valid file's robot: listed (the experiment loads and builds).
    let root = project("good", &robots, &["own-arm"]);
    let (code, out, err) = run(&root, &["list"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("kong2019-own-own-arm"), "{out}");
    // `robots` lists both, the invalid one with its file and field.
    let (code, out, err) = run(&root, &["robots"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("own-arm") && out.contains("puma560"), "{out}");
    let line = out
        .lines()
        .find(|l| l.starts_with("bad-arm"))
        .expect("bad-arm listed");
    assert!(
        line.contains("papers/kong2019/robots/bad-arm.toml") && line.contains("theta"),
        "{line}"
    );
    drop(root);
    // A run of the invalid file's robot: exit 2 naming the file and the field, no panic.
    let root = project("bad", &robots, &["bad-arm"]);
    let (code, _, err) = run(&root, &["list"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("papers/kong2019/robots/bad-arm.toml"), "{err}");
    assert!(err.contains("theta_m"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn a_linked_or_shadowing_robot_file_is_refused_naming_it() {
    let secret = inputs::Scratch::dir("robot-files-secret");
    let outside = secret.join("secret.toml");
    std::fs::write(
        &outside,
        puma("linked-arm", |t| format!("# SECRET-TOKEN-42\n{t}")),
    )
    .unwrap();
    let root = project(
        "link",
        &[("katana6m180", puma("katana6m180", |t| t))],
        &["linked-arm"],
    );
    let link = root.join("papers/kong2019/robots/linked-arm.toml");
    std::os::unix::fs::symlink(&outside, &link).unwrap();
    let (code, _, err) = run(&root, &["list"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("linked-arm.toml"), "{err}");
    assert!(
        !err.contains("SECRET-TOKEN-42") && !err.contains("panicked"),
        "{err}"
    );
    // The file named like the built-in Katana is an error naming the file, for a run of it.
    std::fs::write(
        root.join("experiments/own.toml"),
        std::fs::read_to_string(root.join("experiments/own.toml"))
            .unwrap()
            .replace("linked-arm", "katana6m180")
            .replace(
                "[0.0, -0.7853981633974483, 0.0, 1.5707963267948966, -0.7853981633974483, 0.0]",
                "[1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]",
            ),
    )
    .unwrap();
    let (code, _, err) = run(&root, &["list"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("papers/kong2019/robots/katana6m180.toml"),
        "{err}"
    );
}

#[test]
fn a_urdf_robot_file_is_listed_and_a_broken_urdf_reference_exits_2() {
    let urdf = common::repo_root().join("robots/tests/fixtures/arm6.urdf");
    let urdf_file = |name: &str, path: &str| {
        format!(
            "name = \"{name}\"\nsource = \"handwritten test arm\"\nurdf = \"{path}\"\n\
             base = \"base_link\"\ntip = \"tool0\"\n"
        )
    };
    let robots = [
        ("urdf-arm", urdf_file("urdf-arm", "arm6.urdf")),
        ("urdf-gone", urdf_file("urdf-gone", "gone.urdf")),
    ];
    let root = project("urdf", &robots, &["urdf-arm"]);
    std::fs::copy(&urdf, root.join("papers/kong2019/robots/arm6.urdf")).unwrap();
    let (code, out, err) = run(&root, &["robots"]);
    assert_eq!(code, Some(0), "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("urdf-arm"))
        .expect("urdf-arm listed");
    assert!(line.contains("6 joints, dynamics"), "{line}");
    let line = out
        .lines()
        .find(|l| l.starts_with("urdf-gone"))
        .expect("urdf-gone listed");
    assert!(
        line.contains("papers/kong2019/robots/urdf-gone.toml") && line.contains("`urdf`"),
        "{line}"
    );
    let (code, out, err) = run(&root, &["list"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("kong2019-own-urdf-arm"), "{out}");
    drop(root);
    // A run of the robot whose URDF is missing: exit 2 naming the robot file, the field and
    // the URDF, no panic.
    let root = project("urdf-gone", &robots, &["urdf-gone"]);
    let (code, _, err) = run(&root, &["list"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("papers/kong2019/robots/urdf-gone.toml")
            && err.contains("`urdf`")
            && err.contains("gone.urdf"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// A robot file of `n` joints (DH form): a yaw joint 0.3 m high, then `n - 1` pitch links of
/// 0.9 / (n - 1) m.
fn arm_file(name: &str, n: usize) -> String {
    let mut s = format!(
        "name = \"{name}\"\nsource = \"a test arm\"\nconvention = \"standard\"\ntool = [0.0, 0.0, 0.0]\n"
    );
    for k in 0..n {
        let (a, alpha, d) = if k == 0 {
            (0.0, std::f64::consts::FRAC_PI_2, 0.3)
        } else {
            (0.9 / (n - 1) as f64, 0.0, 0.0)
        };
        s.push_str(&format!(
            "\n[[joint]]\na = {a:?}\nalpha = {alpha:?}\nd = {d:?}\n"
        ));
    }
    s
}

#[test]
fn arms_of_4_8_and_9_joints_are_listed_and_run_from_a_temporary_project() {
    let arms: Vec<(String, usize)> = [4, 8, 9]
        .into_iter()
        .map(|n| (format!("cli-arm-{n}"), n))
        .collect();
    let files: Vec<(&str, String)> = arms
        .iter()
        .map(|(name, n)| (name.as_str(), arm_file(name, *n)))
        .collect();
    let root = project("any-count", &files, &[]);
    let mut toml = String::from("paper = \"kong2019\"\ntitle = \"own arms\"\n");
    for (name, n) in &arms {
        // A bent pose: yaw 0.2, shoulder 1.2, the rest folding back by 2.4 rad in all.
        let pose: Vec<String> = (0..*n)
            .map(|k| match k {
                0 => "0.2".to_string(),
                1 => "1.2".to_string(),
                _ => format!("{:?}", -2.4 / (*n - 1) as f64),
            })
            .collect();
        toml.push_str(&format!(
            r#"
[[experiment]]
id = "kong2019-own-{name}"
paper_output = "none"
robot = "{name}"
tool = [0.0, 0.0, 0.02]
path = {{ name = "circle", duration = 0.5 }}
theta0 = [{pose}]
exact_integrator = {{ method = "bdf", rtol = 1e-8, atol = 1e-10 }}
[[experiment.variant]]
label = "ZNN (eq. 22)"
scheme = {{ kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }}
"#,
            pose = pose.join(", ")
        ));
    }
    std::fs::write(root.join("experiments/own.toml"), toml).unwrap();
    let (code, out, err) = run(&root, &["robots"]);
    assert_eq!(code, Some(0), "{err}");
    for (name, n) in &arms {
        let line = out
            .lines()
            .find(|l| l.starts_with(name.as_str()))
            .unwrap_or_else(|| panic!("{name} listed: {out}"));
        assert!(line.contains(&format!("{n} joints")), "{line}");
    }
    let (code, out, err) = run(&root, &["run", "--dry-run", "--skip-explain"]);
    assert_eq!(code, Some(0), "{out}\n{err}");
    assert!(!err.contains("panicked"), "{err}");
    for (name, _) in &arms {
        assert!(out.contains(&format!("kong2019-own-{name}")), "{out}");
    }
}

/// Robot geometry no run could use is refused when its file is read, as any invalid file is:
/// a URDF nested 10,000 elements deep inside an ignored `<gazebo>` (it overflowed the stack and
/// aborted every command, whether or not a run used the robot) and a robot file whose tool is
/// 1e308 m away (it passed as finite and failed the run late, exit 1). Unused, they leave every
/// command working and `robots` lists their errors; used, the run fails to load with exit 2,
/// naming the file and the bound, without the file's content.
#[test]
fn a_deep_urdf_or_a_huge_length_is_refused_when_read() {
    let levels = 10_000;
    let deep = std::fs::read_to_string(common::repo_root().join("robots/tests/fixtures/arm6.urdf"))
        .unwrap()
        .replace(
            "</robot>",
            &format!(
                "<gazebo>{}SECRET-D33P{}</gazebo></robot>",
                "<a>".repeat(levels),
                "</a>".repeat(levels)
            ),
        );
    let deep_arm = "name = \"deep-arm\"\nsource = \"a deep URDF\"\nurdf = \"deep.urdf\"\n\
                    base = \"base_link\"\ntip = \"tool0\"\n"
        .to_string();
    let huge_arm = puma("huge-arm", |t| {
        t.replacen("tool = [0.0, 0.0, 0.05625]", "tool = [1e308, 0.0, 0.0]", 1)
    });
    let robots = [("deep-arm", deep_arm), ("huge-arm", huge_arm)];
    let with_deep_urdf = |root: &inputs::Scratch| {
        std::fs::write(root.join("papers/kong2019/robots/deep.urdf"), &deep).unwrap();
    };
    let root = project("geometry-unused", &robots, &["puma560"]);
    with_deep_urdf(&root);
    let (code, out, err) = run(&root, &["list"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("kong2019-own-puma560"), "{out}");
    let (code, out, err) = run(&root, &["robots"]);
    assert_eq!(code, Some(0), "{err}");
    let line = |name: &str| {
        out.lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("{name} listed: {out}"))
            .to_string()
    };
    let deep_line = line("deep-arm");
    assert!(
        deep_line.contains("deep.urdf") && deep_line.contains("nested more than 64 levels"),
        "{deep_line}"
    );
    let huge_line = line("huge-arm");
    assert!(
        huge_line.contains("huge-arm.toml")
            && huge_line.contains("tool[0]")
            && huge_line.contains("[-10, 10] m"),
        "{huge_line}"
    );
    assert!(
        !out.contains("SECRET") && !huge_line.contains("0000000000"),
        "{out}"
    );
    drop(root);
    for (robot, expected) in [("deep-arm", "nested more than 64"), ("huge-arm", "tool[0]")] {
        let root = project(&format!("geometry-{robot}"), &robots, &[robot]);
        with_deep_urdf(&root);
        let (code, _, err) = run(&root, &["list"]);
        assert_eq!(code, Some(2), "{robot}: {err}");
        assert!(
            err.contains(&format!("papers/kong2019/robots/{robot}.toml")) && err.contains(expected),
            "{err}"
        );
        assert!(
            !err.contains("SECRET") && !err.contains("panicked"),
            "{err}"
        );
    }
}
