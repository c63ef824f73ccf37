//! `results/dof-cost.csv`: the cost against the number of joints measured by the cost harness
//! (`reproduce::cost`, `reproduce cost`), one [`DofCostRow`] per (scheme, N, quantity, backend)
//! measured, and one per (scheme, quantity, backend) with the fitted growth exponent k of
//! median cost ~ c N^k (fitted by crate `analysis`, `fits`); and the plain data the harness
//! hands over ([`Measurement`], [`Quantity`], [`Summary`], [`RunCounts`], [`SchemeKind`]).
//!
//! Every row carries the machine it was measured on (CPU model and cores, read from
//! `/proc/cpuinfo` at measurement time) and the code revision: times are comparable within one
//! file, not across machines. The file is written whole by `reproduce cost` (a new
//! measurement replaces the old one; two machines' numbers are never mixed).

use crate::percentile::percentile;
use crate::table::{Row, TableError};
use serde::{Deserialize, Serialize};

/// The file name inside `results/`.
pub const FILE: &str = "dof-cost.csv";

/// The joint counts of the n-link arms the cost harness sweeps with both schemes (jia2019's
/// VLTCO and kong2019's ZNN scheme); past the largest it measures kong2019's alone, at the
/// large sizes.
pub const SWEEP_SIZES: [usize; 8] = [3, 5, 6, 7, 10, 15, 20, 30];
/// What a [`DofCostRow`] holds (the `kind` column).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RowKind {
    /// One measurement: a median over samples at one N.
    Measured,
    /// A fitted growth exponent over the measured rows of one (scheme, quantity, backend).
    Fit,
}
/// [`DofCostRow::backend`] of nalgebra's dense LU (`solvers::Backend::Nalgebra`'s id, which the
/// cost harness writes; its tests check the two agree): the backend of every quantity.
pub const NALGEBRA: &str = "nalgebra";
/// [`DofCostRow::backend`] of faer's dense LU (`solvers::Backend::Faer`'s id).
pub const FAER: &str = "faer";

/// The schemes measured, by their scheme kind (`spec::scheme`'s `kind` tag).
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
    /// Both schemes, in the file's order.
    pub const ALL: [SchemeKind; 2] = [SchemeKind::Vltco, SchemeKind::ZnnRmp];

    /// The scheme's id in dof-cost.csv: its canonical `kind` tag (`vltco`, `znn-rmp`).
    /// Files written before the kinds were renamed carry the paper-named tags, which
    /// [`from_reader`] maps onto these (`LEGACY_IDS`).
    pub fn id(self) -> &'static str {
        match self {
            SchemeKind::Vltco => "vltco",
            SchemeKind::ZnnRmp => "znn-rmp",
        }
    }
}

/// What is timed (the harness's module docs say how); stored as its [`Quantity::id`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
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
    /// Every quantity, in the file's order.
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

    /// Whether it is a whole run (one sample per run) rather than one call at one state.
    pub fn is_run(self) -> bool {
        matches!(self, Quantity::RunExact | Quantity::RunNetwork)
    }
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.id())
    }
}

/// Median and 95th percentile of a set of samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// Median of the samples (us).
    pub median_us: f64,
    /// 95th percentile of the samples (us).
    pub p95_us: f64,
    /// Number of samples.
    pub samples: usize,
}

impl Summary {
    /// The summary of `samples_us` ([`crate::percentile()`]; `None` when empty or
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

/// One measured quantity of one (scheme, N) case on one backend.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The scheme measured.
    pub scheme: SchemeKind,
    /// The scheme's own name (`VLTCO`, `ZNN`).
    pub scheme_name: String,
    /// The network's display name (`LVI-PDNN`).
    pub network: String,
    /// Joints N of the n-link arm.
    pub n: usize,
    /// The QP's sizes: variables, equality rows, inequality rows.
    pub nx: usize,
    /// Equality rows of the QP.
    pub n_eq: usize,
    /// Inequality rows of the QP.
    pub n_in: usize,
    /// What is timed.
    pub quantity: Quantity,
    /// The dense LU backend's id ([`DofCostRow::backend`]).
    pub backend: String,
    /// The timings' median and 95th percentile.
    pub summary: Summary,
    /// For runs: accepted steps, RHS evaluations and whether the run completed (of the first
    /// repetition; every repetition is the same deterministic run).
    pub run: Option<RunCounts>,
}

