//! Experiments as data: one TOML file per paper in `experiments/`, read with serde.
//!
//! A file holds a paper id and a list of experiments (ids as in `docs/experiments.md`).
//! An experiment fixes the robot, the path, theta0 (and the scheme's reference theta*0 where a
//! paper distinguishes it) and the integrators, and lists *variants*: each variant is one scheme
//! (with its parameters by the paper's names) run exactly (the QP solved to optimality in the
//! loop) and by each of its neural solvers. A variant may override the robot, path, theta0 or theta_ref, which is how
//! the model check (jaco2 vs jaco2-pen), the star-lines variant and kong2019's two starts are
//! written. A variant with a `sweep` table stands for many (the grammar: [`crate::sweep`]).
//! Every run an experiment file describes is a [`RunSpec`].

use crate::error::{ExperimentError, ExperimentFileError, FieldAt, FieldError, TomlError};
use crate::sweep::{Prefixes, Sweep, CHECKED_WHOLE, NAMES_COMPARED};
use crate::SweepError;
use robots::Mount;
use serde::{Deserialize, Serialize};
use settings::SolverSpec;
use settings::{IntegratorSettings, Method};
use spec::ids::{ExperimentId, VariantId};
use spec::MountError;
use spec::MountSpec;
use spec::NumericalSpec;
use spec::PathSpec;
use spec::RunKey;
use spec::SchemeSpec;
use spec::{slug, MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL};
use spec::{JobPart, LimitsSpec, NetworkInit, RunSpec, Scoring, SetupError, SolverChoice};
use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// One paper's experiment file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperFile {
    /// Paper id (`jia2019`, `zhang2018`, `zhong2021`, `kong2019`).
    pub paper: String,
    /// The paper's subject in a line (e.g. "VLTCO scheme solved by LVI-PDNN (Jaco2)"), shown in
    /// listings and the report.
    pub title: String,
    /// The experiments (`[[experiment]]`), in file order.
    #[serde(rename = "experiment")]
    pub experiments: Vec<Experiment>,
    /// The file's name in its directory (e.g. `kong2019.toml`), as [`PaperFile::load`] read
    /// it; empty for a file parsed from text ([`PaperFile::from_toml`]).
    #[serde(skip)]
    pub file_name: String,
}

/// One experiment of docs/experiments.md.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiment {
    /// The experiment's id: a slug starting with the paper id and `-` (e.g. `jia2019-clover`).
    pub id: String,
    /// What the paper prints for it (e.g. "Table 2; Figs 2-4").
    pub paper_output: String,
    /// The robot's model name ([`robots::robot_by_name`], e.g. `jaco2-pen`).
    pub robot: String,
    /// A tool offset `[x, y, z]` (m) in the robot's tool frame, added to its task point
    /// ([`robots::Mounted`]; needs a robot with a tool frame).
    #[serde(default)]
    pub tool: Option<[f64; 3]>,
    /// Where the robot stands: the run's world from the robot's ([`BaseSpec`]).
    #[serde(default)]
    pub base: Option<BaseSpec>,
    /// The desired path of every variant (a variant may override it).
    pub path: PathSpec,
    /// Initial joint angles theta(0) (rad), one per joint.
    pub theta0: Vec<f64>,
    /// The scheme's joint reference (kong2019's theta*0); theta0 when absent. Paths start at
    /// f(theta_ref).
    #[serde(default)]
    pub theta_ref: Option<Vec<f64>>,
    /// Integrator of the neural runs (default: BDF/NDF, RelTol 1e-6, AbsTol 1e-8, as ode15s).
    #[serde(default)]
    pub integrator: IntegratorSettings,
    /// Integrator of the exact column (the QP solved to optimality in the loop; by default explicit, since
    /// x*(t, theta) is only piecewise smooth and has no cheap Jacobian).
    #[serde(default = "default_exact_integrator")]
    pub exact_integrator: IntegratorSettings,
    /// Joint-angle limits that replace the robot's for every variant (rad).
    #[serde(default)]
    pub joint_limits: Option<LimitsSpec>,
    /// Joint-velocity limits that replace the robot's for every variant (rad/s).
    #[serde(default)]
    pub velocity_limits: Option<LimitsSpec>,
    /// Where the neural runs are scored against the exact optimum: `"every-step"` (default),
    /// `{ max-instants = 2000 }` (a bounded number of exact solves per run) or `"off"`.
    #[serde(default)]
    pub scoring: Scoring,
    /// The variants (`[[experiment.variant]]`), in file order, each sweep kept as its plan in
    /// its place.
    #[serde(rename = "variant")]
    pub variants: Variants,
}

/// The variants of an experiment, in file order: each written variant as read, and each sweep
/// kept as its plan (`catalog::sweep::Sweep`: the base variant and the axes, no variant held),
/// standing for its variants in its place. Variant i of the experiment is the i-th in this
/// order; a swept one is made when asked for, by index ([`PaperFile::variant`]).
#[derive(Clone, Debug)]
pub struct Variants(pub(crate) Vec<Entry>);

/// A written variant, or a sweep.
#[derive(Clone, Debug)]
pub(crate) enum Entry {
    Written(Variant),
    Swept(Sweep),
}

impl Entry {
    /// How many variants it stands for.
    pub(crate) fn len(&self) -> usize {
        match self {
            Entry::Written(_) => 1,
            Entry::Swept(s) => s.len(),
        }
    }

    /// How many runs its variants make (every run, or the exact column alone), none made.
    pub(crate) fn runs(&self, exact_only: bool) -> usize {
        match self {
            Entry::Written(v) if exact_only => usize::from(v.exact),
            Entry::Written(v) => v.run_count(),
            Entry::Swept(s) => s.runs_before(s.len(), exact_only),
        }
    }
}

impl<'de> Deserialize<'de> for Variants {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let written = Vec::<Variant>::deserialize(d)?;
        Ok(Variants(written.into_iter().map(Entry::Written).collect()))
    }
}

