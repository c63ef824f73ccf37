//! The sweep grammar of experiment files: one `[[experiment.variant]]` that stands for many.
//!
//! A variant may give a `sweep` table. Each entry names a parameter by its *dotted path* into
//! the variant table and lists the values it takes; the variant expands into the cartesian
//! product of the entries (the first entry outermost, the last one varying fastest), each copy
//! with its parameters set and its label generated. Expansion happens on the parsed TOML
//! (`toml::Table`): each expanded variant is built as a table and deserialised at once into
//! the [`crate::experiment::PaperFile`]'s variant list (the rest of the file is read first), so
//! an expanded variant is exactly the variant one would have written by hand, and no table is
//! kept per expanded variant (a sweep of 10^6 variants holds 10^6 read variants, not 10^6
//! tables as well; docs/cluster.md has the numbers).
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
//! is then a list with one entry per path.
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
//! [`crate::experiment::PaperFile::load`]): an unknown key path, an empty list, a swept key
//! that is neither a list nor a range, a bad range, a zipped value of the wrong length, a
//! placeholder that names no swept key, and two expanded variants with the same label.

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

/// Most variants one variant may expand into (a typo in a range should not eat the memory),
/// and most the sweeps of a whole experiments directory may expand into together (twenty
/// variants of 999,999 each must not either): the expansion of a file's sweeps takes what is left of it.
pub const MAX_EXPANSION: usize = 1_000_000;

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
/// the rest of the file is read as usual, and expanded afterwards straight into the read
/// variants ([`Sweeps::expand_into`]): no expanded variant is ever held as a TOML table.
#[derive(Debug)]
pub struct Sweeps(Vec<SweepAt>);

/// One sweep variant and where it stood.
#[derive(Debug)]
struct SweepAt {
    /// Index of its experiment in the file, and the experiment's id (for errors).
    experiment: usize,
    id: String,
    /// Its index among the experiment's variants as written.
    variant: usize,
    table: Table,
}

/// Takes every variant with a `sweep` out of the parsed experiment file `doc` (the other
/// variants stay, in order), to be expanded by [`Sweeps::expand_into`] once the file is read.
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
                Value::Table(table) if table.contains_key("sweep") => out.push(SweepAt {
                    experiment: i,
                    id: id.clone(),
                    variant: j,
                    table,
                }),
                other => kept.push(other),
            }
        }
        *vars = kept;
    }
    Sweeps(out)
}

impl Sweeps {
    /// Puts the expansion of every sweep back where its variant stood: `variants` are the
    /// variant lists of the file's experiments, in order, as read without the sweeps; each
    /// expanded table is read by `read` as it is made and dropped. At most `budget` variants
    /// in all (what is left of [`MAX_EXPANSION`] for the files read so far; reduced by what
    /// this file takes), each sweep's product checked against it before anything is built.
    /// `read` takes the expanded variant's [`KeptTraces`] too, counted with `runs` (how many
    /// runs a read variant makes).
    pub fn expand_into<'a, V: 'a>(
        self,
        variants: impl Iterator<Item = &'a mut Vec<V>>,
        read: impl Fn(Table, KeptTraces) -> Result<V, toml::de::Error>,
        runs: impl Fn(&V) -> usize,
        budget: &mut usize,
    ) -> Result<(), SweepError> {
        let mut sweeps = self.0.into_iter().peekable();
        for (i, list) in variants.enumerate() {
            let mut planned = Vec::new();
            while let Some(s) = sweeps.next_if(|s| s.experiment == i) {
                let label = s
                    .table
                    .get("label")
                    .and_then(Value::as_str)
                    .unwrap_or("?")
                    .to_string();
                let at = move |error| SweepError::In {
                    experiment: i,
                    id: s.id.clone(),
                    variant: s.variant,
                    label: label.clone(),
                    error: Box::new(error),
                };
                let plan = Plan::new(&s.table, *budget).map_err(&at)?;
                *budget -= plan.total;
                planned.push((s.variant, plan, at));
            }
            if planned.is_empty() {
                continue;
            }
            // One allocation of the final size: the expansions are read into it directly.
            let total = list.len() + planned.iter().map(|(_, p, _)| p.total).sum::<usize>();
            let mut fixed = std::mem::take(list).into_iter();
            let mut out = Vec::with_capacity(total);
            let mut written = 0;
            for (position, plan, at) in planned {
                out.extend(fixed.by_ref().take(position - written));
                written = position + 1;
                let mut first_run = 0;
                plan.for_each(|t| {
                    let expanded = t
                        .get("label")
                        .and_then(Value::as_str)
                        .unwrap_or("?")
                        .to_string();
                    let kept = KeptTraces {
                        traces: plan.traces,
                        first_run,
                    };
                    let v = read(t, kept).map_err(|error| SweepError::DoesNotRead {
                        expanded,
                        error: error.into(),
                        keys: plan.keys(),
                    })?;
                    first_run += runs(&v);
                    out.push(v);
                    Ok(())
                })
                .map_err(&at)?;
            }
            out.extend(fixed);
            *list = out;
        }
        Ok(())
    }
}