/// Counts of a whole run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunCounts {
    /// Accepted integrator steps.
    pub steps: usize,
    /// Evaluations of the ODE's right-hand side.
    pub rhs_evals: usize,
    /// Whether the run reached the path's end.
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
    /// What is timed (its id, e.g. `network-lu`).
    pub quantity: Quantity,
    /// The dense LU backend ([`NALGEBRA`], [`FAER`]: `solvers::Backend::id`); nalgebra for the
    /// quantities computed on nalgebra alone.
    pub backend: String,
    /// Whether the row is a measurement or a fitted exponent.
    pub kind: RowKind,
    /// Joints (measured rows).
    pub n: Option<usize>,
    /// QP sizes (measured rows).
    pub nx: Option<usize>,
    /// Equality rows of the QP (measured rows).
    pub n_eq: Option<usize>,
    /// Inequality rows of the QP (measured rows).
    pub n_in: Option<usize>,
    /// Median and 95th percentile (us): per call, or per whole run for `run-*`.
    pub median_us: Option<f64>,
    /// 95th percentile (us), as `median_us`.
    pub p95_us: Option<f64>,
    /// Samples behind the median (measured rows) or points fitted (fit rows).
    pub samples: usize,
    /// Fit rows: the exponent k and factor c (us) of median ~ c N^k.
    pub exponent: Option<f64>,
    /// The factor c (us) of median ~ c N^k (fit rows).
    pub factor_us: Option<f64>,
    /// `run-*` rows: accepted steps, RHS evaluations and whether the run completed.
    pub steps: Option<usize>,
    /// Evaluations of the ODE's right-hand side (`run-*` rows).
    pub rhs_evals: Option<usize>,
    /// Whether the run reached the path's end (`run-*` rows).
    pub completed: Option<bool>,
    /// CPU model (`/proc/cpuinfo`'s model name) and logical cores available.
    pub machine: String,
    /// Logical cores available.
    pub cores: usize,
    /// The code revision that measured it (as `runs.csv`'s `git_rev`).
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
            quantity: m.quantity,
            backend: m.backend.clone(),
            kind: RowKind::Measured,
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
        self.kind == RowKind::Fit
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
        if r.kind == RowKind::Measured
            && r.quantity == quantity
            && !out.contains(&r.backend.as_str())
        {
            out.push(&r.backend);
        }
    }
    out.sort_by_key(|b| *b != NALGEBRA);
    out
}

/// Scheme ids of dof-cost.csv files written before the scheme kinds were named for what they
/// are, each with the [`SchemeKind`] it was: `(old id, kind)`.
const LEGACY_IDS: [(&str, SchemeKind); 2] = [
    ("jia2019", SchemeKind::Vltco),
    ("kong2019-znn", SchemeKind::ZnnRmp),
];

/// The rows of the CSV `input` ([`crate::table::from_reader`]); a legacy scheme id
/// (`LEGACY_IDS`) is read as its kind's id.
pub fn from_reader(input: impl std::io::Read) -> Result<Vec<DofCostRow>, TableError> {
    let mut rows: Vec<DofCostRow> = crate::table::from_reader(input)?;
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

    #[test]
    fn summaries_use_the_workspace_percentile() {
        let sum = Summary::of(&[3.0, 1.0, 2.0, 4.0]).unwrap();
        assert_eq!((sum.median_us, sum.samples), (2.5, 4));
        assert!((sum.p95_us - 3.85).abs() < 1e-12);
        assert!(Summary::of(&[]).is_none());
        assert!(Summary::of(&[1.0, f64::NAN]).is_none());
    }

    #[test]
    fn quantities_are_stored_by_their_ids() {
        #[derive(Serialize, Deserialize)]
        struct Cell {
            quantity: Quantity,
        }
        for q in Quantity::ALL {
            let mut w = csv::Writer::from_writer(Vec::new());
            w.serialize(Cell { quantity: q }).unwrap();
            let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
            assert_eq!(text, format!("quantity\n{}\n", q.id()));
            let back: Cell = csv::Reader::from_reader(text.as_bytes())
                .deserialize()
                .next()
                .unwrap()
                .unwrap();
            assert_eq!(back.quantity, q);
        }
        let fit: Result<Cell, _> = csv::Reader::from_reader("quantity\nfit\n".as_bytes())
            .deserialize()
            .next()
            .unwrap();
        assert!(fit.is_err());
    }
}
