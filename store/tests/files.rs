//! Reading and writing results/: a corrupt or old-schema runs.csv is an error naming the file,
//! line and how to recover, never an empty list; stale temporary files of killed writers are
//! removed.

use std::path::PathBuf;

/// The first `lines` lines of the committed results/runs.csv, rewritten by `edit`, in a temp
/// file (removed on return); its path and the result of reading it.
fn read_edited_runs(
    name: &str,
    lines: usize,
    edit: impl Fn(Vec<String>) -> Vec<String>,
) -> (PathBuf, Result<Vec<records::RunRow>, String>) {
    let committed = catalog::root_from_current_dir()
        .unwrap()
        .join("results")
        .join("runs.csv");
    let text = std::fs::read_to_string(committed).unwrap();
    let head: Vec<String> = text.lines().take(lines).map(String::from).collect();
    let dir = inputs::Scratch::dir(&format!("test-runs-{name}"));
    let path = dir.join(format!("{name}.csv"));
    std::fs::write(&path, edit(head).join("\n") + "\n").unwrap();
    let result = store::read_runs(&path).map_err(|e| e.to_string());
    (path, result)
}

#[test]
fn a_corrupt_runs_csv_is_an_error_never_an_empty_list() {
    use store::read_runs;
    let (_, good) = read_edited_runs("good", 4, |l| l);
    assert_eq!(good.unwrap().len(), 3);
    // A row that does not parse (a number column, observe_s, holding text) on line 3.
    let (path, bad) = read_edited_runs("bad_row", 4, |mut l| {
        let mut cells: Vec<&str> = l[2].split(',').collect();
        let k = cells.len() - 3;
        cells[k] = "abc";
        l[2] = cells.join(",");
        l
    });
    let err = bad.expect_err("a corrupt row is an error");
    assert!(err.contains(&path.display().to_string()), "{err}");
    assert!(err.contains("line 3"), "{err}");
    assert!(
        err.contains("git checkout") && err.contains("move"),
        "{err}"
    );
    // A truncated row (a killed writer of an older version, or a bad merge).
    let (_, bad) = read_edited_runs("truncated", 4, |mut l| {
        let cut = l[3].len() / 2;
        l[3].truncate(cut);
        l
    });
    assert!(bad.expect_err("truncated row").contains("line 4"));
    // An old schema: a column this version writes is missing from the header.
    let (path, old) = read_edited_runs("old_schema", 3, |l| {
        l.into_iter()
            .map(|line| {
                let cells: Vec<&str> = line.split(',').collect();
                [&cells[..cells.len() - 3], &cells[cells.len() - 2..]]
                    .concat()
                    .join(",")
            })
            .collect()
    });
    let err = old.expect_err("an old schema is an error");
    assert!(
        err.contains(&path.display().to_string()) && err.contains("line 1"),
        "{err}"
    );
    assert!(err.contains("missing columns: observe_s"), "{err}");
    // An unknown column.
    let (_, foreign) = read_edited_runs("foreign", 2, |mut l| {
        l[0].push_str(",extra");
        l[1].push_str(",1");
        l
    });
    assert!(foreign
        .expect_err("unknown column")
        .contains("unknown columns: extra"));
    // Not a file at all.
    let missing = std::env::temp_dir()
        .join("driftbench-no-such-dir")
        .join("runs.csv");
    let err = read_runs(&missing).expect_err("missing file").to_string();
    assert!(err.contains("runs.csv"), "{err}");
}

#[test]
fn stale_temporary_files_are_removed_and_nothing_else() {
    use store::check_writable;
    use store::results_dir::remove_own_tmp;
    use store::write_atomic;
    use store::OwnedDir;
    let dir = inputs::Scratch::unmade("test-tmp");
    let nested = dir.join("traces").join("x");
    std::fs::create_dir_all(&nested).unwrap();
    std::fs::write(dir.join(".driftbench-tmp.123.0.runs.csv"), "half").unwrap();
    std::fs::write(nested.join(".driftbench-tmp.123.7.a__b.csv"), "half").unwrap();
    // The user's own files, named *.tmp too (some as the old pattern did).
    std::fs::write(dir.join("notes.tmp"), "mine").unwrap();
    std::fs::write(dir.join("notes.2024.12.tmp"), "mine").unwrap();
    std::fs::write(nested.join("draft.tmp"), "mine").unwrap();
    write_atomic(&nested.join("a__b.csv"), b"t\n").unwrap();
    let removed = remove_own_tmp(&OwnedDir::open(&dir).unwrap());
    assert_eq!(removed.len(), 2, "{removed:?}");
    assert!(nested.join("a__b.csv").exists());
    assert!(dir.join("notes.tmp").exists() && nested.join("draft.tmp").exists());
    assert!(dir.join("notes.2024.12.tmp").exists());
    check_writable(&dir.join("new")).unwrap();
    assert!(dir.join("new").is_dir());
    assert!(std::fs::read_dir(dir.join("new")).unwrap().next().is_none());
}
