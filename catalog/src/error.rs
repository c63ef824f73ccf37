//! The catalog's errors, each wrapping the layer below.
//!
//! - The experiment format: [`ExperimentFileError`] (the file) wraps [`ExperimentError`] (the
//!   text), which wraps [`TomlError`], [`SweepError`] (the sweep grammar) and [`FieldError`] at
//!   a [`FieldAt`] (which wraps `spec::SetupError`, the scheme specifications'
//!   `SchemeError` and the naming rules' `NameError`).
//! - Building a run's parts fails with `spec::SetupError` (crate `spec`, beside the run
//!   it describes): the engine (crate `simulation`) returns it when a run cannot be built, and
//!   the experiment format places it at the field at fault when the orchestrator checks a
//!   file's runs ([`crate::experiment::DeclaredRun::at_fault`]).
//!
//! A network's parameter errors (`settings::NetworkError`) and the integrator settings'
//! (`settings::IntegratorError`) are crate `settings`', below both this crate and the
//! solvers.

use settings::{shown, IntegratorError};
use spec::NameError;
use spec::SchemeError;
use std::path::PathBuf;

/// A TOML (or serde) error of an experiment file: its message, line and column, never the
/// source line (the input reader's, crate `inputs`).
pub use inputs::TomlError;

/// Why a `sweep` of an experiment file does not expand (the sweep grammar, `catalog/src/sweep.rs`); each variant
/// names the field, and [`SweepError::In`] the experiment and variant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// The error of the variant `variant` (its label) of experiment `experiment` (its id).
    #[error(
        "experiment[{experiment}] (id {}) variant[{variant}] ({}) {error}",
        shown(id),
        shown(label)
    )]
    In {
        /// The experiment's index in the file (from 0).
        experiment: usize,
        /// The experiment's id.
        id: String,
        /// The variant's index among the experiment's variants as written (from 0).
        variant: usize,
        /// The variant's label (the template), `?` when it has none.
        label: String,
        /// What is wrong with the sweep.
        error: Box<SweepError>,
    },
    /// The first expanded variant does not read as a variant (a misspelt swept field).
    #[error("field `sweep`: the expanded variant {} does not read: {error} (check the swept keys: {})", shown(expanded), keys.join(", "))]
    DoesNotRead {
        /// The expanded variant's label.
        expanded: String,
        /// Why it does not read (serde's error).
        error: TomlError,
        /// The swept keys, each as errors show a text ([`settings::shown`]).
        keys: Vec<String>,
    },
    /// `sweep` is not a table.
    #[error("field `sweep`: must be a table of dotted keys and value lists, e.g. sweep = {{ \"scheme.mu\" = [0.5, 1, 2] }} (got {got})")]
    NotATable {
        /// The TOML type given instead, e.g. `array`.
        got: &'static str,
    },
    /// `traces` is none of its choices.
    #[error("field `traces`: must be \"all\" (the default), \"none\" or {{ every = k }} with an integer k >= 1")]
    Traces,
    /// `sweep` is an empty table.
    #[error("field `sweep`: is empty (give at least one key)")]
    Empty,
    /// The variant's `id` is not a string.
    #[error("field `id`: must be a string (the base of the expanded variants' ids), not {got}")]
    IdNotAString {
        /// The TOML type given instead.
        got: &'static str,
    },
    /// The variant has no string `label` to serve as the template.
    #[error("field `label`: a sweep variant needs a label (the template of the generated labels)")]
    NoLabel,
    /// The variant's sweep alone expands into more than [`crate::sweep::MAX_EXPANSION`]
    /// variants.
    #[error("field `sweep`: expands into more than {max} variants")]
    TooMany {
        /// The limit, [`crate::sweep::MAX_EXPANSION`].
        max: usize,
    },
    /// The variant's sweep fits on its own, but not beside the sweeps read before it.
    #[error("field `sweep`: with the sweeps before it (in this file and the files read before), the experiment files expand into more than {max} variants in all")]
    TooManyInAll {
        /// The limit for all files together, [`crate::sweep::MAX_EXPANSION`].
        max: usize,
    },
    /// Two expanded variants get the same label.
    #[error("field `sweep`: expanded variants {first} and {second} both get the label {}; the label template must tell every value of every key apart (keys: {})", shown(label), keys.join(", "))]
    SameLabel {
        /// The first one's index in the expansion (from 0).
        first: usize,
        /// The second one's index in the expansion.
        second: usize,
        /// The label they share.
        label: String,
        /// The swept keys, each as errors show a text ([`settings::shown`]).
        keys: Vec<String>,
    },
    /// The sweep is larger than [`crate::sweep::CHECKED_WHOLE`] and its axes do not show its
    /// labels and ids distinct, and it is too large to compare them one by one.
    #[error("field `sweep`: its {variants} variants are more than {max} to compare their labels and ids one by one, and its axes do not show them distinct (for that the label must be no template, and every value of every key give a text without \", \" and a slug of one token, distinct within its key: docs/reference/sweeps.md); split it into smaller sweeps or change its values")]
    NamesUndecided {
        /// The sweep's variants.
        variants: usize,
        /// The most compared one by one, [`crate::sweep::NAMES_COMPARED`].
        max: usize,
    },
    /// Another variant's name begins as every label or id of a large sweep does: they might be
    /// the same.
    #[error("field `sweep`: every {what} of its variants begins with {}, and so does {} of another variant of the experiment: give one of them another {what}", shown(prefix), shown(name))]
    MayClash {
        /// `label` or `id`.
        what: &'static str,
        /// What the sweep's names begin with.
        prefix: String,
        /// The other name.
        name: String,
    },
    /// The label template has a placeholder that names no swept key.
    #[error("field `label`: placeholder {} names no swept key (known: {})", shown(&format!("{{{placeholder}}}")), shown_list(known))]
    Placeholder {
        /// The placeholder's name (without braces).
        placeholder: String,
        /// The names the template may use.
        known: Vec<String>,
    },
    /// Two keys of the sweep set the same field of the variant: the same path, two paths
    /// that meet through `*` (`solvers.*.gamma` and `solvers.0.gamma`), or a path and one
    /// under it (`scheme` and `scheme.mu`). Each would overwrite the other's value while the
    /// labels name both.
    #[error("field `sweep`: keys {} and {} both set {} of the variant, and the later would overwrite the earlier's values; a field may be set by one key of a sweep only", shown(first), shown(second), shown(field))]
    SameField {
        /// The first key (in the sweep table's order), as written.
        first: String,
        /// The second key, as written.
        second: String,
        /// The field both set (the deeper of the two, resolved against the variant: `*` as
        /// the entry it stands for), dotted.
        field: String,
    },
    /// Two paths of one zipped group set the same field of the variant (the same path twice,
    /// or paths that meet as in [`SweepError::SameField`]).
    #[error("field `sweep` key {}: its paths {} and {} both set {} of the variant; a zipped group sets each field once", shown(key), shown(first), shown(second), shown(field))]
    SameFieldInGroup {
        /// The group's key, as written.
        key: String,
        /// The first path (in the group's order), as written.
        first: String,
        /// The second path, as written.
        second: String,
        /// The field both set (as in [`SweepError::SameField`]), dotted.
        field: String,
    },
    /// A problem with one key of the sweep.
    #[error("field `sweep` key {}: {error}", shown(key))]
    Key {
        /// The key as written (several paths, comma-separated, for a zipped group).
        key: String,
        /// What is wrong with it.
        error: SweepKeyError,
    },
}

