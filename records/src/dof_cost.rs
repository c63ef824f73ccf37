//! `results/dof-cost.csv`: the cost against the number of joints measured by the cost harness
//! (crate `cost`, `reproduce cost`), one [`DofCostRow`] per (scheme, N, quantity, backend)
//! measured, and one per (scheme, quantity, backend) with the fitted growth exponent k of
//! median cost ~ c N^k ([`fit_rows`]); and the plain data the harness hands over
//! ([`Measurement`], [`Quantity`], [`Summary`], [`RunCounts`], [`SchemeKind`], [`fit_power_law`]).
//!
//! Every row carries the machine it was measured on (CPU model and cores, read from
//! `/proc/cpuinfo` at measurement time) and the code revision: times are comparable within one
//! file, not across machines. The file is written whole by `reproduce cost` (a new
//! measurement replaces the old one; two machines' numbers are never mixed).

use crate::error::{DofCostError, IoAction, IoError};
use crate::percentile::percentile;
use crate::table::Row;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The file name inside `results/`.
pub const FILE: &str = "dof-cost.csv";
/// [`DofCostRow::kind`] of a measured row.
pub const MEASURED: &str = "measured";
/// [`DofCostRow::kind`] of a fitted exponent.
pub const FIT: &str = "fit";
/// [`DofCostRow::backend`] of nalgebra's dense LU (`solvers::Backend::Nalgebra`'s id, which the
/// cost harness writes; its tests check the two agree): the backend of every quantity.
pub const NALGEBRA: &str = "nalgebra";
/// [`DofCostRow::backend`] of faer's dense LU (`solvers::Backend::Faer`'s id).
pub const FAER: &str = "faer";

/// The schemes measured, by their scheme kind (`schemes::spec`'s `kind` tag).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SchemeKind {
    /// jia2019 VLTCO (phi = 0.2, tau = 0.4, kappa = 20, Lambda = 20) on a four-leaf clover:
    /// nx = N + 1, n_eq = 3, n_in = 2N, bounds on every variable.
    Vltco,
    /// kong2019 ZNN scheme (eq. 22, mu = 1, k_p = 1) on a circle: nx = N, n_eq = 3, no
    /// inequalities.
    ZnnRmp,
}

impl SchemeKind {
    pub const ALL: [SchemeKind; 2] = [SchemeKind::Vltco, SchemeKind::ZnnRmp];

    /// The scheme's id in dof-cost.csv: its canonical `kind` tag (`vltco`, `znn-rmp`).
    /// Files written before the kinds were renamed carry the paper-named tags, which
    /// [`read`] maps onto these (`LEGACY_IDS`).
    pub fn id(self) -> &'static str {
        match self {
            SchemeKind::Vltco => "vltco",
            SchemeKind::ZnnRmp => "znn-rmp",
        }
    }
}

/// What is timed (the harness's module docs say how).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Quantity {
    /// The scheme's QP assembly at a state.
    SchemeBuild,
    /// One right-hand side of the network.
    NetworkRhs,
    /// One analytic Jacobian of the network.
    NetworkJacobian,
    /// The LU factorisation of that Jacobian (what an implicit integrator's Newton matrix
    /// costs to factorise: same size), per backend.
    NetworkLu,
    /// The certified active-set solver, hot-started.
    ExactActiveSet,
    /// One Clarabel solve.
    ExactClarabel,
    /// One dense LU solve of the equality-constrained KKT system, per backend.
    KktFloor,
    /// A whole exact run.
    RunExact,
    /// A whole network run.
    RunNetwork,
}

impl Quantity {
    pub const ALL: [Quantity; 9] = [
        Quantity::SchemeBuild,
        Quantity::NetworkRhs,
        Quantity::NetworkJacobian,
        Quantity::NetworkLu,
        Quantity::ExactActiveSet,
        Quantity::ExactClarabel,
        Quantity::KktFloor,
        Quantity::RunExact,
        Quantity::RunNetwork,
    ];

