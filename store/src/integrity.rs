//! The integrity manifest of a directory the program writes: `manifest.toml`, one entry per
//! file it wrote (line count, byte count and SHA-256 of the content), and the code revision
//! that wrote them.
//!
//! The manifest is updated whenever the program writes or removes a file through a
//! [`crate::TrackedDir`] and saved (atomically) at the end of each step that
//! changes the directory, so it always describes what the program left there. Reading it back
//! tells two things:
//!
//! - **edits**: a listed file whose content no longer hashes to its entry was changed by
//!   someone else (a hand edit, a truncation, a merge conflict, a file copied in from another
//!   run). [`Manifest::mismatches`] lists every such file with what differs;
//! - **ownership**: a file the program may delete (a stale trace or figure) must be listed
//!   *and* still hash to its entry; anything else is left in place, so a user's own file is
//!   never removed.
//!
//! SHA-256 is used as a content fingerprint (collisions are not a practical concern); the
//! manifest is not a signature: whoever can write the directory can rewrite it too. What it
//! prevents is a silent mistake, not a determined forger.
//!
//! **The file, streamed.** The manifest is one TOML document: `git_rev`, then a table per
//! file, `[files."<path>"]` with `lines`, `bytes` and `sha256`, the paths in increasing order
//! (of their UTF-8 bytes, a `BTreeMap`'s order). It is never held whole, neither its text nor
//! its entries: a *part* (a table header line and the lines up to the next one; the head is
//! the lines before the first) is read and parsed alone ([`Manifest::entries`]), and each
//! entry checked to come after the one above it, so a file listed twice or out of order is
//! refused as TOML would refuse a table defined twice. [`Manifest::open`] reads every part
//! once, so a manifest that does not parse is refused before anything relies on it; memory is
//! one part (at most [`MAX_PART`] bytes), whatever the number of files. A file is looked up by
//! bisection over the bytes ([`Manifest::get`]): for n entries, about log2(n x 160 bytes /
//! 2 KiB) parts are read, then at most 2 KiB in order. [`write()`] writes a manifest from
//! entries given in order, one at a time: the text is the TOML document of the whole map,
//! byte for byte (`the_streamed_manifest_is_the_whole_document`), so a committed manifest does
//! not change with the way it is written.

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The manifest's file name inside the directory it describes.
pub const FILE: &str = "manifest.toml";

/// The longest part (a table with its keys, or the head) that is read: a part this program
/// writes is its path and three keys, under 1 KB; a longer one is refused, not read into memory.
pub const MAX_PART: usize = 64 * 1024;

/// A bisection ([`Manifest::get`]) reads parts in order once the span left is this short.
const SCAN: u64 = 2048;

/// The read buffer: a few parts, so that each probe of a bisection reads little.
const BUFFER: usize = 1024;

/// The directory sealed by a manifest ([`FILE`]) that is `dir` or one of its ancestors, if any,
/// each looked at once symbolic links are resolved: a directory this program owns (results/,
/// report/, a shard directory), into which no other writer may put files.
pub fn sealed_by(dir: &Path) -> Option<PathBuf> {
    let absolute = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
    absolute
        .ancestors()
        .find(|d| {
            d.canonicalize()
                .unwrap_or_else(|_| d.to_path_buf())
                .join(FILE)
                .is_file()
        })
        .map(Path::to_path_buf)
}

/// A file's size and content hash.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fingerprint {
    /// Newline-terminated lines (for a CSV: the header plus one per row).
    pub lines: usize,
    /// Size (bytes).
    pub bytes: u64,
    /// Lower-case hex.
    pub sha256: String,
}

impl Fingerprint {
    /// The fingerprint of a file's content.
    pub fn of(bytes: &[u8]) -> Self {
        let mut h = Hasher::default();
        h.update(bytes);
        h.finish()
    }