/// What is wrong with one key of a `sweep` table (its dotted path or its values).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepKeyError {
    /// The key has whitespace where the grammar has none: around it, inside a path, or before
    /// a comma (only spaces after a comma, between the paths of a zipped group, are allowed).
    #[error("whitespace in a key: a key is a dotted path without spaces (several joined by commas, a comma followed by spaces if wished: \"path.scale, path.reverse\")")]
    Whitespace,
    /// A dotted path of the key leads nowhere in the variant.
    #[error("unknown key path: {0}")]
    Path(KeyPathError),
    /// The list of values is empty.
    #[error("the list of values is empty")]
    NoValues,
    /// The key's range has no values.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// The values are neither a list nor (for a single path) a range table.
    #[error("must be a list of values{} (got {got})", if *.group { " (each a list with one entry per path of the group)" } else { " or a range { from = a, to = b, step = s }" })]
    NotAList {
        /// Whether the key is a zipped group of several paths (which takes no range).
        group: bool,
        /// The TOML type given instead.
        got: &'static str,
    },
    /// A labelled value's `label` is not a string.
    #[error("value [{index}]: `label` must be a string")]
    LabelNotString {
        /// The value's index in the list (from 0).
        index: usize,
    },
    /// A value of a zipped group is not a list with one entry per path.
    #[error(
        "value [{index}] must be a list of {paths} entries, one per path of the group (got {})",
        shown(got)
    )]
    GroupValue {
        /// The value's index in the list (from 0).
        index: usize,
        /// The number of paths in the group.
        paths: usize,
        /// The value given, as TOML writes it.
        got: String,
    },
}

