//! Every reader of other people's files, fed a committed file of its kind edited at random and
//! seeded with a marker string ([`MARKER`]) where a secret would be (a comment, a broken line,
//! a cell, a string): an experiment file, `paper.toml`, `values.csv`, an integrity manifest,
//! a shard's `shard.toml`, a trajectory CSV and a MAT-file. Each is read or refused; nothing
//! panics, no case takes more than [`HANG`], and no error message holds the marker: the
//! readers name the file, the line and the rule, never the content (a file linked to
//! `/proc/self/environ` would otherwise print the environment). Bounded (150 cases each) to
//! run in a few seconds.

use proptest::prelude::*;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// The stand-in for a secret.
const MARKER: &str = "SECRET_MARKER_7f3a";

/// Past this a case counts as a hang.
const HANG: Duration = Duration::from_secs(10);

fn repo() -> PathBuf {
    catalog::root_from_current_dir().unwrap()
}

/// A fresh scratch directory of one test (a case of it at a time), removed when dropped.
fn scratch(name: &str) -> inputs::Scratch {
    inputs::Scratch::dir(&format!("fuzz-echo-{name}"))
}

/// Lines that carry the marker where a secret would be: as a comment, as a line that is not
/// valid in the file's syntax, inside a string or a cell, after a value.
fn marked_line() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(format!("# {MARKER}")),
        Just(MARKER.to_string()),
        Just(format!("{MARKER} {MARKER}")),
        Just(format!("\"{MARKER}")),
        Just(format!("x = {MARKER}")),
        Just(format!("[{MARKER}")),
        Just(format!("TOKEN={MARKER}")),
        Just(format!("\"{MARKER},\"{MARKER}")),
        Just(format!("{MARKER}\u{0}\u{7f}")),
        Just(format!("1,{MARKER},2")),
    ]
}

/// An edit of a text file's lines.
#[derive(Clone, Debug)]
enum Edit {
    Drop(usize),
    Repeat(usize),
    Insert(usize, String),
    /// The marker appended to the line (after its value).
    Append(usize, String),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        any::<usize>().prop_map(Edit::Drop),
        any::<usize>().prop_map(Edit::Repeat),
        (any::<usize>(), marked_line()).prop_map(|(i, l)| Edit::Insert(i, l)),
        (any::<usize>(), marked_line()).prop_map(|(i, l)| Edit::Append(i, l)),
    ]
}

fn edited(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for e in edits {
        let n = lines.len().max(1);
        match e {
            Edit::Drop(i) if !lines.is_empty() => {
                lines.remove(i % n);
            }
            Edit::Repeat(i) if !lines.is_empty() => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Edit::Insert(i, l) => lines.insert(i % (lines.len() + 1), l.clone()),
            Edit::Append(i, l) if !lines.is_empty() => lines[i % n].push_str(l),
            _ => {}
        }
    }
    lines.join("\n") + "\n"
}

/// `read` of the edited file is read or refused within [`HANG`], and its error does not hold
/// the marker.
fn no_echo(what: &str, read: impl FnOnce() -> Result<(), String>) -> Result<(), TestCaseError> {
    let started = Instant::now();
    let result = read();
    prop_assert!(
        started.elapsed() < HANG,
        "{what} took {:?}",
        started.elapsed()
    );
    if let Err(e) = result {
        prop_assert!(!e.contains(MARKER), "{what}'s error shows its content: {e}");
    }
    Ok(())
}