    /// The fingerprint of what `reader` yields, read in blocks of 64 KiB: the same as
    /// [`Fingerprint::of`] of the whole content, in memory independent of its size.
    pub fn of_reader(mut reader: impl std::io::Read) -> std::io::Result<Self> {
        let mut h = Hasher::default();
        let mut buf = vec![0u8; 64 * 1024];
        loop {
            match reader.read(&mut buf) {
                Ok(0) => return Ok(h.finish()),
                Ok(n) => h.update(&buf[..n]),
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
    }
}

/// A [`Fingerprint`] taken block by block.
#[derive(Default)]
struct Hasher {
    sha: Sha256,
    lines: usize,
    bytes: u64,
}

impl Hasher {
    fn update(&mut self, block: &[u8]) {
        self.sha.update(block);
        self.lines += memchr::memchr_iter(b'\n', block).count();
        self.bytes += block.len() as u64;
    }

    fn finish(self) -> Fingerprint {
        let digest = self.sha.finalize();
        let mut hex = String::with_capacity(64);
        for b in digest {
            hex.push_str(&format!("{b:02x}"));
        }
        Fingerprint {
            lines: self.lines,
            bytes: self.bytes,
            sha256: hex,
        }
    }
}

/// A problem with a manifest or with a file it lists.
#[derive(Debug, thiserror::Error)]
pub enum IntegrityError {
    /// The manifest exists but is not read: a link out of its directory, not a regular file,
    /// over its cap, unreadable ([`inputs::InputError`]: its content is never quoted).
    #[error(transparent)]
    Read(#[from] inputs::InputError),
    /// The manifest is not one this program writes (bad TOML, an unknown field, a listed path
    /// that is not plain and relative, a file listed twice or out of order); the message names
    /// the line and column, never the file's content.
    #[error("{}: not a manifest this program writes: {message}", path.display())]
    Parse {
        /// The manifest's path.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The manifest could not be read on once opened (an I/O error while it was streamed, or
    /// it grew past its cap since).
    #[error("{}: cannot read: {source}", path.display())]
    Stream {
        /// The manifest's path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The manifest could not be written.
    #[error("{path}: cannot write: {message}")]
    Write {
        /// The manifest's path.
        path: PathBuf,
        /// Why (the serialiser's or the I/O error, or entries given out of order).
        message: String,
    },
}

/// How a listed file differs from its entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Mismatch {
    /// The file is listed but absent.
    Missing {
        /// Its path relative to the directory (with `/`).
        file: String,
    },
    /// The file's content no longer matches its entry.
    Changed {
        /// Its path relative to the directory (with `/`).
        file: String,
        /// The fingerprint the manifest lists.
        listed: Fingerprint,
        /// The fingerprint of the file as it is.
        found: Fingerprint,
    },
}

impl std::fmt::Display for Mismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Mismatch::Missing { file } => write!(f, "{file}: listed in {FILE} but missing"),
            Mismatch::Changed { file, listed, found } => write!(
                f,
                "{file}: {} lines / {} bytes / sha256 {}... in {FILE}, but the file has {} lines / {} bytes / sha256 {}...",
                listed.lines,
                listed.bytes,
                &listed.sha256[..12.min(listed.sha256.len())],
                found.lines,
                found.bytes,
                &found.sha256[..12.min(found.sha256.len())]
            ),
        }
    }
}

/// Where a part of a manifest begins: its line when it was read from the start, else its byte
/// (a bisection lands in the middle of the file).
#[derive(Clone, Copy, Debug)]
enum Place {
    Line(usize),
    Byte(u64),
}

impl Place {
    /// What a TOML error's message starts with: nothing when it names the line itself.
    fn prefix(&self) -> String {
        match self {
            Place::Line(_) => String::new(),
            Place::Byte(_) => format!("{self}: "),
        }
    }
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Place::Line(line) => write!(f, "line {line}"),
            Place::Byte(byte) => write!(f, "the part at byte {byte}"),
        }
    }
}

/// Why a manifest's text is not one this program writes (inside [`IntegrityError::Parse`]).
#[derive(Debug, thiserror::Error)]
enum ManifestTextError {
    /// A part does not parse (line and column in the whole text, when known).
    #[error("{}{error}", .place.prefix())]
    Toml {
        /// Where the part begins.
        place: Place,
        /// The error, its line counted in the whole text when the part's line is known.
        error: inputs::TomlError,
    },
    /// A file is listed twice (TOML refuses a table defined twice).
    #[error("{place}: it lists {} twice", settings::shown(file))]
    Twice {
        /// The part of the second listing.
        place: Place,
        /// The file listed twice.
        file: String,
    },
    /// A file is listed before one above it: this program lists files in order.
    #[error("{place}: a file listed out of order (this program lists the files in the order of their paths)")]
    Unordered {
        /// The part of the file out of order.
        place: Place,
    },
    /// A listed path is not plain and relative.
    #[error(
        "{place}: it lists {}, which is not a plain relative path",
        settings::shown(file)
    )]
    NotPlain {
        /// Its part.
        place: Place,
        /// The path.
        file: String,
    },
    /// A part is longer than [`MAX_PART`].
    #[error("{place}: a part longer than {MAX_PART} bytes")]
    TooLong {
        /// Where it begins.
        place: Place,
    },
    /// A line is not UTF-8.
    #[error("{place}: not UTF-8")]
    NotUtf8 {
        /// The line's part.
        place: Place,
    },
}

/// Why a part could not be read: the file (I/O) or its text.
enum ReadError {
    Io(std::io::Error),
    Text(ManifestTextError),
}

impl ReadError {
    fn at(self, path: &Path) -> IntegrityError {
        match self {
            ReadError::Io(source) => IntegrityError::Stream {
                path: path.to_path_buf(),
                source,
            },
            ReadError::Text(e) => IntegrityError::Parse {
                path: path.to_path_buf(),
                message: e.to_string(),
            },
        }
    }
}