/// One axis of a sweep: the paths it sets (several: a zipped group) and its values.
#[derive(Debug)]
struct Axis {
    key: String,
    paths: Vec<Vec<String>>,
    /// Per value: the value of each path, and the text that names it (a labelled value's).
    values: Vec<(Vec<Value>, Option<String>)>,
}

/// Expands one variant table (with its `sweep`) into the variants of the product (at most
/// [`MAX_EXPANSION`]). Errors start with the field (`field `sweep` key `...``), the caller
/// prefixes experiment and variant. The tests' view of one variant; a file's variants expand
/// through [`Sweeps::expand_into`].
#[cfg(test)]
fn expand_variant(variant: &Table) -> Result<Vec<Table>, SweepError> {
    if !variant.contains_key("sweep") {
        return Ok(vec![variant.clone()]);
    }
    let plan = Plan::new(variant, MAX_EXPANSION)?;
    let mut out = Vec::with_capacity(plan.total);
    plan.for_each(|t| {
        out.push(t);
        Ok(())
    })?;
    Ok(out)
}

/// A sweep read and checked, its variants not yet built: the base variant (without `sweep`),
/// the axes, the label and id templates and the size of the product.
struct Plan {
    base: Table,
    axes: Vec<Axis>,
    template: String,
    names: Vec<(String, usize, usize)>,
    id_template: Option<String>,
    total: usize,
    traces: Traces,
}

impl Plan {
    /// Reads the sweep of `variant` into at most `budget` variants (of the [`MAX_EXPANSION`] a
    /// directory's sweeps share), the product checked as each axis is read.
    fn new(variant: &Table, budget: usize) -> Result<Self, SweepError> {
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
        let mut axes = Vec::with_capacity(sweep.len());
        let mut total = 1usize;
        for (key, val) in &sweep {
            let axis = parse_axis(&base, key, val)?;
            total = total
                .checked_mul(axis.values.len())
                .filter(|n| *n <= MAX_EXPANSION)
                .ok_or(SweepError::TooMany { max: MAX_EXPANSION })?;
            if total > budget {
                return Err(SweepError::TooManyInAll { max: MAX_EXPANSION });
            }
            axes.push(axis);
        }
        let names = placeholder_names(&axes);
        check_template(&template, &names)?;
        Ok(Plan {
            base,
            axes,
            template,
            names,
            id_template,
            total,
            traces,
        })
    }

    /// The swept keys, quoted (for errors).
    fn keys(&self) -> Vec<String> {
        self.axes.iter().map(|a| format!("`{}`", a.key)).collect()
    }

