//! Hostile text in an experiment file or on the command line: escape sequences (ESC, OSC, CSI),
//! CR/LF, BEL, C1 (U+0085), bidi and format characters (U+202E, U+2028), and a megabyte-long
//! value. Every error that quotes such a text shows it as `settings::shown` does (escaped, cut
//! after 128 characters with its length), still naming the file, the field and the valid
//! choices; a label refuses control and formatting characters with its own rule, and the
//! file's `title` and an experiment's `paper_output` refuse control characters as a paper's
//! citation does. `reproduce list` is run on scratch projects ([`inputs::Scratch`]).

use crate::common;

use std::process::Output;

/// What a file or an argument can hold that would drive the terminal, fake a line or reverse
/// the text after it, were it printed as it is.
const HOSTILE: &str =
    "x\u{1b}[2J\u{1b}[31mRED\u{1b}]0;pwned\u{7}\r\nfake: all good\u{85}\u{202e}\u{2028}";

/// [`HOSTILE`] as `settings::shown` shows it.
const SHOWN: &str =
    r#""x\u{1b}[2J\u{1b}[31mRED\u{1b}]0;pwned\u{7}\r\nfake: all good\u{85}\u{202e}\u{2028}""#;

/// [`HOSTILE`] as a TOML basic string's escapes write it.
fn toml_escaped(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '"' => "\\\"".to_string(),
            '\\' => "\\\\".to_string(),
            c if c.is_ascii_graphic() || c == ' ' => c.to_string(),
            c => format!("\\U{:08X}", u32::from(c)),
        })
        .collect()
}

/// An experiment file of one cheap experiment, `edit` applied to its text.
fn experiment_file(edit: impl Fn(&str) -> String) -> String {
    edit(common::CHEAP_EXPERIMENT)
}

/// `reproduce list` (and `extra` arguments) on a scratch project whose one experiment file,
/// `experiments/kong2019.toml`, is `text`.
fn list(name: &str, text: &str, extra: &[&str]) -> Output {
    let dir = inputs::Scratch::dir(&format!("hostile-text-{name}"));
    std::fs::create_dir_all(dir.join("experiments")).unwrap();
    std::fs::create_dir_all(dir.join("papers")).unwrap();
    std::fs::write(dir.join("experiments/kong2019.toml"), text).unwrap();
    common::reproduce()
        .arg("--root")
        .arg(&*dir)
        .arg("list")
        .args(extra)
        .output()
        .unwrap()
}

/// The standard error of a refusal with exit code 2, checked to be one line with no control
/// or formatting character in it, short, and to say every text of `must_say`.
fn refused(name: &str, out: &Output, must_say: &[&str]) -> String {
    let err = String::from_utf8(out.stderr.clone()).unwrap();
    assert_eq!(out.status.code(), Some(2), "{name}: {err}");
    let line = err.strip_suffix('\n').unwrap_or(&err);
    assert!(
        !line.chars().any(settings::is_control_or_format),
        "{name}: the error holds a control or formatting character: {err:?}"
    );
    assert!(line.len() < 4096, "{name}: {} bytes of error", err.len());
    for m in must_say {
        assert!(
            err.contains(m),
            "{name}: the error does not say {m:?}: {err}"
        );
    }
    assert!(out.stdout.is_empty(), "{name}: {:?}", out.stdout);
    err
}

#[test]
fn a_hostile_robot_kind_method_or_key_is_shown_escaped_with_the_choices() {
    let hostile = toml_escaped(HOSTILE);
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "robot",
            experiment_file(|t| {
                t.replace("robot = \"katana6m180\"", &format!("robot = \"{hostile}\""))
            }),
            vec![
                "kong2019.toml",
                "field `robot`",
                "unknown robot ",
                SHOWN,
                "the robots are: jaco2-pen",
            ],
        ),
        (
            "scheme-kind",
            experiment_file(|t| {
                t.replace("kind = \"kong2019-znn\"", &format!("kind = \"{hostile}\""))
            }),
            vec![
                "kong2019.toml",
                "line 12",
                "unknown variant ",
                SHOWN,
                "expected one of `jia2019`",
            ],
        ),
        (
            "solver-kind",
            experiment_file(|t| {
                format!("{t}solvers = [{{ kind = \"{hostile}\", gamma = 1.0 }}]\n")
            }),
            vec!["kong2019.toml", "unknown variant ", SHOWN, "`lvi-pdnn`"],
        ),
        (
            "numerical-method",
            experiment_file(|t| format!("{t}numerical = [{{ method = \"{hostile}\" }}]\n")),
            vec![
                "kong2019.toml",
                "unknown QP solver ",
                SHOWN,
                "(known: 94lvi",
            ],
        ),
        (
            "integrator-method",
            experiment_file(|t| {
                t.replace(
                    "exact_integrator = { method = \"bdf\"",
                    &format!("exact_integrator = {{ method = \"{hostile}\""),
                )
            }),
            vec!["kong2019.toml", "unknown variant ", SHOWN, "`dopri5`"],
        ),
        (
            "unknown-key",
            experiment_file(|t| {
                t.replace(
                    "[[experiment.variant]]",
                    &format!("\"{hostile}\" = 1\n[[experiment.variant]]"),
                )
            }),
            vec![
                "kong2019.toml",
                "unknown field ",
                SHOWN,
                "expected one of `id`",
            ],
        ),
        (
            "path-name",
            experiment_file(|t| t.replace("name = \"circle\"", &format!("name = \"{hostile}\""))),
            vec![
                "kong2019.toml",
                "field `path`",
                "unknown path ",
                SHOWN,
                "valid names: four-leaf-clover",
            ],
        ),
        (
            "sweep-key",
            experiment_file(|t| format!("{t}sweep = {{ \"{hostile}\" = [1.0, 2.0] }}\n")),
            vec![
                "kong2019.toml",
                "field `sweep` key ",
                SHOWN,
                // Its line breaks and formatting characters are whitespace in a key.
                "whitespace in a key",
            ],
        ),
        (
            "id",
            experiment_file(|t| {
                t.replace(
                    "id = \"kong2019-cheap\"",
                    &format!("id = \"kong2019-{hostile}\""),
                )
            }),
            vec![
                "kong2019.toml",
                "field `id`",
                "no control or formatting characters",
            ],
        ),
    ];
    for (name, text, must_say) in &cases {
        refused(name, &list(name, text, &[]), must_say);
    }
}

