//! The workspace's layers, read from its `Cargo.toml` files. A rule names a crate and what it
//! may not link, directly or transitively (normal and build dependencies, target-specific ones
//! included; dev-dependencies do not link into the library):
//!
//! - presentation links no crate that simulates or solves (solvers, simulation, control,
//!   explain; the cost harness is reproduce's, which links them): rendering the report and
//!   its figures needs only the records of the runs;
//! - the numerical crates (robots, schemes, settings, solvers) link no experiment-file or
//!   results crate (catalog, records, store): a user can take the arms, the schemes and the solvers
//!   without the experiment files. (robots reads its own robot files, so TOML is allowed, and
//!   reads URDFs through `inputs`, the one reader of files from outside, which holds no file
//!   format of the suite's.)
//! - the experiment-file and results crates (catalog, records, store) link no engine crate
//!   (schemes, solvers, simulation): they state a scheme, a path or a solver as data (crates
//!   `spec` and `settings`), which the engine builds from;
//! - the row schemas (records) link no store: the store (the sealed results directory, its
//!   journal and shards) reads and writes the schemas' rows, never the other way;
//! - `spec` (runs as data) links no workspace member but `settings` (the solvers' settings as
//!   data), which links none;
//! - the engine (simulation, control) links no experiment-file crate (catalog): it builds a
//!   run from spec's `RunSpec`, and the orchestrator (reproduce) loads the files;
//! - the control experiments read no file: control links neither catalog nor the reader of
//!   files from outside (`inputs`) directly, and no source of it opens or reads a file; their
//!   task set is read by catalog (`catalog::load_task_set`) and handed over as data
//!   (`spec::TaskSet`);
//! - the engine (simulation, control) links no verdict crate (analysis): it runs and writes
//!   rows, and the papers' claims are decided from the rows (zhong2021's efficiency claim in
//!   `analysis::control_claim`, called by the orchestrator and the report);
//! - no member links the benches (`driftbench-benches`, which holds the suite's measurements
//!   of itself): the reproduction and its report are built without them.
//! - no member but the benches links the counting allocator (`alloc-count`, which installs
//!   itself as the global allocator): tests take it as a dev-dependency, and no program of the
//!   suite counts its allocations.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates that run simulations or solvers.
const SOLVING: [&str; 4] = ["solvers", "simulation", "control", "explain"];

/// The numerical crates, usable without experiment files.
const NUMERICAL: [&str; 4] = ["robots", "schemes", "settings", "solvers"];

/// What the numerical crates may not link: the experiment-file and results crates (the row
/// schemas and the store).
const FILE_FORMATS: [&str; 3] = ["catalog", "records", "store"];

/// The engine: the crates that build and run schemes and solvers.
const ENGINE: [&str; 3] = ["schemes", "solvers", "simulation"];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn manifest(dir: &Path) -> toml::Table {
    let path = dir.join("Cargo.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: cannot read: {e}", path.display()));
    text.parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The package names a dependency table names (a renamed dependency by its `package`).
fn names(table: Option<&toml::Value>) -> Vec<String> {
    let Some(table) = table.and_then(toml::Value::as_table) else {
        return Vec::new();
    };
    table
        .iter()
        .map(|(key, spec)| {
            spec.get("package")
                .and_then(toml::Value::as_str)
                .unwrap_or(key)
                .to_string()
        })
        .collect()
}

/// The dependencies that link into a package: `[dependencies]`, `[build-dependencies]` and
/// their `[target.<cfg>.…]` forms.
fn linked(manifest: &toml::Table) -> Vec<String> {
    let kinds = ["dependencies", "build-dependencies"];
    let mut out: Vec<String> = kinds.iter().flat_map(|k| names(manifest.get(*k))).collect();
    if let Some(targets) = manifest.get("target").and_then(toml::Value::as_table) {
        for target in targets.values() {
            out.extend(kinds.iter().flat_map(|k| names(target.get(*k))));
        }
    }
    out
}

