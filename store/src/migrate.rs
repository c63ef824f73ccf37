//! Results written before run ids, brought up to date once.
//!
//! Until run ids existed, a run was named by display labels: `runs.csv`, `ladder.csv` and
//! `attribution.csv` had `experiment, variant, solver` (the variant's and the solver's labels,
//! the exact column's solver `exact (Clarabel)`) and no `variant_id, solver_id`; traces were
//! `traces/<experiment>/<slug(variant label)>__<slug(solver label)>.csv`. [`LabelIndex`] maps
//! each (experiment, variant label, solver label) of the experiment files' runs to its
//! [`RunKey`]; [`add_ids`] inserts the two id columns after `experiment` in a legacy table and
//! leaves a current one alone. A row no experiment file describes gets the slugs of its labels
//! (it is then pruned as any undescribed run is). `ResultsDir::migrate_ids` applies this to a
//! results directory and renames the traces.

use settings::slug;
use spec::ids::IdError;
use spec::RunKey;
use spec::RunSpec;
use spec::EXACT_ID;
use std::collections::HashMap;
use std::path::Path;

/// The exact column's label before run ids.
pub const LEGACY_EXACT_LABEL: &str = "exact (Clarabel)";

/// A problem reading a legacy table.
#[derive(Debug, thiserror::Error)]
pub enum MigrateError {
    /// The table is not CSV of one width per row, or the migrated table could not be written.
    #[error("{0}")]
    Csv(#[from] csv::Error),
    /// The legacy table lacks a column the ids are made from (the column's name).
    #[error(
        "a table with ids needs the columns `experiment`, `variant` and `solver`; `{0}` is missing"
    )]
    Column(&'static str),
    /// The migrated table is not UTF-8.
    #[error("{0}")]
    Utf8(#[from] std::string::FromUtf8Error),
    /// A legacy row whose labels make no valid ids.
    #[error("line {line}: {error}")]
    Id {
        /// The row's line in the table (the header is line 1).
        line: usize,
        /// Why its labels make no id.
        error: IdError,
    },
}

/// (experiment, variant label, solver label) -> run key, over the experiment files' runs.
#[derive(Clone, Debug, Default)]
pub struct LabelIndex(HashMap<(String, String, String), RunKey>);

impl LabelIndex {
    /// The index of `jobs` (borrowed or made as they are taken: the runs of the experiment
    /// files need not be collected for it).
    pub fn new(jobs: impl IntoIterator<Item = impl std::borrow::Borrow<RunSpec>>) -> Self {
        let jobs = jobs.into_iter();
        let mut map = HashMap::with_capacity(jobs.size_hint().0);
        for j in jobs {
            let j = j.borrow();
            let label = if j.solver.id() == EXACT_ID {
                LEGACY_EXACT_LABEL.to_string()
            } else {
                j.solver.label()
            };
            map.insert(
                (j.experiment.to_string(), j.variant.clone(), label),
                j.key(),
            );
        }
        LabelIndex(map)
    }

    /// The key of a legacy row: the described run's, or the slugs of its labels (an error
    /// when they make no valid ids).
    pub fn key(&self, experiment: &str, variant: &str, solver: &str) -> Result<RunKey, IdError> {
        if let Some(key) = self
            .0
            .get(&(experiment.into(), variant.into(), solver.into()))
        {
            return Ok(key.clone());
        }
        let solver = if solver == LEGACY_EXACT_LABEL {
            EXACT_ID.to_string()
        } else {
            slug(solver)
        };
        RunKey::from_ids(experiment, &slug(variant), &solver)
    }
}

/// A legacy row's identity: (experiment, variant label, solver label).
pub type LegacyKey = (String, String, String);

/// A migrated table: its text, and each row's legacy key beside its run key.
pub type Migrated = (Vec<u8>, Vec<(LegacyKey, RunKey)>);

/// Whether the table at `path` has the id columns (`variant_id` in its header line), read
/// no further than that line; false when it cannot be read (its reader then says why).
pub fn has_ids(path: &Path) -> bool {
    use std::io::{BufRead, Read};
    let Ok(file) = crate::owned_dir::open_file(path) else {
        return false;
    };
    let mut header = Vec::new();
    std::io::BufReader::new(file)
        .take(1 << 16)
        .read_until(b'\n', &mut header)
        .is_ok()
        && csv::ReaderBuilder::new()
            .from_reader(header.as_slice())
            .headers()
            .is_ok_and(|h| h.iter().any(|c| c == "variant_id"))
}

/// A legacy table's text with `variant_id, solver_id` after `experiment`, each row's ids from
/// the index `index()` makes (only for a legacy table: building it costs a pass over every
/// run of the experiment files); `None` when the table already has ids (or is empty).
pub fn add_ids(
    text: &[u8],
    index: impl FnOnce() -> LabelIndex,
) -> Result<Option<Migrated>, MigrateError> {
    let mut r = csv::ReaderBuilder::new().flexible(false).from_reader(text);
    let header = r.headers()?.clone();
    if header.is_empty() || header.iter().any(|h| h == "variant_id") {
        return Ok(None);
    }
    let col = |name: &'static str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or(MigrateError::Column(name))
    };
    let (e, v, s) = (col("experiment")?, col("variant")?, col("solver")?);
    let index = index();
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    let with_ids = |rec: &csv::StringRecord, ids: [&str; 2]| -> Vec<String> {
        let mut out: Vec<String> = Vec::with_capacity(rec.len() + 2);
        for (i, f) in rec.iter().enumerate() {
            out.push(f.to_string());
            if i == e {
                out.extend(ids.iter().map(|x| x.to_string()));
            }
        }
        out
    };
    w.write_record(with_ids(&header, ["variant_id", "solver_id"]))?;
    let mut keys = Vec::new();
    for rec in r.records() {
        let rec = rec?;
        let legacy = (rec[e].to_string(), rec[v].to_string(), rec[s].to_string());
        let key = index
            .key(&legacy.0, &legacy.1, &legacy.2)
            .map_err(|error| MigrateError::Id {
                line: keys.len() + 2,
                error,
            })?;
        w.write_record(with_ids(&rec, [&key.variant, &key.solver]))?;
        keys.push((legacy, key));
    }
    let bytes = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    Ok(Some((bytes, keys)))
}

