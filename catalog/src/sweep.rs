//! The sweep grammar of experiment files: one `[[experiment.variant]]` that stands for many.
//!
//! A variant may give a `sweep` table. Each entry names a parameter by its *dotted path* into
//! the variant table and lists the values it takes; the variant stands for the cartesian
//! product of the entries (the first entry outermost, the last one varying fastest), each copy
//! with its parameters set and its label generated. The sweep is kept as its *plan*
//! ([`Sweep`]): the base variant (the parsed TOML table without `sweep`), the axes (a list's
//! values as written, a range's three numbers), the label and id templates, and how many runs
//! each variant makes as a sum over the axes. No variant is held: variant i is made when
//! asked for, by its mixed-radix digits `d_a = (i / s_a) mod L_a` (L_a the length of axis a,
//! s_a the product of the later axes' lengths), built as a table and read by
//! [`crate::experiment::PaperFile::variant`], so a made variant is exactly the variant one
//! would have written by hand, and a sweep of 10^7 variants holds its axes, not 10^7 variants
//! (docs/cluster.md has the numbers). The runs of the variants below v are a prefix sum over
//! the axes that set `exact`, `solvers` or `numerical` (`RunCounts`), and the variant of a run
//! is found by bisection over it ([`Sweep::variant_of_run`]).
//!
//! **Checked at load** (docs/reference/sweeps.md): the grammar, every key path and the
//! template; the variants of [`Sweep::checked`] made, read and checked as data (and their runs
//! by the engine, in the orchestrator): all of a sweep of at most [`CHECKED_WHOLE`] variants,
//! else its *lines* (each value of a list, the ends of a range, with the other axes at their
//! first values) and the products of the axes that set one field together; the labels and ids
//! distinct, compared one by one for a sweep of at most [`CHECKED_WHOLE`] (or, when its axes
//! do not decide them, [`NAMES_COMPARED`]) variants, else decided from the axes
//! ([`Sweep::prefixes`], with its proof). Every variant made later is read and checked again
//! as it is made. Where the names are decided from the axes, an id is read back into its
//! variant's index from its tokens ([`IdReader`]), so whether a run key is described is
//! decided without making the sweep (`crate::RunLookup`).
//!
//! ```toml
//! [[experiment.variant]]
//! label = "ZNN (eq. 22)"
//! scheme = { kind = "znn-rmp", k_p = 1.0 }
//! solvers = [{ kind = "znn", gamma = 1.0 }]
//! sweep = { "scheme.mu" = [0.25, 0.5, 2, 4, 8] }
//! # -> "ZNN (eq. 22) [mu=0.25]", "ZNN (eq. 22) [mu=0.5]", "ZNN (eq. 22) [mu=2]", ...
//! ```
//!
//! **Keys** are dotted paths into the variant table: `"scheme.mu"`, `"path.scale"`,
//! `"theta0.2"` (an array index, 0-based), `"solvers.0.gamma"`, `"solvers.*.gamma"` (`*`: every
//! element of the array). The first segment must be a field of a variant (not `label`), every
//! table or array on the way must be given by the variant itself (write e.g. `path = { name =
//! "circle", duration = 9.0 }` on the variant to sweep `path.scale`), and the last segment may be
//! new (a field the base variant leaves at its default); a misspelt field is caught when the
//! expanded variant is read (serde's `unknown field`, with the sweep named). Several paths
//! joined by commas, `"path.scale, path.reverse"`, move *together* (a zipped group): each value
//! is then a list with one entry per path. A key has no whitespace but spaces after a comma
//! (`"solvers.*.gamma "`, `" scheme.mu"`, `"scheme. mu"`, a tab or a line break anywhere are
//! refused: [`SweepKeyError::Whitespace`]), so a path is exactly its text.
//!
//! **One key per field.** The paths are resolved against the variant (`*` into every entry of
//! the base's list, an index into its number), and no two keys, nor two paths of one zipped
//! group, may set the same field: the same path twice, `solvers.*.gamma` beside
//! `solvers.0.gamma`, or a path and one under it (`scheme` beside `scheme.mu`). Each would
//! overwrite the other's value while the labels name both, so they are refused at load
//! ([`SweepError::SameField`], [`SweepError::SameFieldInGroup`], naming both keys and the
//! field).
//!
//! **Values** are a non-empty TOML list (any TOML values: numbers, booleans, strings, tables,
//! lists), or a range `{ from = a, to = b, step = s }` (both ends included). A range counts
//! n = round((b - a) / s) steps and rejects a step that does not divide the interval to 1e-9;
//! its values are a + k s computed in decimal (from the shortest decimal forms of a and s), so
//! `{ from = 0.1, to = 0.3, step = 0.1 }` gives 0.1, 0.2, 0.3 and not 0.30000000000000004. A
//! range of integers gives integers. A list element may be a *labelled value*
//! `{ value = ..., label = "text" }` (a table with exactly these two keys): the text names the
//! value in the generated label instead of the value itself.
//!
//! **Labels.** The variant's `label` is a template. If it contains placeholders `{name}` —
//! `name` the last segment of a swept path (or the whole path, when two paths end alike) —
//! each is replaced by the text of that parameter's value: `label = "{phi} [{reverse}a={scale}]"`.
//! Otherwise the generated label is the label plus ` [k=v, k2=v2]`, k the last segment of each
//! path, in the order of the sweep table (a labelled value contributes its text alone, and
//! nothing when its text is empty). A value's text is its label when labelled, otherwise the
//! value as TOML writes it: `2` for the integer 2, `2.0` for the float 2.0, `0.25`, `true`,
//! strings without quotes.
//!
//! **Ids.** When the variant declares an `id`, each expanded variant's id is that id followed
//! by every swept path's last segment and raw value, slugged: `id = "znn"` with
//! `"scheme.mu" = [0.25]` gives `znn-mu-0.25`. Labelled values enter by their value, so ids do
//! not move when labels are reworded. Without an `id`, the expanded label's slug is the id.
//!
//! **Order.** Keys keep the order written in the file: the workspace enables the `toml` crate's
//! `preserve_order` feature, so tables are insertion-ordered.
//!
//! **Traces.** A sweep variant may say which of its runs keep their trace (the thinned time
//! history under `traces/`): `traces = "all"` (the default), `"none"` or `{ every = k }`
//! (k >= 1). The runs of the variant are enumerated as they are made (expanded variant by
//! expanded variant, each one's exact column first), from 0; with `{ every = k }` run i keeps
//! its trace exactly when i mod k = 0 ([`KeptTraces::keeps`]). Every run writes its row
//! whatever the choice; the field is read here and taken off the base variant, so it is no
//! field of an expanded variant (a variant without a sweep refuses it as an unknown field).
//!
//! **Errors** name the experiment, the variant and the key (the file is added by
//! [`crate::experiment::PaperFile::load`]; a key is shown as every error shows a user's text,
//! quoted with its control and formatting characters escaped, [`settings::shown`]): an
//! unknown key path, whitespace in a key, two keys (or two paths of a group) that set one
//! field, an empty list, a swept key that is neither a list nor a range, a bad range, a zipped
//! value of the wrong length, a placeholder that names no swept key, a variant that does not
//! read, two variants with the same label, and a large sweep whose names cannot be shown
//! distinct.

use crate::error::{KeyPathError, RangeError, SweepError, SweepKeyError};
use crate::fields::VARIANT_FIELDS;
use std::num::NonZeroUsize;
use toml::{Table, Value};

/// Which runs of a sweep keep their trace: the sweep variant's `traces` field (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Traces {
    /// Every run (`"all"`, the default).
    #[default]
    All,
    /// No run (`"none"`): the rows alone.
    None,
    /// The runs whose index in the variant's enumeration is a multiple of k (`{ every = k }`).
    Every(NonZeroUsize),
}

impl Traces {
    /// Reads the `traces` field's value: `"all"`, `"none"` or `{ every = k }` with an integer
    /// k >= 1 (the error names the field and the choices, never the value given).
    fn parse(v: &Value) -> Result<Self, SweepError> {
        match v {
            Value::String(s) if s == "all" => Ok(Traces::All),
            Value::String(s) if s == "none" => Ok(Traces::None),
            Value::Table(t) if t.len() == 1 => match t.get("every") {
                Some(Value::Integer(k)) => usize::try_from(*k)
                    .ok()
                    .and_then(NonZeroUsize::new)
                    .map(Traces::Every)
                    .ok_or(SweepError::Traces),
                _ => Err(SweepError::Traces),
            },
            _ => Err(SweepError::Traces),
        }
    }
}

/// The trace choice of one expanded variant: its sweep's [`Traces`] and the index of its first
/// run in the sweep's enumeration of runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KeptTraces {
    /// The sweep's choice.
    pub traces: Traces,
    /// The index of the variant's first run among the sweep's runs (from 0).
    pub first_run: usize,
}

impl KeptTraces {
    /// Whether the variant's run `run` (from 0, exact column first) keeps its trace: always
    /// with [`Traces::All`], never with [`Traces::None`], and with [`Traces::Every`] k when
    /// `first_run + run` is a multiple of k.
    pub fn keeps(&self, run: usize) -> bool {
        match self.traces {
            Traces::All => true,
            Traces::None => false,
            Traces::Every(k) => (self.first_run + run).is_multiple_of(k.get()),
        }
    }
}

/// Most variants one sweep may stand for, and most the sweeps of a whole experiments directory
/// may stand for together (twenty variants of 999,999,999 each must not either): a sweep's
/// plan takes what is left of it. A sweep is kept as its plan and no variant is held, so this
/// bounds arithmetic, not memory: a run's variant is found by bisection over the variants (at
/// most 30 steps of O(axes) each), so a process's planning cost per run it makes stays bounded,
/// and a sweep of 10^7 or 10^8 runs loads in the time of its axes.
pub const MAX_EXPANSION: usize = 1_000_000_000;

/// A sweep of at most this many variants is checked whole at load, as before plans: every
/// variant made, read, checked and dropped, and the labels and ids of all compared. A larger
/// one is checked by its lines (`Sweep::checked`) and its names decided from its axes
/// (`Sweep::prefixes`); every variant made later is checked again as it is made.
pub const CHECKED_WHOLE: usize = 1 << 16;

/// Most variants of one sweep whose labels and ids are compared one by one (as 16-byte
/// prints, dropped after the load) when its axes do not show them distinct; a larger sweep
/// whose axes do not is refused ([`SweepError::NamesUndecided`]).
pub const NAMES_COMPARED: usize = 1 << 20;

/// Whether any variant of the parsed file gives a `sweep`.
pub fn has_sweeps(doc: &Table) -> bool {
    experiments(doc).any(|e| variants(e).any(|v| v.contains_key("sweep")))
}

fn experiments(doc: &Table) -> impl Iterator<Item = &Table> {
    doc.get("experiment")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(Value::as_table)
}

fn variants(e: &Table) -> impl Iterator<Item = &Table> {
    e.get("variant")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .filter_map(Value::as_table)
}

/// The sweep variants of a parsed experiment file, taken out of it ([`take_sweeps`]) so that
/// the rest of the file is read as usual, then read into their plans ([`Sweeps::plan`]).
#[derive(Debug)]
pub struct Sweeps(Vec<(Place, Table)>);

/// Where a sweep variant stood in its file, for its errors.
#[derive(Clone, Debug)]
struct Place {
    /// Index of its experiment in the file, and the experiment's id.
    experiment: usize,
    id: String,
    /// Its index among the experiment's variants as written.
    variant: usize,
    /// Its label (the template), `?` when it has none.
    label: String,
}

impl Place {
    /// `error`, placed at this sweep variant.
    fn wrap(&self, error: SweepError) -> SweepError {
        SweepError::In {
            experiment: self.experiment,
            id: self.id.clone(),
            variant: self.variant,
            label: self.label.clone(),
            error: Box::new(error),
        }
    }
}

/// Takes every variant with a `sweep` out of the parsed experiment file `doc` (the other
/// variants stay, in order), to be read into plans by [`Sweeps::plan`] once the file is read.
pub fn take_sweeps(doc: &mut Table) -> Sweeps {
    let mut out = Vec::new();
    let Some(Value::Array(exps)) = doc.get_mut("experiment") else {
        return Sweeps(out);
    };
    for (i, e) in exps.iter_mut().enumerate() {
        let Value::Table(e) = e else { continue };
        let id = e
            .get("id")
            .and_then(Value::as_str)
            .unwrap_or("?")
            .to_string();
        let Some(Value::Array(vars)) = e.get_mut("variant") else {
            continue;
        };
        let mut kept = Vec::with_capacity(vars.len());
        for (j, v) in std::mem::take(vars).into_iter().enumerate() {
            match v {
                Value::Table(table) if table.contains_key("sweep") => {
                    let label = table
                        .get("label")
                        .and_then(Value::as_str)
                        .unwrap_or("?")
                        .to_string();
                    let place = Place {
                        experiment: i,
                        id: id.clone(),
                        variant: j,
                        label,
                    };
                    out.push((place, table));
                }
                other => kept.push(other),
            }
        }
        *vars = kept;
    }
    Sweeps(out)
}