impl From<std::io::Error> for ReadError {
    fn from(e: std::io::Error) -> Self {
        ReadError::Io(e)
    }
}

impl From<ManifestTextError> for ReadError {
    fn from(e: ManifestTextError) -> Self {
        ReadError::Text(e)
    }
}

/// One part of a manifest's text (module docs).
struct Part {
    /// Its first byte in the file.
    at: u64,
    /// Where it begins, for messages.
    place: Place,
    text: String,
}

/// A manifest's text read part by part from a byte at which a part begins.
struct Parts<'a> {
    reader: &'a mut BufReader<inputs::Capped>,
    /// The byte of the next line.
    at: u64,
    /// The number of the next line, when read from the start.
    line: Option<usize>,
    /// The next part's first line, read ahead: its byte, its line and its text.
    ahead: Option<(u64, Option<usize>, String)>,
}

impl<'a> Parts<'a> {
    /// The parts from byte `at` (a part's start), whose line is `line` if known.
    fn new(
        reader: &'a mut BufReader<inputs::Capped>,
        at: u64,
        line: Option<usize>,
    ) -> std::io::Result<Self> {
        reader.seek(SeekFrom::Start(at))?;
        Ok(Self {
            reader,
            at,
            line,
            ahead: None,
        })
    }

    fn place(at: u64, line: Option<usize>) -> Place {
        line.map_or(Place::Byte(at), Place::Line)
    }

    /// The next line (with its newline), at most [`MAX_PART`] bytes.
    fn read_line(&mut self) -> Result<Option<String>, ReadError> {
        let place = Self::place(self.at, self.line);
        let mut bytes = Vec::new();
        let n = (&mut *self.reader)
            .take(MAX_PART as u64 + 1)
            .read_until(b'\n', &mut bytes)?;
        if n == 0 {
            return Ok(None);
        }
        if n > MAX_PART {
            return Err(ManifestTextError::TooLong { place }.into());
        }
        self.at += n as u64;
        self.line = self.line.map(|l| l + 1);
        String::from_utf8(bytes)
            .map(Some)
            .map_err(|_| ManifestTextError::NotUtf8 { place }.into())
    }

    /// Skips the rest of the line the current byte is on, then to the first part that begins
    /// after it (a bisection's probe at byte b reads from b - 1: the first part that begins at
    /// or after b).
    fn align(&mut self) -> Result<(), ReadError> {
        self.read_line()?;
        loop {
            let (at, line) = (self.at, self.line);
            match self.read_line()? {
                None => return Ok(()),
                Some(text) if text.trim_start().starts_with('[') => {
                    self.ahead = Some((at, line, text));
                    return Ok(());
                }
                Some(_) => {}
            }
        }
    }

    /// The byte and line the next part begins at.
    fn next_at(&self) -> (u64, Option<usize>) {
        self.ahead
            .as_ref()
            .map_or((self.at, self.line), |(at, line, _)| (*at, *line))
    }

    /// The next part, if any.
    fn next_part(&mut self) -> Result<Option<Part>, ReadError> {
        let (at, line, mut text) = match self.ahead.take() {
            Some(ahead) => ahead,
            None => {
                let (at, line) = (self.at, self.line);
                match self.read_line()? {
                    Some(text) => (at, line, text),
                    None => return Ok(None),
                }
            }
        };
        let place = Self::place(at, line);
        loop {
            let (next_at, next_line) = (self.at, self.line);
            match self.read_line()? {
                None => break,
                Some(next) if next.trim_start().starts_with('[') => {
                    self.ahead = Some((next_at, next_line, next));
                    break;
                }
                Some(next) => {
                    text.push_str(&next);
                    if text.len() > MAX_PART {
                        return Err(ManifestTextError::TooLong { place }.into());
                    }
                }
            }
        }
        Ok(Some(Part { at, place, text }))
    }
}

/// The keys before the first table.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Head<'a> {
    git_rev: std::borrow::Cow<'a, str>,
}

/// One table of the manifest (`[files]`, or one `[files."<path>"]`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Tables {
    #[serde(default)]
    files: BTreeMap<String, Fingerprint>,
}

/// `part` parsed as TOML, the error placed in the whole text.
fn parse_part<T: serde::de::DeserializeOwned>(part: &Part) -> Result<T, ManifestTextError> {
    inputs::parse_toml(&part.text).map_err(|mut error| {
        error.at = match part.place {
            Place::Line(first) => error.at.map(|(line, column)| (line + first - 1, column)),
            Place::Byte(_) => None,
        };
        ManifestTextError::Toml {
            place: part.place,
            error,
        }
    })
}

/// The entries of a part: the form [`write`] writes read directly, anything else as TOML.
fn entries_of(part: &Part) -> Result<Vec<(String, Fingerprint)>, ManifestTextError> {
    match written_entry(&part.text) {
        Some(entry) => Ok(vec![entry]),
        None => Ok(parse_part::<Tables>(part)?.files.into_iter().collect()),
    }
}

