//! Embeds the code revision in the binary (`reproduce::REVISION`, from the
//! environment variable `DRIFTBENCH_REVISION` set here): the commit of a clean checkout, with a
//! hash of the sources when the tree is dirty, or the hash alone without git
//! (`src/revision/source.rs` states the rules). Runs again whenever a source or the checked-out
//! commit changes.

#[path = "src/revision/source.rs"]
mod source;

#[path = "../store/src/fnv.rs"]
mod fnv;

use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest
        .parent()
        .expect("reproduce/ lies in the workspace root")
        .to_path_buf();
    for p in source::source_roots(&root) {
        println!("cargo:rerun-if-changed={}", root.join(p).display());
    }
    for p in source::git_files(&root) {
        println!("cargo:rerun-if-changed={}", p.display());
    }
    println!(
        "cargo:rustc-env=DRIFTBENCH_REVISION={}",
        source::revision(&root, fnv::fnv1a64)
    );
}
