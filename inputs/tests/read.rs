//! The input reader against what a hostile or careless directory holds: a link to a secret
//! outside, a link inside, /dev/zero, a FIFO, a directory, an oversize file, bytes that are not
//! UTF-8. Each is refused with the path and the rule, never the content, and nothing blocks.

#![cfg(unix)]

use inputs::{read, read_text, InputError, Kind, Origin, Via};
use std::path::{Path, PathBuf};
use std::time::Duration;

const CANARY: &str = "CANARY_TOKEN_b7f3e1";

/// A scratch directory `project/` (the confining directory) beside `outside/`.
struct Scratch(inputs::Scratch);

impl Scratch {
    fn new(name: &str) -> Self {
        let base = inputs::Scratch::dir(&format!("inputs-{name}"));
        std::fs::create_dir_all(base.join("project")).unwrap();
        std::fs::create_dir_all(base.join("outside")).unwrap();
        std::fs::write(base.join("outside/secret"), format!("{CANARY}\n")).unwrap();
        Scratch(base)
    }
    fn project(&self) -> PathBuf {
        self.0.join("project")
    }
    fn file(&self, name: &str) -> PathBuf {
        self.project().join(name)
    }
}

/// [`read()`] in a thread, failing the test if it has not returned within 5 s.
fn read_bounded(path: &Path, kind: Kind, under: Option<&Path>) -> Result<Vec<u8>, InputError> {
    let (path, under) = (path.to_path_buf(), under.map(Path::to_path_buf));
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let origin = under.as_deref().map_or(Origin::Named, Origin::Under);
        let _ = tx.send(read(&path, kind, origin));
    });
    rx.recv_timeout(Duration::from_secs(5))
        .expect("the read returned within 5 s (it must not block)")
}

#[test]
fn a_regular_file_and_a_link_inside_are_read() {
    let s = Scratch::new("plain");
    std::fs::write(s.file("a.toml"), "paper = \"x\"\n").unwrap();
    std::os::unix::fs::symlink(s.file("a.toml"), s.file("b.toml")).unwrap();
    for name in ["a.toml", "b.toml"] {
        let text = read_text(&s.file(name), Kind::Experiment, Origin::Under(&s.project())).unwrap();
        assert_eq!(text, "paper = \"x\"\n");
    }
}

#[test]
fn a_link_outside_is_refused_without_its_content() {
    let s = Scratch::new("outside");
    let link = s.file("evil.toml");
    std::os::unix::fs::symlink(s.0.join("outside/secret"), &link).unwrap();
    let e = read_bounded(&link, Kind::Experiment, Some(&s.project())).unwrap_err();
    assert!(
        matches!(e, InputError::Outside { via: Via::Link, .. }),
        "{e:?}"
    );
    let shown = e.to_string();
    assert!(!shown.contains(CANARY), "{shown}");
    assert!(
        shown.contains("evil.toml") && shown.contains("leads outside"),
        "{shown}"
    );
    // /proc/self/environ through a link: refused before it is opened.
    std::os::unix::fs::symlink("/proc/self/environ", s.file("env.toml")).unwrap();
    let e = read_bounded(&s.file("env.toml"), Kind::PaperToml, Some(&s.project())).unwrap_err();
    assert!(matches!(e, InputError::Outside { .. }), "{e:?}");
    // Named on the command line, the link may not lead out of the directory it is named in
    // either; the file itself, named where it is, is read.
    let e = read_bounded(&link, Kind::Baseline, None).unwrap_err();
    assert!(matches!(e, InputError::Outside { .. }), "{e:?}");
    assert!(!e.to_string().contains(CANARY), "{e}");
    let named = read_bounded(&s.0.join("outside/secret"), Kind::Baseline, None).unwrap();
    assert_eq!(named, format!("{CANARY}\n").as_bytes());
}

