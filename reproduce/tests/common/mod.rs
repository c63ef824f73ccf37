//! What the binary's process tests share: a cheap experiment, starting `reproduce` and checking
//! it succeeded, killing a run once it has checkpointed some runs, and comparing a merged
//! results directory with one process's (rows but their timing, traces byte for byte).
// Compiled into each test crate of the binary; each uses a part of it.
#![allow(dead_code)]

use records::RunRow;

use std::path::{Path, PathBuf};
use std::process::Command;
use store::read_runs;

/// An experiment file with one slow run first (the finite-time network integrated by
/// Dormand-Prince, held to steps of ~1e-5 s by the sign-power band's eigenvalues near -2.5e5:
/// ~690,000 steps, ~10 s; with BDF it takes ~3,000 steps), for tests that kill a run while it
/// is in flight; a test appends its quick runs as further variants.
pub const RESUME_EXPERIMENT: &str = r#"paper = "kong2019"
title = "resume"
[[experiment]]
id = "kong2019-resume"
paper_output = "none"
robot = "katana6m180"
path = { name = "circle", duration = 9.0 }
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.5471975511965976]
theta_ref = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
[[experiment.variant]]
label = "finite-time"
exact = false
scheme = { kind = "kong2019-finite-time", beta_theta = 1.0, k_p = 1.0, alpha = 0.1 }
solvers = [{ kind = "finite-time", beta = 1.0, alpha = 0.1, smoothing = 1e-6 }]
integrator = { method = "dopri5", rtol = 1e-6, atol = 1e-8 }
"#;

/// One cheap experiment (kong2019's ZNN scheme, exact column only, BDF at 1e-8: well under a
/// second); tests append variants or rename it.
pub const CHEAP_EXPERIMENT: &str = r#"paper = "kong2019"
title = "one cheap run"
[[experiment]]
id = "kong2019-cheap"
paper_output = "none"
robot = "katana6m180"
path = { name = "circle", duration = 9.0 }
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
exact_integrator = { method = "bdf", rtol = 1e-8, atol = 1e-10 }
[[experiment.variant]]
label = "ZNN (eq. 22)"
scheme = { kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }
"#;

/// The process succeeded (its standard error otherwise in the panic).
pub fn ok(out: std::process::Output) -> std::process::Output {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The `reproduce` binary, started in the workspace root.
pub fn reproduce() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_reproduce"));
    c.current_dir(catalog::root_from_current_dir().unwrap());
    c
}

/// Starts `run()`, waits until the journal of `results` holds `rows` rows (after its header),
/// kills the process and checks that it was killed with exactly those rows checkpointed and no
/// runs.csv written.
pub fn kill_after_checkpoints(run: impl Fn() -> Command, results: &Path, rows: usize) {
    let mut first = run().spawn().unwrap();
    let journal = store::journal::path(results);
    let lines = || {
        std::fs::read_to_string(&journal)
            .map(|t| t.lines().count())
            .unwrap_or(0)
    };
    let started = std::time::Instant::now();
    while lines() < rows + 1 && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    first.kill().unwrap();
    let _ = first.wait();
    assert_eq!(
        lines(),
        rows + 1,
        "the {rows} quick runs are checkpointed before the kill"
    );
    assert!(!results.join("runs.csv").exists());
}

/// Starts `run()` again after [`kill_after_checkpoints`] and checks that it resumes: it says
/// the `done` checkpointed runs are already done, completes, writes `total` rows without a
/// duplicate, and removes the journal.
pub fn resume_completes(run: impl Fn() -> Command, results: &Path, done: usize, total: usize) {
    let second = run().output().unwrap();
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(second.status.success(), "{err}");
    assert!(
        err.contains(&format!(
            "resuming: {done} of the selected runs already done"
        )),
        "{err}"
    );
    let rows = read_runs(&results.join("runs.csv")).unwrap();
    assert_eq!(rows.len(), total);
    let mut keys: Vec<_> = rows.iter().map(|r| r.key()).collect();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), total, "no duplicate row");
    assert!(!store::journal::path(results).exists());
}

/// Copies the directory tree `from` to `to` (created).
pub fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.path().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

/// The workspace root (the parent of `reproduce/`).
pub fn repo_root() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("reproduce/ has a parent")
        .to_path_buf()
}

/// Every `.rs` file under `dir`, as paths relative to `root` with `/` separators.
pub fn rust_files(root: &Path, dir: &Path, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
        return;
    };
    for entry in entries.flatten() {
        let rel = dir.join(entry.file_name());
        match entry.file_type() {
            Ok(t) if t.is_dir() => rust_files(root, &rel, out),
            Ok(_) if rel.extension().is_some_and(|e| e == "rs") => {
                out.push(rel.to_string_lossy().replace('\\', "/"))
            }
            _ => {}
        }
    }
}

/// The workspace members of the root `Cargo.toml`.
pub fn members(root: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(root.join("Cargo.toml")).expect("the root Cargo.toml");
    let doc: toml::Table = text.parse().expect("the root Cargo.toml parses");
    doc["workspace"]["members"]
        .as_array()
        .expect("workspace.members")
        .iter()
        .map(|m| m.as_str().expect("a member path").to_string())
        .collect()
}

/// Every `.rs` file under the `src/` of every workspace member, sorted, as paths relative to
/// `root`; `expected` (one such path) must be among them, so a scan that finds no sources
/// fails instead of passing on nothing.
pub fn library_files(root: &Path, expected: &str) -> Vec<String> {
    let mut files = Vec::new();
    for member in members(root) {
        rust_files(root, &Path::new(&member).join("src"), &mut files);
    }
    assert!(
        files.iter().any(|f| f == expected),
        "the crates' sources were not found under {}",
        root.display()
    );
    files.sort();
    files
}