impl Variants {
    /// How many variants there are, each sweep's counted.
    pub fn len(&self) -> usize {
        self.0.iter().map(Entry::len).sum()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// How many runs the variants make (every run, or with `exact_only` the exact column
    /// alone), none made.
    pub fn run_count(&self, exact_only: bool) -> usize {
        self.0.iter().map(|e| e.runs(exact_only)).sum()
    }

    /// The variants by where they come from, in order: the indices of each written variant
    /// (one) and of each sweep's variants.
    pub fn groups(&self) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
        let mut start = 0;
        self.0.iter().map(move |e| {
            let r = start..start + e.len();
            start = r.end;
            r
        })
    }

    /// The entry that holds variant `i`, and i's index in it (panics past [`Variants::len`],
    /// as indexing does).
    fn locate(&self, i: usize) -> (&Entry, usize) {
        let mut start = 0;
        for e in &self.0 {
            if i < start + e.len() {
                return (e, i - start);
            }
            start += e.len();
        }
        panic!("variant {i} of {} variants", self.len())
    }
}

/// Dormand-Prince 5(4) at RelTol 1e-11, AbsTol 1e-13: x*(t, theta) has kinks where the active
/// set changes, which an explicit pair's error estimate sees late, so the reference column needs
/// five orders more than the papers' 1e-6 / 1e-8 to be converged. The tolerance ladder
/// (`results/ladder.csv`) decides it: at RelTol 1e-8 the jia2019 clover drifts were 0.1-0.3 %
/// off the converged ones, at 1e-10 some drifts (the star's, zhong2021's clover b) still move in
/// the fourth digit, at 1e-11 every exact drift that is not itself zero holds four digits.
pub fn default_exact_integrator() -> IntegratorSettings {
    IntegratorSettings {
        method: Method::Dopri5,
        rtol: 1e-11,
        atol: 1e-13,
        ..IntegratorSettings::default()
    }
}

/// One scheme of an experiment, run exactly and by each listed neural solver.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Variant {
    /// The variant's id in run keys, results and file names (a slug, e.g. `vltco`); when
    /// absent, `slug(label)` ([`Variant::id`]). Declare it to rename the label freely.
    #[serde(default)]
    pub id: Option<String>,
    /// Label as the paper's table column writes it (e.g. "VLTCO"): display only.
    pub label: String,
    /// The scheme and its parameters (`[scheme]`, [`SchemeSpec`]).
    pub scheme: SchemeSpec,
    /// The neural solvers to run the scheme with, one run each.
    #[serde(default)]
    pub solvers: Vec<SolverSpec>,
    /// QP solvers run as this variant's solvers at every instant of a fixed-step loop
    /// ([`spec::NumericalSpec`]).
    #[serde(default)]
    pub numerical: Vec<NumericalSpec>,
    /// Run the exact column (default true).
    #[serde(default = "yes")]
    pub exact: bool,
    /// The robot of this variant (overrides the experiment's).
    #[serde(default)]
    pub robot: Option<String>,
    /// The tool offset of this variant (overrides the experiment's).
    #[serde(default)]
    pub tool: Option<Box<[f64; 3]>>,
    /// The base transform of this variant (overrides the experiment's).
    #[serde(default)]
    pub base: Option<Box<BaseSpec>>,
    /// Boxed, as the other overrides a variant seldom gives (limits, expected failure): a
    /// sweep of 10^6 variants holds 10^6 of these structs, each 200 bytes smaller so.
    #[serde(default)]
    pub path: Option<Box<PathSpec>>,
    /// Initial joint angles of this variant (rad; overrides the experiment's).
    #[serde(default)]
    pub theta0: Option<Vec<f64>>,
    /// The scheme's joint reference of this variant (rad; overrides the experiment's).
    #[serde(default)]
    pub theta_ref: Option<Vec<f64>>,
    /// Joint-angle limits of this variant (override the experiment's and the robot's).
    #[serde(default)]
    pub joint_limits: Option<Box<LimitsSpec>>,
    /// Joint-velocity limits of this variant (override the experiment's and the robot's).
    #[serde(default)]
    pub velocity_limits: Option<Box<LimitsSpec>>,
    /// Integrator of this variant's neural runs (overrides the experiment's).
    #[serde(default)]
    pub integrator: Option<IntegratorSettings>,
    /// Initial state of the networks (the papers do not print it; default: zero).
    #[serde(default)]
    pub network_init: NetworkInit,
    /// Runs of this variant that are expected to fail (a finding, not a fault): they do not
    /// make the binary exit non-zero nor the regression gate complain.
    #[serde(default)]
    pub expected_failure: Option<Box<ExpectedFailure>>,
    /// Explain this variant's neural runs (tolerance ladder, drift attribution) even though no
    /// published column maps onto them (those that are mapped are explained anyway).
    #[serde(default)]
    pub explain: bool,
    /// Which of the variant's runs keep their trace: its sweep's `traces` field and where the
    /// variant stands among the sweep's runs ([`crate::sweep::KeptTraces`]); every run of a
    /// variant without a sweep keeps it.
    #[serde(skip)]
    pub traces: crate::sweep::KeptTraces,
}

/// An expected failure: why, and which of the variant's runs (solver kinds, e.g. `"fp-cdnn"`
/// or `"exact"`; empty: every run of the variant).
#[derive(Clone, Debug, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExpectedFailure {
    /// Why the runs fail (the finding), shown where they are reported.
    pub why: String,
    /// The solver kinds of the runs expected to fail (empty: every run of the variant).
    #[serde(default)]
    pub solvers: Vec<String>,
}

impl ExpectedFailure {
    /// The reason, if the run of `solver` is one of the expected failures.
    fn of(&self, solver: &SolverChoice) -> Option<String> {
        (self.solvers.is_empty() || self.solvers.iter().any(|s| s == solver.kind().id()))
            .then(|| self.why.clone())
    }
}

impl Variant {
    /// The variant's id: the declared `id`, or `slug(label)`.
    pub fn id(&self) -> String {
        self.id.clone().unwrap_or_else(|| slug(&self.label))
    }

