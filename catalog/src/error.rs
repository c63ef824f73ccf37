//! The catalog's errors, each wrapping the layer below.
//!
//! - The experiment format: [`ExperimentFileError`] (the file) wraps [`ExperimentError`] (the
//!   text), which wraps [`TomlError`], [`SweepError`] (the sweep grammar) and [`FieldError`] at
//!   a [`FieldAt`] (which wraps [`SetupError`], the schemes' `SchemeError` and the naming
//!   rules' `NameError`).
//! - Building a run's parts: [`SetupError`], wrapping the schemes' `PathError` and
//!   `SchemeError` and a network's `NetworkError`. The engine (crate `simulation`) returns it
//!   when a run cannot be built, and the experiment format places it at the field at fault when
//!   a file is checked ([`crate::experiment::CheckJob`]).
//!
//! A network's parameter errors (`settings::error::NetworkError`) and the integrator settings'
//! (`settings::error::IntegratorError`) are crate `settings`', below both this crate and the
//! solvers.

use crate::fields::JobPart;
use crate::naming::NameError;
use schemes::paths::PathError;
use schemes::spec::SchemeError;
use settings::error::{IntegratorError, NetworkError};
use std::path::PathBuf;

/// Why a run's parts could not be built from its specification (robot, pose, path, scheme,
/// network), each wrapping its layer's own error.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SetupError {
    #[error("unknown robot \"{0}\"")]
    UnknownRobot(String),
    /// theta0 or theta_ref does not have the robot's joint count.
    #[error("has {given} entries, the robot has {joints} joints")]
    PoseLength {
        part: JobPart,
        given: usize,
        joints: usize,
    },
    #[error("entries must be finite")]
    PoseNotFinite { part: JobPart },
    #[error(transparent)]
    Path(#[from] PathError),
    /// The scheme's error, with a hint naming what would fit (e.g. the robots with dynamics).
    #[error("{error}{hint}")]
    Scheme { error: SchemeError, hint: String },
    /// The suite's network could not be built for the scheme's QP.
    #[error("{network}: {error} (scheme {scheme})")]
    Network {
        network: String,
        scheme: String,
        error: NetworkError,
    },
    /// A network given by the caller (e.g. a Python network) could not be built: its message.
    #[error("{0}")]
    CustomNetwork(String),
    /// Limits were given for a robot whose dynamics model the scheme reads its limits from.
    #[error("joint_limits / velocity_limits cannot replace the limits of \"{robot}\" for the acceleration-level scheme, which reads them from the robot's dynamics model")]
    LimitsWithDynamics { robot: String },
}

impl SetupError {
    /// The part of the job (and so the experiment-file field) at fault.
    pub fn part(&self) -> JobPart {
        match self {
            SetupError::UnknownRobot(_) => JobPart::Robot,
            SetupError::PoseLength { part, .. } | SetupError::PoseNotFinite { part } => *part,
            SetupError::Path(_) => JobPart::Path,
            SetupError::Scheme { .. } => JobPart::Scheme,
            SetupError::Network { .. } | SetupError::CustomNetwork(_) => JobPart::Solver,
            SetupError::LimitsWithDynamics { .. } => JobPart::Limits,
        }
    }
}

/// A TOML (or serde) error of an experiment file: its message, line and column, never the
/// source line (the input reader's, crate `inputs`).
pub use inputs::TomlError;

