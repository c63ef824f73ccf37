//! Task cards: one Markdown page per task (every variant of `experiments/*.toml`, a sweep's
//! variants up to [`MAX_SWEEP_CARDS`] of them, evenly spaced), with everything someone needs to set the same task up in their own code and score
//! its trajectory here (`reproduce score FILE --task ID`): the robot's kinematics (DH table and
//! tool, or its closed form) and limits, the path's formula, parameters and values at a few
//! instants, the duration, theta0 and theta*0, and the scheme's QP (its formulas with the
//! task's parameters, and its numbers at t = 0). The numbers are the suite's own models'
//! (`simulation::task_numbers`), so a card is a check value, not only a description.
//!
//! This module builds each card's model ([`presentation::task_card::TaskCard`]) from the
//! experiment files and the models; presentation renders it. [`write_all`] writes
//! `report/tasks/<experiment>--<variant slug>.md` and the index `report/tasks/README.md`,
//! recorded in `report/manifest.toml` like the figures (a stale card that the program wrote and
//! nobody edited is removed). [`cards`] renders them in memory.

use catalog::{Experiment, ExperimentFileError, PaperFile};
use presentation::task_card::{
    self as card, CardRun, Kinematics as CardKinematics, MountCard, PathCard, QpCard, RobotCard,
    RunSettings, SchemeCard, SchemeForm, StartCard, TaskCard,
};
use qp::Qp;
use robots::{robot_by_name, Kinematics, Model};
use simulation::{task_numbers, TaskNumbers};
use spec::RunSpec;
use spec::SchemeSpec;
use spec::SetupError;
use spec::SolverChoice;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use store::{Removal, TrackedDir, TrackedError};

/// The cards' directory under `report/`.
pub const TASKS: &str = "tasks";

/// The `paper` of the cross experiment, whose tasks make the leaderboard's standard task set.
const CROSS: &str = "cross";