/// Where a sweep goes: its experiment's index in the file and its index among that
/// experiment's variants as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SweepSlot {
    /// The experiment's index in the file.
    pub experiment: usize,
    /// The variant's index among the experiment's variants as written.
    pub variant: usize,
}

impl Sweeps {
    /// Reads every sweep into its plan, in file order, with where it goes. At most `budget`
    /// variants in all (what is left of [`MAX_EXPANSION`] for the files read so far; reduced
    /// by what this file takes); nothing is expanded.
    pub fn plan(self, budget: &mut usize) -> Result<Vec<(SweepSlot, Sweep)>, SweepError> {
        self.0
            .into_iter()
            .map(|(place, table)| {
                let sweep =
                    Sweep::new(&table, *budget, place.clone()).map_err(|e| place.wrap(e))?;
                *budget -= sweep.total;
                let slot = SweepSlot {
                    experiment: place.experiment,
                    variant: place.variant,
                };
                Ok((slot, sweep))
            })
            .collect()
    }
}

/// One axis of a sweep: the paths it sets (several: a zipped group) and its values.
#[derive(Clone, Debug)]
struct Axis {
    key: String,
    paths: Vec<Vec<String>>,
    values: Values,
}

/// The values of an axis: a list as written, or a range computed value by value.
#[derive(Clone, Debug)]
enum Values {
    /// Per value: the value of each path, and the text that names it (a labelled value's).
    List(Vec<(Vec<Value>, Option<String>)>),
    Range(Range),
}

impl Axis {
    fn len(&self) -> usize {
        match &self.values {
            Values::List(l) => l.len(),
            Values::Range(r) => r.len(),
        }
    }

    /// Value `k`: the value of each path, and its label's text when labelled.
    fn value(&self, k: usize) -> (Vec<Value>, Option<String>) {
        match &self.values {
            Values::List(l) => l[k].clone(),
            Values::Range(r) => (vec![r.value(k)], None),
        }
    }

    /// The values checked at load with the other axes at their first: every value of a list
    /// (it is as long as its file), the two ends of a range (its values differ only in
    /// magnitude; a variant made later is checked again as it is made).
    fn checked(&self) -> Vec<usize> {
        match &self.values {
            Values::List(l) => (0..l.len()).collect(),
            Values::Range(r) if r.len() > 1 => vec![0, r.len() - 1],
            Values::Range(_) => vec![0],
        }
    }
}

/// A sweep read and checked, its variants not built: the base variant (without `sweep`), the
/// axes, the label and id templates, the size of the product and how many runs each variant
/// makes. Variant i of the product has digit `(i / s_a) mod L_a` on axis a (L_a its length,
/// s_a the product of the later axes' lengths): the first axis outermost, the last fastest,
/// the order the sweep was always expanded in.
#[derive(Clone, Debug)]
pub struct Sweep {
    place: Place,
    base: Table,
    axes: Vec<Axis>,
    template: String,
    names: Vec<(String, usize, usize)>,
    id_template: Option<String>,
    total: usize,
    traces: Traces,
    /// Per axis, s_a.
    strides: Vec<usize>,
    /// The runs of each variant: every run, and the exact column alone.
    all: RunCounts,
    exact: RunCounts,
}

/// The runs a variant of a sweep makes, as a sum over the axes. A variant makes
/// `exact + len(solvers) + len(numerical)` runs (`Variant::run_count`); each of these fields
/// is set by the axis whose path is the field itself (one at most: two keys that set one field
/// are refused, [`SweepError::SameField`]), or else by the base variant. So a
/// variant's count is a constant (the fields no axis sets) plus, per axis, a term of its digit
/// alone, c_a(d_a), and the runs of the variants below v are
///
/// ```text
/// R(v) = v c + sum_a [ floor(v / (s_a L_a)) s_a C_a(L_a) + s_a C_a(q_a) + r_a c_a(q_a) ]
/// ```
///
/// with `q_a = (v mod s_a L_a) div s_a`, `r_a = v mod s_a` and C_a(x) the sum of c_a over the
/// values below x: each full period of axis a holds every value s_a times, and the partial one
/// the values below q_a s_a times and q_a r_a times.
#[derive(Clone, Debug, Default)]
struct RunCounts {
    constant: usize,
    axes: Vec<AxisRuns>,
}

/// One axis's term of [`RunCounts`].
#[derive(Clone, Debug)]
struct AxisRuns {
    stride: usize,
    per_value: Vec<usize>,
    /// `below[x]`: the sum of `per_value` below x (x = 0..=L).
    below: Vec<usize>,
}

impl RunCounts {
    /// The counted fields of `fields` for `base` and `axes` (module docs of [`RunCounts`]).
    fn new(fields: &[&str], base: &Table, axes: &[Axis], strides: &[usize]) -> Self {
        let mut constant = 0;
        let mut per_axis: Vec<Option<Vec<usize>>> = vec![None; axes.len()];
        for field in fields {
            // The axis whose path is the field itself sets it (one at most, `FieldsSet`).
            let setter = axes.iter().enumerate().rev().find_map(|(a, axis)| {
                let p = axis
                    .paths
                    .iter()
                    .position(|p| p.len() == 1 && p[0] == *field)?;
                Some((a, p))
            });
            match setter {
                None => constant += runs_of(field, base.get(*field)),
                Some((a, p)) => match &axes[a].values {
                    Values::List(l) => {
                        let counts = per_axis[a].get_or_insert_with(|| vec![0; l.len()]);
                        for (c, (v, _)) in counts.iter_mut().zip(l) {
                            *c += runs_of(field, Some(&v[p]));
                        }
                    }
                    // A range's values are numbers: no count field reads one (refused at load).
                    Values::Range(_) => {}
                },
            }
        }
        let axes = per_axis
            .into_iter()
            .zip(strides)
            .filter_map(|(counts, &stride)| {
                let per_value = counts?;
                let mut below = Vec::with_capacity(per_value.len() + 1);
                let mut sum = 0;
                below.push(0);
                for c in &per_value {
                    sum += c;
                    below.push(sum);
                }
                Some(AxisRuns {
                    stride,
                    per_value,
                    below,
                })
            })
            .collect();
        RunCounts { constant, axes }
    }

    /// The runs of the variants below v.
    fn before(&self, v: usize) -> usize {
        let mut n = v * self.constant;
        for a in &self.axes {
            let len = a.per_value.len();
            let period = a.stride * len;
            let (full, m) = (v / period, v % period);
            let (q, r) = (m / a.stride, m % a.stride);
            n += full * a.stride * a.below[len] + a.stride * a.below[q] + r * a.per_value[q];
        }
        n
    }
}

/// How many runs the field `field` of a variant adds when its value is `v` (absent: the
/// default): `exact` (default true) one or none, `solvers` and `numerical` one per entry. A
/// value of another type adds none: such a variant does not read, and the load refuses it.
fn runs_of(field: &str, v: Option<&Value>) -> usize {
    match (field, v) {
        ("exact", None) => 1,
        ("exact", Some(Value::Boolean(b))) => usize::from(*b),
        (_, Some(Value::Array(a))) => a.len(),
        _ => 0,
    }
}

/// The fields whose values set how many runs a variant makes.
const RUN_FIELDS: [&str; 3] = ["exact", "solvers", "numerical"];

/// What every id and every label of a sweep begins with, when its axes show them distinct
/// ([`Sweep::prefixes`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Prefixes {
    /// Every id's beginning.
    pub id: String,
    /// Every label's beginning.
    pub label: String,
}

impl Sweep {
    /// Reads the sweep of `variant` into at most `budget` variants (of the [`MAX_EXPANSION`] a
    /// directory's sweeps share), the product checked as each axis is read.
    fn new(variant: &Table, budget: usize, place: Place) -> Result<Self, SweepError> {
        let mut base = variant.clone();
        let sweep = match base.remove("sweep") {
            Some(Value::Table(s)) if !s.is_empty() => s,
            Some(Value::Table(_)) | None => return Err(SweepError::Empty),
            Some(other) => {
                return Err(SweepError::NotATable {
                    got: other.type_str(),
                })
            }
        };
        let traces = base
            .remove("traces")
            .map_or(Ok(Traces::All), |v| Traces::parse(&v))?;
        let template = match base.get("label") {
            Some(Value::String(s)) => s.clone(),
            _ => return Err(SweepError::NoLabel),
        };
        let id_template = match base.get("id") {
            None => None,
            Some(Value::String(s)) => Some(s.clone()),
            Some(other) => {
                return Err(SweepError::IdNotAString {
                    got: other.type_str(),
                })
            }
        };
        let mut axes: Vec<Axis> = Vec::with_capacity(sweep.len());
        let mut total = 1usize;
        let mut fields = FieldsSet::default();
        for (key, val) in &sweep {
            let (axis, axis_fields) = parse_axis(&base, key, val)?;
            for (p, set) in axis_fields.into_iter().enumerate() {
                fields.add(&axes, &axis, p, set)?;
            }
            total = total
                .checked_mul(axis.len())
                .filter(|n| *n <= MAX_EXPANSION)
                .ok_or(SweepError::TooMany { max: MAX_EXPANSION })?;
            if total > budget {
                return Err(SweepError::TooManyInAll { max: MAX_EXPANSION });
            }
            axes.push(axis);
        }
        let names = placeholder_names(&axes);
        check_template(&template, &names)?;
        let mut strides = vec![1; axes.len()];
        for a in (0..axes.len().saturating_sub(1)).rev() {
            strides[a] = strides[a + 1] * axes[a + 1].len();
        }
        let all = RunCounts::new(&RUN_FIELDS, &base, &axes, &strides);
        let exact = RunCounts::new(&RUN_FIELDS[..1], &base, &axes, &strides);
        Ok(Sweep {
            place,
            base,
            axes,
            template,
            names,
            id_template,
            total,
            traces,
            strides,
            all,
            exact,
        })
    }

    /// How many variants the sweep stands for.
    pub fn len(&self) -> usize {
        self.total
    }

    /// The runs of the variants below `v` (every run, or the exact column alone).
    pub fn runs_before(&self, v: usize, exact_only: bool) -> usize {
        if exact_only {
            self.exact.before(v)
        } else {
            self.all.before(v)
        }
    }