/// Why a `sweep` of an experiment file does not expand (see [`crate::sweep`]); each variant
/// names the field, and [`SweepError::In`] the experiment and variant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// The error of the variant `variant` (its label) of experiment `experiment` (its id).
    #[error("experiment[{experiment}] (id \"{id}\") variant[{variant}] (\"{label}\") {error}")]
    In {
        experiment: usize,
        id: String,
        variant: usize,
        label: String,
        error: Box<SweepError>,
    },
    /// The first expanded variant does not read as a variant (a misspelt swept field).
    #[error("field `sweep`: the expanded variant \"{expanded}\" does not read: {error} (check the swept keys: {})", keys.join(", "))]
    DoesNotRead {
        expanded: String,
        error: TomlError,
        keys: Vec<String>,
    },
    #[error("field `sweep`: must be a table of dotted keys and value lists, e.g. sweep = {{ \"scheme.mu\" = [0.5, 1, 2] }} (got {got})")]
    NotATable { got: &'static str },
    #[error("field `sweep`: is empty (give at least one key)")]
    Empty,
    #[error("field `id`: must be a string (the base of the expanded variants' ids), not {got}")]
    IdNotAString { got: &'static str },
    #[error("field `label`: a sweep variant needs a label (the template of the generated labels)")]
    NoLabel,
    #[error("field `sweep`: expands into more than {max} variants")]
    TooMany { max: usize },
    /// The variant's sweep fits on its own, but not beside the sweeps read before it.
    #[error("field `sweep`: with the sweeps before it (in this file and the files read before), the experiment files expand into more than {max} variants in all")]
    TooManyInAll { max: usize },
    #[error("field `sweep`: expanded variants {first} and {second} both get the label \"{label}\"; the label template must tell every value of every key apart (keys: {})", keys.join(", "))]
    SameLabel {
        first: usize,
        second: usize,
        label: String,
        keys: Vec<String>,
    },
    #[error("field `label`: placeholder {{{placeholder}}} names no swept key (known: {})", known.join(", "))]
    Placeholder {
        placeholder: String,
        known: Vec<String>,
    },
    /// A problem with one key of the sweep.
    #[error("field `sweep` key `{key}`: {error}")]
    Key { key: String, error: SweepKeyError },
}

/// What is wrong with one key of a `sweep` table (its dotted path or its values).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepKeyError {
    #[error("unknown key path: {0}")]
    Path(KeyPathError),
    #[error("the list of values is empty")]
    NoValues,
    #[error(transparent)]
    Range(#[from] RangeError),
    #[error("must be a list of values{} (got {got})", if *.group { " (each a list with one entry per path of the group)" } else { " or a range { from = a, to = b, step = s }" })]
    NotAList { group: bool, got: &'static str },
    #[error("value [{index}]: `label` must be a string")]
    LabelNotString { index: usize },
    #[error(
        "value [{index}] must be a list of {paths} entries, one per path of the group (got {got})"
    )]
    GroupValue {
        index: usize,
        paths: usize,
        got: String,
    },
}

/// Why a swept key's dotted path leads nowhere in the variant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KeyPathError {
    #[error("an empty segment")]
    EmptySegment,
    #[error("`{first}` is not a field of a variant (fields: {})", crate::fields::VARIANT_FIELDS.join(", "))]
    NotAField { first: String },
    #[error("`{done}` has no `{segment}` (give it on the variant to sweep inside it)")]
    NoKey { done: String, segment: String },
    #[error("`{done}` is an empty list")]
    EmptyList { done: String },
    #[error("`{done}` is a list: index it with 0, 1, ... or `*`, not `{segment}`")]
    BadIndex { done: String, segment: String },
    #[error("`{done}` has {len} entries, no [{index}]")]
    NoEntry {
        done: String,
        len: usize,
        index: usize,
    },
    #[error("`{done}` is a {kind}, not a table or a list")]
    NotContainer { done: String, kind: &'static str },
    #[error("the variant gives no `{done}` (write it on the variant, e.g. {done} = {{ ... }}, to sweep inside it)")]
    Missing { done: String },
}

/// Why a range `{ from, to, step }` of a sweep has no values.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RangeError {
    #[error("a range is {{ from = a, to = b, step = s }} (got keys: {})", keys.join(", "))]
    Keys { keys: Vec<String> },
    #[error("range from {from} to {to}: step {step} does not divide the interval")]
    IntegerStep { from: i64, to: i64, step: i64 },
    #[error("range has more than {max} values")]
    TooMany { max: usize },
    #[error("range `{key}` must be a finite number")]
    NotANumber { key: &'static str },
    #[error("range step is 0")]
    ZeroStep,
    #[error("range from {from} to {to}: step {step} does not divide the interval ((to - from) / step = {quotient})")]
    FloatStep {
        from: f64,
        to: f64,
        step: f64,
        quotient: f64,
    },
    #[error("range from {from} to {to}: step {step} points away from `to`")]
    Away { from: f64, to: f64, step: f64 },
}

/// Where in an experiment file a field is: the file's `paper`, an experiment's field, or a
/// variant's field.
#[derive(Clone, Debug, PartialEq)]
pub enum FieldAt {
    Paper,
    Experiment {
        index: usize,
        id: String,
        field: String,
    },
    Variant {
        experiment: usize,
        id: String,
        index: usize,
        label: String,
        field: String,
    },
}

