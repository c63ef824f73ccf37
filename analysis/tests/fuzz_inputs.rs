//! Fuzzing the readers of other people's files: MAT-files (the committed v6 and v7 fixtures
//! mutated: bytes flipped, 32-bit fields overwritten with extreme sizes, cut short, regions
//! repeated; for v7 also the inflated payload mutated and compressed again), `paper.toml` and
//! `values.csv` (the committed kong2019 files with lines dropped, repeated, or given hostile
//! tokens), and trajectory CSVs (headers and cells from a hostile vocabulary). Every input is
//! refused with an error or read into a well-formed value; nothing panics, and no case takes
//! more than [`HANG`] (a hang guard, far above the milliseconds a case takes). Bounded (300
//! cases each) to run in seconds.

use inputs::trajectory::{parse_csv, read, Trajectory};
use proptest::prelude::*;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Past this a case counts as a hang.
const HANG: Duration = Duration::from_secs(20);

fn repo() -> PathBuf {
    catalog::root_from_current_dir().unwrap()
}

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(repo().join("inputs/tests/fixtures").join(name)).unwrap()
}

/// A fresh scratch directory of one test (a case of it at a time), named for the file `name`
/// it holds; removed when dropped.
fn scratch(name: &str) -> inputs::Scratch {
    inputs::Scratch::dir(&format!("fuzz-inputs-{name}"))
}

/// One mutation of a byte string.
#[derive(Clone, Debug)]
enum Mutation {
    Flip {
        at: usize,
        bit: u8,
    },
    /// A little-endian u32 written at a 4-aligned offset (sizes, dimensions, types).
    Word {
        at: usize,
        value: u32,
    },
    Cut {
        at: usize,
    },
    Repeat {
        at: usize,
        len: usize,
    },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let word = prop_oneof![
        Just(0u32),
        Just(1),
        Just(7),
        Just(14),
        Just(15),
        Just(u32::MAX),
        Just(u32::MAX / 2),
        Just(1 << 24),
        any::<u32>(),
    ];
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        (any::<usize>(), word).prop_map(|(at, value)| Mutation::Word { at, value }),
        any::<usize>().prop_map(|at| Mutation::Cut { at }),
        (any::<usize>(), 1usize..64).prop_map(|(at, len)| Mutation::Repeat { at, len }),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    if bytes.is_empty() {
        return;
    }
    let n = bytes.len();
    match *m {
        Mutation::Flip { at, bit } => bytes[at % n] ^= 1 << bit,
        Mutation::Word { at, value } => {
            let at = (at % n) & !3;
            for (i, b) in value.to_le_bytes().into_iter().enumerate() {
                if let Some(x) = bytes.get_mut(at + i) {
                    *x = b;
                }
            }
        }
        Mutation::Cut { at } => bytes.truncate(at % n),
        Mutation::Repeat { at, len } => {
            let at = at % n;
            let part: Vec<u8> = bytes[at..(at + len).min(n)].to_vec();
            bytes.splice(at..at, part);
        }
    }
}

/// A v7 MAT-file's first compressed element (after the 128-byte header): its inflated bytes.
fn inflated_v7() -> (Vec<u8>, Vec<u8>) {
    let file = fixture("trajectory-v7.mat");
    let header = file[..128].to_vec();
    let mut out = Vec::new();
    let mut at = 128;
    while at + 8 <= file.len() {
        let size = u32::from_le_bytes(file[at + 4..at + 8].try_into().unwrap()) as usize;
        let body = &file[at + 8..(at + 8 + size).min(file.len())];
        let mut d = libflate::zlib::Decoder::new(body).unwrap();
        d.read_to_end(&mut out).unwrap();
        at += 8 + size;
    }
    (header, out)
}

/// `header` followed by `payload` compressed as one element (miCOMPRESSED, 15).
fn compressed_v7(header: &[u8], payload: &[u8]) -> Vec<u8> {
    let mut e = libflate::zlib::Encoder::new(Vec::new()).unwrap();
    e.write_all(payload).unwrap();
    let body = e.finish().into_result().unwrap();
    let mut file = header.to_vec();
    file.extend(15u32.to_le_bytes());
    file.extend((body.len() as u32).to_le_bytes());
    file.extend(body);
    file
}