    /// How many runs the variant makes, without making them: the exact column (when `exact`),
    /// one per neural solver and one per numerical method ([`PaperFile::variant_jobs`]).
    pub fn run_count(&self) -> usize {
        usize::from(self.exact) + self.solvers.len() + self.numerical.len()
    }
}

/// Where an experiment's robot stands: the run's world from the robot's own world frame,
/// `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` with `rpy = [roll, pitch, yaw]` (the URDF
/// convention; [`robots::Mount::new`] bounds them).
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BaseSpec {
    /// Translation (m), default zero.
    #[serde(default)]
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw (rad), default zero.
    #[serde(default)]
    pub rpy: [f64; 3],
}

/// The mount of a tool offset and a base, `None` when neither is given (the robot as it is).
/// The mount is checked as the run will build it ([`Mount::new`]).
fn mount_of(
    tool: Option<&[f64; 3]>,
    base: Option<&BaseSpec>,
) -> Result<Option<MountSpec>, MountError> {
    if tool.is_none() && base.is_none() {
        return Ok(None);
    }
    let base = base.cloned().unwrap_or_default();
    let spec = MountSpec {
        tool: tool.copied().unwrap_or([0.0; 3]),
        xyz: base.xyz,
        rpy: base.rpy,
    };
    Mount::new(spec.tool, spec.xyz, spec.rpy)?;
    Ok(Some(spec))
}

fn yes() -> bool {
    true
}

/// Why the ids of a run made from a file are valid: every [`PaperFile`] the program reads comes
/// through [`PaperFile::from_toml`] (or [`PaperFile::load`]), whose check (`PaperFile::validate`)
/// refuses an experiment id or declared variant id that is not a slug, and a variant label whose
/// slug (the derived variant id) would be empty or too long, before any run is made. (A file
/// deserialized by hand, past that check, can make these runs panic.)
const CHECKED_IDS: &str =
    "the experiment file's check refuses an experiment or variant id that is not one";

/// Why the mount of a run made from a file is valid: the file's check builds every
/// experiment's and variant's mount before any run is made.
const CHECKED_MOUNT: &str = "the experiment file's check refuses an invalid tool or base";

impl PaperFile {
    /// Reads (with the input reader, crate `inputs`: a regular file that does not lead out of
    /// its directory, at most [`inputs::Kind::Experiment`]'s cap) and validates one experiment
    /// file as data (see `PaperFile::validate`); whether its runs can be built is checked by
    /// the orchestrator ([`DeclaredRun`]).
    pub fn load(path: &Path) -> Result<Self, ExperimentFileError> {
        Self::load_within(path, &mut crate::sweep::MAX_EXPANSION.clone())
    }

    /// [`PaperFile::load`], its sweeps standing for at most `budget` variants (reduced by
    /// what they take; [`crate::sweep::Sweeps::plan`]).
    fn load_within(path: &Path, budget: &mut usize) -> Result<Self, ExperimentFileError> {
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let text = inputs::read_text(path, inputs::Kind::Experiment, inputs::Origin::Under(dir))?;
        let file = Self::from_toml_within(&text, budget).map_err(|error| {
            ExperimentFileError::Invalid {
                file: path.to_path_buf(),
                error,
            }
        })?;
        Ok(Self {
            file_name: path
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned(),
            ..file
        })
    }

    /// Parses and validates the text of an experiment file (errors without the file name;
    /// [`PaperFile::load`] adds it).
    pub fn from_toml(text: &str) -> Result<Self, ExperimentError> {
        Self::from_toml_within(text, &mut crate::sweep::MAX_EXPANSION.clone())
    }

    /// [`PaperFile::from_toml`], its sweeps expanding into at most `budget` variants.
    fn from_toml_within(text: &str, budget: &mut usize) -> Result<Self, ExperimentError> {
        let mut doc: toml::Table = inputs::parse_toml(text)?;
        // Sweeps (crate::sweep) are taken out of the parsed TOML, the rest is read, and each
        // sweep's plan goes into its place; a file without one is read from its text, so
        // serde's errors keep their line numbers.
        let file: PaperFile = if crate::sweep::has_sweeps(&doc) {
            let sweeps = crate::sweep::take_sweeps(&mut doc);
            let mut file =
                PaperFile::deserialize(toml::Value::Table(doc)).map_err(TomlError::from)?;
            // In file order, so each goes where it was written.
            for (slot, sweep) in sweeps.plan(budget)? {
                file.experiments[slot.experiment]
                    .variants
                    .0
                    .insert(slot.variant, Entry::Swept(sweep));
            }
            file
        } else {
            inputs::parse_toml(text)?
        };
        file.validate()?;
        Ok(file)
    }

    /// Every check of the file as data, in one place. Field ranges are the crates' own
    /// validators ([`IntegratorSettings::validate`], [`SchemeSpec::validate`]); the robot's
    /// joint count against the poses, the mounts, the numerical methods against the path's
    /// duration; then the names: ids and labels that are unsafe as file names, experiment ids,
    /// variant labels and run keys that repeat, and slugs (file names of traces and figures)
    /// that collide. What only building a run can tell (path names, durations, scales and
    /// pose, solver gains, scheme/robot compatibility, solver/scheme compatibility) is the
    /// engine's check, which the orchestrator runs on every [`DeclaredRun`] after loading.
    fn validate(&self) -> Result<(), ExperimentError> {
        check_name(&self.paper, MAX_EXPERIMENT_ID, FieldAt::Paper)?;
        check_id(&self.paper, FieldAt::Paper)?;
        check_one_line(&self.title, FieldAt::Title)?;
        // Hash sets, not lists: a sweep of 10^6 variants is validated in linear time. (An
        // experiment id is its own slug, so two ids share a file name only when they are equal.)
        let mut ids_seen: HashSet<&str> = HashSet::new();
        for (i, e) in self.experiments.iter().enumerate() {
            self.validate_experiment(i, e, &mut ids_seen)?;
        }
        Ok(())
    }

