//! A paper's own arms: every `papers/<paper>/robots/*.toml` is read at run time (through the one
//! reader, [`inputs`]: a regular file inside its directory, at most [`inputs::Kind::RobotFile`]'s
//! cap) and registered with the robot registry (`robots::registry::register_file`) under its
//! file's stem, so that a paper is one folder and a robot file needs no rebuild. Each file is
//! validated as it is registered; a file that cannot be read or is invalid is registered with
//! its error, which only the runs of that robot meet (exit 2, naming the file and the field).
//! A robot file of the URDF form names a URDF in its directory, which the registry reads the
//! same way ([`inputs::Kind::Urdf`], inside that `robots/` directory).

use inputs::{read_text, Kind, Origin};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The directory of a paper's robot files, under its paper directory.
pub const ROBOTS_DIR: &str = "robots";

/// The `papers/` directories registered so far (a directory is registered once per process).
static REGISTERED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Registers every `<papers>/<paper>/robots/*.toml`, in sorted order (papers, then files), once
/// per process. A missing `papers/` or paper without `robots/` registers nothing.
pub fn register_paper_robots(papers: &Path) {
    {
        let mut done = REGISTERED.lock().unwrap_or_else(|p| p.into_inner());
        if done.iter().any(|d| d == papers) {
            return;
        }
        done.push(papers.to_path_buf());
    }
    for dir in sorted_entries(papers) {
        let robots = dir.join(ROBOTS_DIR);
        for file in sorted_entries(&robots) {
            if file.extension().is_none_or(|e| e != "toml") {
                continue;
            }
            let text = read_text(&file, Kind::RobotFile, Origin::Under(&robots));
            robots::registry::register_file(&file, text.as_ref().map(String::as_str));
        }
    }
}

/// The entries of `dir`, sorted (none if it cannot be listed).
fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map(|it| it.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    entries.sort();
    entries
}
