//! `reproduce cost`: what one instant and one whole run cost against the number
//! of joints on the n-link arms, per dense LU backend, written to results/dof-cost.csv with the
//! fitted growth exponents and the machine, then the report re-rendered. The criterion bench
//! `cargo bench -p driftbench-benches --bench dof` times the same calls through this module.
//!
//! # Why the harness is here
//!
//! The harness measures the engine; it is not part of it: `simulation` carries no timing code,
//! and `records` keeps only the plain data handed over ([`records::dof_cost`]: the quantities,
//! summaries, fits and rows). It was a crate of its own (`cost`) so that both this mode and the
//! criterion bench could call it; it is now a module of the binary that writes its table. It
//! cannot live in `benches`: no crate links `driftbench-benches` (the layering test), while
//! `benches` links `reproduce`, so the bench reaches the harness from here.
//!
//! # One harness
//!
//! [`prepare`]: any N, no instantiation per size: the registry's n-link arm `nlink-N` and the
//! scheme (jia2019's VLTCO on a four-leaf clover, kong2019's ZNN scheme, eq. 22, on a circle)
//! through the engine's one path, every quantity, whole runs included, at states sampled from
//! one exact run. Both schemes at N = 3 ... 30 ([`records::dof_cost::SWEEP_SIZES`]),
//! kong2019's alone at N = 40 ... 200. The dense LU quantities (`network-lu`, `kkt-floor`) are
//! timed on both [`solvers::Backend`]s ([`backends`]), from which the report reads the
//! crossover that [`settings::FAER_CROSSOVER`] records. The `measure` module
//! holds the timing (how samples are taken and summarised).

mod case;
mod error;
mod harness;
mod instants;
mod measure;

pub use case::{backends, Case, PreparedCase};
pub use error::CostError;
pub use harness::{prepare, LARGE_STATES};
pub use measure::machine;

use crate::error::ReproduceError;
use crate::project::Project;
use crate::report::{render_report, report_root};
use crate::results::{experiment_files, open_results, Described};

/// Measures, prints the fitted exponents and (unless `dry_run`) writes and re-renders.
pub fn dof_cost(project: &Project, dry_run: bool, git_rev: &str) -> Result<(), ReproduceError> {
    use measure::{measure_all, Budget};
    let (cpu, cores) = machine();
    let root = report_root(project)?;
    let files = if dry_run {
        Vec::new()
    } else {
        experiment_files(project)?
    };
    let all = Described::new(&files);
    let results = (!dry_run)
        .then(|| open_results(project, git_rev, &all))
        .transpose()?;
    eprintln!("measuring the cost against the number of joints on {cpu} ({cores} cores)");
    let started = std::time::Instant::now();
    let measurements = measure_all(&Budget::default(), |case| {
        eprintln!(
            "  {} nlink-{}: done at {:.1} s",
            case.scheme.id(),
            case.n,
            started.elapsed().as_secs_f64()
        );
    });
    let rows = analysis::fits::rows(&measurements, &cpu, cores, git_rev);
    for fit in rows.iter().filter(|r| r.is_fit()) {
        eprintln!(
            "  {} {} ({}): cost ~ N^{:.2}",
            fit.scheme,
            fit.quantity,
            fit.backend,
            fit.exponent.unwrap_or(f64::NAN)
        );
    }
    let Some(results) = results else {
        return Ok(());
    };
    let path = store::dof_cost::write(results.path(), &rows)?;
    results.save()?;
    eprintln!("wrote {} ({} rows)", path.display(), rows.len());
    render_report(project, &root, &results, &all)
}
