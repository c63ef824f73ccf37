//! Reading an input file: where it may be, what it may be, and how much of it is read
//! (crate docs).

use crate::error::{InputError, Via};
use crate::kind::Kind;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Where an input file comes from, which says where it may lead: after following symbolic
/// links it must still be inside that directory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin<'a> {
    /// Found in this directory (the project's `experiments/`, `papers/`, a shard directory
    /// given on the command line).
    Under(&'a Path),
    /// Named on the command line (a trajectory to score, a baseline): the directory it is
    /// named in, so a link there cannot lead a run (a CI job on a pull request, say) to a file
    /// elsewhere, such as `/proc/self/environ`.
    Named,
}

/// The bytes of the input file `path` of kind `kind` (crate docs: regular files only, inside
/// `origin`'s directory, at most [`Kind::cap`] bytes, opened without blocking).
pub fn read(path: &Path, kind: Kind, origin: Origin) -> Result<Vec<u8>, InputError> {
    let mut bytes = Vec::new();
    open(path, kind, origin)?
        .read_to_end(&mut bytes)
        .map_err(|source| match source.kind() {
            std::io::ErrorKind::InvalidData => InputError::TooLarge {
                path: path.to_path_buf(),
                kind,
                cap: kind.cap(),
            },
            _ => InputError::Read {
                path: path.to_path_buf(),
                kind,
                source,
            },
        })?;
    Ok(bytes)
}

/// The input file `path` of kind `kind` opened for reading as a stream, by the rules of
/// [`read()`]: a table far larger than its reader's memory is read row by row. Reading past
/// [`Kind::cap`] bytes (a file that grew since it was opened) is an error of kind
/// `InvalidData`, never a silently shorter file.
pub fn open(path: &Path, kind: Kind, origin: Origin) -> Result<Capped, InputError> {
    let open_error = |source| InputError::Open {
        path: path.to_path_buf(),
        kind,
        source,
    };
    let target = std::fs::canonicalize(path).map_err(open_error)?;
    let dir = match origin {
        Origin::Under(dir) => dir,
        Origin::Named => path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new(".")),
    };
    let canonical_dir = std::fs::canonicalize(dir).map_err(open_error)?;
    if !target.starts_with(&canonical_dir) {
        let via = if lexical(path).starts_with(lexical(dir)) {
            Via::Link
        } else {
            Via::Path
        };
        return Err(InputError::Outside {
            path: path.to_path_buf(),
            kind,
            dir: canonical_dir,
            target,
            via,
        });
    }
    let file = open_nonblocking(&target).map_err(open_error)?;
    let meta = file.metadata().map_err(|source| InputError::Read {
        path: path.to_path_buf(),
        kind,
        source,
    })?;
    if !meta.is_file() {
        return Err(InputError::NotRegular {
            path: path.to_path_buf(),
            kind,
            found: file_type_name(&meta.file_type()),
        });
    }
    let cap = kind.cap();
    if meta.len() > cap {
        return Err(InputError::TooLarge {
            path: path.to_path_buf(),
            kind,
            cap,
        });
    }
    Ok(Capped {
        file,
        left: cap,
        cap,
    })
}

/// An input file opened by [`open()`]: reads at most its kind's cap, then fails.
#[derive(Debug)]
pub struct Capped {
    file: std::fs::File,
    /// Bytes that may still be read.
    left: u64,
    /// The cap.
    cap: u64,
}

impl std::io::Seek for Capped {
    /// Moves within the file; what may still be read is the cap less the new position.
    fn seek(&mut self, to: std::io::SeekFrom) -> std::io::Result<u64> {
        let at = self.file.seek(to)?;
        self.left = self.cap.saturating_sub(at);
        Ok(at)
    }
}

impl Read for Capped {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        // One byte past the cap is asked for, so that a file grown past it is told from one
        // that ends exactly there.
        let want = buf
            .len()
            .min(usize::try_from(self.left + 1).unwrap_or(usize::MAX));
        let n = self.file.read(&mut buf[..want])?;
        if n as u64 > self.left {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("over its cap of {} bytes", self.cap),
            ));
        }
        self.left -= n as u64;
        Ok(n)
    }
}

/// `path` made absolute (against the current directory) and normalised as written, without
/// looking at the file system: `.` dropped, `..` removing the component before it. Only says
/// *why* a path found outside its directory is so ([`Via`]); never used to decide *whether*.
fn lexical(path: &Path) -> PathBuf {
    let absolute = std::env::current_dir().unwrap_or_default().join(path);
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// [`read()`], as UTF-8 text.
pub fn read_text(path: &Path, kind: Kind, origin: Origin) -> Result<String, InputError> {
    String::from_utf8(read(path, kind, origin)?).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        InputError::NotUtf8 {
            path: PathBuf::from(path),
            kind,
            line: valid.iter().filter(|&&b| b == b'\n').count() + 1,
        }
    })
}

/// Opens `path` for reading without waiting for a writer (a FIFO) or a carrier (a terminal).
#[cfg(unix)]
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
}

#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::File::open(path)
}

/// What a file that is not a regular file is, for the message.
fn file_type_name(t: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}
