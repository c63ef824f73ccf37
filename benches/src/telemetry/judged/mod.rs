//! What the suite's measurements of itself say, computed here so that [`super::page`] only
//! formats it: sums of times, shares, floors, ratios and the verdicts against the targets.
//!
//! - [`clock`]: the newcomer's clock (`phases.csv`, `clock.csv`), and [`targets`]: the clock
//!   against its targets;
//! - [`explain_phase`]: where the reproduction's explain phase spends its time (the
//!   reproduction's `results/ladder.csv` rung times against `phases.csv`);
//! - [`build`]: where a cold build spends its time (`build-profile.csv`): its CPU bound, its
//!   critical path, its costliest units;
//! - [`profile`]: what a paper's sampling profile says (`profile.csv`);
//! - [`speedup`]: every paper's runs against an earlier revision (`speedup.csv`).

pub mod build;
pub mod clock;
pub mod explain_phase;
pub mod profile;
pub mod speedup;
pub mod targets;
