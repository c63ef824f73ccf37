//! A trajectory produced elsewhere (MATLAB, Octave, Python), scored, as a row: its file is
//! read by crate `inputs` (`inputs::trajectory`), `simulation::score_trajectory` scores it, and
//! the score is a row of the `results/runs.csv` schema ([`RunRow`], [`score_row`]): the run's
//! metrics (drift, position error, margins, peaks) and score (`score_*`), with `solver_id` =
//! the trajectory's name (`trajectory` unless named), `solver` = `trajectory <file name>`,
//! `solver_kind` = [`TRAJECTORY_KIND`] and `integrator` = [`TRAJECTORY_KIND`] (nothing was
//! integrated: `rtol` and `atol` are 0, `steps` is the number of samples).

use crate::runs::RunRow;
use spec::ids::SolverId;

/// The `solver_kind` (and `integrator`) of a scored trajectory's row.
pub const TRAJECTORY_KIND: &str = "trajectory";

/// The default solver id of a scored trajectory: [`TRAJECTORY_KIND`].
pub fn trajectory_id() -> SolverId {
    SolverId::new(TRAJECTORY_KIND).expect("\"trajectory\" is a slug")
}

/// The row of a scored trajectory (module docs) from the row of its score's record (the
/// engine's `simulation::run_row`); `source` names the file it came from, `name` (a slug,
/// [`TRAJECTORY_KIND`] by default) is its solver id: the row's key is the task and the name,
/// never the exact column's.
pub fn score_row(mut row: RunRow, source: &str, name: &SolverId) -> RunRow {
    row.solver_id = name.clone();
    row.solver = format!("{TRAJECTORY_KIND} {source}");
    row.solver_kind = spec::SolverKind::Trajectory;
    row.integrator = TRAJECTORY_KIND.to_string();
    row.rtol = 0.0;
    row.atol = 0.0;
    row.max_step = None;
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_trajectory_id_is_the_kind() {
        assert_eq!(trajectory_id(), TRAJECTORY_KIND);
    }
}