    /// The variant that holds run `r` of the sweep (every run, or the exact column alone; `r`
    /// below [`Sweep::runs_before`] of the whole sweep): the last v with R(v) <= r, found by
    /// bisection (R is non-decreasing).
    pub fn variant_of_run(&self, r: usize, exact_only: bool) -> usize {
        let (mut lo, mut hi) = (0, self.total);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if self.runs_before(mid, exact_only) <= r {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// The digits of variant `v` (module docs of [`Sweep`]).
    fn digits(&self, v: usize) -> Vec<usize> {
        self.axes
            .iter()
            .zip(&self.strides)
            .map(|(a, s)| (v / s) % a.len())
            .collect()
    }

    /// The values of variant `v`, axis by axis.
    fn values(&self, v: usize) -> Vec<(Vec<Value>, Option<String>)> {
        self.digits(v)
            .into_iter()
            .zip(&self.axes)
            .map(|(d, a)| a.value(d))
            .collect()
    }

    /// The label and id of variant `v` (the id `None` without a declared one: the label's
    /// slug), made from the axes alone.
    pub fn names(&self, v: usize) -> (String, Option<String>) {
        let values = self.values(v);
        let label = make_label(&self.template, &self.axes, &values, &self.names);
        let id = self
            .id_template
            .as_ref()
            .map(|id| make_id(id, &self.axes, &values));
        (label, id)
    }

    /// Variant `v` as a table (what one would have written by hand), and the trace choice of
    /// its runs.
    pub fn table(&self, v: usize) -> (Table, KeptTraces) {
        let values = self.values(v);
        let mut t = self.base.clone();
        for (a, (vals, _)) in self.axes.iter().zip(&values) {
            for (path, value) in a.paths.iter().zip(vals) {
                set(&mut t, path, value.clone());
            }
        }
        if let Some(id) = &self.id_template {
            t.insert(
                "id".to_string(),
                Value::String(make_id(id, &self.axes, &values)),
            );
        }
        let label = make_label(&self.template, &self.axes, &values, &self.names);
        t.insert("label".to_string(), Value::String(label));
        (t, self.traces(v))
    }

    /// The trace choice of variant `v`'s runs: the sweep's, and the index of its first run
    /// among the sweep's runs (from the axes, no variant made).
    pub fn traces(&self, v: usize) -> KeptTraces {
        KeptTraces {
            traces: self.traces,
            first_run: self.all.before(v),
        }
    }

    /// The id of variant `v` (the declared id's expansion, or the label's slug), made from the
    /// axes alone.
    pub fn id(&self, v: usize) -> String {
        let values = self.values(v);
        match &self.id_template {
            Some(id) => make_id(id, &self.axes, &values),
            None => settings::slug(&make_label(
                &self.template,
                &self.axes,
                &values,
                &self.names,
            )),
        }
    }

    /// The digits of variant `v` on the axes that set a field counted in its runs (`exact`,
    /// `solvers`, `numerical`: a path of the axis begins with one), in axis order. The runs
    /// of a variant, and their solvers' ids, are its fields `exact`, `solvers` and
    /// `numerical`, which the base variant and these axes alone set: two variants with the
    /// same such digits make runs of the same solvers, in the same order.
    pub fn run_digits(&self, v: usize) -> Vec<usize> {
        self.axes
            .iter()
            .zip(self.digits(v))
            .filter(|(a, _)| a.paths.iter().any(|p| RUN_FIELDS.contains(&p[0].as_str())))
            .map(|(_, d)| d)
            .collect()
    }

    /// The reader of the sweep's ids back into variant indices ([`IdReader`]), when its
    /// names are decided from its axes ([`Sweep::prefixes`]); `None` otherwise (its ids are
    /// then compared as they are made).
    pub fn id_reader(&self) -> Option<IdReader<'_>> {
        self.prefixes()?;
        let by_label = self.id_template.is_none();
        let tokens = |text: &str| {
            let s = settings::slug(text);
            if s.is_empty() {
                0
            } else {
                s.split('-').count()
            }
        };
        let mut at = tokens(self.id_template.as_deref().unwrap_or(&self.template));
        let mut axes = Vec::with_capacity(self.axes.len());
        for a in &self.axes {
            let labelled = by_label && matches!(&a.values, Values::List(l) if l[0].1.is_some());
            let mut places = Vec::with_capacity(a.paths.len());
            if labelled {
                places.push(at);
                at += 1;
            } else {
                for p in &a.paths {
                    at += tokens(p.last().expect("non-empty path"));
                    places.push(at);
                    at += 1;
                }
            }
            let values = match &a.values {
                Values::Range(r) => ValueTokens::Range(r),
                Values::List(l) => ValueTokens::List(
                    l.iter()
                        .enumerate()
                        .map(|(k, (vals, label))| {
                            let token = match label {
                                Some(text) if labelled => settings::slug(text),
                                _ => vals
                                    .iter()
                                    .map(|v| settings::slug(&display(v)))
                                    .collect::<Vec<_>>()
                                    .join("-"),
                            };
                            (token, k)
                        })
                        .collect(),
                ),
            };
            axes.push(AxisTokens { places, values });
        }
        Some(IdReader {
            sweep: self,
            tokens: at,
            axes,
        })
    }

    /// The error that variant `v` does not read (`error`), placed at the sweep.
    pub fn does_not_read(&self, v: usize, error: toml::de::Error) -> SweepError {
        self.place.wrap(SweepError::DoesNotRead {
            expanded: self.names(v).0,
            error: error.into(),
            keys: self.keys(),
        })
    }

    /// `error`, placed at the sweep.
    pub fn error(&self, error: SweepError) -> SweepError {
        self.place.wrap(error)
    }

    /// The swept keys, quoted (for errors) as errors show a text ([`settings::shown`]).
    pub fn keys(&self) -> Vec<String> {
        self.axes
            .iter()
            .map(|a| settings::shown(&a.key).to_string())
            .collect()
    }

    /// The variants checked at load, in order: every one of a sweep of at most
    /// [`CHECKED_WHOLE`]; of a larger one its *lines*, each checked value of each axis
    /// ([`Axis::checked`]: a list's every value, a range's two ends) with the other axes at
    /// their first values, and, for the axes that set the same field of the variant (a swept
    /// `scheme.kind` beside `scheme.mu`: one table read together), the product of their
    /// checked values when it is at most 4,096. A variant made later is checked again as it is
    /// made (the data checks; the engine's when its runs are built).
    pub fn checked(&self) -> Vec<usize> {
        if self.total <= CHECKED_WHOLE {
            return (0..self.total).collect();
        }
        let mut out = vec![0];
        for (a, s) in self.axes.iter().zip(&self.strides) {
            out.extend(a.checked().into_iter().map(|x| x * s));
        }
        for group in self.interacting() {
            let mut product = vec![0usize];
            for &a in &group {
                let values = self.axes[a].checked();
                if product.len() * values.len() > 4096 {
                    product.clear();
                    break;
                }
                product = product
                    .iter()
                    .flat_map(|p| values.iter().map(move |x| p + x * self.strides[a]))
                    .collect();
            }
            out.extend(product);
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The groups of two or more axes that set the same field of the variant (the first
    /// segment of one of their paths), each in axis order.
    fn interacting(&self) -> Vec<Vec<usize>> {
        let mut groups: Vec<Vec<usize>> = Vec::new();
        let fields: Vec<Vec<&str>> = self
            .axes
            .iter()
            .map(|a| a.paths.iter().map(|p| p[0].as_str()).collect())
            .collect();
        for a in 0..self.axes.len() {
            let joined: Vec<usize> = (0..groups.len())
                .filter(|&g| {
                    groups[g]
                        .iter()
                        .any(|&b| fields[b].iter().any(|f| fields[a].contains(f)))
                })
                .collect();
            let mut group = vec![a];
            for &g in joined.iter().rev() {
                group.extend(groups.remove(g));
            }
            group.sort_unstable();
            groups.push(group);
        }
        groups.retain(|g| g.len() > 1);
        groups
    }

    /// What every id and every label of the sweep begins with, when its axes show its labels
    /// and ids distinct; `None` when they do not (then they are compared one by one). They do
    /// when the label is no template and every value of every axis gives
    ///
    /// - a text without `, ` that is not empty (a labelled value's text, else `k=v` per path;
    ///   every value of the axis labelled, or none, so each gives as many parts and tokens),
    ///   and distinct texts per axis;
    /// - a slug of exactly one token (no `-`, not empty) for each path's raw value (and for a
    ///   labelled value's text when the ids are the labels' slugs), distinct per axis.
    ///
    /// Proof. A label is `T [p_1, ..., p_m]`, the parts p in axis order; with no part empty or
    /// holding `, ` and a fixed number of parts per axis, the text between `T [` and the last
    /// `]` splits at `, ` into the parts one way only, so the part of each axis is at a fixed
    /// place and two variants that differ on an axis (distinct texts per axis) have distinct
    /// labels. An id is the slug of `id k_1=v_1 ...` (or of the label): a slug is the text's
    /// runs of `[a-z0-9.]` joined by `-`, so the id's tokens are the fixed text's tokens with
    /// each value's slug at a fixed place when each is one token; two variants that differ on
    /// an axis (distinct slugs per axis) differ in the token at that place. A range's values
    /// are written as plain decimals (Rust writes no exponent) with at most a sign, so its
    /// slug is one token; they are distinct slugs when the range does not cross zero (the
    /// sign is not in the slug) and distinct numbers when its step is more than 4 epsilon of
    /// its largest end (consecutive values then round apart).
    ///
    /// The prefixes: every label begins with `T [` (and `k=`, k the first axis's first key,
    /// when its values are not labelled), every id with the slug of the declared id (or of T;
    /// and of k) and `-`.
    pub fn prefixes(&self) -> Option<Prefixes> {
        if !placeholders(&self.template).is_empty() {
            return None;
        }
        let by_label = self.id_template.is_none();
        for a in &self.axes {
            match &a.values {
                Values::Range(r) => {
                    if !r.distinct_slugs() {
                        return None;
                    }
                }
                Values::List(values) => {
                    let mut texts = std::collections::HashSet::new();
                    let mut slugs = std::collections::HashSet::new();
                    let labelled = values[0].1.is_some();
                    for (vals, label) in values {
                        let raw: Vec<String> =
                            vals.iter().map(|v| settings::slug(&display(v))).collect();
                        if !raw.iter().all(|s| one_token(s)) || label.is_some() != labelled {
                            return None;
                        }
                        let text: Vec<String> = match label {
                            Some(l) => vec![l.clone()],
                            None => a
                                .paths
                                .iter()
                                .zip(vals)
                                .map(|(p, v)| {
                                    format!("{}={}", p.last().expect("non-empty path"), display(v))
                                })
                                .collect(),
                        };
                        if text.iter().any(|t| t.is_empty() || t.contains(", ")) {
                            return None;
                        }
                        let slug = match label {
                            Some(l) if by_label => {
                                let s = settings::slug(l);
                                if !one_token(&s) {
                                    return None;
                                }
                                vec![s]
                            }
                            _ => raw,
                        };
                        if !texts.insert(text) || !slugs.insert(slug) {
                            return None;
                        }
                    }
                }
            }
        }
        // The first axis's first key follows when its values are not labelled.
        let first = &self.axes[0];
        let key = match &first.values {
            Values::List(l) if l.iter().any(|(_, label)| label.is_some()) => String::new(),
            _ => first.paths[0].last().expect("non-empty path").clone(),
        };
        let base = self.id_template.as_deref().unwrap_or(&self.template);
        if settings::slug(base).is_empty() {
            return None;
        }
        let id = match (key.is_empty(), by_label) {
            (true, _) => settings::slug(base),
            (false, true) => settings::slug(&format!("{base} [{key}")),
            (false, false) => settings::slug(&format!("{base} {key}")),
        };
        let label = match key.is_empty() {
            true => format!("{} [", self.template),
            false => format!("{} [{key}=", self.template),
        };
        Some(Prefixes {
            id: format!("{id}-"),
            label,
        })
    }
}

/// A sweep's ids read back into its variants' indices, for a sweep whose names are decided
/// from its axes ([`Sweep::prefixes`]): every value's slug in an id is then one token (a raw
/// value's, or a labelled value's text's when the ids are the labels' slugs), so an id has a
/// fixed number of tokens (the slug's runs of `[a-z0-9.]`, joined by `-`) and the value of
/// axis a stands at fixed places: after the declared id's (or the label's) tokens, per axis
/// and path the key's tokens and then the value's one token (a labelled value of a label's
/// slug: its text's one token alone). Those tokens name one value of the axis (slugs
/// distinct per axis): a list's by a map from its values' slugs, a range's by arithmetic (its
/// values do not cross zero, so the sign the slug drops is the range's). The digits give the
/// variant `v = sum_a d_a s_a`, and `v` is the answer only when its id, made again from the
/// axes, is the id read: a text that is no id of the sweep (a wrong digit, an extra token, a
/// value of another axis) is no variant of it. So a shard or a merge decides whether a run
/// key is described without making the sweep (docs/cluster.md, "What is still per run").
#[derive(Debug)]
pub struct IdReader<'a> {
    sweep: &'a Sweep,
    /// How many tokens every id of the sweep has.
    tokens: usize,
    /// Per axis, where its value stands and how its tokens name it.
    axes: Vec<AxisTokens<'a>>,
}

/// Where one axis's value stands in an id ([`IdReader`]) and how its tokens name it.
#[derive(Debug)]
struct AxisTokens<'a> {
    /// The places of its value's tokens (one per path; one for a labelled value's text).
    places: Vec<usize>,
    values: ValueTokens<'a>,
}

/// How an axis's tokens in an id name its value.
#[derive(Debug)]
enum ValueTokens<'a> {
    /// A list: each value's tokens (joined by `-`) and its index.
    List(std::collections::HashMap<String, usize>),
    /// A range: computed back from the number.
    Range(&'a Range),
}

impl IdReader<'_> {
    /// The variant of the sweep whose id is `id`, if one is ([`IdReader`]).
    pub fn variant(&self, id: &str) -> Option<usize> {
        let tokens: Vec<&str> = id.split('-').collect();
        if tokens.len() != self.tokens {
            return None;
        }
        let mut v = 0;
        for (a, s) in self.axes.iter().zip(&self.sweep.strides) {
            let d = match &a.values {
                ValueTokens::List(map) => {
                    let t: Vec<&str> = a.places.iter().map(|&p| tokens[p]).collect();
                    *map.get(&t.join("-"))?
                }
                ValueTokens::Range(r) => r.index_of(tokens[a.places[0]])?,
            };
            v += d * s;
        }
        (self.sweep.id(v) == id).then_some(v)
    }
}

/// Whether a slug is one token: not empty, without `-`.
fn one_token(slug: &str) -> bool {
    !slug.is_empty() && !slug.contains('-')
}

/// The fields each path of an axis sets, resolved against the base variant ([`check_path`]).
type AxisFields = Vec<Vec<Vec<Step>>>;

fn parse_axis(base: &Table, key: &str, val: &Value) -> Result<(Axis, AxisFields), SweepError> {
    let at = |error| SweepError::Key {
        key: key.to_string(),
        error,
    };
    let paths = split_key(key).map_err(at)?;
    let fields = paths
        .iter()
        .map(|path| check_path(base, path).map_err(|e| at(SweepKeyError::Path(e))))
        .collect::<Result<Vec<_>, _>>()?;
    let raw: Vec<Value> = match val {
        Value::Array(a) if a.is_empty() => return Err(at(SweepKeyError::NoValues)),
        Value::Array(a) => a.clone(),
        Value::Table(t) if paths.len() == 1 => {
            let axis = Axis {
                key: key.to_string(),
                paths,
                values: Values::Range(Range::parse(t).map_err(|e| at(e.into()))?),
            };
            return Ok((axis, fields));
        }
        other => {
            return Err(at(SweepKeyError::NotAList {
                group: paths.len() != 1,
                got: other.type_str(),
            }))
        }
    };
    let mut values = Vec::with_capacity(raw.len());
    for (k, v) in raw.into_iter().enumerate() {
        let (v, text) = match v {
            Value::Table(t)
                if t.len() == 2 && t.contains_key("value") && t.contains_key("label") =>
            {
                let text = match t.get("label") {
                    Some(Value::String(s)) => s.clone(),
                    _ => return Err(at(SweepKeyError::LabelNotString { index: k })),
                };
                (t["value"].clone(), Some(text))
            }
            v => (v, None),
        };
        let per_path = if paths.len() == 1 {
            vec![v]
        } else {
            match v {
                Value::Array(a) if a.len() == paths.len() => a,
                other => {
                    return Err(at(SweepKeyError::GroupValue {
                        index: k,
                        paths: paths.len(),
                        got: display(&other),
                    }))
                }
            }
        };
        values.push((per_path, text));
    }
    let axis = Axis {
        key: key.to_string(),
        paths,
        values: Values::List(values),
    };
    Ok((axis, fields))
}

/// The dotted paths of a key, split at its commas and dots. Whitespace is allowed only after
/// a comma (`"path.scale, path.reverse"`): around the key, inside a path or before a comma it
/// is refused, so every path is exactly its text and `"solvers.*.gamma "` is no second name
/// of `"solvers.*.gamma"`.
fn split_key(key: &str) -> Result<Vec<Vec<String>>, SweepKeyError> {
    key.split(',')
        .enumerate()
        .map(|(i, p)| {
            let p = if i == 0 { p } else { p.trim_start_matches(' ') };
            if p.chars().any(char::is_whitespace) {
                return Err(SweepKeyError::Whitespace);
            }
            Ok(p.split('.').map(str::to_string).collect())
        })
        .collect()
}

/// One step of a swept path resolved against the base variant: a table's key, or a list's
/// entry (`*` resolved into every entry, an index into its number).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Step {
    Key(String),
    Entry(usize),
}

