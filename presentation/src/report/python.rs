//! What the Python package (`python/`) measured, from two result files its scripts write:
//!
//! - `results/leaderboard-python.csv` (`python python/examples/leaderboard.py`): the numpy GNN
//!   ranked with the suite's networks on the standard task set by `driftbench.leaderboard`, in
//!   the schema of `results/leaderboard.csv` — shown in the Leaderboard section as the Python
//!   entry;
//! - `results/python-call-cost.csv` (`python python/bench/call_cost.py`): the cost of a call
//!   into Python per right-hand-side evaluation against the Rust twin's — shown in the
//!   Performance section.
//!
//! Absent files are said so, with the command that produces them.

use super::leaderboard::ranking;
use super::markdown::{Table, MISSING};
use analysis::leaderboard::{LeaderboardRow, STANDARD_SET};
use records::table::{Row, TableError};
use serde::{Deserialize, Serialize};
use store::table::read_if_present;

/// One case of `results/python-call-cost.csv` (definitions: `python/bench/call_cost.py`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CallCostRow {
    pub network: String,
    pub task: String,
    pub twin: String,
    pub repeats: usize,
    pub python_calls: Option<usize>,
    pub us_per_python_call: Option<f64>,
    pub us_per_rhs_python_run: f64,
    pub rhs_evals_python_run: usize,
    pub us_per_rhs_twin_run: Option<f64>,
    pub rhs_evals_twin_run: Option<usize>,
    pub ratio: Option<f64>,
    pub python: String,
    pub numpy: String,
    pub machine: String,
}

impl Row for CallCostRow {}

/// The Python package's result files (absent = empty).
#[derive(Clone, Debug, Default)]
pub struct PythonResults {
    pub leaderboard: Vec<LeaderboardRow>,
    pub call_cost: Vec<CallCostRow>,
}

impl PythonResults {
    /// Reads both files from the results directory.
    pub fn load(results: &std::path::Path) -> Result<Self, TableError> {
        Ok(PythonResults {
            leaderboard: read_if_present(&results.join(store::results_dir::LEADERBOARD_PYTHON))?,
            call_cost: read_if_present(&results.join(store::results_dir::PYTHON_CALL_COST))?,
        })
    }
}

/// `### A Python entry`, for the Leaderboard section.
pub fn leaderboard(rows: &[LeaderboardRow]) -> String {
    let mut out = String::from(
        "### A Python entry: the numpy GNN\n\nThe gradient network written in numpy \
         (`driftbench.networks.Gnn`, the twin of `examples/gnn_clover.rs`) entered through the \
         Python package: `python python/examples/leaderboard.py` runs it on every standard task \
         with `driftbench.leaderboard`, which ranks it with the suite's networks as above \
         (`results/leaderboard-python.csv`, the schema of `results/leaderboard.csv`). Its runs \
         call Python at every right-hand-side evaluation, so its time column is not the \
         algorithm's alone (see Performance).\n\n",
    );
    let standard: Vec<&LeaderboardRow> =
        rows.iter().filter(|r| r.task_set == STANDARD_SET).collect();
    if standard.is_empty() {
        out.push_str(
            "`results/leaderboard-python.csv` is absent or has no standard-set row: run \
             `python python/examples/leaderboard.py` with the package installed \
             (`pip install -v ./python`).\n\n",
        );
    } else {
        out.push_str(&ranking(&standard));
        out.push('\n');
    }
    out
}

/// `### The cost of a Python call`, for the Performance section.
pub fn call_cost(rows: &[CallCostRow]) -> String {
    let mut out = String::from("### The cost of a Python call\n\n");
    let Some(first) = rows.first() else {
        out.push_str(
            "`results/python-call-cost.csv` is absent: `python python/bench/call_cost.py` \
             measures it (with the package installed, `pip install -v ./python`).\n\n",
        );
        return out;
    };
    out.push_str(&format!(
        "A network written in Python is called back at every right-hand-side (RHS) evaluation. \
         Measured by `python python/bench/call_cost.py` (`results/python-call-cost.csv`; Python \
         {}, numpy {}, {}): each case simulated {} times by `driftbench.simulate`, medians. \
         \"Per Python call\" is the run's `python_seconds / python_calls` (the QP converted into \
         numpy arrays, the method, its result read back); \"per RHS\" is the whole simulation \
         per evaluation of the coupled RHS (`sim_s / rhs_evals`: integrator, arm, scheme, \
         network and Jacobians), of the numpy network's run and of its Rust twin's on the same \
         task.\n\n",
        first.python, first.numpy, first.machine, first.repeats
    ));
    let us = |v: Option<f64>| v.map_or_else(|| MISSING.to_string(), |v| format!("{v} µs"));
    let mut t = Table::new([
        "network",
        "task",
        "per Python call",
        "per RHS, Python run",
        "Rust twin",
        "per RHS, twin's run",
        "Python ÷ Rust",
        "RHS evaluations (Python / twin)",
    ]);
    for r in rows {
        t.push([
            r.network.clone(),
            r.task.clone(),
            us(r.us_per_python_call),
            us(Some(r.us_per_rhs_python_run)),
            if r.twin.is_empty() {
                MISSING.to_string()
            } else {
                r.twin.clone()
            },
            us(r.us_per_rhs_twin_run),
            r.ratio
                .map_or_else(|| MISSING.to_string(), |v| format!("{v}")),
            format!(
                "{} / {}",
                r.rhs_evals_python_run,
                r.rhs_evals_twin_run
                    .map_or_else(|| MISSING.to_string(), |v| v.to_string())
            ),
        ]);
    }
    out.push_str(&t.render());
    out.push('\n');
    out
}