/// Why a swept key's dotted path leads nowhere in the variant.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KeyPathError {
    /// The path has an empty segment (`a..b`, a leading or trailing dot).
    #[error("an empty segment")]
    EmptySegment,
    /// The first segment is not a field a sweep may set.
    #[error("{} is not a field of a variant (fields: {})", shown(first), crate::fields::VARIANT_FIELDS.join(", "))]
    NotAField {
        /// The first segment.
        first: String,
    },
    /// A table on the way lacks the next segment (only the last segment may be new).
    #[error(
        "{} has no {} (give it on the variant to sweep inside it)",
        shown(done),
        shown(segment)
    )]
    NoKey {
        /// The path to the table, dotted.
        done: String,
        /// The segment it lacks.
        segment: String,
    },
    /// `*` stands for every element of a list that has none.
    #[error("{} is an empty list", shown(done))]
    EmptyList {
        /// The path to the list, dotted.
        done: String,
    },
    /// A list is indexed by something that is neither a number nor `*`.
    #[error(
        "{} is a list: index it with 0, 1, ... or `*`, not {}",
        shown(done),
        shown(segment)
    )]
    BadIndex {
        /// The path to the list, dotted.
        done: String,
        /// The segment given as its index.
        segment: String,
    },
    /// A list index is past the list's end.
    #[error("{} has {len} entries, no [{index}]", shown(done))]
    NoEntry {
        /// The path to the list, dotted.
        done: String,
        /// The list's length.
        len: usize,
        /// The index given (from 0).
        index: usize,
    },
    /// The path goes on inside a value that is neither a table nor a list.
    #[error("{} is a {kind}, not a table or a list", shown(done))]
    NotContainer {
        /// The path to the value, dotted.
        done: String,
        /// Its TOML type.
        kind: &'static str,
    },
    /// The path goes inside a field the variant does not give.
    #[error("the variant gives no `{done}` (write it on the variant, e.g. {done} = {{ ... }}, to sweep inside it)")]
    Missing {
        /// The field.
        done: String,
    },
}

/// Why a range `{ from, to, step }` of a sweep has no values.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RangeError {
    /// The range table's keys are not exactly `from`, `to` and `step`.
    #[error(
        "a range is {{ from = a, to = b, step = s }} (got keys: {})",
        shown_list(keys)
    )]
    Keys {
        /// The keys given.
        keys: Vec<String>,
    },
    /// An integer range whose step is 0, does not divide `to - from` or points away from `to`.
    #[error("range from {from} to {to}: step {step} does not divide the interval")]
    IntegerStep {
        /// The first value.
        from: i64,
        /// The last value.
        to: i64,
        /// The step.
        step: i64,
    },
    /// The range has more than [`crate::sweep::MAX_EXPANSION`] values.
    #[error("range has more than {max} values")]
    TooMany {
        /// The limit, [`crate::sweep::MAX_EXPANSION`].
        max: usize,
    },
    /// An end or the step of a non-integer range is not a finite number.
    #[error("range `{key}` must be a finite number")]
    NotANumber {
        /// The key: `from`, `to` or `step`.
        key: &'static str,
    },
    /// A non-integer range's step is 0.
    #[error("range step is 0")]
    ZeroStep,
    /// A non-integer range's step does not divide `to - from` (to 1e-9).
    #[error("range from {from} to {to}: step {step} does not divide the interval ((to - from) / step = {quotient})")]
    FloatStep {
        /// The first value.
        from: f64,
        /// The last value.
        to: f64,
        /// The step.
        step: f64,
        /// (to - from) / step, which is not an integer.
        quotient: f64,
    },
    /// A non-integer range's step points away from `to`.
    #[error("range from {from} to {to}: step {step} points away from `to`")]
    Away {
        /// The first value.
        from: f64,
        /// The last value.
        to: f64,
        /// The step.
        step: f64,
    },
}

/// Where in an experiment file a field is: the file's `paper` or `title`, an experiment's
/// field, or a variant's field.
#[derive(Clone, Debug, PartialEq)]
pub enum FieldAt {
    /// The file's `paper` field.
    Paper,
    /// The file's `title` field.
    Title,
    /// A field of an experiment.
    Experiment {
        /// The experiment's index in the file (from 0).
        index: usize,
        /// The experiment's id.
        id: String,
        /// The field's name, e.g. `theta0` or `integrator`.
        field: String,
    },
    /// A field of a variant.
    Variant {
        /// The experiment's index in the file (from 0).
        experiment: usize,
        /// The experiment's id.
        id: String,
        /// The variant's index in the experiment, sweeps expanded (from 0).
        index: usize,
        /// The variant's label (an expanded sweep variant's generated one).
        label: String,
        /// The field's name, with the entry where it is a list, e.g. `scheme` or `solvers[1]`.
        field: String,
    },
}