#[test]
fn a_path_through_dotdot_is_refused_as_a_path_not_as_a_link() {
    let s = Scratch::new("dotdot");
    // No link anywhere: `project/../outside/secret` names a file outside `project/` by itself.
    let escaping = s.project().join("../outside/secret");
    let e = read_bounded(&escaping, Kind::Experiment, Some(&s.project())).unwrap_err();
    assert!(
        matches!(e, InputError::Outside { via: Via::Path, .. }),
        "{e:?}"
    );
    let shown = e.to_string();
    assert!(
        shown.contains("is named by a path that leads outside") && !shown.contains("symbolic"),
        "{shown}"
    );
    assert!(!shown.contains(CANARY), "{shown}");
    // An absolute path elsewhere is the same case.
    let e = read_bounded(
        &s.0.join("outside/secret"),
        Kind::PaperToml,
        Some(&s.project()),
    )
    .unwrap_err();
    assert!(
        matches!(e, InputError::Outside { via: Via::Path, .. }),
        "{e:?}"
    );
    // A `..` that comes back inside is no escape: read.
    std::fs::create_dir_all(s.file("sub")).unwrap();
    std::fs::write(s.file("a.toml"), "a = 1\n").unwrap();
    let back = s.project().join("sub/../a.toml");
    assert_eq!(
        read_bounded(&back, Kind::Experiment, Some(&s.project())).unwrap(),
        b"a = 1\n"
    );
    // A link inside a path written inside still says "symbolic link".
    std::os::unix::fs::symlink(s.0.join("outside"), s.file("out")).unwrap();
    let e = read_bounded(&s.file("out/secret"), Kind::Experiment, Some(&s.project())).unwrap_err();
    assert!(
        matches!(e, InputError::Outside { via: Via::Link, .. }),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .contains("is a symbolic link that leads outside"),
        "{e}"
    );
}

#[test]
fn devices_fifos_and_directories_are_refused_at_once() {
    let s = Scratch::new("special");
    std::os::unix::fs::symlink("/dev/zero", s.file("zero.csv")).unwrap();
    let e = read_bounded(Path::new("/dev/zero"), Kind::TrajectoryCsv, None).unwrap_err();
    assert!(
        matches!(
            e,
            InputError::NotRegular {
                found: "a character device",
                ..
            }
        ),
        "{e:?}"
    );
    // Through a link, /dev/zero is outside the directory: refused before it is opened.
    let e = read_bounded(&s.file("zero.csv"), Kind::PaperValues, None).unwrap_err();
    assert!(matches!(e, InputError::Outside { .. }), "{e:?}");
    let fifo = s.file("fifo.toml");
    let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let e = read_bounded(&fifo, Kind::Experiment, Some(&s.project())).unwrap_err();
    assert!(
        matches!(
            e,
            InputError::NotRegular {
                found: "a FIFO",
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("not a regular file"), "{e}");
    let e = read_bounded(&s.project(), Kind::Baseline, None).unwrap_err();
    assert!(
        matches!(
            e,
            InputError::NotRegular {
                found: "a directory",
                ..
            }
        ),
        "{e:?}"
    );
}

#[test]
fn a_file_over_its_cap_is_refused_and_one_at_the_cap_is_read() {
    let s = Scratch::new("cap");
    let cap = Kind::Experiment.cap() as usize;
    std::fs::write(s.file("big.toml"), vec![b'#'; cap + 1]).unwrap();
    let e = read_bounded(&s.file("big.toml"), Kind::Experiment, Some(&s.project())).unwrap_err();
    assert!(
        matches!(e, InputError::TooLarge { cap: c, .. } if c as usize == cap),
        "{e:?}"
    );
    std::fs::write(s.file("full.toml"), vec![b'#'; cap]).unwrap();
    let bytes = read_bounded(&s.file("full.toml"), Kind::Experiment, Some(&s.project())).unwrap();
    assert_eq!(bytes.len(), cap);
    // A file whose size the kernel does not report (0) is still cut at the cap: the read stops
    // at cap + 1 bytes (/proc/self/environ is such a file; small, so read).
    assert!(read_bounded(Path::new("/proc/self/environ"), Kind::Experiment, None).is_ok());
}

#[test]
fn text_that_is_not_utf8_names_its_line_only() {
    let s = Scratch::new("utf8");
    std::fs::write(s.file("bad.toml"), b"a = 1\nb = \"\xff\"\n").unwrap();
    let e = read_text(
        &s.file("bad.toml"),
        Kind::Experiment,
        Origin::Under(&s.project()),
    )
    .unwrap_err();
    assert!(matches!(e, InputError::NotUtf8 { line: 2, .. }), "{e:?}");
    let missing = read_text(&s.file("none.toml"), Kind::Experiment, Origin::Named).unwrap_err();
    assert!(missing.is_not_found(), "{missing:?}");
}