/// A read trajectory is well formed: a row of theta (and thetadot) per sample, each as wide.
fn well_formed(tr: &Trajectory) {
    assert_eq!(tr.theta.len(), tr.t.len());
    let width = tr.theta.first().map_or(0, Vec::len);
    assert!(tr.theta.iter().all(|r| r.len() == width));
    if let Some(v) = &tr.thetadot {
        assert_eq!(v.len(), tr.t.len());
        assert!(v.iter().all(|r| r.len() == width));
    }
}

fn read_mat_bytes(bytes: &[u8], name: &str) {
    let dir = scratch(name);
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    let started = Instant::now();
    if let Ok(tr) = read(&path, 2, None) {
        well_formed(&tr);
    }
    assert!(
        started.elapsed() < HANG,
        "a MAT-file took {:?}",
        started.elapsed()
    );
}

/// Hostile tokens for TOML values and CSV cells.
fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e400".to_string()),
        Just("-9e307".to_string()),
        Just(String::new()),
        Just("\"".to_string()),
        Just("\"\"\"".to_string()),
        Just("[[claim]]".to_string()),
        Just("[[mapping]]".to_string()),
        Just("* / * / *".to_string()),
        Just("../../x".to_string()),
        Just("<script>".to_string()),
        Just("a\nb".to_string()),
        (1usize..300).prop_map(|n| "x".repeat(n)),
        "[a-z0-9_ =./*\"-]{0,30}",
    ]
}

/// An edit of a text file's lines.
#[derive(Clone, Debug)]
enum Edit {
    Drop(usize),
    Repeat(usize),
    /// Replace what follows the line's first `=` or `,` with the token.
    Value(usize, String),
    Insert(usize, String),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        any::<usize>().prop_map(Edit::Drop),
        any::<usize>().prop_map(Edit::Repeat),
        (any::<usize>(), token()).prop_map(|(i, t)| Edit::Value(i, t)),
        (any::<usize>(), token()).prop_map(|(i, t)| Edit::Insert(i, t)),
    ]
}

fn edited(text: &str, edits: &[Edit]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    for e in edits {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match e {
            Edit::Drop(i) => {
                lines.remove(i % n);
            }
            Edit::Repeat(i) => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Edit::Value(i, t) => {
                let l = &mut lines[i % n];
                if let Some(at) = l.find(['=', ',']) {
                    l.truncate(at + 1);
                    l.push_str(t);
                }
            }
            Edit::Insert(i, t) => lines.insert(i % n, t.clone()),
        }
    }
    lines.join("\n") + "\n"
}

/// A papers/ folder holding one paper, kong2019, with these files.
fn load_paper(
    name: &str,
    toml_text: &str,
    values: &str,
) -> Result<analysis::papers::Papers, String> {
    let dir = scratch(name);
    std::fs::create_dir_all(dir.join("kong2019")).unwrap();
    std::fs::write(dir.join("kong2019/paper.toml"), toml_text).unwrap();
    std::fs::write(dir.join("kong2019/values.csv"), values).unwrap();
    let started = Instant::now();
    let out = analysis::papers::Papers::load(&dir).map_err(|e| e.to_string());
    assert!(started.elapsed() < HANG);
    out
}

fn committed_paper() -> (String, String) {
    let dir = repo().join("papers/kong2019");
    (
        std::fs::read_to_string(dir.join("paper.toml")).unwrap(),
        std::fs::read_to_string(dir.join("values.csv")).unwrap(),
    )
}

/// What a loaded paper must satisfy, whatever its file said (`analysis::paper_rules`).
fn checked(papers: &analysis::papers::Papers) {
    for p in &papers.papers {
        assert!(p.claims.len() <= analysis::MAX_CLAIMS);
        assert!(analysis::is_one_line(&p.title));
    }
    for v in &papers.values {
        assert!(v.value.is_finite(), "{v:?}");
        assert!(analysis::PUBLISHED_METRICS.contains(&v.metric.as_str()));
    }
}