impl std::fmt::Display for FieldAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FieldAt::Paper => write!(f, "field `paper`"),
            FieldAt::Title => write!(f, "field `title`"),
            FieldAt::Experiment { index, id, field } => {
                write!(f, "experiment[{index}] (id {}) field `{field}`", shown(id))
            }
            FieldAt::Variant {
                experiment,
                id,
                index,
                label,
                field,
            } => write!(
                f,
                "experiment[{experiment}] (id {}) variant[{index}] ({}) field `{field}`",
                shown(id),
                shown(label)
            ),
        }
    }
}

/// What is wrong with one field of an experiment file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FieldError {
    /// The id or label cannot name a file ([`spec::check_name`]).
    #[error(transparent)]
    Name(#[from] NameError),
    /// An id that is not a valid id of its kind (`spec::ids`).
    #[error(transparent)]
    Id(#[from] spec::ids::IdError),
    /// An experiment id does not start with the file's paper id and `-`.
    #[error("must start with the paper id {}", shown(&format!("{paper}-")))]
    PaperPrefix {
        /// The file's paper id.
        paper: String,
    },
    /// A text shown in listings and the report (the file's `title`, an experiment's
    /// `paper_output`) is not one line ([`settings::is_one_line`], the rule of a paper's title
    /// and citation).
    #[error("must be one line of text (no line breaks, control or formatting characters; it holds {found:?})")]
    NotOneLine {
        /// The first control or formatting character.
        found: char,
    },
    /// An experiment id is used twice in the file.
    #[error("experiment id {} is used twice", shown(id))]
    IdTwice {
        /// The id.
        id: String,
    },
    /// The robot is not one of the registry's, or its robot file is invalid.
    #[error("{reason}")]
    UnknownRobot {
        /// The name given.
        robot: String,
        /// The registry's error: the valid choices, or the robot file and field at fault.
        reason: String,
    },
    /// A joint vector (theta0, theta_ref) or a side of a limits override has not one entry per
    /// joint.
    #[error("has {given} entries, the robot has {joints} joints")]
    Length {
        /// The entries given.
        given: usize,
        /// The robot's joint count.
        joints: usize,
    },
    /// A joint vector or a side of a limits override has a NaN or infinite entry.
    #[error("entries must be finite")]
    NotFinite,
    /// The integrator settings' own check.
    #[error(transparent)]
    Integrator(IntegratorError),
    /// The experiment's scoring asks for 0 instants (`max-instants = 0`).
    #[error("max-instants must be at least 1 (use scoring = \"off\" for no scoring)")]
    NoInstants,
    /// The experiment has no variant.
    #[error("at least one [[experiment.variant]] is needed")]
    NoVariants,
    /// Two variants of the experiment have the same label.
    #[error("label {} is used by two variants of the experiment", shown(label))]
    LabelTwice {
        /// The label.
        label: String,
    },
    /// A paper, experiment or variant id is not in id form ([`spec::ids`]).
    #[error(
        "{} is not an id: use lower-case ASCII letters, digits, `.` and single `-` (e.g. {})",
        shown(id),
        shown(suggestion)
    )]
    NotAnId {
        /// The id as written.
        id: String,
        /// Its slug, an id it could be.
        suggestion: String,
    },
    /// Two variants of the experiment have the same id.
    #[error("variants {} and {} both have the id {}{}; give one an `id`", shown(label), shown(other), shown(id), if *derived { " (derived from the label)" } else { "" })]
    IdClash {
        /// The label of the variant found second.
        label: String,
        /// The label of the variant that has the id first.
        other: String,
        /// The id they share.
        id: String,
        /// Whether the second variant's id is its label's slug (it gives no `id`).
        derived: bool,
    },
    /// `expected_failure` names a solver kind none of the variant's runs has.
    #[error(
        "{} is not a solver kind of this variant (its runs: {kinds})",
        shown(kind)
    )]
    UnknownFailureKind {
        /// The kind named.
        kind: String,
        /// The solver kinds of the variant's runs, comma-separated.
        kinds: String,
    },
    /// A variant's robot has another joint count than the experiment's, and the variant gives
    /// no theta0 of its own (or no theta_ref, where the experiment gives one).
    #[error(
        "robot {} has {joints} joints; give theta0/theta_ref for it",
        shown(robot)
    )]
    RobotJoints {
        /// The variant's robot.
        robot: String,
        /// Its joint count.
        joints: usize,
    },
    /// A scheme parameter is out of its range ([`spec::SchemeSpec::validate`]).
    #[error(transparent)]
    Scheme(#[from] SchemeError),
    /// The variant runs nothing: no exact run, no solvers and no numerical methods.
    #[error("variant runs nothing (exact = false and no solvers)")]
    RunsNothing,
    /// A limits override does not fit the robot ([`spec::LimitsSpec::check`]).
    #[error(transparent)]
    Limits(#[from] spec::LimitsError),
    /// A numerical method's specification fails its check (`numerical[k]`).
    #[error(transparent)]
    Numerical(#[from] spec::NumericalSpecError),
    /// A run of the variant cannot be built (robot, pose, path, scheme or network).
    #[error(transparent)]
    Setup(#[from] spec::SetupError),
    /// Two runs of the variant have the same run key.
    #[error(
        "run {} is listed twice (experiment / variant / solver ids must be unique)",
        shown(key)
    )]
    RunTwice {
        /// The run key, `experiment / variant / solver`.
        key: String,
    },
}

/// Why the text of an experiment file is not a valid experiment file (without the file name;
/// [`ExperimentFileError`] adds it). Wraps the TOML, sweep and field errors.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExperimentError {
    /// The text is not TOML, or does not read as an experiment file (a missing, unknown or
    /// mistyped field).
    #[error(transparent)]
    Toml(#[from] TomlError),
    /// A variant's `sweep` does not expand.
    #[error(transparent)]
    Sweep(Box<SweepError>),
    /// A field's value is invalid. (Boxed, as the sweep's: the field's place and error are
    /// large.)
    #[error("{at}: {error}")]
    Field {
        /// Where the field is.
        at: Box<FieldAt>,
        /// What is wrong with it.
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
    /// The file's text is not a valid experiment file.
    #[error("{}: {error}", file.display())]
    Invalid {
        /// The file.
        file: PathBuf,
        /// What is wrong with its text.
        error: ExperimentError,
    },
    /// The experiments directory could not be listed.
    #[error("{}: cannot list: {source}", dir.display())]
    List {
        /// The directory.
        dir: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The experiments directory holds no `*.toml` file.
    #[error("{}: holds no experiment file (*.toml): nothing to run; give the directory of the experiment files (--experiments-dir)", dir.display())]
    NoFiles {
        /// The directory.
        dir: PathBuf,
    },
    /// An experiment id defined in two files.
    #[error("{}: experiment[{index}] (id {}) field `id`: {} is also defined in {}", file.display(), shown(id), shown(id), other_file.display())]
    DefinedTwice {
        /// The file read second (files are read in name order).
        file: PathBuf,
        /// The experiment's index in that file (from 0).
        index: usize,
        /// The experiment id.
        id: String,
        /// The file that defined it first.
        other_file: PathBuf,
    },
}

/// Why the control experiments' standard task set (`experiments/control/tasks.toml`,
/// [`crate::load_task_set`]) cannot be read; each names the file (`path`), and a budget field its
/// valid values.
#[derive(Debug, thiserror::Error)]
pub enum TaskSetError {
    /// The task set file is refused by the input reader (a link out of the experiments
    /// directory, not a regular file, over its cap, not UTF-8; the error names the path).
    #[error(transparent)]
    File(#[from] inputs::InputError),
    /// The task set file is not valid TOML or not a task set (`path` names it; the error gives
    /// line and column, never the file's text).
    #[error("{path}: {source}")]
    Toml {
        /// The file.
        path: String,
        /// The TOML error.
        source: TomlError,
    },
    /// The project declares no standard task set (a project of its own papers may have none).
    #[error("{0} does not exist: the project declares no control task set")]
    Missing(String),
    /// The task set lists no task (the file).
    #[error("{0}: the task set lists no [[task]]")]
    Empty(String),
    /// A field of the task set's `[budget]` is out of its range (`valid` says what it may be;
    /// the value is not quoted).
    #[error("{path}: [budget] {field} must be {valid}")]
    Budget {
        /// The file.
        path: String,
        /// The field of `[budget]`.
        field: &'static str,
        /// Its valid values.
        valid: &'static str,
    },
}

/// Texts (swept keys, placeholder names) as errors show them ([`settings::shown`]),
/// comma-separated.
fn shown_list(texts: &[String]) -> String {
    texts
        .iter()
        .map(|t| shown(t).to_string())
        .collect::<Vec<_>>()
        .join(", ")
}