/// Why the cards could not be written.
#[derive(Debug, thiserror::Error)]
pub enum TaskCardError {
    #[error("task {}: {source}", settings::shown(task))]
    Setup { task: String, source: SetupError },
    #[error(
        "task {}: robot {} is not in the registry",
        settings::shown(task),
        settings::shown(robot)
    )]
    Robot { task: String, robot: String },
    #[error(transparent)]
    Experiments(#[from] ExperimentFileError),
    #[error(transparent)]
    Serialize(#[from] toml::ser::Error),
    #[error(transparent)]
    Report(#[from] TrackedError),
}

/// The most cards one sweep gets (as many as an experiment's per-run figures,
/// presentation::figures::sweep::MAX_RUN_FIGURES): a sweep that expands into more variants
/// gets cards for this many of them, evenly spaced, its first and last among them
/// (`carded`), so the cards of a sweep of 10^5 variants are 24 files, not 10^5.
pub const MAX_SWEEP_CARDS: usize = presentation::figures::sweep::MAX_RUN_FIGURES;

/// The indices of the variants of `e` that get a card, in file order: every written variant,
/// and of each sweep's variants (catalog::Variants::groups) all of them up to
/// [`MAX_SWEEP_CARDS`], else that many evenly spaced: the k-th of m at
/// round(k (n - 1) / (m - 1)).
fn carded(e: &Experiment) -> impl Iterator<Item = usize> + '_ {
    e.variants.groups().flat_map(|group| {
        let (n, m) = (group.len(), MAX_SWEEP_CARDS);
        let picks: Vec<usize> = if n <= m {
            (0..n).collect()
        } else {
            (0..m)
                .map(|k| (k * (n - 1) + (m - 1) / 2) / (m - 1))
                .collect()
        };
        picks.into_iter().map(move |i| group.start + i)
    })
}

/// The cards of the tasks of the experiment files `files` (loaded and checked:
/// [`crate::load_experiments`]; every variant, each sweep's capped: `carded`): file name ->
/// Markdown, the index (`presentation::task_card::INDEX`) included. Each task's runs are made
/// from its variant alone, so what is held is the cards.
pub fn cards(files: &[PaperFile]) -> Result<BTreeMap<String, String>, TaskCardError> {
    let models = files
        .iter()
        .flat_map(|f| {
            f.experiments
                .iter()
                .enumerate()
                .flat_map(move |(index, e)| {
                    carded(e).map(move |i| {
                        let v = f.variant(index, i).map_err(|error| f.in_file(error))?;
                        Ok::<_, TaskCardError>(f.variant_jobs(e, &v))
                    })
                })
        })
        .map(|jobs| {
            let jobs = jobs?;
            let job = &jobs[0];
            let id = job.task().to_string();
            let numbers = task_numbers(job).map_err(|source| TaskCardError::Setup {
                task: id.clone(),
                source,
            })?;
            let robot = robot_by_name(&job.robot).map_err(|_| TaskCardError::Robot {
                task: id.clone(),
                robot: job.robot.clone(),
            })?;
            task_card(&jobs, numbers, &robot)
        })
        .collect::<Result<Vec<TaskCard>, TaskCardError>>()?;
    Ok(card::render(&models))
}

/// Writes the card of every task of the experiment files `files` and the index under
/// `root/report/tasks/` (module docs), removing stale cards this program wrote; returns the
/// directory.
pub fn write_all(files: &[PaperFile], root: &Path) -> Result<PathBuf, TaskCardError> {
    let cards = cards(files)?;
    let report = TrackedDir::open_within(root, "report")?;
    let rel = |name: &str| Path::new(TASKS).join(name);
    let prefix = format!("{TASKS}/");
    for listed in report.listed(&prefix)? {
        let name = listed.trim_start_matches(&prefix);
        if !cards.contains_key(name) {
            if let Removal::Kept(why) = report.remove(&rel(name))? {
                eprintln!("note: {why}");
            }
        }
    }
    for (name, text) in &cards {
        report.write(&rel(name), text.as_bytes())?;
    }
    report.save()?;
    Ok(report.path().join(TASKS))
}

/// `<experiment>--<variant slug>.md`.
fn card_name(job: &RunSpec) -> String {
    format!("{}--{}.md", job.experiment, job.variant_id)
}

/// One task's card model from its runs `jobs` (the first describes the task), its numbers `n`
/// and its robot's model.
fn task_card(jobs: &[RunSpec], n: TaskNumbers, robot: &Model) -> Result<TaskCard, TaskCardError> {
    let job = &jobs[0];
    let runs = jobs
        .iter()
        .map(|j| {
            let settings = match &j.solver {
                SolverChoice::Exact => RunSettings::Exact {
                    integrator: value(&j.integrator)?,
                },
                SolverChoice::Neural(spec) => RunSettings::Neural {
                    spec: value(spec)?,
                    integrator: value(&j.integrator)?,
                },
                // The settings in effect, the solver's defaults filled in (a loaded file's
                // settings fit its solver: checked at load).
                SolverChoice::Numerical(spec) => RunSettings::Numerical {
                    settings: value(&spec.with_defaults().unwrap_or(*spec))?,
                },
            };
            Ok(CardRun {
                label: j.solver.label(),
                settings,
            })
        })
        .collect::<Result<Vec<CardRun>, TaskCardError>>()?;
    let mount = simulation::job_mount(job)
        .map_err(|source| TaskCardError::Setup {
            task: job.task().to_string(),
            source,
        })?
        .map(|m| {
            let (t, b) = (m.tool(), m.base());
            MountCard {
                tool: [t.x, t.y, t.z],
                base_origin: [b.origin.x, b.origin.y, b.origin.z],
                base_rotation_rows: b.rot.transpose().as_slice().to_vec(),
            }
        });
    Ok(TaskCard {
        task: job.task().to_string(),
        file_name: card_name(job),
        paper: job.paper.clone(),
        cross: job.paper == CROSS,
        runs,
        robot: RobotCard {
            name: job.robot.clone(),
            joints: n.joints,
            kinematics: kinematics(robot),
            mount,
            theta_min: n.theta_min,
            theta_max: n.theta_max,
            thetadot_min: n.thetadot_min,
            thetadot_max: n.thetadot_max,
        },
        start: StartCard {
            theta0: job.theta0.clone(),
            theta_ref: job.theta_ref.clone(),
            position0: n.position0,
            jacobian0: n.jacobian0,
        },
        path: PathCard {
            name: job.path.name.clone(),
            params: value(&job.path)?,
            size: job
                .path
                .scale
                .or_else(|| spec::default_scale(&job.path.name)),
            duration: job.path.duration,
            start: n.path_start,
            samples: n.path,
        },
        scheme: SchemeCard {
            name: n.scheme,
            level: n.level,
            params: value(&job.scheme)?,
            form: form(&job.scheme),
            terms: n.terms,
            qp0: qp(&n.qp0),
        },
    })
}

/// The robot's kinematics: the DH table and tool, or the closed form.
fn kinematics(robot: &Model) -> CardKinematics {
    match &robot.kinematics {
        Kinematics::Dh { arm, file } => {
            let chain = arm.chain();
            let (o, t) = (chain.base.origin, arm.tool());
            CardKinematics::Dh {
                file: file.clone(),
                links: chain.params().iter().map(|p| [p.a, p.alpha, p.d]).collect(),
                base_rotation: chain
                    .base
                    .rot
                    .row_iter()
                    .map(|r| r.iter().copied().collect())
                    .collect(),
                base_origin: [o.x, o.y, o.z],
                offsets: arm.offset().to_vec(),
                frame: chain.dof(),
                tool: [t.x, t.y, t.z],
            }
        }
        Kinematics::Katana(k) => CardKinematics::Katana {
            l: [k.l1, k.l2, k.l3, k.l4, k.l5],
        },
        Kinematics::Urdf {
            file,
            urdf,
            base,
            tip,
        } => CardKinematics::Urdf {
            file: file.clone(),
            urdf: urdf.clone(),
            base: base.clone(),
            tip: tip.clone(),
        },
        Kinematics::NLink(n) => CardKinematics::NLink(*n),
    }
}

/// Which formula states the scheme's QP.
fn form(spec: &SchemeSpec) -> SchemeForm {
    match spec {
        SchemeSpec::Vltco { .. } => SchemeForm::Vltco,
        SchemeSpec::Cmco { .. } => SchemeForm::Cmco,
        SchemeSpec::HlJdf { .. } => SchemeForm::HlJdf,
        SchemeSpec::FiniteTimeRmp { .. } => SchemeForm::FiniteTimeRmp,
        SchemeSpec::ZnnRmp { .. } => SchemeForm::ZnnRmp,
        SchemeSpec::VelocityRmp { .. } | SchemeSpec::Composed(_) => SchemeForm::Terms,
    }
}

/// The QP's numbers, matrices by rows.
fn qp(qp: &Qp) -> QpCard {
    let rows = |m: &nalgebra::DMatrix<f64>| -> Vec<Vec<f64>> {
        m.row_iter().map(|r| r.iter().copied().collect()).collect()
    };
    QpCard {
        p: rows(&qp.p),
        a: rows(&qp.a),
        g: rows(&qp.g),
        q: qp.q.as_slice().to_vec(),
        b: qp.b.as_slice().to_vec(),
        h: qp.h.as_slice().to_vec(),
        lower: qp.lower.as_slice().to_vec(),
        upper: qp.upper.as_slice().to_vec(),
    }
}

/// A value as a TOML value, as experiment files write it.
fn value<T: serde::Serialize>(value: &T) -> Result<toml::Value, TaskCardError> {
    Ok(toml::Value::try_from(value)?)
}