/// Rows without what differs between two runs of the same binary: the timing columns.
pub fn comparable(mut rows: Vec<RunRow>) -> Vec<String> {
    for r in &mut rows {
        r.wall_s = 0.0;
        r.sim_s = 0.0;
        r.observe_s = 0.0;
    }
    rows.iter().map(|r| format!("{r:?}")).collect()
}

/// Every file under `dir/traces`, relative path and bytes.
pub fn traces(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    fn walk(base: &Path, d: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                out.push((
                    p.strip_prefix(base).unwrap().to_path_buf(),
                    std::fs::read(&p).unwrap(),
                ));
            }
        }
    }
    let mut out = Vec::new();
    walk(&dir.join("traces"), &dir.join("traces"), &mut out);
    out.sort();
    out
}

/// `merged` holds what one process wrote into `whole`, which has `runs` runs: the same rows
/// (every cell but the timing columns, in the same order) and byte-identical traces.
pub fn assert_same_results(merged: &Path, whole: &Path, runs: usize) {
    let want = read_runs(&whole.join("runs.csv")).unwrap();
    assert_eq!(want.len(), runs);
    assert_eq!(
        comparable(read_runs(&merged.join("runs.csv")).unwrap()),
        comparable(want)
    );
    let (t_whole, t_merged) = (traces(whole), traces(merged));
    assert_eq!(t_whole.len(), runs);
    assert!(t_whole == t_merged, "trace files differ");
}

/// The library part of a source file: everything before its `#[cfg(test)]` test module.
pub fn library_part(text: &str) -> &str {
    let lines: Vec<&str> = text.lines().collect();
    let mut offset = 0;
    for (i, line) in lines.iter().enumerate() {
        let next = lines.get(i + 1).map(|l| l.trim_start()).unwrap_or("");
        if line.trim() == "#[cfg(test)]" && next.starts_with("mod ") {
            return &text[..offset];
        }
        offset += line.len() + 1;
    }
    text
}

/// Rust source split into what the scanning tests read: its code without comments, string and
/// char literals (each replaced by spaces, line breaks kept, so positions and line numbers stay)
/// and its string literals with their 1-based lines.
pub struct Lexed {
    pub code: String,
    /// `"..."` (escapes kept as written), `r"..."` and `r#"..."#`.
    pub literals: Vec<(usize, String)>,
}

/// [`Lexed`] of Rust source `code`: comments, char literals and lifetimes are told apart from
/// string literals.
pub fn lex(code: &str) -> Lexed {
    let c: Vec<char> = code.chars().collect();
    let (mut i, mut line) = (0usize, 1usize);
    let mut out = Lexed {
        code: String::with_capacity(code.len()),
        literals: Vec::new(),
    };
    let newlines = |s: &[char]| s.iter().filter(|&&ch| ch == '\n').count();
    // Blanks c[from..to] into the code (line breaks kept).
    let blank = |out: &mut Lexed, from: usize, to: usize| {
        for &ch in &c[from..to.min(c.len())] {
            out.code.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    while i < c.len() {
        match c[i] {
            '\n' => {
                line += 1;
                out.code.push('\n');
                i += 1;
            }
            '/' if c.get(i + 1) == Some(&'/') => {
                let start = i;
                while i < c.len() && c[i] != '\n' {
                    i += 1;
                }
                blank(&mut out, start, i);
            }
            '/' if c.get(i + 1) == Some(&'*') => {
                let start = i;
                i += 2;
                while i + 1 < c.len() && !(c[i] == '*' && c[i + 1] == '/') {
                    i += 1;
                }
                i = (i + 2).min(c.len());
                line += newlines(&c[start..i]);
                blank(&mut out, start, i);
            }
            '\'' => {
                // A char literal ('x', '\n', '\u{..}') or a lifetime ('a).
                let start = i;
                if c.get(i + 1) == Some(&'\\') {
                    i += 2;
                    while i < c.len() && c[i] != '\'' {
                        i += 1;
                    }
                    i += 1;
                    blank(&mut out, start, i);
                } else if c.get(i + 2) == Some(&'\'') {
                    i += 3;
                    blank(&mut out, start, i);
                } else {
                    out.code.push('\'');
                    i += 1;
                }
            }
            'r' if (c.get(i + 1) == Some(&'"') || c.get(i + 1) == Some(&'#'))
                && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_')) =>
            {
                let mut j = i + 1;
                let mut hashes = 0;
                while c.get(j) == Some(&'#') {
                    hashes += 1;
                    j += 1;
                }
                if c.get(j) != Some(&'"') {
                    out.code.extend(&c[i..j]);
                    i = j;
                    continue;
                }
                let start = j + 1;
                let mut k = start;
                while k < c.len()
                    && !(c[k] == '"' && (1..=hashes).all(|h| c.get(k + h) == Some(&'#')))
                {
                    k += 1;
                }
                let end = k.min(c.len());
                out.literals.push((line, c[start..end].iter().collect()));
                line += newlines(&c[i..end]);
                blank(&mut out, i, end + 1 + hashes);
                i = end + 1 + hashes;
            }
            '"' => {
                let start = i + 1;
                let mut k = start;
                while k < c.len() && c[k] != '"' {
                    k += if c[k] == '\\' { 2 } else { 1 };
                }
                let end = k.min(c.len());
                out.literals.push((line, c[start..end].iter().collect()));
                line += newlines(&c[i..end]);
                blank(&mut out, i, end + 1);
                i = end + 1;
            }
            ch => {
                out.code.push(ch);
                i += 1;
            }
        }
    }
    out
}