/// The entry of a part in exactly the form [`write_entry`] writes it directly (a table header
/// `[files."<path>"]`, `lines = <n>`, `bytes = <n>`, `sha256 = "<hex>"`, and the blank line
/// before the next), where TOML would read the same; `None` for any other text (TOML reads
/// it).
fn written_entry(text: &str) -> Option<(String, Fingerprint)> {
    let text = text.strip_suffix('\n')?;
    let text = text.strip_suffix('\n').unwrap_or(text);
    let mut lines = text.split('\n');
    let file = lines
        .next()?
        .strip_prefix("[files.\"")?
        .strip_suffix("\"]")?;
    let count = lines.next()?.strip_prefix("lines = ")?;
    let bytes = lines.next()?.strip_prefix("bytes = ")?;
    let sha256 = lines
        .next()?
        .strip_prefix("sha256 = \"")?
        .strip_suffix('"')?;
    let number = |n: &str| {
        (n == "0" || (!n.is_empty() && n.len() < 19 && !n.starts_with('0')))
            .then_some(n)
            .filter(|n| n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|n| n.parse::<u64>().ok())
    };
    let fingerprint = Fingerprint {
        lines: usize::try_from(number(count)?).ok()?,
        bytes: number(bytes)?,
        sha256: sha256.to_string(),
    };
    (lines.next().is_none()
        && quoted_as_is(file)
        && sha256.bytes().all(|b| b.is_ascii_alphanumeric()))
    .then(|| (file.to_string(), fingerprint))
}

/// Whether TOML writes the key `file` between double quotes as it is: printable ASCII but `"`
/// and `\`, and at least one character a bare key may not hold.
fn quoted_as_is(file: &str) -> bool {
    file.bytes()
        .all(|b| (b' '..=b'~').contains(&b) && b != b'"' && b != b'\\')
        && file
            .bytes()
            .any(|b| !(b.is_ascii_alphanumeric() || b == b'_' || b == b'-'))
}

/// A manifest file opened to be read by streaming (module docs): its head read, its entries
/// read part by part when asked for, never held.
pub struct Manifest {
    path: PathBuf,
    git_rev: String,
    reader: BufReader<inputs::Capped>,
    /// The byte and line of the first table (the end of the head).
    body: (u64, usize),
    /// The file's length.
    len: u64,
}

impl std::fmt::Debug for Manifest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Manifest")
            .field("path", &self.path)
            .field("git_rev", &self.git_rev)
            .finish_non_exhaustive()
    }
}

impl Manifest {
    /// The manifest of `dir`, or `None` if it has none. It is opened as an input
    /// ([`inputs::open`]): a regular file inside `dir`, at most [`inputs::Kind::Manifest`]'s
    /// cap, never quoted in an error. Every part is read once, so a manifest that does not
    /// parse, lists a path that is not plain and relative, or lists a file twice or out of
    /// order is refused now (the error names the line); nothing of it is held but its head.
    pub fn open(dir: &Path) -> Result<Option<Self>, IntegrityError> {
        let Some(mut m) = Self::open_file(dir, FILE)? else {
            return Ok(None);
        };
        for entry in m.entries()? {
            entry?;
        }
        Ok(Some(m))
    }

    /// The manifest `dir/name` opened, its head read (its entries are checked as they are
    /// read); `None` when there is no such file.
    pub(crate) fn open_file(dir: &Path, name: &str) -> Result<Option<Self>, IntegrityError> {
        let path = dir.join(name);
        let file = match inputs::open(&path, inputs::Kind::Manifest, inputs::Origin::Under(dir)) {
            Ok(file) => file,
            Err(e) if e.is_not_found() => return Ok(None),
            Err(e) => return Err(e.into()),
        };
        let mut reader = BufReader::with_capacity(BUFFER, file);
        let read = |reader: &mut BufReader<inputs::Capped>| -> Result<_, ReadError> {
            let len = reader.seek(SeekFrom::End(0))?;
            let mut parts = Parts::new(reader, 0, Some(1))?;
            let head = parts.next_part()?.unwrap_or(Part {
                at: 0,
                place: Place::Line(1),
                text: String::new(),
            });
            let (at, line) = parts.next_at();
            let git_rev = parse_part::<Head>(&head)?.git_rev.into_owned();
            Ok((len, git_rev, (at, line.unwrap_or(1))))
        };
        let (len, git_rev, body) = read(&mut reader).map_err(|e| e.at(&path))?;
        Ok(Some(Self {
            path,
            git_rev,
            reader,
            body,
            len,
        }))
    }

    /// The code revision of the manifest's last writer.
    pub fn git_rev(&self) -> &str {
        &self.git_rev
    }

