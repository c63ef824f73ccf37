//! The hostile-file kit: one test of a reader against what a hostile pull request or a careless
//! user puts in the place of its file, shared by every reader's tests (the control task set's,
//! the inference family's, ...) instead of written out per reader.
//!
//! [`assert_refuses_hostile_files`] first checks that the reader reads a valid file, then puts
//! in its place, one at a time, and calls the reader on each in a thread of its own:
//!
//! - a symbolic link to a secret outside the reader's directory, and one to
//!   `/proc/self/environ` (where it exists): refused as leading outside, the secret unread;
//! - a FIFO: refused at once as not a regular file (a reader that waited on it would block);
//! - the valid text padded past its kind's cap ([`Kind::cap`]) with lines holding the secret:
//!   refused as larger than its cap, before it is parsed;
//! - TOML errors with the secret on the line at fault, on a comment line before it or inside
//!   an unterminated string, and any the reader's own test adds (a field of the wrong type, an
//!   invalid id): refused with the line and column, never the file's lines.
//!
//! No refusal may show the secret ([`HOSTILE_MARKER`]), and each must come within
//! [`HOSTILE_TIMEOUT`]. It is test code, compiled into the crate (a few functions) rather than
//! behind a feature, so that a test build and the product build the crates above `inputs`
//! once, with the same features. A failed case panics, as an assertion does: the kit is called
//! from tests only.

use crate::{Kind, Scratch};
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

/// The stand-in for a secret that a hostile file would show if a refusal quoted it.
pub const HOSTILE_MARKER: &str = "SECRET_MARKER_h0s7113";

/// How long a reader may take to refuse one case (a FIFO must not block it).
pub const HOSTILE_TIMEOUT: Duration = Duration::from_secs(10);

/// A scratch directory per call, so that tests running at once do not share one.
static CALLS: AtomicUsize = AtomicUsize::new(0);

