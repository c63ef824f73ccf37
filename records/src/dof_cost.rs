//! `results/dof-cost.csv`: the cost against the number of joints ([`simulation::dof_cost`]),
//! one [`DofCostRow`] per (scheme, N, quantity) measured, and one per (scheme, quantity) with
//! the fitted growth exponent k of median cost ~ c N^k ([`fit_rows`]).
//!
//! Every row carries the machine it was measured on (CPU model and cores, read from
//! `/proc/cpuinfo` at measurement time) and the code revision: times are comparable within one
//! file, not across machines. The file is written whole by `reproduce --dof-cost` (a new
//! measurement replaces the old one; two machines' numbers are never mixed).

use crate::table::Row;
use serde::{Deserialize, Serialize};
use simulation::dof_cost::{fit_power_law, Measurement};
use std::path::{Path, PathBuf};

/// The file name inside `results/`.
pub const FILE: &str = "dof-cost.csv";
/// [`DofCostRow::kind`] of a measured row.
pub const MEASURED: &str = "measured";
/// [`DofCostRow::kind`] of a fitted exponent.
pub const FIT: &str = "fit";

/// One row of `results/dof-cost.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DofCostRow {
    /// The paper whose scheme was run (`jia2019`, `kong2019`).
    pub scheme: String,
    /// The scheme's own name (`VLTCO`, `ZNN (eq. 22)`).
    pub scheme_name: String,
    /// The network of the network quantities (`LVI-PDNN`).
    pub network: String,
    /// `scheme-build`, `network-rhs`, ... ([`simulation::dof_cost::Quantity::id`]).
    pub quantity: String,
    /// [`MEASURED`] or [`FIT`].
    pub kind: String,
    /// Joints (measured rows).
    pub n: Option<usize>,
    /// QP sizes (measured rows).
    pub nx: Option<usize>,
    pub n_eq: Option<usize>,
    pub n_in: Option<usize>,
    /// Median and 95th percentile (us): per call, or per whole run for `run-*`.
    pub median_us: Option<f64>,
    pub p95_us: Option<f64>,
    /// Samples behind the median (measured rows) or points fitted (fit rows).
    pub samples: usize,
    /// Fit rows: the exponent k and factor c (us) of median ~ c N^k.
    pub exponent: Option<f64>,
    pub factor_us: Option<f64>,
    /// `run-*` rows: accepted steps, RHS evaluations and whether the run completed.
    pub steps: Option<usize>,
    pub rhs_evals: Option<usize>,
    pub completed: Option<bool>,
    /// CPU model (`/proc/cpuinfo`'s model name) and logical cores available.
    pub machine: String,
    pub cores: usize,
    pub git_rev: String,
}

impl Row for DofCostRow {}

impl DofCostRow {
    /// The row of one measurement.
    pub fn measured(m: &Measurement, machine: &str, cores: usize, git_rev: &str) -> Self {
        DofCostRow {
            scheme: m.scheme.id().to_string(),
            scheme_name: m.scheme_name.clone(),
            network: m.network.clone(),
            quantity: m.quantity.id().to_string(),
            kind: MEASURED.to_string(),
            n: Some(m.n),
            nx: Some(m.dims.nx),
            n_eq: Some(m.dims.n_eq),
            n_in: Some(m.dims.n_in),
            median_us: Some(m.summary.median_us),
            p95_us: Some(m.summary.p95_us),
            samples: m.summary.samples,
            exponent: None,
            factor_us: None,
            steps: m.run.map(|r| r.steps),
            rhs_evals: m.run.map(|r| r.rhs_evals),
            completed: m.run.map(|r| r.completed),
            machine: machine.to_string(),
            cores,
            git_rev: git_rev.to_string(),
        }
    }

    /// Whether this is a fitted exponent.
    pub fn is_fit(&self) -> bool {
        self.kind == FIT
    }
}

