//! A paper's own arms: every `papers/<paper>/robots/*.toml` is read at run time (through the one
//! reader, [`inputs`]: a regular file inside its directory, at most [`inputs::Kind::RobotFile`]'s
//! cap) and registered with the robot registry (`robots::register_file`) under its
//! file's stem, so that a paper is one folder and a robot file needs no rebuild. Each file is
//! validated as it is registered; a file that cannot be read or is invalid is registered with
//! its error, which only the runs of that robot meet (exit 2, naming the file and the field).
//! A robot file of the URDF form names a URDF in its directory, which the registry reads the
//! same way ([`inputs::Kind::Urdf`], inside that `robots/` directory).
//!
//! A caller may also register one robot file, or a folder of them, by its path
//! ([`register_path`]: the Python package's `add_robots`), read the same way. A file is
//! registered once per process: registering its path again does nothing.

use inputs::{read_text, Kind, Origin};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The directory of a paper's robot files, under its paper directory.
pub const ROBOTS_DIR: &str = "robots";

/// The `papers/` directories registered so far (a directory is registered once per process).
static REGISTERED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The robot files registered so far (a file is registered once per process).
static REGISTERED_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Why [`register_path`] registered no robot, or registered an invalid one.
#[derive(Debug, thiserror::Error)]
pub enum RobotPathError {
    /// The path is neither a `.toml` file nor a folder holding one.
    #[error(
        "{path}: no robot file here (give a robot file `<name>.toml`, a paper folder with \
         `robots/*.toml`, or a folder of `*.toml`)"
    )]
    NoRobotFile {
        /// The path given.
        path: PathBuf,
    },
    /// A registered file is invalid, or its name is taken: the registry's error (the file and
    /// the field).
    #[error("{0}")]
    Invalid(robots::RegistryError),
}

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
        for file in robot_files_in(&dir.join(ROBOTS_DIR)) {
            register_robot_file(&file);
        }
    }
}

/// Registers the robot file `file` (read inside its directory), unless it was registered
/// before; its robot's name is the file's stem.
fn register_robot_file(file: &Path) -> String {
    let name = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    {
        let mut done = REGISTERED_FILES.lock().unwrap_or_else(|p| p.into_inner());
        if done.iter().any(|d| d == file) {
            return name;
        }
        done.push(file.to_path_buf());
    }
    let dir = file
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let text = read_text(file, Kind::RobotFile, Origin::Under(dir));
    robots::register_file(file, text.as_ref().map(String::as_str));
    name
}

/// The `*.toml` of `dir`, sorted.
fn robot_files_in(dir: &Path) -> Vec<PathBuf> {
    sorted_entries(dir)
        .into_iter()
        .filter(|f| f.extension().is_some_and(|e| e == "toml"))
        .collect()
}

/// Registers the robot files at `path`: the file itself (`<name>.toml`), a paper folder's
/// `robots/*.toml`, or a folder's own `*.toml`; returns their robots' names in sorted order,
/// each looked up, so that an invalid file is reported here (naming the file and field).
pub fn register_path(path: &Path) -> Result<Vec<String>, RobotPathError> {
    let files = if path.is_dir() {
        let robots = path.join(ROBOTS_DIR);
        robot_files_in(if robots.is_dir() { &robots } else { path })
    } else if path.extension().is_some_and(|e| e == "toml") {
        vec![path.to_path_buf()]
    } else {
        Vec::new()
    };
    if files.is_empty() {
        return Err(RobotPathError::NoRobotFile {
            path: path.to_path_buf(),
        });
    }
    let names: Vec<String> = files.iter().map(|f| register_robot_file(f)).collect();
    for name in &names {
        robots::robot_by_name(name).map_err(RobotPathError::Invalid)?;
    }
    Ok(names)
}

/// The entries of `dir`, sorted (none if it cannot be listed).
fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map(|it| it.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    entries.sort();
    entries
}