    /// Builds the variants of the product one at a time, in order (the last axis varying
    /// fastest), each with its parameters, label and id set, and gives each to `each`; two
    /// with the same label are an error.
    fn for_each(
        &self,
        mut each: impl FnMut(Table) -> Result<(), SweepError>,
    ) -> Result<(), SweepError> {
        // A map, not a list: 10^6 labels are checked in linear time.
        let mut labels: std::collections::HashMap<String, usize> =
            std::collections::HashMap::with_capacity(self.total);
        let mut idx = vec![0usize; self.axes.len()];
        for n in 0..self.total {
            // Odometer: the last axis varies fastest.
            let mut rest = n;
            for (a, i) in self.axes.iter().zip(idx.iter_mut()).rev() {
                *i = rest % a.values.len();
                rest /= a.values.len();
            }
            let mut t = self.base.clone();
            for (a, &i) in self.axes.iter().zip(&idx) {
                for (path, value) in a.paths.iter().zip(&a.values[i].0) {
                    set(&mut t, path, value.clone());
                }
            }
            let label = make_label(&self.template, &self.axes, &idx, &self.names);
            if let Some(m) = labels.get(&label) {
                return Err(SweepError::SameLabel {
                    first: *m,
                    second: n,
                    label,
                    keys: self.keys(),
                });
            }
            if let Some(id) = &self.id_template {
                t.insert(
                    "id".to_string(),
                    Value::String(make_id(id, &self.axes, &idx)),
                );
            }
            t.insert("label".to_string(), Value::String(label.clone()));
            labels.insert(label, n);
            each(t)?;
        }
        Ok(())
    }
}