/// One fit row per (scheme, quantity) of the measured rows among `rows` with at least two
/// distinct N: the exponent of the medians ([`fit_power_law`]), in first-appearance order.
pub fn fit_rows(rows: &[DofCostRow]) -> Vec<DofCostRow> {
    let measured: Vec<&DofCostRow> = rows.iter().filter(|r| r.kind == MEASURED).collect();
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for r in &measured {
        let key = (r.scheme.as_str(), r.quantity.as_str());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .filter_map(|(scheme, quantity)| {
            let members: Vec<&&DofCostRow> = measured
                .iter()
                .filter(|r| r.scheme == scheme && r.quantity == quantity)
                .collect();
            let points: Vec<(f64, f64)> = members
                .iter()
                .filter_map(|r| Some((r.n? as f64, r.median_us?)))
                .collect();
            let fit = fit_power_law(&points)?;
            let first = members[0];
            Some(DofCostRow {
                kind: FIT.to_string(),
                n: None,
                nx: None,
                n_eq: None,
                n_in: None,
                median_us: None,
                p95_us: None,
                samples: fit.points,
                exponent: Some(fit.k),
                factor_us: Some(fit.c),
                steps: None,
                rhs_evals: None,
                completed: None,
                ..(*first).clone()
            })
        })
        .collect()
}

/// The rows of a measurement: every measured row, then the fits.
pub fn rows(
    measurements: &[Measurement],
    machine: &str,
    cores: usize,
    git_rev: &str,
) -> Vec<DofCostRow> {
    let mut rows: Vec<DofCostRow> = measurements
        .iter()
        .map(|m| DofCostRow::measured(m, machine, cores, git_rev))
        .collect();
    let fits = fit_rows(&rows);
    rows.extend(fits);
    rows
}

/// Writes `results_dir/dof-cost.csv` (atomically, replacing the file) and returns its path.
pub fn write(results_dir: &Path, rows: &[DofCostRow]) -> Result<PathBuf, String> {
    let path = results_dir.join(FILE);
    let bytes = crate::table::to_csv(rows).map_err(|e| e.to_string())?;
    crate::runs::write_atomic(&path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

/// Reads `results_dir/dof-cost.csv`; an absent file is no rows.
pub fn read(results_dir: &Path) -> Result<Vec<DofCostRow>, String> {
    let path = results_dir.join(FILE);
    if !path.exists() {
        return Ok(Vec::new());
    }
    crate::table::read(&path).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use schemes::qp::QpDims;
    use simulation::dof_cost::{Quantity, RunCounts, SchemeKind, Summary};

    fn measurement(n: usize, quantity: Quantity, median_us: f64) -> Measurement {
        Measurement {
            scheme: SchemeKind::Jia2019,
            scheme_name: "VLTCO".into(),
            network: "LVI-PDNN".into(),
            n,
            dims: QpDims {
                nx: n + 1,
                n_eq: 3,
                n_in: 2 * n,
            },
            quantity,
            summary: Summary {
                median_us,
                p95_us: 1.25 * median_us,
                samples: 150,
            },
            run: quantity.is_run().then_some(RunCounts {
                steps: 100 * n,
                rhs_evals: 700 * n,
                completed: true,
            }),
        }
    }

    #[test]
    fn the_csv_round_trips_with_its_fits() {
        let mut ms = Vec::new();
        for n in [3, 6, 12, 30] {
            ms.push(measurement(
                n,
                Quantity::ExactClarabel,
                2.0 * (n * n) as f64,
            ));
            ms.push(measurement(n, Quantity::RunExact, 1e3 * n as f64));
        }
        let rows = rows(&ms, "Test CPU @ 1 GHz", 2, "abc123");
        assert_eq!(rows.len(), 8 + 2);
        let fit = rows
            .iter()
            .find(|r| r.is_fit() && r.quantity == "exact-clarabel")
            .unwrap();
        assert!((fit.exponent.unwrap() - 2.0).abs() < 1e-12, "{fit:?}");
        assert_eq!((fit.samples, fit.n, fit.median_us), (4, None, None));
        let run = rows.iter().find(|r| r.quantity == "run-exact").unwrap();
        assert_eq!((run.steps, run.completed), (Some(300), Some(true)));

        let bytes = crate::table::to_csv(&rows).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(
            text.starts_with("scheme,scheme_name,network,quantity,kind,n,"),
            "{text}"
        );
        let back: Vec<DofCostRow> = crate::table::from_reader(bytes.as_slice()).unwrap();
        assert_eq!(back, rows);

        let dir = std::env::temp_dir().join(format!("driftbench-dof-cost-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        assert!(read(&dir).unwrap().is_empty());
        write(&dir, &rows).unwrap();
        assert_eq!(read(&dir).unwrap(), rows);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
