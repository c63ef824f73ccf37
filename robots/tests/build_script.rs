//! The build script (`robots/build.rs`, compiled here as a module) refuses a bad built-in robot
//! file: its entry function, run on a scratch crate whose `data/` holds one file, fails naming
//! the file and the field, and never quotes the file's text.

// `main` (which reads Cargo's environment) and the parts of the included modules the build
// script does not use are unused here.
#[allow(dead_code)]
#[path = "../build.rs"]
mod build;

/// Text no error may contain: the file's `source`, a free-text field.
const CANARY: &str = "CANARY_SECRET_41";

/// The built-in PUMA 560 file with `source` replaced by [`CANARY`].
fn puma_with_canary() -> String {
    let text = robots::builtin_files()
        .iter()
        .find(|(f, _)| *f == "puma560.toml")
        .map(|(_, t)| *t)
        .unwrap();
    let start = text.find("source = \"").unwrap() + "source = \"".len();
    let end = start + text[start..].find('"').unwrap();
    format!("{}{CANARY}{}", &text[..start], &text[end..])
}

/// A scratch crate `root/` with `root/data/puma560.toml` holding `text`, and an output
/// directory.
struct Scratch(inputs::Scratch);

impl Scratch {
    fn new(tag: &str, text: &str) -> Self {
        let base = inputs::Scratch::dir(&format!("robots-build-{tag}"));
        std::fs::create_dir_all(base.join("root/data")).unwrap();
        std::fs::create_dir_all(base.join("out")).unwrap();
        std::fs::write(base.join("root/data/puma560.toml"), text).unwrap();
        Scratch(base)
    }

    /// The build script's entry function on the scratch crate: its error message, if any.
    fn build(&self) -> Result<String, String> {
        build::embed_robots(&self.0.join("root"), &self.0.join("out"))
            .map_err(|e| e.to_string())?;
        Ok(std::fs::read_to_string(self.0.join("out/builtin_robots.rs")).unwrap())
    }
}

#[test]
fn a_valid_file_is_embedded() {
    let s = Scratch::new("valid", &puma_with_canary());
    let out = s.build().unwrap();
    assert!(out.contains("(\"puma560.toml\", include_str!("), "{out}");
}

#[test]
fn a_bad_built_in_file_fails_the_build_naming_file_and_field() {
    let good = puma_with_canary();
    let joints = good
        .match_indices("[[joint]]")
        .map(|(i, _)| i)
        .collect::<Vec<_>>();
    let cases: [(&str, String, &str); 6] = [
        (
            "range",
            good.replacen("theta_min = -2.7751", "theta_min = 2.8", 1),
            "joint 1: theta_min = 2.8 is not below theta_max",
        ),
        (
            "nan",
            good.replacen("a = 0.4318", "a = nan", 1),
            "joint 2: a = NaN",
        ),
        (
            "missing",
            good.replacen("\ntool = ", "\n# tool = ", 1),
            "missing field `tool`",
        ),
        (
            "one-joint",
            good[..joints[1]].replace("stated_pose", "# stated_pose"),
            "field `joint`: 1 joints",
        ),
        (
            "stem",
            good.replacen("name = \"puma560\"", "name = \"puma\"", 1),
            "field `name`",
        ),
        (
            "velocity",
            good.replacen("velocity_max = 1.5", "velocity_max = -1.5", 1),
            "joint 1: velocity_max = -1.5, must be > 0",
        ),
    ];
    for (tag, text, field) in cases {
        let message = Scratch::new(tag, &text).build().expect_err(tag);
        assert!(
            message.starts_with("robots/data/puma560.toml: "),
            "{tag}: {message}"
        );
        assert!(message.contains(field), "{tag}: {message}");
        assert!(!message.contains(CANARY), "{tag}: {message}");
    }
}
