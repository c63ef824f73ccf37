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

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The manifest's file name inside the directory it describes.
pub const FILE: &str = "manifest.toml";

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

/// What the program wrote into one directory.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The code revision (git, `-dirty` when the tree had changes) of the last writer.
    pub git_rev: String,
    /// Relative path (with `/`) -> fingerprint.
    pub files: BTreeMap<String, Fingerprint>,
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
        self.lines += block.iter().filter(|&&b| b == b'\n').count();
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
    /// that is not plain and relative); the message names the line and column, never the
    /// file's content.
    #[error("{}: not a manifest this program writes: {message}", path.display())]
    Parse {
        /// The manifest's path.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The manifest could not be written.
    #[error("{path}: cannot write: {message}")]
    Write {
        /// The manifest's path.
        path: PathBuf,
        /// Why (the serialiser's or the I/O error).
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

/// Why a manifest's text is not one this program writes (inside [`IntegrityError::Parse`]).
#[derive(Debug, thiserror::Error)]
enum ManifestTextError {
    /// A table or the keys before the first do not parse (line and column in the whole text).
    #[error(transparent)]
    Toml(inputs::TomlError),
    /// A file is listed twice (TOML refuses a table defined twice).
    #[error("line {line}: it lists {file:?} twice")]
    Twice {
        /// The line of the second listing.
        line: usize,
        /// The file listed twice.
        file: String,
    },
}

impl Manifest {
    /// The manifest of `dir`, or `None` if it has none. It is read as an input
    /// ([`inputs::read_text`]): a regular file inside `dir`, at most
    /// [`inputs::Kind::Manifest`]'s cap, never quoted in an error.
    pub fn read(dir: &Path) -> Result<Option<Self>, IntegrityError> {
        let path = dir.join(FILE);
        let text =
            match inputs::read_text(&path, inputs::Kind::Manifest, inputs::Origin::Under(dir)) {
                Ok(t) => t,
                Err(e) if e.is_not_found() => return Ok(None),
                Err(e) => return Err(e.into()),
            };
        let m = Self::parse(&text).map_err(|e| IntegrityError::Parse {
            path: path.clone(),
            message: e.to_string(),
        })?;
        if let Some(bad) = m.files.keys().find(|k| !is_plain(k)) {
            return Err(IntegrityError::Parse {
                path,
                message: format!("it lists {bad:?}, which is not a plain relative path"),
            });
        }
        Ok(Some(m))
    }

    /// The manifest `text`, parsed table by table: the keys before the first table header
    /// (`git_rev`), then each table (`[files."<path>"]` and its keys, as [`Manifest::write`]
    /// writes them) alone, so memory is the text, the map and one table's document, not a
    /// document of every entry (about 1.5 KB per file listed). A file listed twice is refused,
    /// as TOML refuses a table defined twice. The error names the line and column in the
    /// whole text.
    fn parse(text: &str) -> Result<Self, ManifestTextError> {
        /// The keys before the first table.
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Head {
            git_rev: String,
        }
        /// One table of the manifest (`[files]`, or one `[files."<path>"]`).
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Tables {
            #[serde(default)]
            files: BTreeMap<String, Fingerprint>,
        }
        /// `text` (from line `first`, counted from 1) parsed, the error's line in the whole.
        fn part<T: serde::de::DeserializeOwned>(
            text: &str,
            first: usize,
        ) -> Result<T, ManifestTextError> {
            inputs::parse_toml(text).map_err(|mut e| {
                e.at = e.at.map(|(line, column)| (line + first - 1, column));
                ManifestTextError::Toml(e)
            })
        }
        // Each part: (its first line, its text); a part begins at a table header.
        let mut parts: Vec<(usize, &str)> = Vec::new();
        let (mut start, mut at, mut first) = (0, 0, 1);
        for (index, line) in text.split_inclusive('\n').enumerate() {
            if line.trim_start().starts_with('[') && at > 0 {
                parts.push((first, &text[start..at]));
                (start, first) = (at, index + 1);
            }
            at += line.len();
        }
        parts.push((first, &text[start..]));
        let mut parts = parts.into_iter();
        let (line, head) = parts.next().unwrap_or((1, ""));
        let head: Head = part(head, line)?;
        let mut files = BTreeMap::new();
        for (line, table) in parts {
            let table: Tables = part(table, line)?;
            for (file, fingerprint) in table.files {
                if files.contains_key(&file) {
                    return Err(ManifestTextError::Twice { line, file });
                }
                files.insert(file, fingerprint);
            }
        }
        Ok(Manifest {
            git_rev: head.git_rev,
            files,
        })
    }

    /// Saves the manifest into `dir` (atomically), streamed: the same text as one TOML
    /// document of the whole manifest, written entry by entry (each entry's table serialised
    /// alone), so memory is one entry's, not a document of every entry (about 1.5 KB per file
    /// listed, the peak of a shard or merge of many runs before).
    pub fn write(&self, dir: &Path) -> Result<(), IntegrityError> {
        let path = dir.join(FILE);
        let error = |message: String| IntegrityError::Write {
            path: path.clone(),
            message,
        };
        /// One entry's table: serialised alone it is `[files."<path>"]` and its three keys.
        #[derive(Serialize)]
        struct Entry<'a> {
            files: BTreeMap<&'a str, &'a Fingerprint>,
        }
        #[derive(Serialize)]
        struct Head<'a> {
            git_rev: &'a str,
        }
        let head = toml::to_string(&Head {
            git_rev: &self.git_rev,
        })
        .map_err(|e| error(e.to_string()))?;
        let mut failed = None;
        crate::atomic::write_atomic_with(&path, |w| {
            w.write_all(head.as_bytes())?;
            if self.files.is_empty() {
                return w.write_all(b"\n[files]\n");
            }
            for (file, fingerprint) in &self.files {
                let entry = Entry {
                    files: BTreeMap::from([(file.as_str(), fingerprint)]),
                };
                match toml::to_string(&entry) {
                    Ok(text) => {
                        w.write_all(b"\n")?;
                        w.write_all(text.as_bytes())?;
                    }
                    Err(e) => {
                        failed = Some(e.to_string());
                        return Err(std::io::Error::other("serialisation failed"));
                    }
                }
            }
            Ok(())
        })
        .map_err(|e| error(failed.take().unwrap_or_else(|| e.to_string())))
    }

    /// Every listed file of `dir` whose name `select` accepts and whose content is not what
    /// the manifest says.
    pub fn mismatches(&self, dir: &Path, select: impl Fn(&str) -> bool) -> Vec<Mismatch> {
        self.files
            .iter()
            .filter(|(file, _)| select(file))
            .filter_map(
                |(file, listed)| match crate::owned_dir::fingerprint(&dir.join(file)) {
                    Err(_) => Some(Mismatch::Missing { file: file.clone() }),
                    Ok(found) => (found != *listed).then(|| Mismatch::Changed {
                        file: file.clone(),
                        listed: listed.clone(),
                        found,
                    }),
                },
            )
            .collect()
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

    /// The streamed manifest is byte for byte the TOML document of the whole manifest (so a
    /// committed `results/manifest.toml` is unchanged), for no file, one, and several with
    /// keys TOML quotes differently, and reads back equal.
    #[test]
    fn the_streamed_manifest_is_the_whole_document() {
        let dir =
            std::env::temp_dir().join(format!("driftbench-integrity-doc-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let mut m = Manifest {
            git_rev: "abc\"d".into(),
            ..Default::default()
        };
        let names = [
            "runs.csv",
            "plain_name-1",
            "traces/a b/it's.csv",
            "traces/x\"y.csv",
            "é/ü.svg",
        ];
        for count in [0, 1, names.len()] {
            m.files = names[..count]
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), Fingerprint::of(&vec![b'x'; i])))
                .collect();
            m.write(&dir).unwrap();
            let written = std::fs::read_to_string(dir.join(FILE)).unwrap();
            assert_eq!(written, toml::to_string(&m).unwrap(), "{count} file(s)");
            assert_eq!(Manifest::read(&dir).unwrap().unwrap(), m);
        }
        let _ = std::fs::remove_dir_all(&dir);
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
        let dir = std::env::temp_dir().join(format!("driftbench-integrity-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let text = b"a,b\n1,2\n3,4\n";
        std::fs::write(dir.join("runs.csv"), text).unwrap();
        std::fs::write(dir.join("other.csv"), text).unwrap();
        let mut m = Manifest {
            git_rev: "abc".into(),
            ..Default::default()
        };
        for f in ["runs.csv", "other.csv"] {
            m.files.insert(f.into(), Fingerprint::of(text));
        }
        m.write(&dir).unwrap();
        let m = Manifest::read(&dir).unwrap().unwrap();
        assert!(m.mismatches(&dir, |_| true).is_empty());
        // Cut at a row boundary.
        std::fs::write(dir.join("runs.csv"), b"a,b\n1,2\n").unwrap();
        std::fs::remove_file(dir.join("other.csv")).unwrap();
        let found = m.mismatches(&dir, |_| true);
        assert_eq!(found.len(), 2);
        assert!(found[0].to_string().contains("missing"), "{}", found[0]);
        assert!(
            found[1].to_string().contains("3 lines") && found[1].to_string().contains("2 lines"),
            "{}",
            found[1]
        );
        assert!(m.mismatches(&dir, |f| f == "absent.csv").is_empty());
        // A manifest that lists a path outside the directory is refused.
        std::fs::write(
            dir.join(FILE),
            "git_rev = \"x\"\n[files.\"../x.csv\"]\nlines = 1\nbytes = 1\nsha256 = \"00\"\n",
        )
        .unwrap();
        assert!(Manifest::read(&dir).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Read table by table, the manifest is what TOML reads of the whole text, and a text TOML
    /// refuses is refused, its line counted in the whole text.
    #[test]
    fn tables_read_one_by_one_are_the_whole_document() {
        let whole = "git_rev = \"r\"\n\n[files.\"a.csv\"]\nlines = 1\nbytes = 2\nsha256 = \"00\"\n\n[files]\n\"b/c\" = { lines = 3, bytes = 4, sha256 = \"11\" }\n";
        let m = Manifest::parse(whole).unwrap();
        assert_eq!(m, toml::from_str::<Manifest>(whole).unwrap());
        assert_eq!(m.files.len(), 2);
        let twice = "git_rev = \"r\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\n";
        assert!(toml::from_str::<Manifest>(twice).is_err());
        assert!(Manifest::parse(twice)
            .unwrap_err()
            .to_string()
            .contains("twice"));
        let unknown =
            "git_rev = \"r\"\n[files.\"a\"]\nlines = 1\nbytes = 2\nsha256 = \"0\"\nextra = 1\n";
        assert!(Manifest::parse(unknown)
            .unwrap_err()
            .to_string()
            .contains("line 6"));
        for refused in [
            "",
            "[files]\n",
            "git_rev = \"r\"\n[other]\n",
            "git_rev = \"r\"\nfiles = 1\n",
        ] {
            assert!(toml::from_str::<Manifest>(refused).is_err(), "{refused:?}");
            assert!(Manifest::parse(refused).is_err(), "{refused:?}");
        }
    }
}