fn committed(rel: &str) -> String {
    std::fs::read_to_string(repo().join(rel)).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, ..ProptestConfig::default() })]

    #[test]
    fn experiment_files_never_echo(edits in prop::collection::vec(edit(), 1..5)) {
        let dir = scratch("experiment");
        let path = dir.join("kong2019.toml");
        std::fs::write(&path, edited(&committed("experiments/kong2019.toml"), &edits)).unwrap();
        no_echo("an experiment file", || {
            catalog::PaperFile::load(&path)
                .map(drop)
                .map_err(|e| e.to_string())
        })?;
    }

    #[test]
    fn paper_files_never_echo(
        toml_edits in prop::collection::vec(edit(), 0..4),
        value_edits in prop::collection::vec(edit(), 0..4),
    ) {
        let dir = scratch("papers");
        std::fs::create_dir_all(dir.join("kong2019")).unwrap();
        let (toml_text, values) = (committed("papers/kong2019/paper.toml"), committed("papers/kong2019/values.csv"));
        std::fs::write(dir.join("kong2019/paper.toml"), edited(&toml_text, &toml_edits)).unwrap();
        std::fs::write(dir.join("kong2019/values.csv"), edited(&values, &value_edits)).unwrap();
        no_echo("a paper", || {
            analysis::papers::Papers::load(&dir).map(drop).map_err(|e| e.to_string())
        })?;
    }

    #[test]
    fn integrity_manifests_never_echo(edits in prop::collection::vec(edit(), 1..5)) {
        let dir = scratch("manifest");
        let seed = "git_rev = \"abc\"\n\n[files.\"runs.csv\"]\nlines = 3\nbytes = 10\nsha256 = \"00\"\n";
        std::fs::write(dir.join(store::integrity::FILE), edited(seed, &edits)).unwrap();
        no_echo("an integrity manifest", || {
            store::integrity::Manifest::open(&dir).map(drop).map_err(|e| e.to_string())
        })?;
    }

    #[test]
    fn shard_manifests_never_echo(edits in prop::collection::vec(edit(), 1..5)) {
        let dir = scratch("shard");
        let seed = "shard = 1\nshards = 2\ngit_rev = \"abc\"\nselection = \"all\"\nexperiments_hash = \"00\"\nruns = [\"e / v / s\"]\n";
        std::fs::write(dir.join(store::shard::MANIFEST), edited(seed, &edits)).unwrap();
        no_echo("a shard manifest", || {
            store::shard::Manifest::read(&dir).map(drop).map_err(|e| e.to_string())
        })?;
    }

    #[test]
    fn trajectory_csvs_never_echo(edits in prop::collection::vec(edit(), 1..5)) {
        let dir = scratch("csv");
        let path = dir.join("t.csv");
        std::fs::write(&path, edited("t,theta_1,theta_2\n0,1,2\n0.5,1.5,2.5\n1,2,3\n", &edits)).unwrap();
        no_echo("a trajectory CSV", || {
            inputs::trajectory::read(&path, 2, None).map(drop).map_err(|e| e.to_string())
        })?;
    }

    #[test]
    fn mat_files_never_echo(
        v7 in any::<bool>(),
        at in any::<usize>(),
        cut in any::<bool>(),
    ) {
        let name = if v7 { "trajectory-v7.mat" } else { "trajectory-v6.mat" };
        let mut bytes = std::fs::read(repo().join("inputs/tests/fixtures").join(name)).unwrap();
        // The marker written over the file (a variable's name, its data, the header), or
        // appended after the file cut short.
        let at = at % bytes.len();
        if cut {
            bytes.truncate(at);
            bytes.extend_from_slice(MARKER.as_bytes());
        } else {
            let end = (at + MARKER.len()).min(bytes.len());
            bytes[at..end].copy_from_slice(&MARKER.as_bytes()[..end - at]);
        }
        let dir = scratch("mat");
        let path = dir.join("t.mat");
        std::fs::write(&path, &bytes).unwrap();
        no_echo("a MAT-file", || {
            inputs::trajectory::read(&path, 2, None).map(drop).map_err(|e| e.to_string())
        })?;
    }
}

/// The seeds read unedited, so the cases above are not refused for a reason of their own.
#[test]
fn the_seeds_read_unedited() {
    let dir = scratch("seeds");
    let path = dir.join("kong2019.toml");
    std::fs::write(&path, committed("experiments/kong2019.toml")).unwrap();
    catalog::PaperFile::load(&path).unwrap();
    let path = dir.join("t.csv");
    std::fs::write(&path, "t,theta_1,theta_2\n0,1,2\n0.5,1.5,2.5\n1,2,3\n").unwrap();
    inputs::trajectory::read(&path, 2, None).unwrap();
    let seed =
        "git_rev = \"abc\"\n\n[files.\"runs.csv\"]\nlines = 3\nbytes = 10\nsha256 = \"00\"\n";
    std::fs::write(dir.join(store::integrity::FILE), seed).unwrap();
    assert!(store::integrity::Manifest::open(&dir).unwrap().is_some());
}