    /// The checks of experiment `e`, the `index`-th of the file: its id (a name, with the
    /// paper's prefix, not in `ids_seen` yet), robot, poses, integrators, limits and scoring,
    /// then each variant: its names ([`check_variant_names`]) and everything else
    /// ([`PaperFile::validate_variant`]).
    fn validate_experiment<'a>(
        &self,
        index: usize,
        e: &'a Experiment,
        ids_seen: &mut HashSet<&'a str>,
    ) -> Result<(), ExperimentError> {
        let at = |field: &str| experiment_at(index, e, field);
        check_name(&e.id, MAX_EXPERIMENT_ID, at("id"))?;
        check_id(&e.id, at("id"))?;
        if !e.id.starts_with(&format!("{}-", self.paper)) {
            let paper = self.paper.clone();
            return Err(field(at("id"), FieldError::PaperPrefix { paper }));
        }
        if !ids_seen.insert(&e.id) {
            let id = e.id.clone();
            return Err(field(at("id"), FieldError::IdTwice { id }));
        }
        check_one_line(&e.paper_output, at("paper_output"))?;
        let n = robot_dof(&e.robot).map_err(|e| field(at("robot"), e))?;
        mount_of(e.tool.as_ref(), e.base.as_ref())
            .map_err(|err| field(at(err.field()), SetupError::Mount(err)))?;
        check_len(&e.theta0, n, at("theta0"))?;
        if let Some(r) = &e.theta_ref {
            check_len(r, n, at("theta_ref"))?;
        }
        check_integrator(&e.integrator, at("integrator"))?;
        check_integrator(&e.exact_integrator, at("exact_integrator"))?;
        for (name, limits, velocity) in [
            ("joint_limits", &e.joint_limits, false),
            ("velocity_limits", &e.velocity_limits, true),
        ] {
            if let Some(l) = limits {
                l.check(n, velocity).map_err(|err| field(at(name), err))?;
            }
        }
        if e.scoring == Scoring::MaxInstants(0) {
            return Err(field(at("scoring"), FieldError::NoInstants));
        }
        if e.variants.is_empty() {
            return Err(field(at("variant"), FieldError::NoVariants));
        }
        self.check_names(index, e)?;
        for (range, entry) in e.variants.groups().zip(&e.variants.0) {
            match entry {
                Entry::Written(v) => {
                    let vat = |field: &str| variant_at((index, e), (range.start, v), field);
                    self.validate_variant(e, v, n, &vat)?;
                }
                Entry::Swept(s) => {
                    for local in s.checked() {
                        self.make(index, s, range.start + local, local)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// That the labels and ids of experiment `e`'s variants (the `index`-th of the file) are
    /// names, each once in the experiment. The names of the written variants and of every
    /// sweep of at most [`CHECKED_WHOLE`] variants are compared one by one, as 16-byte prints
    /// (made from the axes, no variant read). A larger sweep's are decided from its axes
    /// ([`Sweep::prefixes`]: distinct among themselves), and no other name of the experiment
    /// may begin as all of them do (nor may two such sweeps' beginnings begin one another);
    /// a larger sweep whose axes do not decide them is compared one by one up to
    /// [`NAMES_COMPARED`] variants, and refused past that.
    fn check_names(&self, index: usize, e: &Experiment) -> Result<(), ExperimentError> {
        let mut decided: Vec<(usize, &Sweep, Prefixes)> = Vec::new();
        for (range, entry) in e.variants.groups().zip(&e.variants.0) {
            let Entry::Swept(s) = entry else { continue };
            if s.len() <= CHECKED_WHOLE {
                continue;
            }
            match s.prefixes() {
                Some(p) => decided.push((range.start, s, p)),
                None if s.len() > NAMES_COMPARED => {
                    return Err(s
                        .error(SweepError::NamesUndecided {
                            variants: s.len(),
                            max: NAMES_COMPARED,
                        })
                        .into())
                }
                None => {}
            }
        }
        for (k, (_, s, p)) in decided.iter().enumerate() {
            for (_, _, q) in &decided[k + 1..] {
                for (what, a, b) in [("id", &p.id, &q.id), ("label", &p.label, &q.label)] {
                    if a.starts_with(b.as_str()) || b.starts_with(a.as_str()) {
                        let (prefix, name) = (a.clone(), b.clone());
                        return Err(s.error(SweepError::MayClash { what, prefix, name }).into());
                    }
                }
            }
        }
        let mut names = Names::default();
        for (range, entry) in e.variants.groups().zip(&e.variants.0) {
            match entry {
                Entry::Written(v) => {
                    let name = Name {
                        index: range.start,
                        label: v.label.clone(),
                        id: v.id(),
                        declared: v.id.is_some(),
                    };
                    names.add(index, e, name, &decided)?;
                }
                Entry::Swept(s) if !decided.iter().any(|(start, ..)| *start == range.start) => {
                    for local in 0..s.len() {
                        let (label, id) = s.names(local);
                        let name = Name {
                            index: range.start + local,
                            declared: id.is_some(),
                            id: id.unwrap_or_else(|| slug(&label)),
                            label,
                        };
                        names.add(index, e, name, &decided)?;
                    }
                }
                Entry::Swept(_) => {}
            }
        }
        Ok(())
    }

    /// Variant `i` of experiment `index` of the file (panics past [`Variants::len`], as
    /// indexing does): a written one as read; a swept one made from its sweep's plan, read,
    /// and checked as data as the load checks a written one (its label and id, its fields and
    /// runs), so that a variant a shard makes is held to the file's rules. Its distinctness
    /// from the others was decided at load.
    pub fn variant(&self, index: usize, i: usize) -> Result<Cow<'_, Variant>, ExperimentError> {
        match self.experiments[index].variants.locate(i) {
            (Entry::Written(v), _) => Ok(Cow::Borrowed(v)),
            (Entry::Swept(s), local) => self.make(index, s, i, local).map(Cow::Owned),
        }
    }

    /// Variant `i` of experiment `index`, the `local`-th of its sweep `s`, made and checked
    /// ([`PaperFile::variant`]).
    fn make(
        &self,
        index: usize,
        s: &Sweep,
        i: usize,
        local: usize,
    ) -> Result<Variant, ExperimentError> {
        let e = &self.experiments[index];
        let (table, traces) = s.table(local);
        let v = Variant::deserialize(toml::Value::Table(table))
            .map_err(|error| s.does_not_read(local, error))?;
        let v = Variant { traces, ..v };
        let n = robot_dof(&e.robot).map_err(|err| field(experiment_at(index, e, "robot"), err))?;
        {
            let vat = |name: &str| variant_at((index, e), (i, &v), name);
            check_name(&v.label, MAX_VARIANT_LABEL, vat("label"))?;
            if let Some(id) = &v.id {
                check_name(id, MAX_VARIANT_LABEL, vat("id"))?;
                check_id(id, vat("id"))?;
            }
            self.validate_variant(e, &v, n, &vat)?;
        }
        Ok(v)
    }

    /// The label of variant `i` of `e`, made from the axes for a swept one.
    fn label_of(e: &Experiment, i: usize) -> String {
        match e.variants.locate(i) {
            (Entry::Written(v), _) => v.label.clone(),
            (Entry::Swept(s), local) => s.names(local).0,
        }
    }

    /// The checks of variant `v` of experiment `e` (whose robot has `n` joints) but its names:
    /// its robot and poses against the experiment's, its integrator, scheme and limits, that it
    /// runs something, then its runs ([`PaperFile::validate_runs`]) and its expected failure.
    /// `at` places a field of the experiment, `vat` one of the variant.
    fn validate_variant(
        &self,
        e: &Experiment,
        v: &Variant,
        n: usize,
        vat: &dyn Fn(&str) -> FieldAt,
    ) -> Result<(), ExperimentError> {
        let robot = v.robot.as_deref().unwrap_or(&e.robot);
        let vn = robot_dof(robot).map_err(|e| field(vat("robot"), e))?;
        if vn != n && (v.theta0.is_none() || (e.theta_ref.is_some() && v.theta_ref.is_none())) {
            return Err(field(
                vat("robot"),
                FieldError::RobotJoints {
                    robot: robot.to_string(),
                    joints: vn,
                },
            ));
        }
        mount_of(v.tool.as_deref(), v.base.as_deref())
            .map_err(|err| field(vat(err.field()), SetupError::Mount(err)))?;
        if let Some(t) = &v.theta0 {
            check_len(t, vn, vat("theta0"))?;
        }
        if let Some(t) = &v.theta_ref {
            check_len(t, vn, vat("theta_ref"))?;
        }
        if let Some(s) = &v.integrator {
            check_integrator(s, vat("integrator"))?;
        }
        v.scheme
            .validate()
            .map_err(|err| field(vat("scheme"), err))?;
        if !v.exact && v.solvers.is_empty() && v.numerical.is_empty() {
            return Err(field(vat("solvers"), FieldError::RunsNothing));
        }
        for (name, limits, velocity) in [
            ("joint_limits", v.joint_limits.as_deref(), false),
            ("velocity_limits", v.velocity_limits.as_deref(), true),
        ] {
            if let Some(l) = limits {
                l.check(vn, velocity).map_err(|err| field(vat(name), err))?;
            }
        }
        self.validate_runs(e, v, vat)?;
        if let Some(f) = &v.expected_failure {
            self.check_expected_failure(e, v, f, vat)?;
        }
        Ok(())
    }

    /// The runs of variant `v`: its numerical methods' settings against the path's duration,
    /// then each run's solver label and run key (valid, and once in the variant). Whether a
    /// run can be built is the engine's to say ([`DeclaredRun`]).
    fn validate_runs(
        &self,
        e: &Experiment,
        v: &Variant,
        vat: &dyn Fn(&str) -> FieldAt,
    ) -> Result<(), ExperimentError> {
        let duration = v.path.as_deref().unwrap_or(&e.path).duration;
        // Run keys are experiment / variant / solver ids, and an experiment's variant
        // ids are distinct (above): two runs can share a key only within one variant,
        // so the set is the variant's (not 10^6 keys held for a sweep's validation).
        let mut keys: HashSet<RunKey> = HashSet::new();
        for (k, s) in v.numerical.iter().enumerate() {
            s.validate(duration)
                .map_err(|err| field(vat(&format!("numerical[{k}]")), err))?;
        }
        for (k, job) in self.variant_jobs(e, v).iter().enumerate() {
            let solver_at = || vat(&run_field(v, k));
            check_name(&job.solver.label(), MAX_SOLVER_LABEL, solver_at())?;
            job.solver_id().map_err(|e| field(solver_at(), e))?;
            let key = job.key();
            if keys.contains(&key) {
                return Err(field(
                    solver_at(),
                    FieldError::RunTwice {
                        key: key.to_string(),
                    },
                ));
            }
            keys.insert(key);
        }
        Ok(())
    }

    /// That the solver kinds an expected failure `f` of variant `v` names are kinds of the
    /// variant's runs.
    fn check_expected_failure(
        &self,
        e: &Experiment,
        v: &Variant,
        f: &ExpectedFailure,
        vat: &dyn Fn(&str) -> FieldAt,
    ) -> Result<(), ExperimentError> {
        let kinds: Vec<String> = self
            .variant_jobs(e, v)
            .iter()
            .map(|j| j.solver.kind().id().to_string())
            .collect();
        if let Some(bad) = f.solvers.iter().find(|s| !kinds.contains(s)) {
            return Err(field(
                vat("expected_failure"),
                FieldError::UnknownFailureKind {
                    kind: bad.clone(),
                    kinds: kinds.join(", "),
                },
            ));
        }
        Ok(())
    }

    /// The runs of one variant `v` of this file's experiment `e` (exact column first; as many
    /// as [`Variant::run_count`]). Its experiment and variant ids were checked before the runs
    /// are made (`CHECKED_IDS`).
    pub fn variant_jobs(&self, e: &Experiment, v: &Variant) -> Vec<RunSpec> {
        let mut jobs = Vec::new();
        let theta0 = v.theta0.clone().unwrap_or_else(|| e.theta0.clone());
        let theta_ref = v
            .theta_ref
            .clone()
            .or_else(|| e.theta_ref.clone())
            .unwrap_or_else(|| theta0.clone());
        let base = RunSpec {
            paper: self.paper.clone(),
            experiment: ExperimentId::new(e.id.clone()).expect(CHECKED_IDS),
            variant_id: VariantId::new(v.id()).expect(CHECKED_IDS),
            variant: v.label.clone(),
            robot: v.robot.clone().unwrap_or_else(|| e.robot.clone()),
            path: v.path.as_deref().unwrap_or(&e.path).clone(),
            theta0,
            theta_ref,
            joint_limits: v
                .joint_limits
                .as_deref()
                .or(e.joint_limits.as_ref())
                .cloned(),
            velocity_limits: v
                .velocity_limits
                .as_deref()
                .or(e.velocity_limits.as_ref())
                .cloned(),
            mount: mount_of(
                v.tool.as_deref().or(e.tool.as_ref()),
                v.base.as_deref().or(e.base.as_ref()),
            )
            .expect(CHECKED_MOUNT),
            scheme: v.scheme.clone(),
            solver: SolverChoice::Exact,
            integrator: e.exact_integrator,
            scoring: e.scoring,
            network_init: NetworkInit::Zero,
            explain: v.explain,
            keep_trace: true,
            expected_failure: v
                .expected_failure
                .as_ref()
                .and_then(|f| f.of(&SolverChoice::Exact)),
        };
        if v.exact {
            jobs.push(base.clone());
        }
        for s in &v.solvers {
            let integrator = v.integrator.unwrap_or(e.integrator);
            let solver = SolverChoice::Neural(s.clone());
            jobs.push(RunSpec {
                expected_failure: v.expected_failure.as_ref().and_then(|f| f.of(&solver)),
                solver,
                integrator,
                network_init: v.network_init,
                ..base.clone()
            });
        }
        for s in &v.numerical {
            let solver = SolverChoice::Numerical(*s);
            jobs.push(RunSpec {
                expected_failure: v.expected_failure.as_ref().and_then(|f| f.of(&solver)),
                solver,
                ..base.clone()
            });
        }
        for (i, job) in jobs.iter_mut().enumerate() {
            job.keep_trace = v.traces.keeps(i);
        }
        jobs
    }

    /// Every run of the file, in file order (variant by variant, exact column first), or the
    /// first swept variant that does not make.
    pub fn jobs(&self) -> Result<Vec<RunSpec>, ExperimentFileError> {
        self.iter_jobs().collect()
    }

    /// [`PaperFile::jobs`] made one variant at a time as they are taken: a caller that
    /// filters, counts or prints them holds none of them.
    pub fn iter_jobs(&self) -> impl Iterator<Item = Result<RunSpec, ExperimentFileError>> + '_ {
        (0..self.experiments.len()).flat_map(move |i| {
            let n = self.experiments[i].variants.run_count(false);
            self.runs_at(i, false, 0..n)
                .map(|r| r.map(|d| d.spec).map_err(|error| self.in_file(error)))
        })
    }

    /// `error`, of this file (named as it was read).
    pub fn in_file(&self, error: ExperimentError) -> ExperimentFileError {
        ExperimentFileError::Invalid {
            file: PathBuf::from(&self.file_name),
            error,
        }
    }

    /// The runs of experiment `index` of the file whose indices among its runs are `at`
    /// (increasing; below its [`Variants::run_count`] with `exact_only`), each with the place
    /// that declares it. The runs are numbered variant by variant, each one's exact column
    /// first (with `exact_only`, its exact column alone). Only the variants that hold one of
    /// them are made ([`PaperFile::variant`]), each once: the entry by its first run, and in a
    /// sweep the variant by bisection over its runs' prefix sums
    /// (`Sweep::variant_of_run`), so a shard of a sweep of 10^7 runs makes
    /// its own variants alone.
    pub fn runs_at<'a>(
        &'a self,
        index: usize,
        exact_only: bool,
        at: impl IntoIterator<Item = usize> + 'a,
    ) -> impl Iterator<Item = Result<DeclaredRun<'a>, ExperimentError>> + 'a {
        let e = &self.experiments[index];
        // Per entry: the index of its first run and of its first variant.
        let mut bounds = Vec::with_capacity(e.variants.0.len());
        let (mut runs, mut variants) = (0, 0);
        for entry in &e.variants.0 {
            bounds.push((runs, variants));
            runs += entry.runs(exact_only);
            variants += entry.len();
        }
        // The variant made last: the index of its first run, and its runs.
        let mut current: Option<(usize, Vec<DeclaredRun<'a>>)> = None;
        at.into_iter().map(move |r| {
            let held = current
                .as_ref()
                .is_some_and(|(first, runs)| (*first..first + runs.len()).contains(&r));
            if !held {
                let k = bounds.partition_point(|&(first, _)| first <= r) - 1;
                let (first, variant) = bounds[k];
                let (i, first) = match &e.variants.0[k] {
                    Entry::Written(_) => (variant, first),
                    Entry::Swept(s) => {
                        let v = s.variant_of_run(r - first, exact_only);
                        (variant + v, first + s.runs_before(v, exact_only))
                    }
                };
                current = Some((first, self.declared(index, i, exact_only)?));
            }
            let (first, runs) = current.as_ref().expect("made above");
            Ok(runs[r - first].clone())
        })
    }

    /// The runs of variant `i` of experiment `index` (every run, or its exact column alone),
    /// each with its place.
    fn declared(
        &self,
        index: usize,
        i: usize,
        exact_only: bool,
    ) -> Result<Vec<DeclaredRun<'_>>, ExperimentError> {
        let e = &self.experiments[index];
        let v = self.variant(index, i)?;
        let jobs = self.variant_jobs(e, &v);
        let v = Rc::new(v);
        Ok(jobs
            .into_iter()
            .enumerate()
            .filter(|(_, j)| !exact_only || j.solver == SolverChoice::Exact)
            .map(|(run, spec)| DeclaredRun {
                spec,
                experiment: (index, e),
                variant: (i, v.clone()),
                run,
            })
            .collect())
    }

    /// The runs the orchestrator checks with the engine at load, in file order: every run of
    /// every written variant and of each sweep's variants checked at load
    /// (`Sweep::checked`: all of a sweep of at most
    /// [`crate::sweep::CHECKED_WHOLE`], the lines of a larger one). A swept variant made later
    /// is read and checked as data as it is made ([`PaperFile::variant`]); what only the
    /// engine can tell of it (a path or gain the engine cannot build) is its runs' failure,
    /// with its reason, as for any run.
    pub fn checked_runs(
        &self,
    ) -> impl Iterator<Item = Result<DeclaredRun<'_>, ExperimentError>> + '_ {
        self.experiments
            .iter()
            .enumerate()
            .flat_map(move |(index, e)| {
                e.variants
                    .groups()
                    .zip(&e.variants.0)
                    .flat_map(move |(range, entry)| {
                        let picks: Vec<usize> = match entry {
                            Entry::Written(_) => vec![range.start],
                            Entry::Swept(s) => {
                                s.checked().into_iter().map(|l| range.start + l).collect()
                            }
                        };
                        picks
                            .into_iter()
                            .map(move |i| self.declared(index, i, false))
                    })
            })
            .flat_map(|runs| match runs {
                Ok(runs) => runs.into_iter().map(Ok).collect::<Vec<_>>(),
                Err(e) => vec![Err(e)],
            })
    }
}

/// A run of a file with the place that declares it. This crate reads and validates the files
/// as data and cannot build a run; the orchestrator checks declared runs with the engine's
/// setup (`simulation::run::check_job`: robot, path from f(theta_ref), scheme and network
/// built as the run builds them, nothing integrated) after loading, before anything runs
/// ([`PaperFile::checked_runs`]), and places a failure with [`DeclaredRun::at_fault`]: a file
/// is so rejected for exactly what would make one of its runs fail at t = 0, the error naming
/// the file and the field.
#[derive(Clone, Debug)]
pub struct DeclaredRun<'a> {
    /// The run.
    pub spec: RunSpec,
    /// Its experiment, with its index in the file.
    experiment: (usize, &'a Experiment),
    /// Its variant (made, for a swept one), with its index in the experiment.
    variant: (usize, Rc<Cow<'a, Variant>>),
    /// Its index among the variant's runs ([`PaperFile::variant_jobs`]).
    run: usize,
}

impl DeclaredRun<'_> {
    /// `error`, why the run cannot be built, placed at the field at fault
    /// ([`SetupError::part`]): the solver's entry (`exact`, `solvers[i]` or `numerical[i]`)
    /// for the solver, the variant's path where it has one or else the experiment's, and the
    /// variant's field of any other part.
    pub fn at_fault(&self, error: SetupError) -> ExperimentError {
        let (j, v) = (self.variant.0, &**self.variant.1);
        let vat = |name: &str| variant_at(self.experiment, (j, v), name);
        let place = match error.part() {
            JobPart::Solver => vat(&run_field(v, self.run)),
            JobPart::Path if v.path.is_some() => vat("path"),
            JobPart::Path => experiment_at(self.experiment.0, self.experiment.1, "path"),
            part => vat(part.field()),
        };
        field(place, error)
    }
}

/// The field `name` of experiment `e`, the `index`-th of its file.
fn experiment_at(index: usize, e: &Experiment, name: &str) -> FieldAt {
    FieldAt::Experiment {
        index,
        id: e.id.clone(),
        field: name.to_string(),
    }
}

/// The field `name` of variant `v` (with its index) of experiment `e` (with its index).
fn variant_at(
    (experiment, e): (usize, &Experiment),
    (index, v): (usize, &Variant),
    name: &str,
) -> FieldAt {
    variant_field(experiment, e, index, &v.label, name)
}

/// The field `name` of the variant labelled `label`, the `index`-th of experiment `e` (the
/// `experiment`-th of its file).
fn variant_field(
    experiment: usize,
    e: &Experiment,
    index: usize,
    label: &str,
    name: &str,
) -> FieldAt {
    FieldAt::Variant {
        experiment,
        id: e.id.clone(),
        index,
        label: label.to_string(),
        field: name.to_string(),
    }
}

/// The field of variant `v` that declares its `k`-th run: `exact`, `solvers[i]` or
/// `numerical[i]`, in the order of [`PaperFile::variant_jobs`].
fn run_field(v: &Variant, k: usize) -> String {
    match k.checked_sub(usize::from(v.exact)) {
        None => "exact".to_string(),
        Some(i) if i < v.solvers.len() => format!("solvers[{i}]"),
        Some(i) => format!("numerical[{}]", i - v.solvers.len()),
    }
}

/// One variant's names, for [`Names::add`].
struct Name {
    /// The variant's index in its experiment.
    index: usize,
    label: String,
    /// Its id, declared or its label's slug.
    id: String,
    declared: bool,
}

/// The labels and ids of an experiment's variants seen so far, as 16-byte prints ([`print`]),
/// each with the index of the variant that has it.
#[derive(Default)]
struct Names {
    labels: HashMap<u128, usize>,
    ids: HashMap<u128, usize>,
}

impl Names {
    /// That `name` of a variant of experiment `e` (the `index`-th of its file) is a label and,
    /// declared, an id; that neither its label nor its id is one an earlier variant has, nor
    /// begins as every name of a sweep of `decided` does ([`PaperFile::check_names`]).
    fn add(
        &mut self,
        index: usize,
        e: &Experiment,
        name: Name,
        decided: &[(usize, &Sweep, Prefixes)],
    ) -> Result<(), ExperimentError> {
        let vat = |f: &str| variant_field(index, e, name.index, &name.label, f);
        check_name(&name.label, MAX_VARIANT_LABEL, vat("label"))?;
        if name.declared {
            check_name(&name.id, MAX_VARIANT_LABEL, vat("id"))?;
            check_id(&name.id, vat("id"))?;
        }
        for (_, s, p) in decided {
            for (what, prefix, own) in [("label", &p.label, &name.label), ("id", &p.id, &name.id)] {
                if own.starts_with(prefix.as_str()) {
                    let (prefix, name) = (prefix.clone(), own.clone());
                    return Err(s.error(SweepError::MayClash { what, prefix, name }).into());
                }
            }
        }
        if let Some(&first) = self.labels.get(&print(&name.label)) {
            // Two of one sweep: the sweep's error, with their places in it.
            let (range, entry) = e
                .variants
                .groups()
                .zip(&e.variants.0)
                .find(|(r, _)| r.contains(&name.index))
                .expect("the variant's own group");
            if let (Entry::Swept(s), true) = (entry, range.contains(&first)) {
                return Err(s
                    .error(SweepError::SameLabel {
                        first: first - range.start,
                        second: name.index - range.start,
                        label: name.label.clone(),
                        keys: s.keys(),
                    })
                    .into());
            }
            return Err(field(
                vat("label"),
                FieldError::LabelTwice {
                    label: name.label.clone(),
                },
            ));
        }
        if let Some(&other) = self.ids.get(&print(&name.id)) {
            return Err(field(
                vat("id"),
                FieldError::IdClash {
                    label: name.label.clone(),
                    other: PaperFile::label_of(e, other),
                    id: name.id.clone(),
                    derived: !name.declared,
                },
            ));
        }
        self.labels.insert(print(&name.label), name.index);
        self.ids.insert(print(&name.id), name.index);
        Ok(())
    }
}

/// A 16-byte print of `text`: two SipHashes of it, told apart by a leading byte. Two names
/// share one with probability ~2^-128.
fn print(text: &str) -> u128 {
    use std::hash::{DefaultHasher, Hash, Hasher};
    let half = |k: u8| {
        let mut h = DefaultHasher::new();
        (k, text).hash(&mut h);
        h.finish()
    };
    (u128::from(half(0)) << 64) | u128::from(half(1))
}

/// An id or label becomes a directory or file name (results/traces/<id>/<label>__<solver>.csv,
/// report/figures/): see [`spec::check_name`].
fn check_name(name: &str, max: usize, at: FieldAt) -> Result<(), ExperimentError> {
    spec::check_name(name, max).map_err(|e| field(at, e))
}

/// An id (paper, experiment, variant) must already be a slug: ids name files and reach the
/// report's links as they are.
fn check_id(id: &str, at: FieldAt) -> Result<(), ExperimentError> {
    if spec::ids::is_id_form(id) {
        return Ok(());
    }
    let (id, suggestion) = (id.to_string(), slug(id));
    Err(field(at, FieldError::NotAnId { id, suggestion }))
}

/// The error `error` at the field `at`.
/// Checks that `text` (the file's `title`, an experiment's `paper_output`: shown by `list` and in
/// the report) is one line, as a paper's title and citation must be ([`settings::is_one_line`]).
fn check_one_line(text: &str, at: FieldAt) -> Result<(), ExperimentError> {
    if settings::is_one_line(text) {
        return Ok(());
    }
    let found = text
        .chars()
        .find(|c| !settings::is_one_line(c.encode_utf8(&mut [0; 4])))
        .unwrap_or(char::REPLACEMENT_CHARACTER);
    Err(field(at, FieldError::NotOneLine { found }))
}

fn field(at: FieldAt, error: impl Into<FieldError>) -> ExperimentError {
    ExperimentError::Field {
        at: Box::new(at),
        error: Box::new(error.into()),
    }
}

/// Joint count of the robot called `name` (see [`robots::robot_by_name`]), or why there is none (an
/// unknown name, with the valid choices; an invalid robot file, with its file and field).
fn robot_dof(name: &str) -> Result<usize, FieldError> {
    robots::robot_by_name(name)
        .map(|r| r.dof())
        .map_err(|e| FieldError::UnknownRobot {
            robot: name.to_string(),
            reason: e.to_string(),
        })
}

fn check_len(v: &[f64], n: usize, at: FieldAt) -> Result<(), ExperimentError> {
    if v.len() != n {
        let given = v.len();
        return Err(field(at, FieldError::Length { given, joints: n }));
    }
    if v.iter().any(|x| !x.is_finite()) {
        return Err(field(at, FieldError::NotFinite));
    }
    Ok(())
}

fn check_integrator(s: &IntegratorSettings, at: FieldAt) -> Result<(), ExperimentError> {
    s.validate()
        .map_err(|e| field(at, FieldError::Integrator(e)))
}

/// Loads every `*.toml` of `dir`, sorted by file name, and checks what spans files: an
/// experiment id (or its file name, the slug) is defined in one file only, and the sweeps of
/// all files expand into at most [`crate::sweep::MAX_EXPANSION`] variants together.
pub fn load_dir(dir: &Path) -> Result<Vec<PaperFile>, ExperimentFileError> {
    let entries = std::fs::read_dir(dir).map_err(|source| ExperimentFileError::List {
        dir: dir.to_path_buf(),
        source,
    })?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    if paths.is_empty() {
        return Err(ExperimentFileError::NoFiles {
            dir: dir.to_path_buf(),
        });
    }
    let mut files = Vec::with_capacity(paths.len());
    let mut seen: HashMap<String, &Path> = HashMap::new();
    // The sweeps of every file share one budget of variants.
    let mut budget = crate::sweep::MAX_EXPANSION;
    for path in &paths {
        let file = PaperFile::load_within(path, &mut budget)?;
        for (i, e) in file.experiments.iter().enumerate() {
            if let Some(other_file) = seen.get(&e.id) {
                return Err(ExperimentFileError::DefinedTwice {
                    file: path.clone(),
                    index: i,
                    id: e.id.clone(),
                    other_file: other_file.to_path_buf(),
                });
            }
            seen.insert(e.id.clone(), path);
        }
        files.push(file);
    }
    Ok(files)
}