    /// Every entry, in order: `(path, fingerprint)`, read part by part.
    pub fn entries(&mut self) -> Result<Entries<'_>, IntegrityError> {
        let (at, line) = self.body;
        let parts = Parts::new(&mut self.reader, at, Some(line))
            .map_err(|e| ReadError::Io(e).at(&self.path))?;
        Ok(Entries::new(&self.path, parts, None))
    }

    /// The entries whose paths are `from` or after it, in order, found by bisection (module
    /// docs): a listing of the paths under a prefix reads those and a few parts more.
    pub fn entries_from(&mut self, from: &str) -> Result<Entries<'_>, IntegrityError> {
        let start = self.bisect(from).map_err(|e| e.at(&self.path))?;
        let line = (start == self.body.0).then_some(self.body.1);
        let parts = Parts::new(&mut self.reader, start, line)
            .map_err(|e| ReadError::Io(e).at(&self.path))?;
        Ok(Entries::new(&self.path, parts, Some(from.to_string())))
    }

    /// The entry of `file`, if listed.
    pub fn get(&mut self, file: &str) -> Result<Option<Fingerprint>, IntegrityError> {
        match self.entries_from(file)?.next().transpose()? {
            Some((found, fingerprint)) if found == file => Ok(Some(fingerprint)),
            _ => Ok(None),
        }
    }

    /// A byte at which a part begins such that every entry from `from` on is read from it:
    /// the start of the last part whose first path is before `from` (or of the first part).
    fn bisect(&mut self, from: &str) -> Result<u64, ReadError> {
        let (mut lo, mut hi) = (self.body.0, self.len);
        // Every part that begins before lo lists paths before `from` only; every part that
        // begins at hi or after lists `from` or later paths only.
        while hi - lo > SCAN {
            let mid = lo + (hi - lo) / 2;
            let mut parts = Parts::new(&mut self.reader, mid - 1, None)?;
            parts.align()?;
            // The first part at or after mid that lists a file, and that file.
            let mut first = None;
            while let Some(part) = parts.next_part()? {
                if part.at >= hi {
                    break;
                }
                if let Some((file, _)) = entries_of(&part)?.into_iter().next() {
                    first = Some((part.at, file));
                    break;
                }
            }
            match first {
                Some((start, file)) if file.as_str() < from => lo = start,
                Some((start, _)) => hi = start,
                None => hi = mid,
            }
        }
        Ok(lo)
    }

    /// Every listed file of `dir` whose name `select` accepts and whose content is not what
    /// the manifest says, the manifest read by streaming.
    pub fn mismatches(
        &mut self,
        dir: &Path,
        select: impl Fn(&str) -> bool,
    ) -> Result<Vec<Mismatch>, IntegrityError> {
        let mut found = Vec::new();
        for entry in self.entries()? {
            let (file, listed) = entry?;
            if !select(&file) {
                continue;
            }
            match crate::owned_dir::fingerprint(&dir.join(&file)) {
                Err(_) => found.push(Mismatch::Missing { file }),
                Ok(now) if now != listed => found.push(Mismatch::Changed {
                    file,
                    listed,
                    found: now,
                }),
                Ok(_) => {}
            }
        }
        Ok(found)
    }
}

/// A manifest's entries read in order ([`Manifest::entries`]), each checked: a plain relative
/// path, after the one above it.
pub struct Entries<'a> {
    path: &'a Path,
    parts: Parts<'a>,
    /// The entries of the part read last, not yet given, and its place.
    part: std::vec::IntoIter<(String, Fingerprint)>,
    place: Place,
    /// The path given last.
    last: Option<String>,
    /// Entries before this path are skipped.
    from: Option<String>,
    failed: bool,
}

impl<'a> Entries<'a> {
    fn new(path: &'a Path, parts: Parts<'a>, from: Option<String>) -> Self {
        Self {
            path,
            parts,
            part: Vec::new().into_iter(),
            place: Place::Line(1),
            last: None,
            from,
            failed: false,
        }
    }

    fn next_checked(&mut self) -> Result<Option<(String, Fingerprint)>, ReadError> {
        loop {
            let Some((file, fingerprint)) = self.part.next() else {
                match self.parts.next_part()? {
                    Some(part) => {
                        self.place = part.place;
                        self.part = entries_of(&part)?.into_iter();
                        continue;
                    }
                    None => return Ok(None),
                }
            };
            let place = self.place;
            if !is_plain(&file) {
                return Err(ManifestTextError::NotPlain { place, file }.into());
            }
            match self.last.as_deref() {
                Some(last) if last == file => {
                    return Err(ManifestTextError::Twice { place, file }.into())
                }
                Some(last) if last > file.as_str() => {
                    return Err(ManifestTextError::Unordered { place }.into())
                }
                _ => {}
            }
            self.last = Some(file.clone());
            if self
                .from
                .as_deref()
                .is_some_and(|from| file.as_str() < from)
            {
                continue;
            }
            return Ok(Some((file, fingerprint)));
        }
    }
}