/// Every workspace member by package name: its linked dependencies.
fn workspace() -> BTreeMap<String, Vec<String>> {
    let root_manifest = manifest(&root());
    let members = root_manifest["workspace"]["members"]
        .as_array()
        .expect("the root Cargo.toml lists [workspace] members");
    members
        .iter()
        .map(|m| {
            let m = manifest(&root().join(m.as_str().expect("a member is a path")));
            let name = m["package"]["name"]
                .as_str()
                .expect("a member has a package name")
                .to_string();
            (name, linked(&m))
        })
        .collect()
}

/// The packages `package` depends on, directly or transitively, each with the chain that
/// reaches it: the workspace members it reaches, and the outside crates those link directly.
fn closure(graph: &BTreeMap<String, Vec<String>>, package: &str) -> BTreeMap<String, Vec<String>> {
    let mut reached: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut stack = vec![vec![package.to_string()]];
    let mut seen = BTreeSet::from([package.to_string()]);
    while let Some(chain) = stack.pop() {
        let last = chain.last().expect("a chain is never empty");
        for dep in graph.get(last).into_iter().flatten() {
            if !seen.insert(dep.clone()) {
                continue;
            }
            let mut longer = chain.clone();
            longer.push(dep.clone());
            reached.insert(dep.clone(), longer.clone());
            if graph.contains_key(dep) {
                stack.push(longer);
            }
        }
    }
    reached
}

#[test]
fn the_workspace_graph_is_read() {
    let graph = workspace();
    assert!(
        graph["presentation"].iter().any(|d| d == "records"),
        "presentation reads the results through records"
    );
    assert!(
        closure(&graph, "control").contains_key("solvers"),
        "control runs the solvers: the graph must show it"
    );
}

/// The chains by which `package` links any of `forbidden`.
fn offending(
    graph: &BTreeMap<String, Vec<String>>,
    package: &str,
    forbidden: &[&str],
) -> Vec<String> {
    let reached = closure(graph, package);
    forbidden
        .iter()
        .filter_map(|f| reached.get(*f))
        .map(|chain| chain.join(" -> "))
        .collect()
}

#[test]
fn presentation_links_no_solver() {
    let graph = workspace();
    let found = offending(&graph, "presentation", &SOLVING);
    assert!(
        found.is_empty(),
        "presentation links crates that simulate or solve:\n  {}",
        found.join("\n  ")
    );
}

#[test]
fn the_numerical_crates_link_no_file_format() {
    let graph = workspace();
    for package in NUMERICAL {
        assert!(
            graph.contains_key(package),
            "{package} is a workspace member"
        );
        let found = offending(&graph, package, &FILE_FORMATS);
        assert!(
            found.is_empty(),
            "{package} links an experiment-file or results crate:\n  {}",
            found.join("\n  ")
        );
    }
}

#[test]
fn the_file_formats_link_no_engine() {
    let graph = workspace();
    for package in FILE_FORMATS {
        assert!(
            graph.contains_key(package),
            "{package} is a workspace member"
        );
        let found = offending(&graph, package, &ENGINE);
        assert!(
            found.is_empty(),
            "{package} links an engine crate:\n  {}",
            found.join("\n  ")
        );
    }
}

#[test]
fn the_schemas_link_no_store() {
    let graph = workspace();
    assert!(
        graph["store"].iter().any(|d| d == "records"),
        "the store reads and writes the schemas' rows: the graph must show it"
    );
    let found = offending(&graph, "records", &["store"]);
    assert!(
        found.is_empty(),
        "records links the store (the schemas only serialise rows):\n  {}",
        found.join("\n  ")
    );
}

#[test]
fn the_specifications_are_a_leaf() {
    let graph = workspace();
    // spec states runs with the solvers' settings (crate `settings`, a leaf of plain data too)
    // and links nothing else of the workspace.
    let members: Vec<&str> = graph
        .keys()
        .map(String::as_str)
        .filter(|m| *m != "settings")
        .collect();
    let found = offending(&graph, "spec", &members);
    assert!(
        found.is_empty(),
        "spec links workspace members other than settings:\n  {}",
        found.join("\n  ")
    );
    assert!(
        offending(&graph, "settings", &members).is_empty(),
        "settings, which spec links, links no workspace member"
    );
    assert!(
        graph["catalog"].iter().any(|d| d == "spec"),
        "catalog reads experiment files into spec's types: the graph must show it"
    );
}

