//! Fuzzing what the program reads back from results directories: the committed runs.csv cut,
//! its cells replaced by hostile names (paths, `..`, absolute paths, control characters, very
//! long ids) or duplicated; arbitrary shard manifests (`shard.toml`) and integrity manifests
//! (`manifest.toml`). Every input is either rejected with an error or accepted with every name
//! safe to use as a file name; nothing panics. Bounded (200 cases each) to run in seconds.

use proptest::prelude::*;
use store::read_runs;

use inputs::Scratch;

fn committed_runs() -> Vec<String> {
    let path = catalog::root_from_current_dir()
        .unwrap()
        .join("results/runs.csv");
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .take(12)
        .map(String::from)
        .collect()
}

/// A scratch directory of the test `test` (one case of it at a time), removed when dropped.
fn scratch(test: &str) -> Scratch {
    Scratch::dir(&format!("fuzz-results-{test}"))
}

/// Names an attacker would put in a row.
fn hostile_name() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("../../../somewhere".to_string()),
        Just("/etc".to_string()),
        Just("..".to_string()),
        Just("a\\b".to_string()),
        Just("a\nb".to_string()),
        Just(String::new()),
        (1usize..400).prop_map(|n| "x".repeat(n)),
        "[a-zA-Z0-9 ()./_-]{0,40}",
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn hostile_rows_are_rejected_or_safe(
        line in 1usize..12,
        column in 0usize..4,
        name in hostile_name(),
        keep in 1usize..13,
        duplicate in any::<bool>(),
    ) {
        let mut lines = committed_runs();
        let mut cells: Vec<String> = lines[line].split(',').map(String::from).collect();
        // paper, experiment, variant are the first columns, solver the fifth.
        let index = [0, 1, 2, 4][column];
        let quoted = format!("\"{}\"", name.replace('"', "\"\""));
        if index < cells.len() {
            cells[index] = quoted;
        }
        lines[line] = cells.join(",");
        if duplicate {
            let copy = lines[line].clone();
            lines.push(copy);
        }
        lines.truncate(keep.max(1));
        let base = scratch("hostile-rows");
        let path = base.join(format!("runs-{line}-{column}-{keep}.csv"));
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        if let Ok(rows) = read_runs(&path) {
            for r in &rows {
                // The ids of every row read can name files (their types checked them).
                use spec::{check_name, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL};
                prop_assert!(check_name(&r.experiment, MAX_EXPERIMENT_ID).is_ok());
                prop_assert!(check_name(&r.variant_id, MAX_VARIANT_LABEL).is_ok());
                prop_assert!(check_name(&r.solver_id, MAX_SOLVER_LABEL).is_ok());
            }
            let mut keys: Vec<_> = rows.iter().map(|r| r.key()).collect();
            keys.sort();
            keys.dedup();
            prop_assert_eq!(keys.len(), rows.len());
        }
    }

    #[test]
    fn arbitrary_shard_manifests_never_panic(text in "(shard|shards|git_rev|runs|selection|experiments_hash|paper|=|\\[|\\]|\"|[0-9]|\n| |\\.\\./x|[a-z]){0,120}") {
        let base = scratch("shard-manifests");
        let dir = base.join("shard-manifest");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join(store::shard::MANIFEST), &text).unwrap();
        let _ = store::shard::Manifest::read(&dir);
    }

    #[test]
    fn integrity_manifests_list_only_plain_paths(
        key in prop_oneof![
            Just("runs.csv".to_string()),
            Just("../x.csv".to_string()),
            Just("/etc/passwd".to_string()),
            Just("traces/../../x".to_string()),
            Just("traces/e/v__s.csv".to_string()),
            "[a-z./]{0,20}",
        ],
        lines in 0usize..5,
    ) {
        let base = scratch("integrity-manifests");
        let dir = base.join("integrity-manifest");
        std::fs::create_dir_all(&dir).unwrap();
        let text = format!(
            "git_rev = \"x\"\n[files.\"{key}\"]\nlines = {lines}\nbytes = 1\nsha256 = \"00\"\n"
        );
        std::fs::write(dir.join(store::integrity::FILE), text).unwrap();
        if let Ok(Some(mut m)) = store::integrity::Manifest::open(&dir) {
            let keys: Vec<String> = m.entries().unwrap().map(|e| e.unwrap().0).collect();
            for k in &keys {
                prop_assert!(!k.starts_with('/') && !k.split('/').any(|s| s == ".." || s.is_empty()), "{}", k);
            }
        }
    }
}

/// The fuzz cases above check what a reader returns when it accepts a file; these two make sure
/// the readers do accept well-formed files, so that those checks cannot pass vacuously.
#[test]
fn the_fuzzed_readers_accept_well_formed_files() {
    let lines = committed_runs();
    let base = scratch("well-formed");
    let path = base.join("runs-unmutated.csv");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let rows = read_runs(&path).expect("the committed runs.csv reads");
    assert_eq!(rows.len(), lines.len() - 1);

    let dir = base.join("integrity-manifest-plain");
    std::fs::create_dir_all(&dir).unwrap();
    let text =
        "git_rev = \"x\"\n[files.\"traces/e/v__s.csv\"]\nlines = 1\nbytes = 1\nsha256 = \"00\"\n";
    std::fs::write(dir.join(store::integrity::FILE), text).unwrap();
    let mut m = store::integrity::Manifest::open(&dir)
        .expect("a well-formed manifest reads")
        .expect("and is found");
    assert!(m.get("traces/e/v__s.csv").unwrap().is_some());
}

/// The fuzzed readers above accept well-formed inputs, so their checks on what was read cannot
/// pass only because every input was refused: the committed rows they start from read, and a
/// manifest of one plain path reads with that path.
#[test]
fn the_unmutated_inputs_read() {
    let lines = committed_runs();
    let base = scratch("unmutated");
    let path = base.join("runs-unmutated.csv");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let rows = read_runs(&path).expect("the committed rows read");
    assert_eq!(rows.len(), lines.len() - 1);

    let dir = base.join("integrity-manifest-plain");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join(store::integrity::FILE),
        "git_rev = \"x\"\n[files.\"traces/e/v__s.csv\"]\nlines = 1\nbytes = 1\nsha256 = \"00\"\n",
    )
    .unwrap();
    let mut manifest = store::integrity::Manifest::open(&dir)
        .expect("a plain manifest reads")
        .expect("the manifest exists");
    assert!(manifest.get("traces/e/v__s.csv").unwrap().is_some());
}