impl Iterator for Entries<'_> {
    type Item = Result<(String, Fingerprint), IntegrityError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        match self.next_checked() {
            Ok(entry) => entry.map(Ok),
            Err(e) => {
                self.failed = true;
                Some(Err(e.at(self.path)))
            }
        }
    }
}

/// Saves the manifest of `dir` (atomically): `git_rev`, then `entries`, which must come in
/// increasing order of their paths, written one at a time (module docs: the text is the TOML
/// document of the whole map). Memory is one entry's, whatever their number.
pub fn write(
    dir: &Path,
    git_rev: &str,
    entries: impl Iterator<Item = Result<(String, Fingerprint), IntegrityError>>,
) -> Result<(), IntegrityError> {
    let path = dir.join(FILE);
    write_to(&path, git_rev, entries, |path, write| {
        crate::atomic::write_atomic_with(path, write)
    })
}

/// [`write`] to `path` by `create` (an atomic write, or a plain one for a temporary file).
pub(crate) fn write_to(
    path: &Path,
    git_rev: &str,
    entries: impl Iterator<Item = Result<(String, Fingerprint), IntegrityError>>,
    create: impl FnOnce(
        &Path,
        &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>,
    ) -> std::io::Result<()>,
) -> Result<(), IntegrityError> {
    let error = |message: String| IntegrityError::Write {
        path: path.to_path_buf(),
        message,
    };
    let head = toml::to_string(&Head {
        git_rev: git_rev.into(),
    })
    .map_err(|e| error(e.to_string()))?;
    let mut failed: Option<IntegrityError> = None;
    let mut entries = Some(entries);
    let written = create(path, &mut |w: &mut dyn Write| {
        w.write_all(head.as_bytes())?;
        let mut last: Option<String> = None;
        for entry in entries.take().into_iter().flatten() {
            let (file, fingerprint) = match entry {
                Ok(entry) => entry,
                Err(e) => {
                    failed = Some(e);
                    return Err(std::io::Error::other("the entries stopped"));
                }
            };
            if last.as_deref().is_some_and(|last| last >= file.as_str()) {
                failed = Some(error(format!(
                    "the files were given out of order ({file:?} after {:?})",
                    last.unwrap_or_default()
                )));
                return Err(std::io::Error::other("out of order"));
            }
            if let Err(e) = write_entry(w, &file, &fingerprint)? {
                failed = Some(error(e.to_string()));
                return Err(std::io::Error::other("serialisation failed"));
            }
            last = Some(file);
        }
        if last.is_none() {
            w.write_all(b"\n[files]\n")?;
        }
        Ok(())
    });
    match (failed, written) {
        (Some(e), _) => Err(e),
        (None, Err(e)) => Err(error(e.to_string())),
        (None, Ok(())) => Ok(()),
    }
}

/// Writes one entry's table (after a blank line) as TOML writes it in the whole document:
/// directly when its path is one TOML quotes as it is ([`quoted_as_is`]) and its hash is
/// alphanumeric, else through the serialiser. The inner error is the serialiser's.
fn write_entry(
    w: &mut dyn Write,
    file: &str,
    fingerprint: &Fingerprint,
) -> std::io::Result<Result<(), toml::ser::Error>> {
    if quoted_as_is(file)
        && fingerprint
            .sha256
            .bytes()
            .all(|b| b.is_ascii_alphanumeric())
    {
        write!(
            w,
            "\n[files.\"{file}\"]\nlines = {}\nbytes = {}\nsha256 = \"{}\"\n",
            fingerprint.lines, fingerprint.bytes, fingerprint.sha256
        )?;
        return Ok(Ok(()));
    }
    /// One entry's table: serialised alone it is `[files."<path>"]` and its three keys.
    #[derive(Serialize)]
    struct Entry<'a> {
        files: BTreeMap<&'a str, &'a Fingerprint>,
    }
    match toml::to_string(&Entry {
        files: BTreeMap::from([(file, fingerprint)]),
    }) {
        Ok(text) => {
            w.write_all(b"\n")?;
            w.write_all(text.as_bytes())?;
            Ok(Ok(()))
        }
        Err(e) => Ok(Err(e)),
    }
}

