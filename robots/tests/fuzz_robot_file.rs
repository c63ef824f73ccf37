//! Fuzzing the robot file reader (`RobotForm::parse_named`, then `DataRobot::new` for a DH
//! table that parses): every built-in robot file and a URDF-form file, edited at random
//! (lines dropped or repeated, bytes flipped, numbers made extreme, the joint table repeated)
//! and seeded with a marker string ([`MARKER`]) where a secret would be (a comment, a line
//! that is not TOML, after a value). Each case is read or refused; nothing panics, no case
//! takes more than [`HANG`], and no error holds the marker: the reader names the file, the
//! line and the field, never the content. A seeded loop (ChaCha8, seed fixed) of [`CASES`]
//! cases, so a failure replays; it runs in a few seconds.

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use robots::builtin_files;
use robots::DataRobot;
use robots::RobotForm;
use std::time::{Duration, Instant};

/// The stand-in for a secret.
const MARKER: &str = "SECRET_MARKER_r0b07";

/// Past this a case counts as a hang.
const HANG: Duration = Duration::from_secs(10);

/// How many edited files are read.
const CASES: usize = 1500;

/// A robot file of the URDF form (parsed only: the URDF is read later, by `build`).
const URDF_FORM: &str = "name = \"arm\"\nsource = \"a test arm\"\nurdf = \"arm6.urdf\"\n\
                         base = \"base_link\"\ntip = \"tool0\"\ntool = [0.0, 0.0, 0.1]\n\
                         stated_pose = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]\n";

/// Lines that carry the marker where a secret would be.
const MARKED: [&str; 8] = [
    "# {M}",
    "{M}",
    "\"{M}",
    "x = {M}",
    "[{M}",
    "TOKEN={M}",
    "{M}\u{0}\u{7f}",
    "a = [1, {M}]",
];

/// Numbers a hostile file puts where a value is.
const EXTREME: [&str; 10] = [
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "-0.0",
    "0",
    "1e999",
    "99999999999999999999",
    "-1",
];

/// One random edit of `lines`.
fn edit(rng: &mut ChaCha8Rng, lines: &mut Vec<String>) {
    let n = lines.len().max(1);
    let at = rng.gen_range(0..n);
    let marked = MARKED.choose(rng).unwrap().replace("{M}", MARKER);
    match rng.gen_range(0..7) {
        0 if !lines.is_empty() => {
            lines.remove(at);
        }
        1 if !lines.is_empty() => {
            let l = lines[at].clone();
            lines.insert(at, l);
        }
        2 => lines.insert(rng.gen_range(0..=lines.len()), marked),
        3 if !lines.is_empty() => lines[at].push_str(&marked),
        4 if !lines.is_empty() => {
            // A value replaced by an extreme number.
            if let Some(eq) = lines[at].find(" = ") {
                let v = EXTREME.choose(rng).unwrap();
                lines[at].replace_range(eq + 3.., v);
            }
        }
        5 if !lines.is_empty() => {
            // A byte of the line flipped (kept UTF-8 by staying in ASCII).
            let bytes = lines[at].as_bytes();
            if !bytes.is_empty() {
                let k = rng.gen_range(0..bytes.len());
                if bytes[k].is_ascii() && lines[at].is_char_boundary(k) {
                    let c = (bytes[k] ^ (1 << rng.gen_range(0..7))) as char;
                    lines[at].replace_range(k..k + 1, &c.to_string());
                }
            }
        }
        _ => {
            // The joint table (from its first `[[joint]]`) repeated up to 20 times.
            if let Some(start) = lines.iter().position(|l| l == "[[joint]]") {
                let table: Vec<String> = lines[start..].to_vec();
                for _ in 0..rng.gen_range(1..20) {
                    lines.extend(table.iter().cloned());
                }
            }
        }
    }
}

#[test]
fn edited_robot_files_are_read_or_refused_without_echo() {
    let mut seeds: Vec<(&str, &str)> = builtin_files().to_vec();
    seeds.push(("arm.toml", URDF_FORM));
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    let (mut read, mut refused) = (0, 0);
    for case in 0..CASES {
        let (file, text) = seeds[case % seeds.len()];
        let stem = file.trim_end_matches(".toml");
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        for _ in 0..rng.gen_range(1..5) {
            edit(&mut rng, &mut lines);
        }
        let text = lines.join("\n") + "\n";
        let started = Instant::now();
        let result = RobotForm::parse_named(file, stem, &text).map(|form| match form {
            RobotForm::Dh(spec) => drop(DataRobot::new(&spec)),
            RobotForm::Urdf(_) => {}
        });
        assert!(
            started.elapsed() < HANG,
            "case {case} ({file}) took {:?}",
            started.elapsed()
        );
        match result {
            Ok(()) => read += 1,
            Err(e) => {
                refused += 1;
                let shown = e.to_string();
                assert!(
                    !shown.contains(MARKER),
                    "case {case} ({file}): the error shows the file's content: {shown}"
                );
                assert!(shown.starts_with(file), "case {case}: {shown}");
            }
        }
    }
    // Both outcomes occur, so the edits neither break every file nor leave them all valid.
    assert!(
        read > CASES / 20 && refused > CASES / 4,
        "{read} read, {refused} refused"
    );
}

#[test]
fn the_seeds_read_unedited() {
    for (file, text) in builtin_files() {
        let stem = file.trim_end_matches(".toml");
        match RobotForm::parse_named(file, stem, text).unwrap() {
            RobotForm::Dh(spec) => drop(DataRobot::new(&spec)),
            RobotForm::Urdf(_) => {}
        }
    }
    assert!(matches!(
        RobotForm::parse_named("arm.toml", "arm", URDF_FORM).unwrap(),
        RobotForm::Urdf(_)
    ));
}