/// A resolved field, dotted (for errors).
fn dotted(field: &[Step]) -> String {
    field
        .iter()
        .map(|s| match s {
            Step::Key(k) => k.clone(),
            Step::Entry(i) => i.to_string(),
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// The fields the axes set so far, each with the axis and the path of the axis that sets it,
/// to refuse two keys (or two paths of a zipped group) that set one field
/// ([`SweepError::SameField`], [`SweepError::SameFieldInGroup`]). Two set one field when one's
/// resolved field is the other's or begins with it (`scheme` and `scheme.mu`); in the sorted
/// map of the fields set, a field that begins with the new one is the first at or after it.
#[derive(Default)]
struct FieldsSet(std::collections::BTreeMap<Vec<Step>, (usize, usize)>);

impl FieldsSet {
    /// Records `set`, the fields path `p` of `axis` sets ([`check_path`]; the axis after
    /// `axes`, the axes read so far), or the error of the first one another path sets.
    fn add(
        &mut self,
        axes: &[Axis],
        axis: &Axis,
        p: usize,
        set: Vec<Vec<Step>>,
    ) -> Result<(), SweepError> {
        let a = axes.len();
        let axis_at = |b: usize| if b == a { axis } else { &axes[b] };
        for field in set {
            let under = (1..=field.len())
                .find_map(|k| self.0.get(&field[..k]).map(|&other| (other, field.clone())));
            let over = || {
                let (f, &other) = self
                    .0
                    .range::<[Step], _>((
                        std::ops::Bound::Included(&field[..]),
                        std::ops::Bound::Unbounded,
                    ))
                    .next()?;
                f.starts_with(&field).then(|| (other, f.clone()))
            };
            if let Some(((b, q), deeper)) = under.or_else(over) {
                let text = |b: usize, q: usize| axis_at(b).paths[q].join(".");
                return Err(if b == a {
                    SweepError::SameFieldInGroup {
                        key: axis.key.clone(),
                        first: text(b, q),
                        second: text(a, p),
                        field: dotted(&deeper),
                    }
                } else {
                    SweepError::SameField {
                        first: axes[b].key.clone(),
                        second: axis.key.clone(),
                        field: dotted(&deeper),
                    }
                });
            }
            self.0.insert(field, (a, p));
        }
        Ok(())
    }
}

/// A path is known when its first segment is a variant field and every table or array on the
/// way is there (the last segment may be new in a table). Returns the fields of the variant it
/// sets, one per entry a `*` stands for.
fn check_path(base: &Table, path: &[String]) -> Result<Vec<Vec<Step>>, KeyPathError> {
    let first = &path[0];
    if path.iter().any(String::is_empty) {
        return Err(KeyPathError::EmptySegment);
    }
    if !VARIANT_FIELDS.contains(&first.as_str()) {
        return Err(KeyPathError::NotAField {
            first: first.clone(),
        });
    }
    /// Walks `rest` below `v` (reached by `at`, shown as `done`), pushing every field it
    /// reaches onto `out`.
    fn walk(
        v: Option<&Value>,
        rest: &[String],
        done: &str,
        at: &mut Vec<Step>,
        out: &mut Vec<Vec<Step>>,
    ) -> Result<(), KeyPathError> {
        let Some((seg, rest)) = rest.split_first() else {
            out.push(at.clone());
            return Ok(());
        };
        let here = format!("{done}.{seg}");
        let mut enter = |x: Option<&Value>, step: Step, at: &mut Vec<Step>| {
            at.push(step);
            let walked = walk(x, rest, &here, at, out);
            at.pop();
            walked
        };
        match v {
            Some(Value::Table(t)) => match t.get(seg.as_str()) {
                // The last segment of a table may be new.
                x if rest.is_empty() || x.is_some() => enter(x, Step::Key(seg.clone()), at),
                _ => Err(KeyPathError::NoKey {
                    done: done.to_string(),
                    segment: seg.clone(),
                }),
            },
            Some(Value::Array(a)) => {
                if seg == "*" {
                    if a.is_empty() {
                        return Err(KeyPathError::EmptyList {
                            done: done.to_string(),
                        });
                    }
                    a.iter()
                        .enumerate()
                        .try_for_each(|(i, x)| enter(Some(x), Step::Entry(i), at))
                } else {
                    let i: usize = seg.parse().map_err(|_| KeyPathError::BadIndex {
                        done: done.to_string(),
                        segment: seg.clone(),
                    })?;
                    match a.get(i) {
                        Some(x) => enter(Some(x), Step::Entry(i), at),
                        None => Err(KeyPathError::NoEntry {
                            done: done.to_string(),
                            len: a.len(),
                            index: i,
                        }),
                    }
                }
            }
            Some(other) => Err(KeyPathError::NotContainer {
                done: done.to_string(),
                kind: other.type_str(),
            }),
            None => Err(KeyPathError::Missing {
                done: done.to_string(),
            }),
        }
    }
    let mut out = Vec::new();
    let mut at = vec![Step::Key(first.clone())];
    walk(
        base.get(first.as_str()),
        &path[1..],
        first,
        &mut at,
        &mut out,
    )?;
    Ok(out)
}

/// Sets `path` of `t` to `v` (`*` sets every element of a list). The path was checked.
fn set(t: &mut Table, path: &[String], v: Value) {
    fn go(x: &mut Value, rest: &[String], v: &Value) {
        let Some((seg, rest)) = rest.split_first() else {
            *x = v.clone();
            return;
        };
        match x {
            Value::Table(t) => {
                let entry = t
                    .entry(seg.clone())
                    .or_insert_with(|| Value::Boolean(false));
                go(entry, rest, v);
            }
            Value::Array(a) if seg == "*" => a.iter_mut().for_each(|e| go(e, rest, v)),
            Value::Array(a) => {
                if let Some(e) = seg.parse::<usize>().ok().and_then(|i| a.get_mut(i)) {
                    go(e, rest, v);
                }
            }
            _ => {}
        }
    }
    let mut root = Value::Table(std::mem::take(t));
    go(&mut root, path, &v);
    if let Value::Table(r) = root {
        *t = r;
    }
}

/// The names a label template may use: per axis and path, the last segment when no other
/// swept path ends alike, and always the whole path.
fn placeholder_names(axes: &[Axis]) -> Vec<(String, usize, usize)> {
    let mut names = Vec::new();
    let lasts: Vec<&String> = axes
        .iter()
        .flat_map(|a| a.paths.iter().map(|p| p.last().expect("non-empty path")))
        .collect();
    for (ai, a) in axes.iter().enumerate() {
        for (pi, p) in a.paths.iter().enumerate() {
            let last = p.last().expect("non-empty path");
            if lasts.iter().filter(|l| **l == last).count() == 1 {
                names.push((last.clone(), ai, pi));
            }
            names.push((p.join("."), ai, pi));
        }
    }
    names
}

/// The placeholders `{name}` of a template (text between braces without spaces).
fn placeholders(template: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        match after.find('}') {
            Some(close) if !after[..close].is_empty() && !after[..close].contains([' ', '{']) => {
                out.push(after[..close].to_string());
                rest = &after[close + 1..];
            }
            _ => rest = after,
        }
    }
    out
}

fn check_template(template: &str, names: &[(String, usize, usize)]) -> Result<(), SweepError> {
    for p in placeholders(template) {
        if !names.iter().any(|(n, _, _)| *n == p) {
            let mut known: Vec<String> = names.iter().map(|(n, _, _)| n.clone()).collect();
            known.dedup();
            return Err(SweepError::Placeholder {
                placeholder: p,
                known,
            });
        }
    }
    Ok(())
}

/// The label of the variant whose values (axis by axis) are `values`.
fn make_label(
    template: &str,
    axes: &[Axis],
    values: &[(Vec<Value>, Option<String>)],
    names: &[(String, usize, usize)],
) -> String {
    let text = |ai: usize, pi: usize| {
        let (vals, label) = &values[ai];
        label.clone().unwrap_or_else(|| display(&vals[pi]))
    };
    let used = placeholders(template);
    if !used.is_empty() {
        let mut out = template.to_string();
        for (name, ai, pi) in names {
            out = out.replace(&format!("{{{name}}}"), &text(*ai, *pi));
        }
        return out;
    }
    let mut parts = Vec::new();
    for (a, (vals, label)) in axes.iter().zip(values) {
        match label {
            Some(l) if l.is_empty() => {}
            Some(l) => parts.push(l.clone()),
            None => {
                for (p, v) in a.paths.iter().zip(vals) {
                    parts.push(format!(
                        "{}={}",
                        p.last().expect("non-empty path"),
                        display(v)
                    ));
                }
            }
        }
    }
    format!("{template} [{}]", parts.join(", "))
}

/// The id of one variant: the base `id` followed by every swept path's last segment and raw
/// value (labelled values by their value, not their text), as a slug: ids do not move when a
/// label or a labelled value's text is reworded.
fn make_id(base: &str, axes: &[Axis], values: &[(Vec<Value>, Option<String>)]) -> String {
    let mut text = base.to_string();
    for (a, (vals, _)) in axes.iter().zip(values) {
        for (p, v) in a.paths.iter().zip(vals) {
            text.push_str(&format!(
                " {}={}",
                p.last().expect("non-empty path"),
                display(v)
            ));
        }
    }
    settings::slug(&text)
}

/// A value as TOML writes it: `2`, `2.0`, `0.25`, `true`; strings without quotes.
pub fn display(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Integer(i) => i.to_string(),
        Value::Float(f) => {
            let s = f.to_string();
            if f.is_finite() && !s.contains(['.', 'e', 'E']) {
                format!("{s}.0")
            } else {
                s
            }
        }
        Value::Boolean(b) => b.to_string(),
        other => other.to_string(),
    }
}

/// A range `{ from = a, to = b, step = s }`: n + 1 values a + k s, k = 0..=n, each computed
/// when asked for (a range of 10^7 values holds three numbers).
#[derive(Clone, Debug)]
struct Range {
    /// n: the values are k = 0..=n.
    n: usize,
    arithmetic: Arithmetic,
}

/// How a range's values are computed.
#[derive(Clone, Copy, Debug)]
enum Arithmetic {
    /// Integers: a + k s in i128 (a value lies between a and b: an i64).
    Integer { a: i128, s: i128 },
    /// Decimals: (ma + k ms) 10^-e, exact in i128 (the ends' mantissas fit, so every one
    /// between does).
    Decimal { ma: i128, ms: i128, e: u32 },
    /// Floats of extreme magnitudes whose mantissas do not fit: a + k s in f64.
    Float { a: f64, s: f64 },
}

impl Range {
    /// Reads a range table `{ from, to, step }`.
    fn parse(t: &Table) -> Result<Self, RangeError> {
        let keys: Vec<&str> = t.keys().map(String::as_str).collect();
        if keys.len() != 3 || !["from", "to", "step"].iter().all(|k| keys.contains(k)) {
            return Err(RangeError::Keys {
                keys: keys.iter().map(|k| k.to_string()).collect(),
            });
        }
        if let (Some(Value::Integer(a)), Some(Value::Integer(b)), Some(Value::Integer(s))) =
            (t.get("from"), t.get("to"), t.get("step"))
        {
            let (a, b, s) = (*a, *b, *s);
            // In i128: no difference or quotient of two i64 overflows it.
            let (wa, wb, ws) = (i128::from(a), i128::from(b), i128::from(s));
            if s == 0 || (wb - wa) % ws != 0 || (wb - wa) / ws < 0 {
                return Err(RangeError::IntegerStep {
                    from: a,
                    to: b,
                    step: s,
                });
            }
            let n = (wb - wa) / ws;
            if n >= MAX_EXPANSION as i128 {
                return Err(RangeError::TooMany { max: MAX_EXPANSION });
            }
            return Ok(Range {
                n: n as usize,
                arithmetic: Arithmetic::Integer { a: wa, s: ws },
            });
        }
        let num = |key: &'static str| match t.get(key) {
            Some(Value::Integer(i)) => Ok(*i as f64),
            Some(Value::Float(f)) if f.is_finite() => Ok(*f),
            _ => Err(RangeError::NotANumber { key }),
        };
        float_range(num("from")?, num("to")?, num("step")?)
    }

    fn len(&self) -> usize {
        self.n + 1
    }

    /// Value k (k <= n).
    fn value(&self, k: usize) -> Value {
        match self.arithmetic {
            Arithmetic::Integer { a, s } => Value::Integer((a + k as i128 * s) as i64),
            Arithmetic::Decimal { ma, ms, e } => {
                let m = ma + ms * k as i128;
                Value::Float(format!("{m}e-{e}").parse().expect("a decimal number"))
            }
            Arithmetic::Float { a, s } => Value::Float(a + k as f64 * s),
        }
    }

    /// Whether the values' slugs are distinct ([`Sweep::prefixes`]): the range does not cross
    /// zero, and a float range's step is more than 4 epsilon of its largest end.
    fn distinct_slugs(&self) -> bool {
        let (first, last) = (self.value(0), self.value(self.n));
        match (self.arithmetic, first, last) {
            (Arithmetic::Integer { .. }, Value::Integer(a), Value::Integer(b)) => {
                a.min(b) >= 0 || a.max(b) <= 0
            }
            (_, Value::Float(a), Value::Float(b)) => {
                let step = if self.n == 0 {
                    f64::INFINITY
                } else {
                    (b - a).abs() / self.n as f64
                };
                (a.min(b) >= 0.0 || a.max(b) <= 0.0)
                    && step > 4.0 * f64::EPSILON * a.abs().max(b.abs())
            }
            _ => false,
        }
    }

    /// The index of the value whose slug is `token`, if one is: a range's values do not cross
    /// zero (a range whose slugs are distinct, [`Range::distinct_slugs`]), so the sign the slug
    /// drops is the range's. Integers exactly; decimals and floats by the nearest index to the
    /// number and its two neighbours, the one whose slug is `token` (the estimate is within
    /// 0.7 of the index when the step is more than 4 epsilon of the larger end).
    fn index_of(&self, token: &str) -> Option<usize> {
        let negative = |v: Value| match v {
            Value::Integer(i) => i < 0,
            Value::Float(f) => f < 0.0,
            _ => false,
        };
        let minus = negative(self.value(0)) || negative(self.value(self.n));
        if let Arithmetic::Integer { a, s } = self.arithmetic {
            if !token.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            let t = token.parse::<i128>().ok()?;
            let d = (if minus { -t } else { t }) - a;
            let k = usize::try_from(d / s).ok()?;
            return (d % s == 0 && k <= self.n).then_some(k);
        }
        let t = token.parse::<f64>().ok()?;
        let x = if minus { -t } else { t };
        let number = |k: usize| match self.value(k) {
            Value::Float(f) => f,
            _ => f64::NAN,
        };
        let (a, b) = (number(0), number(self.n));
        let k = if self.n == 0 {
            0.0
        } else {
            ((x - a) / (b - a) * self.n as f64).round()
        };
        if k.is_nan() || k < -1.0 || k > self.n as f64 + 1.0 {
            return None;
        }
        let k = (k.max(0.0) as usize).min(self.n);
        (k.saturating_sub(1)..=(k + 1).min(self.n))
            .find(|&k| settings::slug(&display(&self.value(k))) == token)
    }

    /// Every value (the tests' view).
    #[cfg(test)]
    fn values(&self) -> Vec<Value> {
        (0..self.len()).map(|k| self.value(k)).collect()
    }
}