/// A legacy trace's path under the traces directory (`results/traces/`):
/// `<experiment>/<slug(variant)>__<slug(solver)>.csv`.
pub fn legacy_trace_name(experiment: &str, variant: &str, solver: &str) -> std::path::PathBuf {
    std::path::Path::new(experiment).join(format!("{}__{}.csv", slug(variant), slug(solver)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table's ids are read off its header line alone: a current header says yes, a legacy
    /// one or a missing file no.
    #[test]
    fn ids_are_read_off_the_header_line() {
        let dir = inputs::Scratch::dir("has-ids");
        let (current, legacy) = (dir.join("current.csv"), dir.join("legacy.csv"));
        std::fs::write(&current, "paper,experiment,variant_id,solver_id\np,e,v,s\n").unwrap();
        std::fs::write(&legacy, "paper,experiment,variant,solver\np,e,v,s\n").unwrap();
        assert!(has_ids(&current));
        assert!(!has_ids(&legacy));
        assert!(!has_ids(&dir.join("absent.csv")));
    }

    #[test]
    fn legacy_tables_get_ids_and_current_ones_are_left_alone() {
        let legacy = b"paper,experiment,variant,scheme,solver,x\np,p-e,VLTCO [star-lines],S,exact (Clarabel),1\np,p-e,Gone,S,LVI-PDNN,2\n";
        let (text, keys) = add_ids(legacy, LabelIndex::default).unwrap().unwrap();
        let text = String::from_utf8(text).unwrap();
        assert_eq!(
            text,
            "paper,experiment,variant_id,solver_id,variant,scheme,solver,x\np,p-e,vltco-star-lines,exact,VLTCO [star-lines],S,exact (Clarabel),1\np,p-e,gone,lvi-pdnn,Gone,S,LVI-PDNN,2\n"
        );
        assert_eq!(
            keys[0].1,
            RunKey::from_ids("p-e", "vltco-star-lines", "exact").unwrap()
        );
        // A current table is left alone without the index being made (a pass over every run).
        let unused = || -> LabelIndex { panic!("the index of a current table was made") };
        assert!(add_ids(text.as_bytes(), unused).unwrap().is_none());
        assert!(matches!(
            add_ids(b"paper,variant,solver\n", LabelIndex::default),
            Err(MigrateError::Column("experiment"))
        ));
        assert_eq!(
            legacy_trace_name("e", "VLTCO", "exact (Clarabel)"),
            std::path::Path::new("e/vltco__exact-clarabel.csv")
        );
    }
}
