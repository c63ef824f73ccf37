//! `reproduce cost` (`--dof-cost`): the cost against the number of joints
//! (crate `cost`) measured on the n-link arms, written to results/dof-cost.csv with
//! the fitted growth exponents and the machine, then the report re-rendered.

use crate::error::ReproduceError;
use crate::project::Project;
use crate::report::{render_report, report_root};
use crate::results::{experiment_files, open_results, Described};

/// Measures, prints the fitted exponents and (unless `dry_run`) writes and re-renders.
pub fn dof_cost(project: &Project, dry_run: bool, git_rev: &str) -> Result<(), ReproduceError> {
    use cost::{machine, measure_all, Budget};
    let (cpu, cores) = machine();
    let root = report_root(project)?;
    let results = (!dry_run)
        .then(|| {
            open_results(
                project,
                git_rev,
                &Described::new(&experiment_files(project)?),
            )
        })
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
    let path = records::dof_cost::write(results.path(), &rows)?;
    results.save()?;
    eprintln!("wrote {} ({} rows)", path.display(), rows.len());
    render_report(project, &root, &results)
}
