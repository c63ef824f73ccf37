//! Fuzzing the experiment-file loader: the committed files, mutated (numbers set to 0, negative,
//! inf, nan, huge or tiny; lines deleted or duplicated; quoted names swapped), either load or
//! are rejected with an error; the loader never panics. Bounded (200 cases) to run in seconds.

use proptest::prelude::*;

fn committed_files() -> Vec<(String, String)> {
    let dir = catalog::root_from_current_dir()
        .unwrap()
        .join("experiments");
    let mut files: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

/// Byte ranges of the numeric literals of `text` outside comments and strings.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let (mut i, mut in_str, mut in_comment) = (0, false, false);
    while i < b.len() {
        let c = b[i];
        if in_comment {
            in_comment = c != b'\n';
        } else if in_str {
            in_str = c != b'"';
        } else if c == b'#' {
            in_comment = true;
        } else if c == b'"' {
            in_str = true;
        } else if c.is_ascii_digit() || (c == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            let prev_ok = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
            let start = i;
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_digit()
                    || matches!(b[i], b'.' | b'e' | b'E' | b'_')
                    || (matches!(b[i], b'+' | b'-') && matches!(b[i - 1], b'e' | b'E')))
            {
                i += 1;
            }
            if prev_ok {
                out.push((start, i));
            }
            continue;
        }
        i += 1;
    }
    out
}

/// Byte ranges of the quoted strings (with their quotes) outside comments.
fn strings(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let (mut i, mut in_comment) = (0, false);
    while i < b.len() {
        if in_comment {
            in_comment = b[i] != b'\n';
        } else if b[i] == b'#' {
            in_comment = true;
        } else if b[i] == b'"' {
            if let Some(len) = text[i + 1..].find('"') {
                out.push((i, i + len + 2));
                i += len + 2;
                continue;
            }
        }
        i += 1;
    }
    out
}

const VALUES: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "-1.0",
    "-1e-9",
    "inf",
    "-inf",
    "nan",
    "1e300",
    "-1e300",
    "1e-300",
    "1.0",
    "0.5",
    "0.999999",
    "7",
    "18446744073709551615",
    "99999999999999999999",
];

#[derive(Clone, Debug)]
enum Mutation {
    Number(usize, usize),
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapString(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..VALUES.len()).prop_map(|(n, v)| Mutation::Number(n, v)),
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        2 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapString(a, b)),
    ]
}

fn apply(text: &str, m: &Mutation) -> String {
    match *m {
        Mutation::Number(n, v) => {
            let spots = numbers(text);
            if spots.is_empty() {
                return text.to_string();
            }
            let (a, b) = spots[n % spots.len()];
            format!("{}{}{}", &text[..a], VALUES[v], &text[b..])
        }
        Mutation::DeleteLine(n) | Mutation::DuplicateLine(n) => {
            let mut lines: Vec<&str> = text.lines().collect();
            let k = n % lines.len();
            if matches!(m, Mutation::DeleteLine(_)) {
                lines.remove(k);
            } else {
                lines.insert(k, lines[k]);
            }
            lines.join("\n")
        }
        Mutation::SwapString(a, b) => {
            let spots = strings(text);
            if spots.is_empty() {
                return text.to_string();
            }
            let (a0, a1) = spots[a % spots.len()];
            let (b0, b1) = spots[b % spots.len()];
            format!("{}{}{}", &text[..a0], &text[b0..b1], &text[a1..])
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn mutated_experiment_files_load_or_are_rejected(
        file in any::<usize>(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let files = committed_files();
        let (name, text) = &files[file % files.len()];
        let mutated = mutations.iter().fold(text.clone(), |t, m| apply(&t, m));
        match reproduce::experiments_from_toml(&mutated) {
            Ok(f) => {
                // A file that loads expands into runs, each with a unique key.
                let jobs = f.jobs().unwrap();
                let mut keys: Vec<spec::RunKey> = jobs.iter().map(|j| j.key()).collect();
                keys.sort();
                keys.dedup();
                prop_assert_eq!(keys.len(), jobs.len(), "{}: duplicate run keys", name);
            }
            Err(e) => prop_assert!(!e.to_string().trim().is_empty(), "{}: empty error", name),
        }
    }
}

#[test]
fn the_mutators_find_what_they_mutate() {
    let text = "a = 1.5e-3 # 2\nb = \"x-1\"\nc = [-2, 3]\n";
    let n: Vec<&str> = numbers(text).iter().map(|&(a, b)| &text[a..b]).collect();
    assert_eq!(n, ["1.5e-3", "-2", "3"]);
    let s: Vec<&str> = strings(text).iter().map(|&(a, b)| &text[a..b]).collect();
    assert_eq!(s, ["\"x-1\""]);
    for (_, t) in committed_files() {
        reproduce::experiments_from_toml(&t).unwrap();
    }
}