fn parse_axis(base: &Table, key: &str, val: &Value) -> Result<Axis, SweepError> {
    let at = |error| SweepError::Key {
        key: key.to_string(),
        error,
    };
    let paths: Vec<Vec<String>> = key
        .split(',')
        .map(|p| p.trim().split('.').map(|s| s.trim().to_string()).collect())
        .collect();
    for path in &paths {
        check_path(base, path).map_err(|e| at(SweepKeyError::Path(e)))?;
    }
    let raw: Vec<Value> = match val {
        Value::Array(a) if a.is_empty() => return Err(at(SweepKeyError::NoValues)),
        Value::Array(a) => a.clone(),
        Value::Table(t) if paths.len() == 1 => range(t).map_err(|e| at(e.into()))?,
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
    Ok(Axis {
        key: key.to_string(),
        paths,
        values,
    })
}

/// A path is known when its first segment is a variant field and every table or array on the
/// way is there (the last segment may be new in a table).
fn check_path(base: &Table, path: &[String]) -> Result<(), KeyPathError> {
    let first = &path[0];
    if path.iter().any(String::is_empty) {
        return Err(KeyPathError::EmptySegment);
    }
    if !VARIANT_FIELDS.contains(&first.as_str()) {
        return Err(KeyPathError::NotAField {
            first: first.clone(),
        });
    }
    fn walk(v: Option<&Value>, rest: &[String], done: &str) -> Result<(), KeyPathError> {
        let Some((seg, rest)) = rest.split_first() else {
            return Ok(());
        };
        let here = format!("{done}.{seg}");
        match v {
            Some(Value::Table(t)) => {
                if rest.is_empty() {
                    Ok(())
                } else {
                    match t.get(seg.as_str()) {
                        Some(x) => walk(Some(x), rest, &here),
                        None => Err(KeyPathError::NoKey {
                            done: done.to_string(),
                            segment: seg.clone(),
                        }),
                    }
                }
            }
            Some(Value::Array(a)) => {
                if seg == "*" {
                    if a.is_empty() {
                        return Err(KeyPathError::EmptyList {
                            done: done.to_string(),
                        });
                    }
                    a.iter().try_for_each(|x| walk(Some(x), rest, &here))
                } else {
                    let i: usize = seg.parse().map_err(|_| KeyPathError::BadIndex {
                        done: done.to_string(),
                        segment: seg.clone(),
                    })?;
                    match a.get(i) {
                        Some(x) => walk(Some(x), rest, &here),
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
    walk(base.get(first.as_str()), &path[1..], first)
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

fn make_label(
    template: &str,
    axes: &[Axis],
    idx: &[usize],
    names: &[(String, usize, usize)],
) -> String {
    let text = |ai: usize, pi: usize| {
        let (vals, label) = &axes[ai].values[idx[ai]];
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
    for (ai, a) in axes.iter().enumerate() {
        let (vals, label) = &a.values[idx[ai]];
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

/// The id of one expanded variant: the base `id` followed by every swept path's last segment
/// and raw value (labelled values by their value, not their text), as a slug: ids do not move
/// when a label or a labelled value's text is reworded.
fn make_id(base: &str, axes: &[Axis], idx: &[usize]) -> String {
    let mut text = base.to_string();
    for (ai, a) in axes.iter().enumerate() {
        for (p, v) in a.paths.iter().zip(&a.values[idx[ai]].0) {
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

/// The values of a range table `{ from, to, step }`.
fn range(t: &Table) -> Result<Vec<Value>, RangeError> {
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
        // a + k s lies between a and b: an i64 (k s alone may not be).
        return Ok((0..=n)
            .map(|k| Value::Integer((wa + k * ws) as i64))
            .collect());
    }
    let num = |key: &'static str| match t.get(key) {
        Some(Value::Integer(i)) => Ok(*i as f64),
        Some(Value::Float(f)) if f.is_finite() => Ok(*f),
        _ => Err(RangeError::NotANumber { key }),
    };
    let (a, b, s) = (num("from")?, num("to")?, num("step")?);
    float_range(a, b, s)?
        .into_iter()
        .map(|x| Ok(Value::Float(x)))
        .collect()
}

/// a, a + s, ..., b: n = round((b - a) / s), which must be an integer to 1e-9; values in
/// decimal arithmetic.
pub fn float_range(a: f64, b: f64, s: f64) -> Result<Vec<f64>, RangeError> {
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
    let n = n as i64;
    Ok(decimal_range(a, s, n).unwrap_or_else(|| (0..=n).map(|k| a + k as f64 * s).collect()))
}

/// a + k s for k = 0..=n in decimal arithmetic (m * 10^-e, exact in i128), or None when a
/// mantissa does not fit (a float range of extreme magnitudes is then computed in f64).
fn decimal_range(a: f64, s: f64, n: i64) -> Option<Vec<f64>> {
    let ((ma, ea), (ms, es)) = (decimal(a)?, decimal(s)?);
    let e = ea.max(es);
    let scale = |m: i128, from: u32| 10i128.checked_pow(e - from)?.checked_mul(m);
    let (ma, ms) = (scale(ma, ea)?, scale(ms, es)?);
    (0..=n)
        .map(|k| {
            let m = ms.checked_mul(i128::from(k))?.checked_add(ma)?;
            format!("{m}e-{e}").parse::<f64>().ok()
        })
        .collect()
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

    /// The variant lists of the file `text`, its sweeps taken out and expanded back in place
    /// (as tables: what `PaperFile` does with variants).
    fn expand_file(text: &str, budget: &mut usize) -> Result<Vec<Vec<Table>>, SweepError> {
        let mut doc: Table = toml::from_str(text).unwrap();
        let sweeps = take_sweeps(&mut doc);
        assert!(!has_sweeps(&doc));
        let mut lists: Vec<Vec<Table>> = experiments(&doc)
            .map(|e| variants(e).cloned().collect())
            .collect();
        sweeps.expand_into(lists.iter_mut(), |t, _| Ok(t), |_| 1, budget)?;
        Ok(lists)
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
        assert_eq!(float_range(1e29, 1e29, 1e-20).unwrap(), [1e29]);
        assert_eq!(float_range(-1e29, 1e29, 1e29).unwrap(), [-1e29, 0.0, 1e29]);
        assert!(float_range(-1e308, 1e308, 1e-308).is_err());
        let ints = |text: &str| {
            range(&toml::from_str::<Table>(text).unwrap()).map(|v| {
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
        assert_eq!(float_range(0.1, 0.3, 0.1).unwrap(), [0.1, 0.2, 0.3]);
        assert_eq!(
            float_range(0.0, 1.0, 0.25).unwrap(),
            [0.0, 0.25, 0.5, 0.75, 1.0]
        );
        assert_eq!(float_range(1.0, 0.7, -0.1).unwrap(), [1.0, 0.9, 0.8, 0.7]);
        assert_eq!(float_range(2.5, 2.5, 1.0).unwrap(), [2.5]);
        assert!(float_range(0.0, 1.0, 0.3).is_err());
        assert!(float_range(0.0, 1.0, 0.0).is_err());
        assert!(float_range(0.0, 1.0, -0.5).is_err());
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
            e.contains("key `schem.mu`") && e.contains("unknown key path"),
            "{e}"
        );
        let e = err(r#"{ "path.scale" = [1.0] }"#);
        assert!(
            e.contains("key `path.scale`") && e.contains("gives no `path`"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu.x" = [1.0] }"#);
        assert!(
            e.contains("key `scheme.mu.x`") && e.contains("not a table"),
            "{e}"
        );
        let e = err(r#"{ "solvers.3.gamma" = [1.0] }"#);
        assert!(e.contains("no [3]"), "{e}");
        let e = err(r#"{ "scheme.mu" = [] }"#);
        assert!(e.contains("key `scheme.mu`") && e.contains("empty"), "{e}");
        let e = err(r#"{ "scheme.mu" = 1.0 }"#);
        assert!(
            e.contains("key `scheme.mu`") && e.contains("must be a list"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu" = { from = 0, to = 1, step = 0.3 } }"#);
        assert!(
            e.contains("key `scheme.mu`") && e.contains("does not divide"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu" = { from = 0, to = 1 } }"#);
        assert!(
            e.contains("key `scheme.mu`") && e.contains("a range is"),
            "{e}"
        );
        let e = err(r#"{ "scheme.mu, scheme.nu" = [[1.0]] }"#);
        assert!(e.contains("one per path"), "{e}");
        let e = err(r#"{ "scheme.mu" = [1, 1] }"#);
        assert!(e.contains("both get the label \"L [mu=1]\""), "{e}");
        let e = err("{}");
        assert!(e.contains("empty"), "{e}");
        let v = variant(
            "label = \"L {nu}\"\nscheme = { kind = \"x\" }\nsweep = { \"scheme.mu\" = [1] }",
        );
        let e = expand_variant(&v).unwrap_err().to_string();
        assert!(e.contains("placeholder {nu}"), "{e}");
    }

    #[test]
    fn every_expanded_variant_is_read_in_place_and_one_that_does_not_read_is_named() {
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
sweep = { "scheme.mu" = [3, 4, 5] }
"#;
        let mut doc: Table = toml::from_str(text).unwrap();
        let sweeps = take_sweeps(&mut doc);
        let read = |t: Table, _| -> Result<String, toml::de::Error> {
            let label = t["label"].as_str().unwrap().to_string();
            if label == "B [mu=4]" {
                return Err(serde::de::Error::custom("mu 4 refused"));
            }
            Ok(label)
        };
        let mut lists = [vec!["plain".to_string()]];
        let e = sweeps
            .expand_into(lists.iter_mut(), read, |_| 1, &mut MAX_EXPANSION.clone())
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("experiment[0] (id \"p-e\") variant[2] (\"B\") field `sweep`: the expanded variant \"B [mu=4]\" does not read: mu 4 refused"),
            "{e}"
        );
        let mut doc: Table = toml::from_str(&text.replace("[3, 4, 5]", "[3, 5]")).unwrap();
        let mut lists = [vec!["plain".to_string()]];
        take_sweeps(&mut doc)
            .expand_into(lists.iter_mut(), read, |_| 1, &mut MAX_EXPANSION.clone())
            .unwrap();
        assert_eq!(
            lists[0],
            ["A [mu=1]", "A [mu=2]", "plain", "B [mu=3]", "B [mu=5]"]
        );
        assert_eq!(lists[0].capacity(), 5, "one allocation of the final size");
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
                "experiment[0] (id \"p-e\") variant[0] (\"S\") field `sweep` key `scheme.mu`"
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
        file.experiments[0]
            .variants
            .iter()
            .map(|v| v.id())
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
