//! Errors are typed in library code: no `Result<_, String>` in the `src/` of any workspace member
//! (read from the root `Cargo.toml`; each crate has its error enums in `error.rs`, each layer
//! wrapping the one below). A `Result` whose error type is `String` is found by matching its
//! angle brackets, so nested types (`Result<Vec<(A, B)>, String>`) are caught too; comments are
//! skipped.
//!
//! Not searched: the files of [`ALLOWED`], each with its reason.

use crate::common;

use common::{library_files, repo_root};

/// Files that may still return `Result<_, String>`, each being replaced or rewritten elsewhere:
/// remove an entry when its file is replaced (the test then holds the new file to the rule).
const ALLOWED: &[&str] = &[];

/// The 1-based lines of `text` where a `Result<T, String>` starts (outside `//` comments).
fn string_results(text: &str) -> Vec<usize> {
    let code: String = text
        .lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n");
    let bytes = code.as_bytes();
    let mut hits = Vec::new();
    let mut from = 0;
    while let Some(i) = code[from..].find("Result<") {
        let start = from + i;
        from = start + "Result<".len();
        let word_start =
            start == 0 || !(bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_');
        if !word_start {
            continue;
        }
        // Split the arguments at depth 1 until the matching `>`.
        let (mut depth, mut arg_start, mut args) = (1usize, from, Vec::new());
        for (k, c) in code[from..].char_indices() {
            let at = from + k;
            match c {
                // The arrow of a function type (`Fn() -> T`) is not a bracket.
                '>' if code[..at].ends_with('-') => {}
                '<' | '(' | '[' => depth += 1,
                '>' | ')' | ']' => {
                    depth -= 1;
                    if depth == 0 {
                        args.push(&code[arg_start..at]);
                        break;
                    }
                }
                ',' if depth == 1 => {
                    args.push(&code[arg_start..at]);
                    arg_start = at + 1;
                }
                _ => {}
            }
        }
        if args.len() == 2 && args[1].trim() == "String" {
            hits.push(code[..start].matches('\n').count() + 1);
        }
    }
    hits
}

#[test]
fn the_finder_sees_nested_and_plain_string_results() {
    let text = "fn a() -> Result<(), String> {}\n// Result<(), String>\nfn b() -> Result<Vec<(u8, u8)>, String> {}\nfn c() -> PyResult<String> {}\nfn d() -> Result<String, E> {}\ntype F = Result<Box<dyn Fn() -> u8>, String>;\n";
    assert_eq!(string_results(text), [1, 3, 6]);
}

#[test]
fn library_code_has_no_string_errors() {
    let root = repo_root();
    let files = library_files(&root, "simulation/src/error.rs");
    let sites: Vec<String> = files
        .iter()
        .filter(|f| !ALLOWED.contains(&f.as_str()))
        .flat_map(|f| {
            let text = std::fs::read_to_string(root.join(f)).expect("a readable source file");
            string_results(&text)
                .into_iter()
                .map(move |line| format!("  {f}:{line}"))
        })
        .collect();
    assert!(
        sites.is_empty(),
        "{} `Result<_, String>` in library code; give them a typed error (the crate's error.rs):\n{}",
        sites.len(),
        sites.join("\n")
    );
}
