//! `reproduce list` and `reproduce robots`: what the experiment files describe (each paper's
//! experiments with their runs, by key and by label; with `--shards N`, how many runs each
//! shard gets) and the robots they can name, with the check values of each (tip position and
//! singular values of J at the stated pose).

use crate::error::ReproduceError;
use crate::select::Kept;
use catalog::PaperFile;
use std::fmt::Write as _;
use std::io::Write;

/// Writes to `out` the experiments of `files` that have runs `kept` keeps, each with those
/// runs, under its paper's header (a paper with no run kept is left out, header and all). The
/// runs are counted without being made (from each experiment's plan), and only the kept ones
/// are made, as they are written: listing a sweep of 10^7 runs holds none of them, and
/// listing one shard makes that shard's runs alone. A closed output (`reproduce list |
/// head`) ends the list and is no error; a variant that does not make is.
pub fn list(out: &mut impl Write, files: &[PaperFile], kept: Kept) -> Result<(), ReproduceError> {
    match write(out, files, kept) {
        Ok(()) | Err(Stop::Closed) => Ok(()),
        Err(Stop::Made(e)) => Err(*e),
    }
}

/// Why a list stops early.
enum Stop {
    /// The output is closed.
    Closed,
    /// A run could not be made.
    Made(Box<ReproduceError>),
}

impl From<std::io::Error> for Stop {
    fn from(_: std::io::Error) -> Self {
        Stop::Closed
    }
}

/// [`list`]'s writing.
fn write(out: &mut impl Write, files: &[PaperFile], kept: Kept) -> Result<(), Stop> {
    let mut start = 0;
    for f in files {
        // Per experiment: the index of its first selected run, and how many of its runs are kept.
        let counts: Vec<(usize, usize)> = f
            .experiments
            .iter()
            .map(|e| {
                let first = start;
                let selected = kept.selected_in(f, e);
                start += selected;
                (first, kept.owned_in(first, selected))
            })
            .collect();
        if counts.iter().all(|&(_, n)| n == 0) {
            continue;
        }
        writeln!(out, "{} — {}", f.paper, f.title)?;
        for (i, (e, (first, n))) in f.experiments.iter().zip(counts).enumerate() {
            if n == 0 {
                continue;
            }
            writeln!(
                out,
                "  {:<28} {} on {} (T = {} s), {}: {n} runs",
                e.id, e.robot, e.path.name, e.path.duration, e.paper_output
            )?;
            // The key (ids: what --task, papers/ and the results use), then the labels.
            for j in kept.experiment_runs(f, i, first) {
                let j = j.map_err(|e| Stop::Made(Box::new(e)))?;
                let k = j.key();
                writeln!(
                    out,
                    "      {:<48} {} · {}",
                    format!("{} / {}", k.variant, k.solver),
                    j.variant,
                    j.solver.label()
                )?;
            }
        }
    }
    Ok(())
}

/// How many of `total` selected runs each of `n` shards gets (`list --shards N`).
pub fn shard_plan(total: usize, n: usize) -> String {
    store::shard::plan(total, n)
        .iter()
        .enumerate()
        .map(|(k, c)| format!("shard {}/{n}: {c} runs\n", k + 1))
        .collect()
}