/// The range a, a + s, ..., b of floats: n = round((b - a) / s), which must be an integer to
/// 1e-9; its values in decimal arithmetic.
fn float_range(a: f64, b: f64, s: f64) -> Result<Range, RangeError> {
    if s == 0.0 {
        return Err(RangeError::ZeroStep);
    }
    let q = (b - a) / s;
    let n = q.round();
    if (q - n).abs() > 1e-9 {
        return Err(RangeError::FloatStep {
            from: a,
            to: b,
            step: s,
            quotient: q,
        });
    }
    if n < 0.0 {
        return Err(RangeError::Away {
            from: a,
            to: b,
            step: s,
        });
    }
    if n >= MAX_EXPANSION as f64 {
        return Err(RangeError::TooMany { max: MAX_EXPANSION });
    }
    let n = n as usize;
    let arithmetic = decimal_arithmetic(a, s, n).unwrap_or(Arithmetic::Float { a, s });
    Ok(Range { n, arithmetic })
}

/// a + k s for k = 0..=n in decimal arithmetic (m 10^-e, exact in i128), or None when a
/// mantissa does not fit (a float range of extreme magnitudes is then computed in f64). The
/// mantissas are monotonic in k, so when the last one fits, every one does.
fn decimal_arithmetic(a: f64, s: f64, n: usize) -> Option<Arithmetic> {
    let ((ma, ea), (ms, es)) = (decimal(a)?, decimal(s)?);
    let e = ea.max(es);
    let scale = |m: i128, from: u32| 10i128.checked_pow(e - from)?.checked_mul(m);
    let (ma, ms) = (scale(ma, ea)?, scale(ms, es)?);
    ms.checked_mul(i128::try_from(n).ok()?)?.checked_add(ma)?;
    Some(Arithmetic::Decimal { ma, ms, e })
}