    /// The name in `results/dof-cost.csv` and in the criterion ids.
    pub fn id(self) -> &'static str {
        match self {
            Quantity::SchemeBuild => "scheme-build",
            Quantity::NetworkRhs => "network-rhs",
            Quantity::NetworkJacobian => "network-jacobian",
            Quantity::NetworkLu => "network-lu",
            Quantity::ExactActiveSet => "exact-active-set",
            Quantity::ExactClarabel => "exact-clarabel",
            Quantity::KktFloor => "kkt-floor",
            Quantity::RunExact => "run-exact",
            Quantity::RunNetwork => "run-network",
        }
    }

    /// The quantity named `id` ([`Self::id`]).
    pub fn from_id(id: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|q| q.id() == id)
    }

    /// Whether it is a whole run (one sample per run) rather than one call at one state.
    pub fn is_run(self) -> bool {
        matches!(self, Quantity::RunExact | Quantity::RunNetwork)
    }
}

/// Median and 95th percentile of a set of samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub median_us: f64,
    pub p95_us: f64,
    pub samples: usize,
}

impl Summary {
    /// The summary of `samples_us` ([`crate::percentile::percentile`]; `None` when empty or
    /// not finite).
    pub fn of(samples_us: &[f64]) -> Option<Self> {
        if samples_us.is_empty() || samples_us.iter().any(|v| !v.is_finite()) {
            return None;
        }
        Some(Summary {
            median_us: percentile(samples_us, 0.5),
            p95_us: percentile(samples_us, 0.95),
            samples: samples_us.len(),
        })
    }
}

/// A least-squares fit of cost = c N^k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerFit {
    /// The growth exponent k.
    pub k: f64,
    /// The factor c (the cost's unit).
    pub c: f64,
    /// Points fitted.
    pub points: usize,
}

/// Fits cost = c N^k to `(N, cost)` points by least squares on the logarithms:
/// with u = ln N and v = ln cost, the line v = ln c + k u minimising sum (v_i - ln c - k u_i)^2
/// has
///
/// ```text
/// k = sum (u_i - u_mean)(v_i - v_mean) / sum (u_i - u_mean)^2,   ln c = v_mean - k u_mean.
/// ```
///
/// So a relative error in each cost weighs the same at every N (the measurements' noise is
/// relative). Points with a non-positive or non-finite N or cost are left out; `None` with fewer
/// than two distinct N left.
pub fn fit_power_law(points: &[(f64, f64)]) -> Option<PowerFit> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, y)| n.is_finite() && y.is_finite() && *n > 0.0 && *y > 0.0)
        .map(|(n, y)| (n.ln(), y.ln()))
        .collect();
    let m = logs.len() as f64;
    let u_mean = logs.iter().map(|p| p.0).sum::<f64>() / m;
    let v_mean = logs.iter().map(|p| p.1).sum::<f64>() / m;
    let suu: f64 = logs.iter().map(|(u, _)| (u - u_mean).powi(2)).sum();
    let suv: f64 = logs.iter().map(|(u, v)| (u - u_mean) * (v - v_mean)).sum();
    if logs.len() < 2 || suu <= 0.0 {
        return None;
    }
    let k = suv / suu;
    Some(PowerFit {
        k,
        c: (v_mean - k * u_mean).exp(),
        points: logs.len(),
    })
}

/// One measured quantity of one (scheme, N) case on one backend.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    pub scheme: SchemeKind,
    /// The scheme's own name (`VLTCO`, `ZNN`).
    pub scheme_name: String,
    /// The network's display name (`LVI-PDNN`).
    pub network: String,
    pub n: usize,
    /// The QP's sizes: variables, equality rows, inequality rows.
    pub nx: usize,
    pub n_eq: usize,
    pub n_in: usize,
    pub quantity: Quantity,
    /// The dense LU backend's id ([`DofCostRow::backend`]).
    pub backend: String,
    pub summary: Summary,
    /// For runs: accepted steps, RHS evaluations and whether the run completed (of the first
    /// repetition; every repetition is the same deterministic run).
    pub run: Option<RunCounts>,
}