/// Every robot of the registry with its joint count and check values at its stated pose (the
/// n-link family by two of its members); a robot whose file is invalid shows its error instead.
pub fn robots() -> String {
    use robots::{nlink_name, robot_by_name, robot_names};
    use robots::{NLINK_MAX, NLINK_MIN};
    let mut out = String::new();
    for name in robot_names()
        .into_iter()
        .chain([nlink_name(7), nlink_name(200)])
    {
        let robot = match robot_by_name(&name) {
            Ok(robot) => robot,
            Err(e) => {
                let _ = writeln!(out, "{name:<14} invalid: {e}");
                continue;
            }
        };
        let theta = &robot.stated_pose;
        let (p, sv) = robot
            .check_values(theta)
            .expect("the stated pose has the robot's joint count");
        let shown = if theta.len() > 10 {
            format!("[{} angles]", theta.len())
        } else {
            format!("{theta:.4?}")
        };
        let _ = writeln!(
            out,
            "{name:<14} {} joints{}, theta = {shown}\n               f = ({:.6}, {:.6}, {:.6}), sigma(J) = {sv:.6?}",
            robot.dof(),
            if robot.has_dynamics() { ", dynamics" } else { "" },
            p.x,
            p.y,
            p.z,
        );
    }
    let _ = writeln!(
        out,
        "nlink-<n>      the n-link family: any n from {NLINK_MIN} to {NLINK_MAX} joints"
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    use spec::RunSpec;
    use store::shard::{Selection, Shard};
    /// The fixture paper of tests/fixtures/fifth-paper (one experiment, two variants).
    fn fixture() -> (Vec<PaperFile>, Vec<RunSpec>) {
        let dir =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/fifth-paper/experiments");
        let files = crate::experiments::load_dir(&dir).unwrap();
        let jobs = files.iter().flat_map(|f| f.jobs().unwrap()).collect();
        (files, jobs)
    }

    /// The list of every run of `files`, or of one shard's.
    fn text(files: &[PaperFile], shard: Option<Shard>) -> String {
        let mut out = Vec::new();
        let selection = Selection::default();
        let kept = Kept {
            selection: &selection,
            shard,
        };
        list(&mut out, files, kept).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn the_list_names_each_run_by_key_then_label() {
        let (files, jobs) = fixture();
        let text = text(&files, None);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], format!("{} — {}", files[0].paper, files[0].title));
        assert_eq!(
            lines[1],
            format!(
                "  {:<28} katana6m180 on circle (T = 9 s), Table 1: {} runs",
                "demo2026-circle",
                jobs.len()
            )
        );
        assert_eq!(lines.len(), 2 + jobs.len());
        for (line, job) in lines[2..].iter().zip(&jobs) {
            let key = job.key();
            assert!(
                line.trim_start()
                    .starts_with(&format!("{} / {}", key.variant, key.solver)),
                "{line}"
            );
            assert!(
                line.ends_with(&format!("{} · {}", job.variant, job.solver.label())),
                "{line}"
            );
        }
    }

    #[test]
    fn an_experiment_without_selected_runs_is_left_out() {
        let (files, jobs) = fixture();
        // No run of the shard (more shards than runs): not even the paper's header.
        let n = jobs.len() + 1;
        assert_eq!(text(&files, Some(Shard::new(n, n).unwrap())), "");
        // One run of the shard: that run alone, the second of the selection.
        let n = jobs.len();
        let one = text(&files, Some(Shard::new(2, n).unwrap()));
        assert!(one.contains(": 1 runs\n"), "{one}");
        let key = jobs[1].key();
        assert!(
            one.contains(&format!("{} / {}", key.variant, key.solver)),
            "{one}"
        );
        assert_eq!(one.lines().count(), 3, "{one}");
    }

    #[test]
    fn the_shard_plan_counts_every_run_once() {
        let (_, jobs) = fixture();
        let plan = shard_plan(jobs.len(), 3);
        let counts: Vec<usize> = plan
            .lines()
            .enumerate()
            .map(|(k, l)| {
                let rest = l.strip_prefix(&format!("shard {}/3: ", k + 1)).expect(l);
                rest.strip_suffix(" runs").unwrap().parse().unwrap()
            })
            .collect();
        assert_eq!(counts.len(), 3);
        assert_eq!(counts.iter().sum::<usize>(), jobs.len());
    }

    #[test]
    fn every_robot_is_listed_with_its_joint_count() {
        use robots::{robot_by_name, robot_names};
        let text = robots();
        let names: Vec<String> = robot_names()
            .into_iter()
            .chain(["nlink-7".to_string(), "nlink-200".to_string()])
            .collect();
        assert_eq!(text.lines().count(), 2 * names.len() + 1);
        assert!(text.contains("nlink-200      200 joints"), "{text}");
        for (name, line) in names.iter().zip(text.lines().step_by(2)) {
            let dof = robot_by_name(name).unwrap().dof();
            assert!(
                line.starts_with(&format!("{name:<14} {dof} joints")),
                "{line}"
            );
        }
    }
}