/// Trajectory CSV header names and cells.
fn header_name() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("t".to_string()),
        Just("theta_1".to_string()),
        Just("theta_2".to_string()),
        Just("thetadot_1".to_string()),
        Just("thetadot_2".to_string()),
        Just("theta_0".to_string()),
        Just("theta_99999999999999999999".to_string()),
        Just("theta_".to_string()),
        Just("x".to_string()),
        Just("\"t\"".to_string()),
    ]
}

fn cell() -> impl Strategy<Value = String> {
    prop_oneof![
        "-?[0-9]{1,3}(\\.[0-9]{1,4})?(e-?[0-9]{1,3})?",
        Just("9e307".to_string()),
        Just("-9e307".to_string()),
        Just("1e300".to_string()),
        Just("NaN".to_string()),
        Just("inf".to_string()),
        Just(String::new()),
        Just("abc".to_string()),
        Just("\"1,2\"".to_string()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_mat_files_are_refused_or_read_well_formed(
        v7 in any::<bool>(),
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        let mut bytes = fixture(if v7 { "trajectory-v7.mat" } else { "trajectory-v6.mat" });
        for m in &mutations {
            apply(&mut bytes, m);
        }
        read_mat_bytes(&bytes, "mutated.mat");
    }

    #[test]
    fn v7_files_with_a_mutated_payload_are_refused_or_read_well_formed(
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        let (header, mut payload) = inflated_v7();
        for m in &mutations {
            apply(&mut payload, m);
        }
        read_mat_bytes(&compressed_v7(&header, &payload), "payload.mat");
    }

    #[test]
    fn edited_paper_files_are_refused_or_loaded_checked(
        toml_edits in prop::collection::vec(edit(), 0..5),
        value_edits in prop::collection::vec(edit(), 0..5),
    ) {
        let (toml_text, values) = committed_paper();
        if let Ok(papers) = load_paper("papers", &edited(&toml_text, &toml_edits), &edited(&values, &value_edits)) {
            checked(&papers);
        }
    }

    #[test]
    fn hostile_trajectory_csvs_are_refused_or_read_well_formed(
        header in prop::collection::vec(header_name(), 1..6),
        rows in prop::collection::vec(prop::collection::vec(cell(), 0..7), 0..8),
    ) {
        let mut text = header.join(",");
        for r in &rows {
            text.push('\n');
            text.push_str(&r.join(","));
        }
        let started = Instant::now();
        if let Ok(tr) = parse_csv(text.as_bytes(), Path::new("fuzz.csv")) {
            well_formed(&tr);
            // Each column is named once.
            let mut names = header.clone();
            names.sort();
            names.dedup();
            prop_assert_eq!(names.len(), header.len());
        }
        prop_assert!(started.elapsed() < HANG);
    }
}

/// The fuzzers' seeds are accepted unmutated, so a reader that refused everything would fail.
#[test]
fn the_fuzzed_inputs_are_read_when_unmutated() {
    for name in ["trajectory-v6.mat", "trajectory-v7.mat"] {
        let dir = scratch(name);
        let path = dir.join(name);
        std::fs::write(&path, fixture(name)).unwrap();
        well_formed(&read(&path, 2, None).unwrap());
    }
    let (header, payload) = inflated_v7();
    let dir = scratch("recompressed.mat");
    let path = dir.join("recompressed.mat");
    std::fs::write(&path, compressed_v7(&header, &payload)).unwrap();
    let tr = read(&path, 2, None).unwrap();
    assert_eq!(tr.t, [0.0, 0.5, 1.0]);
    let (toml_text, values) = committed_paper();
    checked(&load_paper("papers-unmutated", &toml_text, &values).unwrap());
    let tr = parse_csv(b"t,theta_1\n0,1\n1,2\n", Path::new("ok.csv")).unwrap();
    assert_eq!(tr.theta, [vec![1.0], vec![2.0]]);
}
