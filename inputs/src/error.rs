//! Why an input file is not read. Messages name the path, the kind of file and the rule it
//! breaks; none quotes the file's content.

use crate::kind::Kind;
use std::path::PathBuf;

/// An input file refused or unreadable ([`crate::read()`]).
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    #[error("{}: cannot open the {kind}: {source}", path.display())]
    Open {
        path: PathBuf,
        kind: Kind,
        source: std::io::Error,
    },
    /// The file (after following links) is not inside the directory it was found in.
    #[error("{}: the {kind} {via} leads outside {} (to {}); it is not read", path.display(), dir.display(), target.display())]
    Outside {
        path: PathBuf,
        kind: Kind,
        dir: PathBuf,
        target: PathBuf,
        via: Via,
    },
    /// A FIFO, a device, a socket or a directory.
    #[error("{}: the {kind} is {found}, not a regular file; it is not read", path.display())]
    NotRegular {
        path: PathBuf,
        kind: Kind,
        found: &'static str,
    },
    #[error("{}: the {kind} is larger than its cap of {cap} bytes; it is not read", path.display())]
    TooLarge { path: PathBuf, kind: Kind, cap: u64 },
    #[error("{}: cannot read the {kind}: {source}", path.display())]
    Read {
        path: PathBuf,
        kind: Kind,
        source: std::io::Error,
    },
    /// Text that is not UTF-8 (the line of the first invalid byte).
    #[error("{}: the {kind} is not UTF-8 text (line {line})", path.display())]
    NotUtf8 {
        path: PathBuf,
        kind: Kind,
        line: usize,
    },
}

/// What leads a file outside its directory ([`InputError::Outside`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Via {
    /// The path itself, read as written (`..` components taken lexically), already names a
    /// place outside the directory (`experiments/../secret`, an absolute path elsewhere).
    Path,
    /// The path, read as written, stays inside; a symbolic link on the way leads out.
    Link,
}

impl std::fmt::Display for Via {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Via::Path => "is named by a path that",
            Via::Link => "is a symbolic link that",
        })
    }
}

impl InputError {
    /// Whether the file does not exist (callers that treat a missing file as "not there").
    pub fn is_not_found(&self) -> bool {
        matches!(self, InputError::Open { source, .. } if source.kind() == std::io::ErrorKind::NotFound)
    }
}
