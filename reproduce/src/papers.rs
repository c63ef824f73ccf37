//! The papers as data (`papers/` under the project root, [`analysis::papers::Papers`]) as the
//! modes load them: published numbers that contradict the paper's own are warned on stderr,
//! and what the papers name is checked against the runs of the experiment files before
//! anything runs.

use crate::error::ReproduceError;
use crate::project::Project;
use crate::results::Described;

/// The papers as data (`papers/` under the project root). Their published numbers that
/// contradict the paper's own are warned on stderr, once per process, with file and line.
pub fn load_papers(project: &Project) -> Result<analysis::papers::Papers, ReproduceError> {
    static WARNED: std::sync::Once = std::sync::Once::new();
    let root = &project.root;
    let papers = analysis::papers::Papers::load(&root.join("papers"))?;
    WARNED.call_once(|| {
        for w in &papers.warnings {
            let file = w.file.strip_prefix(root).unwrap_or(&w.file);
            eprintln!("warning: {}:{}: {}", file.display(), w.line, w.message);
        }
    });
    Ok(papers)
}

/// The papers as data ([`load_papers`]), with what they name checked against every run of the
/// experiment files (`all`), before anything runs: a mapping that names no run of a defined
/// experiment, or a claim that selects none, is refused; what names an experiment the files do
/// not define is said on stderr, once per process ([`analysis::check_paper_runs`]).
pub fn load_checked_papers(
    project: &Project,
    all: &Described,
) -> Result<analysis::papers::Papers, ReproduceError> {
    static NOTED: std::sync::Once = std::sync::Once::new();
    let papers = load_papers(project)?;
    let absent =
        analysis::check_paper_runs(&papers, &project.root.join("papers"), &all.run_keys()?)?;
    NOTED.call_once(|| {
        if let Some(first) = absent.first() {
            let file = first
                .file
                .strip_prefix(&project.root)
                .unwrap_or(&first.file);
            let first = analysis::AbsentRun {
                file: file.to_path_buf(),
                ..first.clone()
            };
            eprintln!(
                "note: {first}{}",
                match absent.len() {
                    1 => String::new(),
                    n => format!(" (and {} more such names)", n - 1),
                }
            );
        }
    });
    Ok(papers)
}