/// Relative, `/`-separated, every segment a plain name.
fn is_plain(p: &str) -> bool {
    !p.is_empty()
        && !p.starts_with('/')
        && p.split('/')
            .all(|s| !s.is_empty() && s != "." && s != ".." && !s.contains('\\'))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> inputs::Scratch {
        inputs::Scratch::dir(&format!("integrity-{name}"))
    }

    /// The whole manifest as one TOML document (what the manifest was written as before it
    /// was streamed).
    #[derive(Serialize)]
    struct Whole<'a> {
        git_rev: &'a str,
        files: &'a BTreeMap<String, Fingerprint>,
    }

    fn save(dir: &Path, git_rev: &str, files: &BTreeMap<String, Fingerprint>) {
        write(
            dir,
            git_rev,
            files.iter().map(|(k, f)| Ok((k.clone(), f.clone()))),
        )
        .unwrap();
    }

    fn read_all(dir: &Path) -> BTreeMap<String, Fingerprint> {
        Manifest::open(dir)
            .unwrap()
            .unwrap()
            .entries()
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    }

    /// The streamed manifest is byte for byte the TOML document of the whole manifest (so a
    /// committed `results/manifest.toml` is unchanged), for no file, one, and several with
    /// keys TOML writes bare, quoted as they are, and escaped, and reads back equal.
    #[test]
    fn the_streamed_manifest_is_the_whole_document() {
        let dir = scratch("doc");
        let names = [
            "runs.csv",
            "plain_name-1",
            "traces/a b/it's.csv",
            "traces/x\"y.csv",
            "é/ü.svg",
            "traces/kong2019/znn-mu-0.5__znn.csv",
            "tab\there",
            "del\u{7f}.csv",
        ];
        for count in [0, 1, names.len()] {
            let files: BTreeMap<String, Fingerprint> = names[..count]
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), Fingerprint::of(&vec![b'x'; i])))
                .collect();
            save(&dir, "abc\"d", &files);
            let written = std::fs::read_to_string(dir.join(FILE)).unwrap();
            let whole = Whole {
                git_rev: "abc\"d",
                files: &files,
            };
            assert_eq!(written, toml::to_string(&whole).unwrap(), "{count} file(s)");
            assert_eq!(read_all(&dir), files);
            let mut m = Manifest::open(&dir).unwrap().unwrap();
            assert_eq!(m.git_rev(), "abc\"d");
            for (name, fingerprint) in &files {
                assert_eq!(m.get(name).unwrap().as_ref(), Some(fingerprint), "{name}");
            }
        }
        // Given out of order, nothing is written.
        let before = std::fs::read(dir.join(FILE)).unwrap();
        let f = Fingerprint::of(b"");
        let refused = write(
            &dir,
            "r",
            [("b", f.clone()), ("a", f)]
                .into_iter()
                .map(|(k, f)| Ok((k.to_string(), f))),
        );
        assert!(refused.unwrap_err().to_string().contains("out of order"));
        assert_eq!(std::fs::read(dir.join(FILE)).unwrap(), before);
    }

    /// Looked up by bisection, every listed file is found with its entry and no other is, and
    /// a listing from a path gives exactly the entries from it on; in a manifest of thousands
    /// of entries of uneven lengths, and in one whose parts list several files each (TOML's
    /// other form, which this program reads but does not write).
    #[test]
    fn bisection_finds_every_entry_and_only_those() {
        let dir = scratch("bisect");
        let files: BTreeMap<String, Fingerprint> = (0..3000)
            .map(|i| {
                let name = format!("traces/e{}/v-{i}{}.csv", i % 7, "x".repeat(i % 90));
                (name, Fingerprint::of(i.to_string().as_bytes()))
            })
            .chain([("runs.csv".to_string(), Fingerprint::of(b"r"))])
            .collect();
        save(&dir, "r", &files);
        let mut m = Manifest::open(&dir).unwrap().unwrap();
        for (name, fingerprint) in &files {
            assert_eq!(m.get(name).unwrap().as_ref(), Some(fingerprint), "{name}");
            let absent = format!("{name}-not");
            assert_eq!(m.get(&absent).unwrap(), None, "{absent}");
        }
        for from in [
            "",
            "a",
            "traces/e3/",
            "traces/e3/v-1",
            "traces/e6/v-2999",
            "zzz",
        ] {
            let want: Vec<&String> = files.keys().filter(|k| k.as_str() >= from).collect();
            let got: Vec<String> = m
                .entries_from(from)
                .unwrap()
                .map(|e| e.unwrap().0)
                .collect();
            assert_eq!(got.iter().collect::<Vec<_>>(), want, "from {from:?}");
        }
        // Parts of several entries each, in TOML's inline form.
        let mut text = String::from("git_rev = \"r\"\n");
        let names: Vec<String> = (0..400).map(|i| format!("f{i:04}.csv")).collect();
        for chunk in names.chunks(7) {
            text.push_str("\n[files]\n");
            for n in chunk {
                text.push_str(&format!(
                    "\"{n}\" = {{ lines = 1, bytes = 2, sha256 = \"ab\" }}\n"
                ));
            }
        }
        std::fs::write(dir.join(FILE), text).unwrap();
        let mut m = Manifest::open(&dir).unwrap().unwrap();
        for n in &names {
            assert_eq!(m.get(n).unwrap().map(|f| f.bytes), Some(2), "{n}");
            assert_eq!(m.get(&format!("{n}x")).unwrap(), None);
        }
        assert_eq!(m.entries_from("f0390").unwrap().count(), 10);
    }

    #[test]
    fn sha256_is_the_standard_function() {
        // FIPS 180-2 test vector.
        assert_eq!(
            Fingerprint::of(b"abc").sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(Fingerprint::of(b"a,b\n1,2\n").lines, 2);
        // Block by block, the same as at once, across block boundaries.
        let long: Vec<u8> = (0..200_000u32).map(|i| (i % 251) as u8).collect();
        let streamed = Fingerprint::of_reader(long.as_slice()).unwrap();
        assert_eq!(streamed, Fingerprint::of(&long));
        assert_eq!(streamed.bytes, 200_000);
    }

    #[test]
    fn edits_truncations_and_removals_are_found() {
        let dir = scratch("edits");
        let text = b"a,b\n1,2\n3,4\n";
        std::fs::write(dir.join("runs.csv"), text).unwrap();
        std::fs::write(dir.join("other.csv"), text).unwrap();
        let files = ["other.csv", "runs.csv"]
            .into_iter()
            .map(|f| (f.to_string(), Fingerprint::of(text)))
            .collect();
        save(&dir, "abc", &files);
        let mut m = Manifest::open(&dir).unwrap().unwrap();
        assert!(m.mismatches(&dir, |_| true).unwrap().is_empty());
        // Cut at a row boundary.
        std::fs::write(dir.join("runs.csv"), b"a,b\n1,2\n").unwrap();
        std::fs::remove_file(dir.join("other.csv")).unwrap();
        let found = m.mismatches(&dir, |_| true).unwrap();
        assert_eq!(found.len(), 2);
        assert!(found[0].to_string().contains("missing"), "{}", found[0]);
        assert!(
            found[1].to_string().contains("3 lines") && found[1].to_string().contains("2 lines"),
            "{}",
            found[1]
        );
        assert!(m
            .mismatches(&dir, |f| f == "absent.csv")
            .unwrap()
            .is_empty());
        // A manifest that lists a path outside the directory is refused.
        std::fs::write(
            dir.join(FILE),
            "git_rev = \"x\"\n[files.\"../x.csv\"]\nlines = 1\nbytes = 1\nsha256 = \"00\"\n",
        )
        .unwrap();
        assert!(Manifest::open(&dir).is_err());
    }

    /// Read part by part, the manifest is what TOML reads of the whole text, and a text TOML
    /// refuses is refused, its line counted in the whole text; so is a file listed out of
    /// order, and a part longer than the cap.
    #[test]
    fn parts_read_one_by_one_are_the_whole_document() {
        #[derive(Deserialize, PartialEq, Debug)]
        #[serde(deny_unknown_fields)]
        struct Read {
            git_rev: String,
            files: BTreeMap<String, Fingerprint>,
        }
        let dir = scratch("parts");
        let open = |text: &str| {
            std::fs::write(dir.join(FILE), text).unwrap();
            Manifest::open(&dir).map(|m| {
                let mut m = m.unwrap();
                let files = m.entries().unwrap().collect::<Result<_, _>>().unwrap();
                Read {
                    git_rev: m.git_rev().to_string(),
                    files,
                }
            })
        };
        let whole = "git_rev = \"r\"\n\n[files.\"a.csv\"]\nlines = 1\nbytes = 2\nsha256 = \"00\"\n\n[files]\n\"b/c\" = { lines = 3, bytes = 4, sha256 = \"11\" }\n";
        let m = open(whole).unwrap();
        assert_eq!(m, toml::from_str::<Read>(whole).unwrap());
        assert_eq!(m.files.len(), 2);
        let twice = "git_rev = \"r\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n";
        assert!(toml::from_str::<Read>(twice).is_err());
        let e = open(twice).unwrap_err().to_string();
        assert!(e.contains("twice") && e.contains("line 6"), "{e}");
        let unknown =
            "git_rev = \"r\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\nextra = 1\n";
        assert!(open(unknown).unwrap_err().to_string().contains("line 6"));
        let unordered = "git_rev = \"r\"\n[files.\"b\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n";
        let e = open(unordered).unwrap_err().to_string();
        assert!(e.contains("line 6") && e.contains("out of order"), "{e}");
        for refused in [
            "",
            "[files]\n",
            "git_rev = \"r\"\n[other]\n",
            "git_rev = \"r\"\nfiles = 1\n",
        ] {
            assert!(toml::from_str::<Read>(refused).is_err(), "{refused:?}");
            assert!(open(refused).is_err(), "{refused:?}");
        }
        let long = format!(
            "git_rev = \"r\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"{}\"\n",
            "0".repeat(MAX_PART)
        );
        let e = open(&long).unwrap_err().to_string();
        assert!(e.contains("longer than") && e.contains("line 5"), "{e}");
    }
}