/// Holds the reader `read` to the rules of this crate (module docs). `file` is where the
/// reader finds its file (its directory exists; whatever is at `file` is replaced, and nothing
/// is left there afterwards); `kind` is the file's kind; `valid` is a valid file's text, which
/// the padded and the malformed files start from; `also` are malformed texts of the reader's
/// own, each holding [`HOSTILE_MARKER`] and refused as a TOML error is. `read` reads the file as
/// the reader does and returns its refusal's message, or `None` when it read the file.
///
/// # Panics
///
/// When the valid file is refused, or a hostile one is read, is refused without naming the
/// rule, shows the marker, or is not refused within [`HOSTILE_TIMEOUT`]: each panic names the
/// case and the message.
pub fn assert_refuses_hostile_files<F>(
    file: &Path,
    kind: Kind,
    valid: &str,
    also: &[String],
    read: F,
) where
    F: Fn() -> Option<String> + Clone + Send + 'static,
{
    let refusal = |case: &str| {
        let read = read.clone();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(read());
        });
        rx.recv_timeout(HOSTILE_TIMEOUT)
            .unwrap_or_else(|_| panic!("{case}: not refused within {HOSTILE_TIMEOUT:?}"))
    };
    let refused = |case: &str, rule: &str| {
        let e = refusal(case).unwrap_or_else(|| panic!("{case}: read, not refused"));
        assert!(
            e.contains(rule) && !e.contains(HOSTILE_MARKER),
            "{case}: the refusal must say \"{rule}\" and not show the secret: {e}"
        );
    };
    let _ = std::fs::remove_file(file);
    std::fs::write(file, valid).unwrap();
    if let Some(e) = refusal("the valid file") {
        panic!("the valid file is refused: {e}");
    }
    std::fs::remove_file(file).unwrap();

    // Removed when the kit returns or panics (a failed case).
    let outside = Scratch::dir(&format!(
        "hostile-secret-{}",
        CALLS.fetch_add(1, Ordering::Relaxed)
    ));
    let secret = outside.join("secret");
    std::fs::write(&secret, format!("{HOSTILE_MARKER}\n")).unwrap();
    let environ = Path::new("/proc/self/environ");
    for target in [secret.as_path(), environ] {
        if target.exists() {
            std::os::unix::fs::symlink(target, file).unwrap();
            refused(
                &format!("a symbolic link to {}", target.display()),
                "leads outside",
            );
            std::fs::remove_file(file).unwrap();
        }
    }
    drop(outside);

    let path = std::ffi::CString::new(file.as_os_str().as_bytes()).unwrap();
    // SAFETY: `path` is a NUL-terminated string that outlives the call.
    assert_eq!(unsafe { libc::mkfifo(path.as_ptr(), 0o600) }, 0, "mkfifo");
    refused("a FIFO", "a FIFO, not a regular file");
    std::fs::remove_file(file).unwrap();

    let line = format!("# {HOSTILE_MARKER}\n");
    let lines = usize::try_from(kind.cap()).unwrap() / line.len() + 1;
    std::fs::write(file, format!("{valid}\n{}", line.repeat(lines))).unwrap();
    refused("a file over its cap", "larger than its cap");

    let malformed = [
        format!("{valid}\n# {HOSTILE_MARKER}\nnot toml\n"),
        format!("{valid}\nkey = \"v\" {HOSTILE_MARKER}\n"),
        format!("{valid}\n\"{HOSTILE_MARKER}\n"),
    ];
    for text in malformed.iter().chain(also) {
        assert!(text.contains(HOSTILE_MARKER), "{text:?} holds no marker");
        std::fs::write(file, text).unwrap();
        refused(&format!("{text:?}"), "line ");
    }
    std::fs::remove_file(file).unwrap();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{parse_toml, read_text, Origin};
    use std::path::PathBuf;

    fn scratch(tag: &str) -> Scratch {
        Scratch::dir(&format!("hostile-kit-{tag}"))
    }

    /// This crate's reader and TOML parser, as every reader of a TOML file uses them.
    fn through_inputs(dir: PathBuf) -> impl Fn() -> Option<String> + Clone + Send + 'static {
        move || {
            let path = dir.join("x.toml");
            read_text(&path, Kind::TaskSet, Origin::Under(&dir))
                .map_err(|e| e.to_string())
                .and_then(|text| parse_toml::<toml::Table>(&text).map_err(|e| e.to_string()))
                .err()
        }
    }

    #[test]
    fn a_reader_through_this_crate_passes() {
        let dir = scratch("pass");
        assert_refuses_hostile_files(
            &dir.join("x.toml"),
            Kind::TaskSet,
            "a = 1\n",
            &[],
            through_inputs(dir.to_path_buf()),
        );
        assert!(!dir.join("x.toml").exists());
    }

    #[test]
    fn a_reader_that_follows_links_or_quotes_its_file_fails() {
        let dir = scratch("fail");
        let file = dir.join("x.toml");
        // std's reader and toml's own message: the link is followed, the lines quoted.
        let naive = {
            let file = file.clone();
            move || {
                std::fs::read_to_string(&file)
                    .map_err(|e| e.to_string())
                    .and_then(|t| toml::from_str::<toml::Table>(&t).map_err(|e| e.to_string()))
                    .err()
            }
        };
        let kit = std::panic::catch_unwind(|| {
            assert_refuses_hostile_files(&file, Kind::TaskSet, "a = 1\n", &[], naive)
        });
        assert!(kit.is_err(), "the kit passed a reader that follows links");
        // A reader that refuses everything fails on the valid file.
        let kit = std::panic::catch_unwind(|| {
            assert_refuses_hostile_files(&file, Kind::TaskSet, "a = 1\n", &[], || {
                Some("no".to_string())
            })
        });
        assert!(kit.is_err(), "the kit passed a reader that reads nothing");
        // A malformed text of the reader's own must hold the marker.
        let kit = std::panic::catch_unwind(|| {
            assert_refuses_hostile_files(
                &file,
                Kind::TaskSet,
                "a = 1\n",
                &["b = \n".to_string()],
                through_inputs(dir.to_path_buf()),
            )
        });
        assert!(
            kit.is_err(),
            "the kit took a malformed text without its marker"
        );
    }
}
