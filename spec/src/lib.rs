//! driftbench's runs as data: what the experiment files say and the engine builds from.
//!
//! - [`scheme`]: a scheme and its parameters by the papers' names ([`scheme::SchemeSpec`]),
//!   its checks, and the list of terms each preset expands to;
//! - [`terms`]: a composed scheme's terms ([`terms::ComposedSpec`], [`terms::TermSpec`]);
//! - [`path`]: a desired path by name, duration, size and pose ([`path::PathSpec`]), the path
//!   names with their default sizes and durations, and the checks of its fields;
//! - [`rmp`]: the three readings of the repetitive-motion term's linear coefficient.
//!
//! Crate `catalog` reads experiment files into these types; the engine (crate `schemes`, then
//! `simulation`) builds its runtime objects from them. The crate links no engine and no file
//! format, so that the experiment files' reader and the results' schemas can state a scheme or
//! a path without compiling kinematics.

#![deny(missing_docs)]

pub mod path;
pub mod rmp;
pub mod scheme;
pub mod terms;