#[test]
fn a_megabyte_value_is_cut_saying_how_long_it_was() {
    let long = "A".repeat(1_000_000);
    let text =
        experiment_file(|t| t.replace("robot = \"katana6m180\"", &format!("robot = \"{long}\"")));
    let err = refused(
        "long-robot",
        &list("long-robot", &text, &[]),
        &[
            "field `robot`",
            "(1000000 characters, the first 128 shown)",
            "the robots are: jaco2-pen",
        ],
    );
    assert!(
        err.contains(&format!("unknown robot \"{}\"...", "A".repeat(128))),
        "{err}"
    );
    let key = experiment_file(|t| {
        t.replace(
            "[[experiment.variant]]",
            &format!("{long} = 1\n[[experiment.variant]]"),
        )
    });
    refused(
        "long-key",
        &list("long-key", &key, &[]),
        &[
            "unknown field ",
            "(1000000 characters, the first 128 shown)",
            "expected one of `id`",
        ],
    );
}

#[test]
fn a_label_with_a_control_or_formatting_character_is_refused_by_its_own_rule() {
    for (name, label, found) in [
        ("bel", "a\u{7}b", r"'\u{7}'"),
        ("tab", "a\tb", r"'\t'"),
        ("nel", "a\u{85}b", r"'\u{85}'"),
        ("rlo", "abc\u{202e}fed", r"'\u{202e}'"),
        ("line-separator", "a\u{2028}b", r"'\u{2028}'"),
        ("esc", "x\u{1b}[2J", r"'\u{1b}'"),
    ] {
        let text = experiment_file(|t| {
            t.replace(
                "label = \"ZNN (eq. 22)\"",
                &format!("label = \"{}\"", toml_escaped(label)),
            )
        });
        let err = refused(
            name,
            &list(name, &text, &[]),
            &[
                "kong2019.toml",
                "field `label`",
                "no control or formatting characters",
                found,
            ],
        );
        assert!(!err.contains("must not contain `/`"), "{name}: {err}");
    }
    // The separators keep their own rule.
    let text = experiment_file(|t| t.replace("label = \"ZNN (eq. 22)\"", "label = \"a/b\""));
    let err = refused(
        "slash",
        &list("slash", &text, &[]),
        &["field `label`", "must not contain `/`"],
    );
    assert!(!err.contains("control"), "{err}");
}

#[test]
fn a_title_or_paper_output_that_is_not_one_line_is_refused_naming_the_field() {
    for (name, field, text) in [
        (
            "title-esc",
            "field `title`",
            experiment_file(|t| {
                t.replace(
                    "title = \"one cheap run\"",
                    "title = \"T\\u001b[2J\\u001b[31mEVIL\"",
                )
            }),
        ),
        (
            "title-newline",
            "field `title`",
            experiment_file(|t| {
                t.replace("title = \"one cheap run\"", "title = \"a\\n## Summary\"")
            }),
        ),
        (
            "paper-output-osc",
            "field `paper_output`",
            experiment_file(|t| {
                t.replace(
                    "paper_output = \"none\"",
                    "paper_output = \"P\\u001b]0;pwned\\u0007\\u001b[31mX\"",
                )
            }),
        ),
    ] {
        refused(
            name,
            &list(name, &text, &[]),
            &[
                "kong2019.toml",
                field,
                "must be one line of text (no line breaks, control or formatting characters",
            ],
        );
    }
    // One line is listed as it is.
    let text = experiment_file(|t| {
        t.replace(
            "title = \"one cheap run\"",
            "title = \"Jia & Li, “Drift-free…”\"",
        )
    });
    let out = list("title-ok", &text, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("Jia & Li, “Drift-free…”"));
}

#[test]
fn a_hostile_command_line_argument_is_shown_escaped() {
    let text = common::CHEAP_EXPERIMENT.to_string();
    for (name, args, must_say) in [
        (
            "experiment",
            vec!["--experiment", HOSTILE],
            vec!["invalid value ", SHOWN, "experiment id ", "is not a slug"],
        ),
        ("option", vec![HOSTILE], vec!["unexpected argument ", SHOWN]),
    ] {
        let out = list(name, &text, &args);
        let err = String::from_utf8(out.stderr.clone()).unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(
            !err.chars()
                .any(|c| c != '\n' && settings::is_control_or_format(c)),
            "{name}: {err:?}"
        );
        for m in must_say {
            assert!(
                err.contains(m),
                "{name}: the error does not say {m:?}: {err}"
            );
        }
    }
}
