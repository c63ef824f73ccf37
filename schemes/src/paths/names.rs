//! The names of the paths an experiment file may give (`path = { name = ... }`): below both the
//! paths' specification ([`super::spec`], which builds each) and their errors ([`super::error`],
//! which list them when a name is unknown).

/// Every path name [`super::build_path`] accepts.
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
