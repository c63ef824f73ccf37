//! The kinds of network ([`NetworkKind`]): the identity of a [`crate::SolverSpec`]
//! variant, as experiment files name it (`kind = "lvi-pdnn"`) and as `runs.csv` stores it in
//! `solver_kind`. Code that treats one kind apart compares this enum, never a label or an id
//! prefix.

use std::fmt;
use std::str::FromStr;

/// A kind of network (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum NetworkKind {
    /// jia2019 (2.23).
    LviPdnn,
    /// zhong2021's simplified LVI-PDNN.
    SLviPdnn,
    /// zhong2021 (2.19)-(2.30): the varying-parameter network with a penalty function.
    VpRnnPf,
    /// zhang2018's fixed-parameter convergence-differential network.
    FpCdnn,
    /// zhang2018's varying-parameter convergence-differential network.
    VpCdnn,
    /// kong2019 (14): the finite-time network.
    FiniteTime,
    /// kong2019 (22): the zeroing network.
    Znn,
    /// The group code's zeroing network.
    GroupZnn,
    /// A zeroing network given as a point of the vocabulary (`crate::zeroing`).
    Zeroing,
    /// A projection-family network given as a point of the vocabulary (`crate::projection`).
    Projection,
}

impl NetworkKind {
    /// Every kind, in the order of [`crate::SolverSpec`]'s variants.
    pub const ALL: [NetworkKind; 10] = [
        NetworkKind::LviPdnn,
        NetworkKind::SLviPdnn,
        NetworkKind::VpRnnPf,
        NetworkKind::FpCdnn,
        NetworkKind::VpCdnn,
        NetworkKind::FiniteTime,
        NetworkKind::Znn,
        NetworkKind::GroupZnn,
        NetworkKind::Zeroing,
        NetworkKind::Projection,
    ];

    /// The id experiment files and `runs.csv` use.
    pub fn id(self) -> &'static str {
        match self {
            NetworkKind::LviPdnn => "lvi-pdnn",
            NetworkKind::SLviPdnn => "s-lvi-pdnn",
            NetworkKind::VpRnnPf => "vp-rnn-pf",
            NetworkKind::FpCdnn => "fp-cdnn",
            NetworkKind::VpCdnn => "vp-cdnn",
            NetworkKind::FiniteTime => "finite-time",
            NetworkKind::Znn => "znn",
            NetworkKind::GroupZnn => "group-znn",
            NetworkKind::Zeroing => "zeroing",
            NetworkKind::Projection => "projection",
        }
    }
}

impl fmt::Display for NetworkKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

/// A `solver_kind` that is not a network's (the exact column, a numerical method, a scored
/// trajectory, or an unknown id).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{} is not a network kind", crate::shown(.0))]
pub struct NotANetwork(pub String);

impl FromStr for NetworkKind {
    type Err = NotANetwork;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        NetworkKind::ALL
            .into_iter()
            .find(|k| k.id() == s)
            .ok_or_else(|| NotANetwork(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_read_back_and_nothing_else_reads() {
        for k in NetworkKind::ALL {
            assert_eq!(k.id().parse::<NetworkKind>(), Ok(k));
        }
        for other in ["exact", "94lvi", "trajectory", "VP-RNN-PF", ""] {
            assert!(other.parse::<NetworkKind>().is_err(), "{other}");
        }
    }
}