/// Counts of a whole run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunCounts {
    pub steps: usize,
    pub rhs_evals: usize,
    pub completed: bool,
}

/// One row of `results/dof-cost.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DofCostRow {
    /// The paper whose scheme was run (`jia2019`, `kong2019`).
    pub scheme: String,
    /// The scheme's own name (`VLTCO`, `ZNN (eq. 22)`).
    pub scheme_name: String,
    /// The network of the network quantities (`LVI-PDNN`).
    pub network: String,
    /// `scheme-build`, `network-rhs`, ... ([`Quantity::id`]).
    pub quantity: String,
    /// The dense LU backend ([`NALGEBRA`], [`FAER`]: `solvers::Backend::id`); nalgebra for the
    /// quantities computed on nalgebra alone.
    pub backend: String,
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
            backend: m.backend.clone(),
            kind: MEASURED.to_string(),
            n: Some(m.n),
            nx: Some(m.nx),
            n_eq: Some(m.n_eq),
            n_in: Some(m.n_in),
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

/// The backends `quantity` was measured on among `rows`: [`NALGEBRA`] first (every quantity's
/// backend), then the others in order of first appearance. Which backends a quantity is
/// measured on is the cost harness's choice; what was measured is in the file.
pub fn backends<'a>(
    rows: impl IntoIterator<Item = &'a DofCostRow>,
    quantity: Quantity,
) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for r in rows {
        if r.kind == MEASURED && r.quantity == quantity.id() && !out.contains(&r.backend.as_str()) {
            out.push(&r.backend);
        }
    }
    out.sort_by_key(|b| *b != NALGEBRA);
    out
}