#[test]
fn the_engine_reads_no_experiment_file() {
    let graph = workspace();
    for package in ["simulation", "control"] {
        assert!(
            graph.contains_key(package),
            "{package} is a workspace member"
        );
        let found = offending(&graph, package, &["catalog"]);
        assert!(
            found.is_empty(),
            "{package} links the experiment files' crate (the engine builds from spec's types; \
             the orchestrator loads the files):\n  {}",
            found.join("\n  ")
        );
    }
}

/// What in `code` opens or reads a file, one name per finding.
fn file_reads(code: &str) -> Vec<&'static str> {
    [
        "std::fs",
        "fs::read",
        "File::open",
        "read_to_string",
        "inputs::",
    ]
    .into_iter()
    .filter(|name| code.contains(name))
    .collect()
}

#[test]
fn the_control_experiments_read_no_file() {
    let graph = workspace();
    assert!(
        graph["catalog"].iter().any(|d| d == "inputs"),
        "catalog reads the task set through the input reader: the graph must show it"
    );
    let direct: Vec<&String> = graph["control"]
        .iter()
        .filter(|d| *d == "inputs" || *d == "catalog")
        .collect();
    assert!(
        direct.is_empty(),
        "control links a reader of files {direct:?} (its task set is catalog::load_task_set's to \
         read, and comes as spec::TaskSet)"
    );
    let src = root().join("control/src");
    let mut found = Vec::new();
    for entry in std::fs::read_dir(&src).unwrap_or_else(|e| panic!("{}: {e}", src.display())) {
        let path = entry.expect("a directory entry").path();
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // Code only: the line before a `//` (the docs may name the file the set comes from).
        let code: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap_or(""))
            .collect::<Vec<_>>()
            .join("\n");
        for name in file_reads(&code) {
            found.push(format!("{}: {name}", path.display()));
        }
    }
    assert!(
        found.is_empty(),
        "control reads a file (the orchestrator reads, the engine takes data):\n  {}",
        found.join("\n  ")
    );
    assert_eq!(
        file_reads("let t = std::fs::read_to_string(p)?;"),
        ["std::fs", "fs::read", "read_to_string"],
        "the detector finds a read"
    );
}

#[test]
fn the_engine_decides_no_claim() {
    let graph = workspace();
    for package in ["simulation", "control"] {
        assert!(
            graph.contains_key(package),
            "{package} is a workspace member"
        );
        let found = offending(&graph, package, &["analysis"]);
        assert!(
            found.is_empty(),
            "{package} links the verdicts (claims are decided from the rows):\n  {}",
            found.join("\n  ")
        );
    }
}

#[test]
fn nothing_links_the_benches() {
    let graph = workspace();
    assert!(
        closure(&graph, "driftbench-benches").contains_key("records"),
        "the benches are a member that reads records"
    );
    for package in graph.keys().filter(|p| *p != "driftbench-benches") {
        let found = offending(&graph, package, &["driftbench-benches"]);
        assert!(
            found.is_empty(),
            "{package} links the benches (the suite's measurements of itself):\n  {}",
            found.join("\n  ")
        );
    }
}

#[test]
fn only_the_benches_link_the_counting_allocator() {
    let graph = workspace();
    assert!(
        graph["driftbench-benches"]
            .iter()
            .any(|d| d == "alloc-count"),
        "the benches count allocations per timed call"
    );
    for package in graph.keys().filter(|p| *p != "driftbench-benches") {
        let found = offending(&graph, package, &["alloc-count"]);
        assert!(
            found.is_empty(),
            "{package} links the counting allocator (a dev-dependency only):\n  {}",
            found.join("\n  ")
        );
    }
}

#[test]
fn the_rule_sees_an_outside_crate_through_a_member() {
    let graph = workspace();
    let found = offending(&graph, "schemes", &["toml"]);
    assert!(
        found.iter().any(|c| c.ends_with("-> robots -> toml")),
        "schemes reaches toml through robots' robot files: {found:?}"
    );
}
