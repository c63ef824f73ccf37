//! The names of the paths an experiment file may give (`path = { name = ... }`): below both the
//! paths' specification ([`super::PathSpec`]) and their errors ([`super::PathError`],
//! which list them when a name is unknown).

/// Every path name a [`super::PathSpec`] may give (`schemes::paths::build_path` builds each).
pub const PATH_NAMES: &[&str] = &[
    "four-leaf-clover",
    "five-point-star",
    "star-lines",
    "ping",
    "dai",
    "butterfly",
    "butterfly-as-printed",
    "cardioid",
    "triangle",
    "circle",
];