impl std::fmt::Display for FieldAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FieldAt::Paper => write!(f, "field `paper`"),
            FieldAt::Experiment { index, id, field } => {
                write!(f, "experiment[{index}] (id \"{id}\") field `{field}`")
            }
            FieldAt::Variant {
                experiment,
                id,
                index,
                label,
                field,
            } => write!(
                f,
                "experiment[{experiment}] (id \"{id}\") variant[{index}] (\"{label}\") field `{field}`"
            ),
        }
    }
}

/// What is wrong with one field of an experiment file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FieldError {
    #[error(transparent)]
    Name(#[from] NameError),
    #[error("must start with the paper id \"{paper}-\"")]
    PaperPrefix { paper: String },
    #[error("experiment id \"{id}\" is used twice")]
    IdTwice { id: String },
    #[error("unknown robot \"{robot}\" (known: {known})")]
    UnknownRobot { robot: String, known: String },
    #[error("has {given} entries, the robot has {joints} joints")]
    Length { given: usize, joints: usize },
    #[error("entries must be finite")]
    NotFinite,
    /// The integrator settings' own check.
    #[error(transparent)]
    Integrator(IntegratorError),
    #[error("max-instants must be at least 1 (use scoring = \"off\" for no scoring)")]
    NoInstants,
    #[error("at least one [[experiment.variant]] is needed")]
    NoVariants,
    #[error("label \"{label}\" is used by two variants of the experiment")]
    LabelTwice { label: String },
    #[error("\"{id}\" is not an id: use lower-case ASCII letters, digits, `.` and single `-` (e.g. \"{suggestion}\")")]
    NotAnId { id: String, suggestion: String },
    #[error("variants \"{label}\" and \"{other}\" both have the id \"{id}\"{}; give one an `id`", if *derived { " (derived from the label)" } else { "" })]
    IdClash {
        label: String,
        other: String,
        id: String,
        derived: bool,
    },
    #[error("\"{kind}\" is not a solver kind of this variant (its runs: {kinds})")]
    UnknownFailureKind { kind: String, kinds: String },
    #[error("robot \"{robot}\" has {joints} joints; give theta0/theta_ref for it")]
    RobotJoints { robot: String, joints: usize },
    #[error(transparent)]
    Scheme(#[from] SchemeError),
    #[error("variant runs nothing (exact = false and no solvers)")]
    RunsNothing,
    #[error("joint {joint}: lower = {lower}, upper = {upper} (must be {requirement})")]
    LimitOrder {
        joint: usize,
        lower: f64,
        upper: f64,
        requirement: &'static str,
    },
    #[error(transparent)]
    Numerical(#[from] crate::numerical_spec::NumericalSpecError),
    /// A run of the variant cannot be built (robot, pose, path, scheme or network).
    #[error(transparent)]
    Setup(#[from] SetupError),
    #[error("run \"{key}\" is listed twice (experiment / variant / solver ids must be unique)")]
    RunTwice { key: String },
}

/// Why the text of an experiment file is not a valid experiment file (without the file name;
/// [`ExperimentFileError`] adds it). Wraps the TOML, sweep and field errors.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExperimentError {
    #[error(transparent)]
    Toml(#[from] TomlError),
    #[error(transparent)]
    Sweep(Box<SweepError>),
    /// (Boxed, as the sweep's: the field's place and error are large.)
    #[error("{at}: {error}")]
    Field {
        at: Box<FieldAt>,
        error: Box<FieldError>,
    },
}

impl From<SweepError> for ExperimentError {
    fn from(e: SweepError) -> Self {
        ExperimentError::Sweep(Box::new(e))
    }
}

/// A problem with an experiment file or the directory of them, naming the file (and, through
/// [`ExperimentError`], the field).
#[derive(Debug, thiserror::Error)]
pub enum ExperimentFileError {
    /// The file could not be read, or was refused (a link outside the experiments directory, a
    /// FIFO or device, over its cap): the input reader's error names the file.
    #[error(transparent)]
    Read(#[from] inputs::InputError),
    #[error("{}: {error}", file.display())]
    Invalid {
        file: PathBuf,
        error: ExperimentError,
    },
    #[error("{}: cannot list: {source}", dir.display())]
    List {
        dir: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: holds no experiment file (*.toml): nothing to run; give the directory of the experiment files (--experiments-dir)", dir.display())]
    NoFiles { dir: PathBuf },
    /// An experiment id defined in two files.
    #[error("{}: experiment[{index}] (id \"{id}\") field `id`: \"{id}\" is also defined in {}", file.display(), other_file.display())]
    DefinedTwice {
        file: PathBuf,
        index: usize,
        id: String,
        other_file: PathBuf,
    },
}
