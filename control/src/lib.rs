//! The controller's view of the four papers' redundancy-resolution schemes (issue 19).
//!
//! Every run of the rest of the suite is continuous time and one cycle, integrated by a
//! variable-step ODE solver, as the papers simulate. A robot runs its redundancy resolution as a
//! discrete loop at a fixed rate and repeats its task. Here:
//!
//! - [`run_loop`] (module `control_loop`): a scheme run at a fixed control period h (default 1 ms), the command
//!   held over each tick and the arm integrated exactly between ticks (`arm`), with the
//!   per-tick solver (a [`Method`], called through one interface: [`TickSolver`]) either a
//!   network stepped in discrete time ([`Discretisation`]: forward Euler; for the zeroing networks also
//!   the Taylor-type discrete-time ZNN) or any QP solver of the one seam (`qp::QpSolver`, from
//!   the registry: E47, 94LVI, the hot-started active set, Clarabel, OSQP, or one registered
//!   from outside), a tick solver with no adapter; latency per tick (`latency`),
//!   tracking error, |x - x*| and drift; with [`Rounding::OneUlp`] the same run with its joint
//!   angles moved by one ulp after every tick (`rounding`: the rounding-noise probe);
//! - `stability`: each network's largest stable step, from the spectrum of its Jacobian
//!   (forward Euler is stable iff |1 + s lambda| <= 1 for every eigenvalue lambda), beside the
//!   papers' gains;
//! - zhong2021's claim that the networks are more efficient than E47 and 94LVI: its check runs,
//!   measured in operation counts ([`records::control::ClaimCheck`]; crate `analysis` decides
//!   the claim);
//! - `trend`: the drift after each of K cycles and its trend, at the control period and in
//!   continuous time (`continuous`, the exact column as the papers integrate);
//! - [`reproduce()`]: the entry point that runs all of it and writes `results/control*.csv`,
//!   `results/cycles.csv` (the rows: [`records::control`]).
//!
//! The standard task set and the budget of its runs are declared in
//! `experiments/control/tasks.toml`; the orchestrator reads it (`catalog::load_task_set`) and hands
//! it over as data (`spec::TaskSet`), with every run of the experiment files: this
//! crate reads no file.

// Every module is private; what other crates (the orchestrator, the benches) and the tests use
// is re-exported below.
mod arm;
mod continuous;
mod control_loop;
mod error;
mod latency;
mod method;
mod network_tick;
mod noise_floor;
mod reproduce;
mod rounding;
mod stability;
mod task;
mod tick;
mod trend;

pub use control_loop::{run_loop, LoopOutcome, LoopSettings, Observer, Status as LoopStatus};
pub use error::ControlError;
pub use method::{Method, Numerical};
pub use network_tick::Discretisation;
pub use reproduce::{reproduce, Summary};
pub use rounding::Rounding;
pub use task::{load_tasks, with_task, Task, TaskArm};
pub use tick::TickSolver;
