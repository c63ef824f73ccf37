//! The kind of solver behind a row ([`SolverKind`]): the `solver_kind` column of
//! `results/runs.csv` and `results/leaderboard.csv`. It is an identity, not a label: code that
//! treats one kind apart matches this enum, never the text it is stored as.
//!
//! The text is the kind's id: `exact` (the QP's optimum in the loop), a network's kind as
//! experiment files name it ([`NetworkKind::id`]: `lvi-pdnn`, ...), a registered QP solver's id
//! (`settings::qp_solver`: `94lvi`, ..., `active-set`, `clarabel`, an outside solver's), `trajectory` (a trajectory made elsewhere and
//! scored) or `python` (a network written in Python and run through the Python package).

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use settings::qp_solver::{QpSolverInfo, QpSolverKey};
use settings::NetworkKind;
use std::fmt;
use std::str::FromStr;

/// What kind of solver a row's run used (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SolverKind {
    /// The QP's optimum in the loop (the exact column).
    Exact,
    /// A recurrent network of one of the papers.
    Network(NetworkKind),
    /// A registered QP solver (robio2018's numerical methods, the active set, Clarabel, an
    /// outside one), solving the QP at every instant of a fixed-step loop.
    Numerical(QpSolverKey),
    /// A trajectory made elsewhere and scored (`reproduce score`, `driftbench.score`).
    Trajectory,
    /// A network written in Python, run by the Python package.
    Python,
}

impl SolverKind {
    /// The id `runs.csv` stores (module docs).
    pub fn id(self) -> &'static str {
        match self {
            SolverKind::Exact => "exact",
            SolverKind::Network(k) => k.id(),
            SolverKind::Numerical(m) => m.id(),
            SolverKind::Trajectory => "trajectory",
            SolverKind::Python => "python",
        }
    }

    /// The network's kind, for a network's row.
    pub fn network(self) -> Option<NetworkKind> {
        match self {
            SolverKind::Network(k) => Some(k),
            _ => None,
        }
    }

    /// Every kind, networks and QP solvers in their registries' orders.
    pub fn all() -> impl Iterator<Item = SolverKind> {
        [SolverKind::Exact]
            .into_iter()
            .chain(NetworkKind::ALL.into_iter().map(SolverKind::Network))
            .chain(
                settings::qp_solver::all()
                    .into_iter()
                    .map(|i| SolverKind::Numerical(QpSolverInfo::key(i))),
            )
            .chain([SolverKind::Trajectory, SolverKind::Python])
    }
}

impl fmt::Display for SolverKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

/// A `solver_kind` that names no kind.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown solver kind {} (known: {known})", settings::shown(given))]
pub struct UnknownSolverKind {
    /// The text read.
    pub given: String,
    /// The valid ids, comma-separated.
    pub known: String,
}

impl FromStr for SolverKind {
    type Err = UnknownSolverKind;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        SolverKind::all()
            .find(|k| k.id() == s)
            .ok_or_else(|| UnknownSolverKind {
                given: s.to_string(),
                known: SolverKind::all()
                    .map(SolverKind::id)
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}

impl Serialize for SolverKind {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.id())
    }
}

impl<'de> Deserialize<'de> for SolverKind {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = std::borrow::Cow::<str>::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_reads_back_and_ids_are_unique() {
        let ids: Vec<&str> = SolverKind::all().map(SolverKind::id).collect();
        let mut sorted = ids.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), ids.len(), "{ids:?}");
        for k in SolverKind::all() {
            assert_eq!(k.id().parse::<SolverKind>(), Ok(k));
        }
        for other in ["", "Exact", "LVI-PDNN", "94LVI", "traject"] {
            let e = other.parse::<SolverKind>().unwrap_err();
            assert!(e.to_string().contains("known: exact, lvi-pdnn"), "{e}");
        }
    }

    fn lvi94() -> SolverKind {
        SolverKind::Numerical(settings::qp_solver::lookup("94lvi").unwrap().key())
    }

    #[test]
    fn csv_round_trip_stores_the_id() {
        #[derive(Serialize, Deserialize, PartialEq, Debug)]
        struct Row {
            solver_kind: SolverKind,
        }
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(Row {
            solver_kind: lvi94(),
        })
        .unwrap();
        let text = String::from_utf8(w.into_inner().unwrap()).unwrap();
        assert_eq!(text, "solver_kind\n94lvi\n");
        let back: Row = csv::Reader::from_reader(text.as_bytes())
            .deserialize()
            .next()
            .unwrap()
            .unwrap();
        assert_eq!(back.solver_kind, lvi94());
        assert!(csv::Reader::from_reader("solver_kind\nnope\n".as_bytes())
            .deserialize::<Row>()
            .next()
            .unwrap()
            .is_err());
    }
}
