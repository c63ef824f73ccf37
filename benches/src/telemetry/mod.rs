//! The suite's measurements of itself, kept out of the reproduction's `results/` and `report/`:
//! how long a newcomer waits from clone to report, where a build and a run spend their time,
//! and how this revision's runs compare with an earlier one's. None of them is a result of the
//! papers; a reader of the reproduction finds the solvers' cost and the papers' times on the
//! report's Performance page instead.
//!
//! Files (`benches/results/`, each written by a script of `benches/` or by `reproduce run
//! --phases`), their schemas here:
//!
//! - [`clock`]: fresh clones timed from build to tests, per revision (`clock.csv`, by
//!   `benches/clock/clock.sh`);
//! - [`build_profile`]: a cold build, unit by unit (`build-profile.csv`, by
//!   `benches/clock/build_profile.sh`);
//! - `phases.csv`: where one `reproduce run`'s wall time went, phase by phase (its schema is
//!   the writer's, `reproduce::phases`);
//! - [`profile`]: where a paper's reproduction spends its time (`profile.csv`, by
//!   `benches/profile/paper.sh`);
//! - [`profile_active_set`]: where the hot-started active-set solve spends its time
//!   (`profile-active-set.csv`, by `benches/profile/active_set.sh`);
//! - [`speedup`]: every run timed alone under an earlier revision and this one
//!   (`speedup.csv`, by `benches/speedup/papers.sh`);
//! - `sweep-e2e.csv`: a sweep of short runs end to end (its shards, the merge, the page), peak
//!   memory, CPU, wall time and disk per process against the number of runs (its schema is the
//!   script's header, `benches/sweep_e2e/run.sh`; docs/cluster.md reads it);
//! - [`side_by_side`]: the cold release build of `reproduce` at issue 38's baseline and at
//!   another revision, one after the other (`side-by-side/build.csv`, by
//!   `benches/side_by_side/build_and_runs.sh`);
//! - [`throughput`]: one thread's runs per CPU second on a kong2019 ZNN sweep at two revisions,
//!   and where a right-hand side's time goes (`throughput.csv`, `throughput-profile.csv`, by
//!   `benches/throughput/kong2019_sweep.sh`).
//!
//! [`judged`] decides what they say against their targets; [`page`] formats it into
//! `benches/REPORT.md` (`cargo run --release -p driftbench-benches --bin telemetry`).

pub mod build_profile;
pub mod clock;
pub mod judged;
pub mod page;
pub mod profile;
pub mod profile_active_set;
pub mod side_by_side;
pub mod speedup;
pub mod throughput;