/// x as m * 10^-e from its shortest decimal form (None when that does not fit).
fn decimal(x: f64) -> Option<(i128, u32)> {
    let s = format!("{x}");
    let (neg, s) = match s.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, s.as_str()),
    };
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    if int.len() + frac.len() > 30 || frac.len() > 20 {
        return None;
    }
    let m: i128 = format!("{int}{frac}").parse().ok()?;
    Some((if neg { -m } else { m }, frac.len() as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn variant(text: &str) -> Table {
        toml::from_str(text).unwrap()
    }

    fn labels(t: &[Table]) -> Vec<&str> {
        t.iter().map(|v| v["label"].as_str().unwrap()).collect()
    }

    /// The variants of one variant table's sweep, made one by one from its plan (as tables).
    fn expand_variant(variant: &Table) -> Result<Vec<Table>, SweepError> {
        let place = Place {
            experiment: 0,
            id: "e".to_string(),
            variant: 0,
            label: "?".to_string(),
        };
        let s = Sweep::new(variant, MAX_EXPANSION, place)?;
        Ok((0..s.len()).map(|v| s.table(v).0).collect())
    }

    /// The variant lists of the file `text`, its sweeps taken out, planned and made back in
    /// place (as tables).
    fn expand_file(text: &str, budget: &mut usize) -> Result<Vec<Vec<Table>>, SweepError> {
        let mut doc: Table = toml::from_str(text).unwrap();
        let sweeps = take_sweeps(&mut doc);
        assert!(!has_sweeps(&doc));
        let mut lists: Vec<Vec<Table>> = experiments(&doc)
            .map(|e| variants(e).cloned().collect())
            .collect();
        let mut offset = vec![0; lists.len()];
        for (slot, s) in sweeps.plan(budget)? {
            let at = slot.variant + offset[slot.experiment];
            let tables: Vec<Table> = (0..s.len()).map(|v| s.table(v).0).collect();
            offset[slot.experiment] += tables.len() - 1;
            lists[slot.experiment].splice(at..at, tables);
        }
        Ok(lists)
    }

    /// A float range's values.
    fn floats(a: f64, b: f64, s: f64) -> Result<Vec<f64>, RangeError> {
        float_range(a, b, s).map(|r| r.values().iter().map(|v| v.as_float().unwrap()).collect())
    }

    #[test]
    fn default_labels_in_written_order() {
        let v = variant(
            r#"label = "VLTCO"
path = { name = "circle", duration = 9.0 }
scheme = { kind = "vltco" }
sweep = { "path.scale" = [0.1, 0.15], "path.reverse" = [false, true] }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(
            labels(&out),
            [
                "VLTCO [scale=0.1, reverse=false]",
                "VLTCO [scale=0.1, reverse=true]",
                "VLTCO [scale=0.15, reverse=false]",
                "VLTCO [scale=0.15, reverse=true]",
            ]
        );
        assert_eq!(out[3]["path"]["scale"].as_float(), Some(0.15));
        assert_eq!(out[3]["path"]["reverse"].as_bool(), Some(true));
        assert_eq!(out[3]["path"]["name"].as_str(), Some("circle"));
        assert!(!out[0].contains_key("sweep"));
    }

    #[test]
    fn values_are_named_as_written() {
        let v = variant(
            r#"label = "ZNN"
scheme = { kind = "znn-rmp", mu = 1.0 }
sweep = { "scheme.mu" = [0.25, 2, 2.0, 1e7] }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(
            labels(&out),
            [
                "ZNN [mu=0.25]",
                "ZNN [mu=2]",
                "ZNN [mu=2.0]",
                "ZNN [mu=10000000.0]"
            ]
        );
    }

    #[test]
    fn templates_labelled_values_zips_and_wildcards() {
        let v = variant(
            r#"label = "{phi} [{reverse}a={scale}] k={a_d}"
path = { name = "circle", duration = 9.0 }
scheme = { kind = "vltco", kappa = 20.0 }
solvers = [{ kind = "fp-cdnn", perturbation = { a_d = 0.0, a_s = 0.0 } }, { kind = "vp-cdnn", perturbation = { a_d = 0.0, a_s = 0.0 } }]
sweep = { "path.reverse" = [{ value = false, label = "" }, { value = true, label = "reversed, " }], "path.scale" = [0.1], "scheme.phi, scheme.tau" = [{ value = [1.0, 0.0], label = "MVN" }, { value = [0.2, 0.4], label = "VLTCO" }], "solvers.*.perturbation.a_d, solvers.*.perturbation.a_s" = [[0.5, 0.75]] }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(
            labels(&out),
            [
                "MVN [a=0.1] k=0.5",
                "VLTCO [a=0.1] k=0.5",
                "MVN [reversed, a=0.1] k=0.5",
                "VLTCO [reversed, a=0.1] k=0.5"
            ]
        );
        assert_eq!(out[1]["scheme"]["tau"].as_float(), Some(0.4));
        assert_eq!(out[1]["scheme"]["kappa"].as_float(), Some(20.0));
        for s in out[0]["solvers"].as_array().unwrap() {
            assert_eq!(s["perturbation"]["a_s"].as_float(), Some(0.75));
        }
        // Array indices; a labelled value without a template adds its text alone.
        let v = variant(
            r#"label = "X"
solvers = [{ kind = "fp-cdnn", gamma = 1.0 }]
theta0 = [1.0, 2.0]
sweep = { "solvers.0.gamma" = [20.0, 2000.0], "theta0.1" = [{ value = 3.0, label = "moved" }] }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(
            labels(&out),
            ["X [gamma=20.0, moved]", "X [gamma=2000.0, moved]"]
        );
        assert_eq!(out[1]["theta0"][1].as_float(), Some(3.0));
    }

    #[test]
    fn extreme_ranges_neither_overflow_nor_panic() {
        // The decimal mantissas would overflow i128: computed in f64 instead.
        assert_eq!(floats(1e29, 1e29, 1e-20).unwrap(), [1e29]);
        assert_eq!(floats(-1e29, 1e29, 1e29).unwrap(), [-1e29, 0.0, 1e29]);
        assert!(floats(-1e308, 1e308, 1e-308).is_err());
        let ints = |text: &str| {
            Range::parse(&toml::from_str::<Table>(text).unwrap()).map(|r| {
                let v = r.values();
                v.iter()
                    .map(|x| x.as_integer().unwrap())
                    .collect::<Vec<_>>()
            })
        };
        let (min, max) = (i64::MIN, i64::MAX);
        assert_eq!(
            ints(&format!("from = {}\nto = {max}\nstep = {max}", -max)).unwrap(),
            [-max, 0, max]
        );
        assert!(ints(&format!("from = {min}\nto = {max}\nstep = {max}")).is_err());
        assert!(ints(&format!("from = {min}\nto = {max}\nstep = 1")).is_err());
        assert!(ints(&format!("from = {max}\nto = {min}\nstep = -1")).is_err());
        assert!(ints(&format!("from = 0\nto = {min}\nstep = -1")).is_err());
    }

    #[test]
    fn the_sweeps_of_a_file_share_one_budget() {
        let text = |n: usize| {
            format!(
                "paper = \"p\"\n[[experiment]]\nid = \"p-e\"\n{}",
                (0..n)
                    .map(|i| format!("[[experiment.variant]]\nlabel = \"S{i}\"\nscheme = {{ kind = \"x\" }}\nsweep = {{ \"scheme.mu\" = {{ from = 1, to = 3, step = 1 }} }}\n"))
                    .collect::<String>()
            )
        };
        let mut budget = 6;
        expand_file(&text(2), &mut budget).unwrap();
        assert_eq!(budget, 0);
        let e = expand_file(&text(3), &mut 8).unwrap_err();
        assert!(
            matches!(&e, SweepError::In { variant: 2, error, .. } if matches!(**error, SweepError::TooManyInAll { .. })),
            "{e}"
        );
        assert!(e.to_string().contains("in all"), "{e}");
    }

    #[test]
    fn ranges_are_decimal_safe() {
        assert_eq!(floats(0.1, 0.3, 0.1).unwrap(), [0.1, 0.2, 0.3]);
        assert_eq!(floats(0.0, 1.0, 0.25).unwrap(), [0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(floats(1.0, 0.7, -0.1).unwrap(), [1.0, 0.9, 0.8, 0.7]);
        assert_eq!(floats(2.5, 2.5, 1.0).unwrap(), [2.5]);
        assert!(floats(0.0, 1.0, 0.3).is_err());
        assert!(floats(0.0, 1.0, 0.0).is_err());
        assert!(floats(0.0, 1.0, -0.5).is_err());
        let v = variant(
            r#"label = "Z"
scheme = { kind = "x" }
sweep = { "scheme.mu" = { from = 0.1, to = 0.3, step = 0.1 }, "scheme.n" = { from = 1, to = 5, step = 2 } }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(out.len(), 9);
        assert_eq!(out[8]["label"].as_str(), Some("Z [mu=0.3, n=5]"));
        assert_eq!(out[8]["scheme"]["n"].as_integer(), Some(5));
        assert_eq!(out[3]["scheme"]["mu"].as_float(), Some(0.2));
    }

    #[test]
    fn every_error_names_the_key() {
        let err = |sweep: &str| {
            let v = variant(&format!(
                "label = \"L\"\nscheme = {{ kind = \"x\", mu = 1.0 }}\nsolvers = [{{ kind = \"znn\" }}]\nsweep = {sweep}"
            ));
            expand_variant(&v).unwrap_err().to_string()
        };
        let e = err(r#"{ "schem.mu" = [1.0] }"#);
        assert!(
            e.contains("key \"schem.mu\"") && e.contains("unknown key path"),
            "{e}"
        );
        let e = err(r#"{ "path.scale" = [1.0] }"#);
        assert!(
            e.contains("key \"path.scale\"") && e.contains("gives no `path`"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu.x" = [1.0] }"#);
        assert!(
            e.contains("key \"scheme.mu.x\"") && e.contains("not a table"),
            "{e}"
        );
        let e = err(r#"{ "solvers.3.gamma" = [1.0] }"#);
        assert!(e.contains("no [3]"), "{e}");
        let e = err(r#"{ "scheme.mu" = [] }"#);
        assert!(
            e.contains("key \"scheme.mu\"") && e.contains("empty"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu" = 1.0 }"#);
        assert!(
            e.contains("key \"scheme.mu\"") && e.contains("must be a list"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu" = { from = 0, to = 1, step = 0.3 } }"#);
        assert!(
            e.contains("key \"scheme.mu\"") && e.contains("does not divide"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu" = { from = 0, to = 1 } }"#);
        assert!(
            e.contains("key \"scheme.mu\"") && e.contains("a range is"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu, scheme.nu" = [[1.0]] }"#);
        assert!(e.contains("one per path"), "{e}");
        let e = err("{}");
        assert!(e.contains("empty"), "{e}");
        let v = variant(
            "label = \"L {nu}\"\nscheme = { kind = \"x\" }\nsweep = { \"scheme.mu\" = [1] }",
        );
        let e = expand_variant(&v).unwrap_err().to_string();
        assert!(e.contains("placeholder \"{nu}\""), "{e}");
    }

    /// The sweep of `sweep` (the TOML of its table) on a variant with a scheme, two solvers,
    /// a path and theta0, in a file: its error, placed at the experiment and the variant.
    fn refused_in_file(sweep: &str) -> SweepError {
        let text = format!(
            "paper = \"p\"\n[[experiment]]\nid = \"p-e\"\n[[experiment.variant]]\nlabel = \"V\"\n\
             scheme = {{ kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }}\n\
             solvers = [{{ kind = \"znn\", gamma = 1.0 }}, {{ kind = \"znn\", gamma = 2.0 }}]\n\
             path = {{ name = \"circle\", duration = 0.1 }}\ntheta0 = [1.0, 2.0, 3.0]\n\
             sweep = {sweep}\n"
        );
        expand_file(&text, &mut MAX_EXPANSION.clone()).unwrap_err()
    }

    /// The error inside the placing of [`refused_in_file`], and its text (which must name the
    /// experiment and the variant).
    fn inner(e: SweepError) -> (SweepError, String) {
        let text = e.to_string();
        assert!(
            text.starts_with("experiment[0] (id \"p-e\") variant[0] (\"V\") field `sweep`"),
            "{text}"
        );
        match e {
            SweepError::In { error, .. } => (*error, text),
            other => panic!("not placed: {other:?}"),
        }
    }

    /// The red team's cases: two keys that set one field ran both labels at the last value
    /// (gamma=0.1 and gamma=0.2 both ran gamma = 5).
    #[test]
    fn two_keys_that_set_one_field_are_refused_naming_both() {
        let same = |first: &str, second: &str, field: &str| SweepError::SameField {
            first: first.to_string(),
            second: second.to_string(),
            field: field.to_string(),
        };
        // `*` meets an index (either order), with the field resolved.
        let (e, text) = inner(refused_in_file(
            r#"{ "solvers.0.gamma" = [0.1, 0.2], "solvers.*.gamma" = [5.0] }"#,
        ));
        assert_eq!(
            e,
            same("solvers.0.gamma", "solvers.*.gamma", "solvers.0.gamma")
        );
        assert!(
            text.contains(
                "keys \"solvers.0.gamma\" and \"solvers.*.gamma\" both set \"solvers.0.gamma\""
            ),
            "{text}"
        );
        let (e, _) = inner(refused_in_file(
            r#"{ "solvers.*.gamma" = [5.0], "solvers.1.gamma" = [0.1, 0.2] }"#,
        ));
        assert_eq!(
            e,
            same("solvers.*.gamma", "solvers.1.gamma", "solvers.1.gamma")
        );
        let (e, _) = inner(refused_in_file(
            r#"{ "theta0.2" = [0.5], "theta0.*" = [1.0] }"#,
        ));
        assert_eq!(e, same("theta0.2", "theta0.*", "theta0.2"));
        // An index written two ways is one entry.
        let (e, _) = inner(refused_in_file(
            r#"{ "solvers.1.gamma" = [0.5], "solvers.+1.gamma" = [1.0] }"#,
        ));
        assert_eq!(
            e,
            same("solvers.1.gamma", "solvers.+1.gamma", "solvers.1.gamma")
        );
        // A key and a key under it, either order: the deeper field is named.
        let (e, text) = inner(refused_in_file(
            r#"{ "scheme" = [{ kind = "znn-rmp", mu = 2.0, k_p = 1.0 }], "scheme.mu" = [1.0, 4.0] }"#,
        ));
        assert_eq!(e, same("scheme", "scheme.mu", "scheme.mu"));
        assert!(text.contains("keys \"scheme\" and \"scheme.mu\""), "{text}");
        let (e, _) = inner(refused_in_file(
            r#"{ "solvers.*.gamma" = [1.0, 4.0], "solvers" = [[{ kind = "znn", gamma = 3.0 }]] }"#,
        ));
        assert_eq!(e, same("solvers.*.gamma", "solvers", "solvers.0.gamma"));
        let (e, _) = inner(refused_in_file(
            r#"{ "path.scale" = [0.1], "path" = [{ name = "circle", duration = 0.1 }] }"#,
        ));
        assert_eq!(e, same("path.scale", "path", "path.scale"));
        // Through a zipped group of another key.
        let (e, _) = inner(refused_in_file(
            r#"{ "scheme.mu, path.scale" = [[1.0, 0.1]], "path.scale" = [0.2] }"#,
        ));
        assert_eq!(e, same("scheme.mu, path.scale", "path.scale", "path.scale"));
    }

    #[test]
    fn a_zipped_group_that_names_one_field_twice_is_refused() {
        let (e, text) = inner(refused_in_file(
            r#"{ "solvers.0.gamma, solvers.0.gamma" = [[1.0, 2.0], [3.0, 4.0]] }"#,
        ));
        assert_eq!(
            e,
            SweepError::SameFieldInGroup {
                key: "solvers.0.gamma, solvers.0.gamma".to_string(),
                first: "solvers.0.gamma".to_string(),
                second: "solvers.0.gamma".to_string(),
                field: "solvers.0.gamma".to_string(),
            }
        );
        assert!(
            text.contains("key \"solvers.0.gamma, solvers.0.gamma\": its paths \"solvers.0.gamma\" and \"solvers.0.gamma\" both set"),
            "{text}"
        );
        let (e, _) = inner(refused_in_file(
            r#"{ "scheme, scheme.mu" = [[{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }, 2.0]] }"#,
        ));
        assert!(
            matches!(&e, SweepError::SameFieldInGroup { first, second, field, .. }
                if first == "scheme" && second == "scheme.mu" && field == "scheme.mu"),
            "{e:?}"
        );
        let (e, _) = inner(refused_in_file(
            r#"{ "solvers.*.gamma, solvers.1.gamma" = [[1.0, 2.0]] }"#,
        ));
        assert!(
            matches!(&e, SweepError::SameFieldInGroup { field, .. } if field == "solvers.1.gamma"),
            "{e:?}"
        );
    }

    #[test]
    fn keys_that_set_different_fields_are_accepted() {
        let v = variant(
            r#"label = "X"
scheme = { kind = "x", mu = 1.0, m = 1.0 }
solvers = [{ kind = "znn", gamma = 1.0 }, { kind = "znn", gamma = 2.0 }]
theta0 = [1.0, 2.0]
sweep = { "scheme.kind" = ["x", "y"], "scheme.mu" = [1.0], "scheme.m" = [2.0], "solvers.0.gamma, solvers.1.gamma" = [[3.0, 4.0]], "theta0.0" = [0.5], "theta0.1" = [0.25], "scheme.new" = [1] }"#,
        );
        let out = expand_variant(&v).unwrap();
        assert_eq!(out.len(), 2);
        assert_eq!(out[1]["scheme"]["kind"].as_str(), Some("y"));
        assert_eq!(out[1]["solvers"][1]["gamma"].as_float(), Some(4.0));
        assert_eq!(out[1]["theta0"][1].as_float(), Some(0.25));
    }

    /// The red team's `"solvers.*.gamma "` (a trailing space) was a second key for one field.
    #[test]
    fn whitespace_is_allowed_only_after_a_comma() {
        for key in [
            "solvers.*.gamma ",
            " solvers.*.gamma",
            "solvers. *.gamma",
            "solvers.*.gamma\t",
            "solvers.*.gam ma",
            "scheme.mu , path.scale",
            "scheme.mu,\tpath.scale",
            "scheme.mu,\u{a0}path.scale",
            "scheme.mu, path.scale ",
            "scheme.mu,\npath.scale",
        ] {
            let toml_key = format!("\"{}\"", key.replace('\t', "\\t").replace('\n', "\\n"));
            let (e, text) = inner(refused_in_file(&format!("{{ {toml_key} = [[1.0, 0.1]] }}")));
            assert_eq!(
                e,
                SweepError::Key {
                    key: key.to_string(),
                    error: SweepKeyError::Whitespace
                },
                "{key:?}"
            );
            assert!(text.contains("whitespace in a key"), "{text}");
            assert!(
                !text.contains(['\t', '\n', '\u{a0}']),
                "shown escaped: {text}"
            );
        }
        let (_, text) = inner(refused_in_file(r#"{ "solvers.*.gamma " = [1.0] }"#));
        assert!(
            text.contains("key \"solvers.*.gamma \": whitespace"),
            "{text}"
        );
        let (_, text) = inner(refused_in_file(
            "{ \"scheme.mu,\\tpath.scale\" = [[1.0, 0.1]] }",
        ));
        assert!(text.contains("key \"scheme.mu,\\tpath.scale\""), "{text}");
        // A control character in a key is shown escaped wherever the key is named.
        let (_, text) = inner(refused_in_file("{ \"sch\\u001bem.mu\" = [1.0] }"));
        assert!(text.contains("key \"sch\\u{1b}em.mu\""), "{text}");
        // After a comma, spaces (any number) or none.
        for key in [
            "path.scale,path.reverse",
            "path.scale, path.reverse",
            "path.scale,   path.reverse",
        ] {
            let v = variant(&format!(
                "label = \"X\"\npath = {{ name = \"circle\", duration = 9.0 }}\nsweep = {{ \"{key}\" = [[0.1, true]] }}"
            ));
            let out = expand_variant(&v).unwrap();
            assert_eq!(out[0]["path"]["reverse"].as_bool(), Some(true), "{key}");
            assert_eq!(out[0]["path"]["scale"].as_float(), Some(0.1), "{key}");
        }
    }

    #[test]
    fn every_variant_is_made_in_place() {
        let text = r#"paper = "p"
[[experiment]]
id = "p-e"
[[experiment.variant]]
label = "A"
scheme = { kind = "x" }
sweep = { "scheme.mu" = [1, 2] }
[[experiment.variant]]
label = "plain"
[[experiment.variant]]
label = "B"
scheme = { kind = "x" }
sweep = { "scheme.mu" = [3, 5] }
"#;
        let lists = expand_file(text, &mut MAX_EXPANSION.clone()).unwrap();
        assert_eq!(
            labels(&lists[0]),
            ["A [mu=1]", "A [mu=2]", "plain", "B [mu=3]", "B [mu=5]"]
        );
    }

    #[test]
    fn expand_file_names_experiment_and_variant() {
        let text = r#"paper = "p"
[[experiment]]
id = "p-e"
[[experiment.variant]]
label = "plain"
[[experiment.variant]]
label = "S"
scheme = { kind = "x" }
sweep = { "scheme.mu" = [1, 2] }
[[experiment.variant]]
label = "last"
"#;
        assert!(has_sweeps(&toml::from_str(text).unwrap()));
        let mut budget = MAX_EXPANSION;
        let lists = expand_file(text, &mut budget).unwrap();
        assert_eq!(budget, MAX_EXPANSION - 2);
        assert_eq!(labels(&lists[0]), ["plain", "S [mu=1]", "S [mu=2]", "last"]);
        assert!(lists[0][1..3].iter().all(|v| !v.contains_key("sweep")));
        let e = expand_file(
            "paper = \"p\"\n[[experiment]]\nid = \"p-e\"\n[[experiment.variant]]\nlabel = \"S\"\nscheme = { kind = \"x\" }\nsweep = { \"scheme.mu\" = [] }\n",
            &mut MAX_EXPANSION.clone(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with(
                "experiment[0] (id \"p-e\") variant[0] (\"S\") field `sweep` key \"scheme.mu\""
            ),
            "{e}"
        );
    }
}

#[cfg(test)]
mod trace_tests {
    use crate::experiment::PaperFile;

    /// A sweep of three variants of two runs each (exact column and one network), with `traces`.
    fn file(traces: &str) -> String {
        format!(
            r#"{}[[experiment.variant]]
id = "znn"
label = "ZNN"
scheme = {{ kind = "znn-rmp", k_p = 1.0 }}
solvers = [{{ kind = "znn", gamma = 1.0 }}]
{traces}
sweep = {{ "scheme.mu" = [0.5, 1, 2] }}
"#,
            fixtures::katana_circle("t", "kong2019-t", 1.0, "")
        )
    }

    fn kept(traces: &str) -> Vec<bool> {
        PaperFile::from_toml(&file(traces))
            .unwrap()
            .jobs()
            .unwrap()
            .iter()
            .map(|j| j.keep_trace)
            .collect()
    }

    #[test]
    fn traces_choose_runs_by_their_index_in_the_sweep() {
        assert_eq!(kept(""), [true; 6]);
        assert_eq!(kept("traces = \"all\""), [true; 6]);
        assert_eq!(kept("traces = \"none\""), [false; 6]);
        // Runs 0..6 in order (exact, znn per variant): 0 and 3 are multiples of 3.
        assert_eq!(
            kept("traces = { every = 3 }"),
            [true, false, false, true, false, false]
        );
        assert_eq!(kept("traces = { every = 1 }"), [true; 6]);
    }

    /// A variant of a sweep that does not read is named, with its sweep's place; two with one
    /// label are the sweep's error, with their places in it.
    #[test]
    fn a_variant_that_does_not_read_and_two_with_one_label_are_named() {
        let e = PaperFile::from_toml(&file("").replace("[0.5, 1, 2]", "[0.5, \"x\", 2]"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("experiment[0] (id \"kong2019-t\") variant[0] (\"ZNN\") field `sweep`: the expanded variant \"ZNN [mu=x]\" does not read:"),
            "{e}"
        );
        let e = PaperFile::from_toml(&file("").replace("[0.5, 1, 2]", "[0.5, 1, 1]"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("variant[0] (\"ZNN\") field `sweep`: expanded variants 1 and 2 both get the label \"ZNN [mu=1]\""),
            "{e}"
        );
    }

    /// A sweep larger than [`super::CHECKED_WHOLE`] whose lines are valid loads; a variant off
    /// its lines is checked as it is made, and one that fails (here a label past 100 bytes:
    /// the range's ends are short, its inner values long) is refused then, naming the variant
    /// and the field.
    #[test]
    fn a_variant_off_the_lines_is_checked_as_it_is_made() {
        let text = format!(
            "{}[[experiment.variant]]\nlabel = \"{}\"\nscheme = {{ kind = \"znn-rmp\", mu = 1.0, k_p = 1.0 }}\nsweep = {{ \"scheme.mu\" = {{ from = 1.0, to = 2.0, step = 0.00001 }} }}\n",
            fixtures::katana_circle("t", "kong2019-t", 1.0, ""),
            "L".repeat(90)
        );
        let file = PaperFile::from_toml(&text).unwrap();
        assert_eq!(file.experiments[0].variants.len(), 100_001);
        assert!(file.variant(0, 0).is_ok() && file.variant(0, 100_000).is_ok());
        let e = file.variant(0, 1).unwrap_err().to_string();
        assert!(
            e.starts_with("experiment[0] (id \"kong2019-t\") variant[1] (")
                && e.contains("[mu=1.00001]\") field `label`"),
            "{e}"
        );
    }

    #[test]
    fn a_bad_traces_value_is_refused_naming_the_field_and_choices_not_the_value() {
        for bad in [
            "traces = \"some-secret\"",
            "traces = { every = 0 }",
            "traces = { every = -2 }",
            "traces = { every = 1.5 }",
            "traces = { every = 2, more = 1 }",
            "traces = 3",
        ] {
            let e = PaperFile::from_toml(&file(bad)).unwrap_err().to_string();
            assert!(
                e.contains("variant[0]")
                    && e.contains("field `traces`: must be \"all\" (the default), \"none\" or { every = k } with an integer k >= 1"),
                "{bad}: {e}"
            );
            assert!(!e.contains("secret") && !e.contains("1.5"), "{e}");
        }
        // Not a field of a variant without a sweep.
        let plain = file("traces = \"none\"")
            .replace("sweep = { \"scheme.mu\" = [0.5, 1, 2] }\n", "")
            .replace("k_p = 1.0", "k_p = 1.0, mu = 1.0");
        let e = PaperFile::from_toml(&plain).unwrap_err().to_string();
        assert!(e.contains("unknown field `traces`"), "{e}");
    }
}

/// What the ids of a sweep's product depend on, as the load decides it by expanding every
/// variant: the facts a check of the ids from the axes' raw values alone (shard planning by
/// index, issue 43 item 2) must reproduce. An expanded id is the slug of the whole text
/// `id k1=v1 k2=v2 ...` (module docs), not the per-axis slugs joined.
#[cfg(test)]
mod id_tests {
    use crate::experiment::PaperFile;

    /// A kong2019 file whose one variant, `id = "z"`, sweeps `sweep` (over fields the file's
    /// own check reads as free text: the path's name, built by the engine later, and the
    /// expected failure's reason).
    fn file(sweep: &str) -> String {
        format!(
            r#"paper = "kong2019"
title = "t"
[[experiment]]
id = "kong2019-t"
paper_output = "-"
robot = "katana6m180"
path = {{ name = "circle", duration = 1.0 }}
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.0471975511965976]
[[experiment.variant]]
id = "z"
label = "Z"
scheme = {{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }}
path = {{ name = "circle", duration = 1.0 }}
expected_failure = {{ why = "w" }}
sweep = {{ {sweep} }}
"#
        )
    }

    /// The ids of the sweep's variants.
    fn ids(sweep: &str) -> Vec<String> {
        let file = PaperFile::from_toml(&file(sweep)).unwrap();
        (0..file.experiments[0].variants.len())
            .map(|i| file.variant(0, i).unwrap().id())
            .collect()
    }

    /// Why the file of the sweep is refused.
    fn refused(sweep: &str) -> String {
        PaperFile::from_toml(&file(sweep)).unwrap_err().to_string()
    }

    /// Two values of one axis with the same slug (0.5 and -0.5: the sign is a separator) give
    /// every pair of variants that differ only there the same id: refused. So distinct slugs
    /// per axis are necessary.
    #[test]
    fn values_of_one_axis_with_one_slug_clash() {
        let e = refused(r#""scheme.mu" = [0.5, -0.5]"#);
        assert!(e.contains("z-mu-0.5"), "{e}");
        assert_eq!(ids(r#""scheme.mu" = [0.5, 1.5]"#), ["z-mu-0.5", "z-mu-1.5"]);
    }

    /// Distinct slugs per axis are not sufficient: a value whose slug holds `-<next key>-`
    /// shifts the text between the axes, and two tuples of distinct per-axis slugs give one
    /// id ("z-name-x-why-y-why-w" for (name "x why y", why "w") and (name "x", why "y why w")),
    /// which the load refuses. A check from the axes' values must also show that the joined
    /// text splits back into the axes one way only (e.g. every value's slug one token, without
    /// `-`), or enumerate the ids.
    #[test]
    fn distinct_slugs_per_axis_can_still_give_one_id() {
        let e =
            refused(r#""path.name" = ["x why y", "x"], "expected_failure.why" = ["w", "y why w"]"#);
        assert!(e.contains("z-name-x-why-y-why-w"), "{e}");
        // With one-token slugs, distinct per axis, the ids are distinct.
        assert_eq!(
            ids(r#""path.name" = ["a", "b"], "expected_failure.why" = ["w", "v"]"#),
            [
                "z-name-a-why-w",
                "z-name-a-why-v",
                "z-name-b-why-w",
                "z-name-b-why-v"
            ]
        );
    }
}

/// The plan against a straightforward expansion, on many random small sweeps: variant i made
/// from its digits is the i-th of an odometer over the axes (first outermost, last fastest),
/// the runs' prefix sums and the bisection agree with the runs counted variant by variant, and
/// whenever [`Sweep::prefixes`] decides the names, they are distinct and begin as it says.
/// Texts near the id `id` (the tests of [`IdReader`] and of `crate::RunLookup`): each digit
/// changed, a token added or dropped, each token replaced by another of its tokens (a value
/// slug at another axis's place, a key's token at a value's) and by the token at its place in
/// each of `others` (ids of other variants).
#[cfg(test)]
pub(crate) fn near_misses(id: &str, others: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for (i, c) in id.char_indices() {
        if let Some(d) = c.to_digit(10) {
            let mut m = id.to_string();
            m.replace_range(i..=i, &((d + 1) % 10).to_string());
            out.push(m);
        }
    }
    out.push(format!("{id}-0.5"));
    out.push(format!("{id}-x"));
    out.push(format!("x-{id}"));
    let tokens: Vec<&str> = id.split('-').collect();
    if tokens.len() > 1 {
        out.push(tokens[..tokens.len() - 1].join("-"));
    }
    for i in 0..tokens.len() {
        let mut put = |t: &str| {
            let mut m = tokens.clone();
            m[i] = t;
            out.push(m.join("-"));
        };
        for j in 0..tokens.len() {
            if tokens[j] != tokens[i] {
                put(tokens[j]);
            }
        }
        for other in others {
            if let Some(t) = other.split('-').nth(i) {
                put(t);
            }
        }
    }
    out.retain(|m| m != id);
    out
}

/// The axes of `axes` that set no field an earlier one sets (the same dotted path, or
/// one under another: refused at load, [`SweepError::SameField`]), so that the property
/// tests make sweeps that load. (The generators write each index one way and use no `*`,
/// so the dotted texts decide.)
#[cfg(test)]
pub(crate) fn apart(axes: &[(String, String)]) -> Vec<(String, String)> {
    let mut kept: Vec<(String, String)> = Vec::new();
    let paths =
        |key: &str| -> Vec<String> { key.split(',').map(|p| p.trim_start().to_string()).collect() };
    let meet = |a: &str, b: &str| {
        a == b || a.starts_with(&format!("{b}.")) || b.starts_with(&format!("{a}."))
    };
    for (k, v) in axes {
        let clash = kept.iter().any(|(other, _)| {
            paths(other)
                .iter()
                .any(|a| paths(k).iter().any(|b| meet(a, b)))
        });
        if !clash {
            kept.push((k.clone(), v.clone()));
        }
    }
    kept
}

#[cfg(test)]
mod plan_tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::HashSet;

    /// The sweep of `axes` (key, values as TOML) on a base variant with a scheme, one solver
    /// and a path; with a declared id when `id`.
    fn sweep(axes: &[(String, String)], id: bool) -> Option<Sweep> {
        let entries: Vec<String> = super::apart(axes)
            .iter()
            .map(|(k, v)| format!("\"{k}\" = {v}"))
            .collect();
        let text = format!(
            "label = \"L\"\n{}scheme = {{ kind = \"x\", mu = 1.0 }}\nsolvers = [{{ kind = \"znn\" }}]\npath = {{ name = \"circle\" }}\nexpected_failure = {{ why = \"w\" }}\nsweep = {{ {} }}",
            if id { "id = \"z\"\n" } else { "" },
            entries.join(", ")
        );
        let t: Table = toml::from_str(&text).unwrap();
        let place = Place {
            experiment: 0,
            id: "e".to_string(),
            variant: 0,
            label: "L".to_string(),
        };
        Sweep::new(&t, MAX_EXPANSION, place).ok()
    }

    /// Every variant of `s`, by an odometer over its axes (the last digit turning fastest).
    fn odometer(s: &Sweep) -> Vec<Table> {
        let mut out = Vec::new();
        let mut idx = vec![0; s.axes.len()];
        loop {
            let mut t = s.base.clone();
            t.remove("label");
            t.remove("id");
            for (a, &i) in s.axes.iter().zip(&idx) {
                for (path, value) in a.paths.iter().zip(a.value(i).0) {
                    set(&mut t, path, value);
                }
            }
            out.push(t);
            let mut a = idx.len();
            loop {
                if a == 0 {
                    return out;
                }
                a -= 1;
                idx[a] += 1;
                if idx[a] < s.axes[a].len() {
                    break;
                }
                idx[a] = 0;
            }
        }
    }

    /// How many runs a variant table makes: the exact column (default true) and its solvers.
    fn runs(t: &Table, exact_only: bool) -> usize {
        let exact = t.get("exact").is_none_or(|v| v.as_bool() == Some(true));
        let solvers = t
            .get("solvers")
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        usize::from(exact) + if exact_only { 0 } else { solvers }
    }

    fn list(values: &[String]) -> String {
        format!("[{}]", values.join(", "))
    }

    /// An axis of the run-count tests: its key and its values.
    fn axis() -> impl Strategy<Value = (String, String)> {
        let n = 1usize..4;
        prop_oneof![
            n.clone().prop_map(|n| (
                "scheme.mu".to_string(),
                list(&(0..n).map(|k| format!("{k}.5")).collect::<Vec<_>>())
            )),
            Just(("exact".to_string(), "[true, false]".to_string())),
            Just(("exact".to_string(), "[false]".to_string())),
            n.clone().prop_map(|n| (
                "solvers".to_string(),
                list(
                    &(0..n)
                        .map(|k| list(&vec!["{ kind = \"znn\" }".to_string(); k]))
                        .collect::<Vec<_>>()
                )
            )),
            (0i64..3, 1i64..3, 0i64..4).prop_map(|(a, s, n)| (
                "scheme.n".to_string(),
                format!("{{ from = {a}, to = {}, step = {s} }}", a + s * n)
            )),
            (0u32..3, 0u32..4).prop_map(|(a, n)| (
                "scheme.r".to_string(),
                format!("{{ from = 0.{a}, to = {}.{a}, step = 0.5 }}", n)
            )),
            n.clone().prop_map(|n| (
                "exact, scheme.q".to_string(),
                list(
                    &(0..n)
                        .map(|k| format!("[{}, {k}]", k % 2 == 0))
                        .collect::<Vec<_>>()
                )
            )),
            n.prop_map(|n| (
                "path.scale".to_string(),
                list(
                    &(0..n)
                        .map(|k| format!("{{ value = {k}, label = \"s{k}\" }}"))
                        .collect::<Vec<_>>()
                )
            )),
        ]
    }

    /// A value of the name tests: texts whose slugs are one token or not, repeated or not.
    fn named() -> impl Strategy<Value = String> {
        prop_oneof![
            Just("\"a\"".to_string()),
            Just("\"b\"".to_string()),
            Just("\"x why y\"".to_string()),
            Just("\"y why w\"".to_string()),
            Just("\"x\"".to_string()),
            Just("\"a, b\"".to_string()),
            Just("\"A\"".to_string()),
            Just("\"\"".to_string()),
            Just("0.5".to_string()),
            Just("-0.5".to_string()),
            Just("{ value = 1, label = \"one\" }".to_string()),
            Just("{ value = 2, label = \"\" }".to_string()),
            Just("{ value = 3, label = \"t w\" }".to_string()),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn a_made_variant_is_the_odometers_and_runs_are_found_by_bisection(
            axes in proptest::collection::vec(axis(), 1..4),
            id in any::<bool>(),
        ) {
            let Some(s) = sweep(&axes, id) else { return Ok(()) };
            let all = odometer(&s);
            prop_assert_eq!(all.len(), s.len());
            for (i, want) in all.iter().enumerate() {
                let (mut t, kept) = s.table(i);
                let (label, made_id) = s.names(i);
                prop_assert_eq!(t.remove("label").and_then(|l| l.as_str().map(String::from)), Some(label));
                prop_assert_eq!(t.remove("id").and_then(|l| l.as_str().map(String::from)), made_id);
                prop_assert_eq!(&t, want);
                let before: usize = all[..i].iter().map(|t| runs(t, false)).sum();
                prop_assert_eq!(kept.first_run, before);
            }
            for exact_only in [false, true] {
                let mut before = 0;
                for (v, t) in all.iter().enumerate() {
                    prop_assert_eq!(s.runs_before(v, exact_only), before);
                    for r in before..before + runs(t, exact_only) {
                        prop_assert_eq!(s.variant_of_run(r, exact_only), v);
                    }
                    before += runs(t, exact_only);
                }
                prop_assert_eq!(s.runs_before(s.len(), exact_only), before);
            }
        }

        #[test]
        fn names_decided_from_the_axes_are_distinct(
            axes in proptest::collection::vec(
                (prop_oneof![Just("path.name"), Just("expected_failure.why"), Just("scheme.mu")],
                 proptest::collection::vec(named(), 1..4)),
                1..4,
            ),
            id in any::<bool>(),
        ) {
            let axes: Vec<(String, String)> =
                axes.into_iter().map(|(k, v)| (k.to_string(), list(&v))).collect();
            let Some(s) = sweep(&axes, id) else { return Ok(()) };
            let Some(p) = s.prefixes() else {
                prop_assert!(s.id_reader().is_none());
                return Ok(());
            };
            let (mut labels, mut ids) = (HashSet::new(), HashSet::new());
            for v in 0..s.len() {
                let (label, made) = s.names(v);
                let id = made.unwrap_or_else(|| settings::slug(&label));
                prop_assert_eq!(&s.id(v), &id);
                prop_assert!(label.starts_with(&p.label), "{} {:?}", label, p);
                prop_assert!(id.starts_with(&p.id), "{} {:?}", id, p);
                prop_assert!(labels.insert(label.clone()), "label {} twice", label);
                prop_assert!(ids.insert(id.clone()), "id {} twice", id);
            }
            reads_back(&s)?;
        }

        /// Where the names are decided from the axes, every id is read back into its variant,
        /// and a text near one (a wrong digit, an extra or a missing token, a value slug of
        /// another axis, another variant's token) into the variant that has it, or none.
        #[test]
        fn ids_are_read_back_into_their_variants(
            axes in proptest::collection::vec(axis(), 1..4),
            id in any::<bool>(),
        ) {
            let Some(s) = sweep(&axes, id) else { return Ok(()) };
            prop_assert_eq!(s.id_reader().is_some(), s.prefixes().is_some());
            reads_back(&s)?;
        }
    }

    /// That the ids of `s` are read back into their variants, and the texts near them into
    /// the variant whose id they are, or none ([`IdReader`]); nothing when its names are not
    /// decided from its axes.
    fn reads_back(s: &Sweep) -> Result<(), TestCaseError> {
        let Some(r) = s.id_reader() else {
            return Ok(());
        };
        let ids: Vec<String> = (0..s.len()).map(|v| s.id(v)).collect();
        for (v, id) in ids.iter().enumerate() {
            prop_assert_eq!(r.variant(id), Some(v), "{}", id);
            let others: Vec<String> = ids.iter().skip(v + 1).take(3).cloned().collect();
            for near in near_misses(id, &others) {
                let want = ids.iter().position(|i| *i == near);
                prop_assert_eq!(r.variant(&near), want, "{} near {}", near, id);
            }
        }
        Ok(())
    }

    /// A range's values are read back from their slugs, across zero on either side, in
    /// integers, decimals and floats too fine for decimals.
    #[test]
    fn a_range_reads_its_values_back_from_their_slugs() {
        for t in [
            "{ from = 3, to = 30, step = 3 }",
            "{ from = -30, to = 0, step = 3 }",
            "{ from = 0, to = -12, step = -4 }",
            "{ from = 1.0, to = 2.0, step = 0.01 }",
            "{ from = -2.5, to = -0.5, step = 0.25 }",
            "{ from = 1e-300, to = 1.1e-299, step = 1e-300 }",
            "{ from = 1e200, to = 1.5e201, step = 1e200 }",
        ] {
            let table: Table = toml::from_str(&format!("r = {t}")).unwrap();
            let r = Range::parse(table["r"].as_table().unwrap()).unwrap();
            assert!(r.distinct_slugs(), "{t}");
            for (k, v) in r.values().iter().enumerate() {
                let slug = settings::slug(&display(v));
                assert_eq!(r.index_of(&slug), Some(k), "{t}: {slug}");
                for near in [
                    format!("{slug}1"),
                    format!("1{slug}"),
                    slug.replace('.', ""),
                ] {
                    let want = r
                        .values()
                        .iter()
                        .position(|v| settings::slug(&display(v)) == near);
                    assert_eq!(r.index_of(&near), want, "{t}: {near}");
                }
            }
            assert_eq!(r.index_of("x"), None);
            assert_eq!(r.index_of(""), None);
        }
    }

    /// The two facts of docs/cluster.md that a decision from the axes must keep: a value whose
    /// slug is not one token (it moves text between axes) and two values of one axis with one
    /// slug (0.5 and -0.5) leave the names undecided, so they are compared one by one (and
    /// the load refuses the clash: `id_tests`).
    #[test]
    fn names_that_could_clash_are_not_decided_from_the_axes() {
        let s = |axes: &[(&str, &str)]| {
            let axes: Vec<(String, String)> = axes
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect();
            sweep(&axes, true).unwrap().prefixes()
        };
        assert_eq!(
            s(&[
                ("path.name", "[\"x why y\", \"x\"]"),
                ("expected_failure.why", "[\"w\", \"y why w\"]")
            ]),
            None
        );
        assert_eq!(s(&[("scheme.mu", "[0.5, -0.5]")]), None);
        assert_eq!(
            s(&[("scheme.mu", "{ from = -1.0, to = 1.0, step = 0.5 }")]),
            None
        );
        assert_eq!(
            s(&[
                ("scheme.mu", "{ from = 1.0, to = 2.0, step = 0.5 }"),
                ("path.name", "[\"a\", \"b\"]")
            ]),
            Some(Prefixes {
                id: "z-mu-".to_string(),
                label: "L [mu=".to_string()
            })
        );
    }
}