/// One fit row per (scheme, quantity, backend) of the measured rows among `rows` with at least
/// two distinct N: the exponent of the medians ([`fit_power_law`]), in first-appearance order.
pub fn fit_rows(rows: &[DofCostRow]) -> Vec<DofCostRow> {
    let measured: Vec<&DofCostRow> = rows.iter().filter(|r| r.kind == MEASURED).collect();
    let mut keys: Vec<(&str, &str, &str)> = Vec::new();
    for r in &measured {
        let key = (r.scheme.as_str(), r.quantity.as_str(), r.backend.as_str());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .filter_map(|(scheme, quantity, backend)| {
            let members: Vec<&&DofCostRow> = measured
                .iter()
                .filter(|r| r.scheme == scheme && r.quantity == quantity && r.backend == backend)
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

/// Where faer's dense LU overtakes nalgebra's for one (scheme, quantity).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossover {
    /// The smallest measured N from which faer's median is below nalgebra's at this and every
    /// larger N measured on both (`None`: faer is slower at the largest N).
    pub n: Option<usize>,
    /// The size of the matrix factorised at that N: nx + n_eq for the KKT floor, the
    /// primal-dual network state nx + n_eq + n_in for the network Jacobian (LVI-PDNN's).
    pub lu_size: Option<usize>,
    /// nalgebra's median over faer's at the largest N measured on both, and that N.
    pub speedup_at_largest: f64,
    pub largest_n: usize,
}

/// The [`Crossover`] of `quantity` for `scheme` among the measured rows: `None` when no N was
/// measured on both backends.
pub fn crossover(rows: &[DofCostRow], scheme: &str, quantity: Quantity) -> Option<Crossover> {
    let median = |backend: &str, n: usize| {
        rows.iter()
            .find(|r| {
                r.kind == MEASURED
                    && r.scheme == scheme
                    && r.quantity == quantity.id()
                    && r.backend == backend
                    && r.n == Some(n)
            })
            .and_then(|r| Some((r.median_us?, r)))
    };
    let mut ns: Vec<usize> = rows
        .iter()
        .filter(|r| r.kind == MEASURED && r.scheme == scheme && r.quantity == quantity.id())
        .filter_map(|r| r.n)
        .collect();
    ns.sort_unstable();
    ns.dedup();
    // (N, nalgebra / faer, LU size) where both were measured, by increasing N.
    let both: Vec<(usize, f64, Option<usize>)> = ns
        .into_iter()
        .filter_map(|n| {
            let (nalgebra, row) = median(NALGEBRA, n)?;
            let (faer, _) = median(FAER, n)?;
            let kkt = row.nx.zip(row.n_eq).map(|(a, b)| a + b);
            let size = match quantity {
                Quantity::NetworkLu => kkt.zip(row.n_in).map(|(a, c)| a + c),
                _ => kkt,
            };
            Some((n, nalgebra / faer, size))
        })
        .collect();
    let &(largest_n, speedup_at_largest, _) = both.last()?;
    let from = both
        .iter()
        .rposition(|&(_, ratio, _)| ratio <= 1.0)
        .map_or(0, |i| i + 1);
    let first = both.get(from);
    Some(Crossover {
        n: first.map(|c| c.0),
        lu_size: first.and_then(|c| c.2),
        speedup_at_largest,
        largest_n,
    })
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
pub fn write(results_dir: &Path, rows: &[DofCostRow]) -> Result<PathBuf, DofCostError> {
    let path = results_dir.join(FILE);
    let bytes = crate::table::to_csv(rows).map_err(|source| DofCostError::Csv {
        path: path.clone(),
        source,
    })?;
    crate::runs::write_atomic(&path, &bytes).map_err(IoError::at(path.clone(), IoAction::Write))?;
    Ok(path)
}

/// Scheme ids of dof-cost.csv files written before the scheme kinds were named for what they
/// are, each with the [`SchemeKind`] it was: `(old id, kind)`.
const LEGACY_IDS: [(&str, SchemeKind); 2] = [
    ("jia2019", SchemeKind::Vltco),
    ("kong2019-znn", SchemeKind::ZnnRmp),
];

/// Reads `results_dir/dof-cost.csv`; an absent file is no rows. A legacy scheme id
/// (`LEGACY_IDS`) is read as its kind's id.
pub fn read(results_dir: &Path) -> Result<Vec<DofCostRow>, DofCostError> {
    let path = results_dir.join(FILE);
    if !path.exists() {
        return Ok(Vec::new());
    }
    let mut rows: Vec<DofCostRow> = crate::table::read(&path)?;
    for r in &mut rows {
        if let Some((_, kind)) = LEGACY_IDS.iter().find(|(old, _)| *old == r.scheme) {
            r.scheme = kind.id().to_string();
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measurement(n: usize, quantity: Quantity, median_us: f64) -> Measurement {
        on(NALGEBRA, n, quantity, median_us)
    }

    fn on(backend: &str, n: usize, quantity: Quantity, median_us: f64) -> Measurement {
        Measurement {
            backend: backend.to_string(),
            scheme: SchemeKind::Vltco,
            scheme_name: "VLTCO".into(),
            network: "LVI-PDNN".into(),
            n,
            nx: n + 1,
            n_eq: 3,
            n_in: 2 * n,
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
            text.starts_with("scheme,scheme_name,network,quantity,backend,kind,n,"),
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

    #[test]
    fn each_backend_gets_its_own_fit_and_rows_round_trip() {
        let mut ms = Vec::new();
        for n in [3, 30, 100, 200] {
            let n3 = (n * n * n) as f64;
            ms.push(on(NALGEBRA, n, Quantity::KktFloor, 0.01 * n3));
            ms.push(on(FAER, n, Quantity::KktFloor, 5.0 * (n * n) as f64));
        }
        let rows = rows(&ms, "Test CPU", 2, "abc123");
        let fit = |backend: &str| {
            rows.iter()
                .find(|r| r.is_fit() && r.backend == backend)
                .and_then(|r| r.exponent)
                .unwrap()
        };
        assert!((fit("nalgebra") - 3.0).abs() < 1e-12);
        assert!((fit("faer") - 2.0).abs() < 1e-12);
        let back: Vec<DofCostRow> =
            crate::table::from_reader(crate::table::to_csv(&rows).unwrap().as_slice()).unwrap();
        assert_eq!(back, rows);
        assert_eq!(back.iter().filter(|r| r.backend == "faer").count(), 4 + 1);
        assert_eq!(backends(&rows, Quantity::KktFloor), [NALGEBRA, FAER]);
        assert_eq!(
            backends(rows.iter().rev(), Quantity::KktFloor),
            [NALGEBRA, FAER]
        );
        assert!(backends(&rows, Quantity::NetworkRhs).is_empty());
    }

    #[test]
    fn the_fit_recovers_an_exact_power_law() {
        let sizes = [3.0, 5.0, 7.0, 30.0, 100.0, 200.0];
        let points: Vec<(f64, f64)> = sizes.iter().map(|&n| (n, 3.0 * n * n)).collect();
        let fit = fit_power_law(&points).unwrap();
        assert!((fit.k - 2.0).abs() < 1e-12, "{fit:?}");
        assert!((fit.c - 3.0).abs() < 1e-10, "{fit:?}");
        assert_eq!(fit.points, sizes.len());
        // With a deterministic relative noise of up to +-10 %: within 0.1 of the exponent.
        let noisy: Vec<(f64, f64)> = sizes
            .iter()
            .enumerate()
            .map(|(i, &n)| (n, 0.5 * n.powf(1.5) * (1.0 + 0.1 * (i as f64 * 2.3).sin())))
            .collect();
        assert!((fit_power_law(&noisy).unwrap().k - 1.5).abs() < 0.1);
    }

    #[test]
    fn the_fit_needs_two_distinct_positive_points() {
        assert!(fit_power_law(&[]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (3.0, 2.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (6.0, 0.0), (f64::NAN, 1.0)]).is_none());
        let fit = fit_power_law(&[(3.0, 1.0), (6.0, 2.0), (9.0, -1.0)]).unwrap();
        assert_eq!(fit.points, 2);
        assert!((fit.k - 1.0).abs() < 1e-12);
    }

    #[test]
    fn summaries_use_the_workspace_percentile() {
        let sum = Summary::of(&[3.0, 1.0, 2.0, 4.0]).unwrap();
        assert_eq!((sum.median_us, sum.samples), (2.5, 4));
        assert!((sum.p95_us - 3.85).abs() < 1e-12);
        assert!(Summary::of(&[]).is_none());
        assert!(Summary::of(&[1.0, f64::NAN]).is_none());
    }

    #[test]
    fn quantity_ids_round_trip() {
        for q in Quantity::ALL {
            assert_eq!(Quantity::from_id(q.id()), Some(q));
        }
        assert_eq!(Quantity::from_id("fit"), None);
    }

    #[test]
    fn the_crossover_is_where_faer_stays_ahead() {
        // faer slower at 3 and 10, ahead at 30, behind at 50 (noise), ahead from 100 on.
        let mut ms = Vec::new();
        for (n, nalgebra, faer) in [
            (3, 1.0, 2.0),
            (10, 3.0, 4.0),
            (30, 9.0, 8.0),
            (50, 20.0, 21.0),
            (100, 90.0, 30.0),
            (200, 700.0, 100.0),
        ] {
            ms.push(on(NALGEBRA, n, Quantity::KktFloor, nalgebra));
            ms.push(on(FAER, n, Quantity::KktFloor, faer));
        }
        let rows = rows(&ms, "Test CPU", 2, "abc123");
        let c = crossover(&rows, "vltco", Quantity::KktFloor).unwrap();
        assert_eq!((c.n, c.lu_size, c.largest_n), (Some(100), Some(104), 200));
        assert!((c.speedup_at_largest - 7.0).abs() < 1e-12);
        assert!(crossover(&rows, "vltco", Quantity::NetworkLu).is_none());
        let slower: Vec<_> = ms.iter().filter(|m| m.n < 30).cloned().collect();
        let c = crossover(
            &super::rows(&slower, "Test CPU", 2, "abc"),
            "vltco",
            Quantity::KktFloor,
        );
        assert_eq!(c.map(|c| c.n), Some(None));
    }
}
