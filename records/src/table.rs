//! CSV tables of rows, with per-joint columns that follow the robot's joint count.
//!
//! A row type ([`Row`]) is a serde struct; most fields are one column each. A type may also hold
//! a per-joint vector (a run's drift theta(T) - theta(0), n entries for an n-joint arm), kept in
//! the struct as a `Vec<f64>` (`#[serde(skip)]`) and written as the columns
//! `<stem>_1 .. <stem>_K`, K the largest joint count among the file's rows, placed just before
//! the column [`Row::JOINTS_BEFORE`]. A row of an arm with fewer joints leaves the rest empty; a
//! row without the vector (a failed run) leaves them all empty. So a file of 5- and 6-joint runs
//! has six drift columns, one with a 7-joint Panda seven, and nothing is ever fixed at six.
//!
//! Reading checks the header against the type's fields exactly (a missing or an unknown column
//! is an old or a foreign file, never silently defaulted) and the per-joint columns for being
//! numbered 1..K without gaps; any problem is a [`TableError`] naming the line.

use serde::de::DeserializeOwned;
use serde::Serialize;

/// A row of a CSV table (see the module docs).
pub trait Row: Serialize + DeserializeOwned {
    /// Stem of the per-joint columns (`drift` -> `drift_1 ..`); `None`: the type has none.
    const JOINTS: Option<&'static str> = None;
    /// The column the per-joint columns are written before.
    const JOINTS_BEFORE: &'static str = "";
    /// The row's per-joint values (empty: none).
    fn joints(&self) -> &[f64] {
        &[]
    }
    /// Sets the per-joint values read from a file.
    fn set_joints(&mut self, _values: Vec<f64>) {}
    /// Optional columns added after a file of this type was first committed: a file that
    /// lacks them is read with them empty (an older file, not a foreign one).
    const ADDED: &'static [&'static str] = &[];
}

/// Implements [`Row`] for a struct whose per-joint vector is its field `$field` (a
/// `#[serde(skip)] Vec<f64>`), written as the columns `drift_1 .. drift_K` before `$before`.
#[macro_export]
macro_rules! drift_columns {
    ($row:ty, $field:ident, $before:literal) => {
        $crate::drift_columns!($row, $field, $before, []);
    };
    ($row:ty, $field:ident, $before:literal, [$($added:literal),*]) => {
        impl $crate::table::Row for $row {
            const JOINTS: Option<&'static str> = Some("drift");
            const ADDED: &'static [&'static str] = &[$($added),*];
            const JOINTS_BEFORE: &'static str = $before;
            fn joints(&self) -> &[f64] {
                &self.$field
            }
            fn set_joints(&mut self, values: Vec<f64>) {
                self.$field = values;
            }
        }
    };
}

/// A problem reading a table: where and what.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}{what}", .path.as_ref().map(|p| format!("{}: ", p.display())).unwrap_or_default(), if *.line > 0 { format!("line {}: ", .line) } else { String::new() })]
pub struct TableError {
    /// The file, when read from one.
    pub path: Option<std::path::PathBuf>,
    /// 1-based line (the header is line 1; 0: the file as a whole).
    pub line: u64,
    /// What is wrong.
    pub what: String,
}

/// The serde field names of `T`, in order (the fixed columns).
pub fn fields<T: DeserializeOwned>() -> &'static [&'static str] {
    use serde::de::{self, Visitor};
    struct Grab<'a>(&'a mut &'static [&'static str]);
    impl<'de> de::Deserializer<'de> for Grab<'_> {
        type Error = de::value::Error;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
            Err(de::Error::custom("not a struct"))
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Self::Error> {
            *self.0 = fields;
            Err(de::Error::custom("fields taken"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
            option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
            ignored_any
        }
    }
    let mut fields: &'static [&'static str] = &[];
    let _ = T::deserialize(Grab(&mut fields));
    fields
}

/// The header of a table of `T` whose rows have at most `k` per-joint values.
pub fn header<T: Row>(k: usize) -> Vec<String> {
    let mut out = Vec::new();
    for f in fields::<T>() {
        if let Some(stem) = T::JOINTS.filter(|_| *f == T::JOINTS_BEFORE) {
            out.extend((1..=k).map(|i| format!("{stem}_{i}")));
        }
        out.push(f.to_string());
    }
    out
}

/// The rows as CSV bytes (header first; a header even without rows), with as many per-joint
/// columns as the longest per-joint vector.
pub fn to_csv<T: Row>(rows: &[T]) -> Result<Vec<u8>, csv::Error> {
    let k = rows.iter().map(|r| r.joints().len()).max().unwrap_or(0);
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header::<T>(k))?;
    for r in rows {
        w.write_record(record(r, k)?)?;
    }
    w.into_inner().map_err(|e| csv::Error::from(e.into_error()))
}

/// The cells of one row in a table with `k` per-joint columns (`k` at least the row's count).
pub fn record<T: Row>(row: &T, k: usize) -> Result<Vec<String>, csv::Error> {
    // The fixed columns through serde, then the per-joint cells spliced in.
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    w.serialize(row)?;
    let bytes = w
        .into_inner()
        .map_err(|e| csv::Error::from(e.into_error()))?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes.as_slice());
    let fixed = reader.records().next().transpose()?.unwrap_or_default();
    let mut cells: Vec<String> = fixed.iter().map(String::from).collect();
    if T::JOINTS.is_some() {
        if let Some(at) = fields::<T>().iter().position(|f| *f == T::JOINTS_BEFORE) {
            let mut joints: Vec<String> = row.joints().iter().map(|v| format_f64(*v)).collect();
            joints.resize(k.max(joints.len()), String::new());
            cells.splice(at..at, joints);
        }
    }
    Ok(cells)
}

/// A float as the csv crate's serde writer writes it (shortest round-trip form), so per-joint
/// cells look like every other number of the file.
fn format_f64(v: f64) -> String {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    w.serialize(v).expect("a float serialises");
    let bytes = w.into_inner().expect("in-memory writer");
    String::from_utf8(bytes)
        .expect("ASCII")
        .trim_end()
        .to_string()
}

/// Reads a table of `T` from CSV text; see the module docs for what is checked.
pub fn from_reader<T: Row, R: std::io::Read>(input: R) -> Result<Vec<T>, TableError> {
    rows(input)?.collect()
}

/// The rows of a table of `T` read from CSV text one at a time, each checked as
/// [`from_reader`] checks it: a table far larger than memory is read in memory of one row.
pub fn rows<T: Row, R: std::io::Read>(input: R) -> Result<Rows<T, R>, TableError> {
    let mut reader = csv::Reader::from_reader(input);
    let header = reader
        .headers()
        .map_err(|e| at_line(e.position().map_or(1, |p| p.line()), e.to_string()))?
        .clone();
    let layout = Layout::of(&header)?;
    Ok(Rows {
        reader,
        layout,
        record: csv::StringRecord::new(),
        next: 2,
    })
}

/// The rows of a table, read one at a time ([`rows`]).
pub struct Rows<T, R> {
    reader: csv::Reader<R>,
    /// `None`: an empty file (no header, no rows).
    layout: Option<Layout<T>>,
    record: csv::StringRecord,
    /// The line of the next row, should the reader not tell it.
    next: u64,
}

impl<T: Row, R: std::io::Read> Rows<T, R> {
    /// The per-joint columns of the table's header (K of `drift_1 .. drift_K`).
    pub fn joints(&self) -> usize {
        self.layout.as_ref().map_or(0, Layout::joints)
    }

    /// Where the next row starts (byte offset and line), for [`Rows::seek`].
    pub fn position(&self) -> csv::Position {
        self.reader.position().clone()
    }
}

impl<T: Row, R: std::io::Read + std::io::Seek> Rows<T, R> {
    /// Moves to a row start taken earlier by [`Rows::position`]: a table read in another
    /// order than it was written (a journal, folded in key order).
    pub fn seek(&mut self, at: csv::Position) -> Result<(), TableError> {
        let line = at.line();
        self.next = line;
        self.reader
            .seek(at)
            .map_err(|e| at_line(line, format!("cannot seek: {e}")))
    }
}

impl<T: Row, R: std::io::Read> Iterator for Rows<T, R> {
    type Item = Result<T, TableError>;

    fn next(&mut self) -> Option<Self::Item> {
        let layout = self.layout.as_ref()?;
        let fallback = self.next;
        self.next += 1;
        match self.reader.read_record(&mut self.record) {
            Ok(false) => None,
            Ok(true) => {
                let line = self.record.position().map_or(fallback, |p| p.line());
                Some(layout.decode(&self.record, line))
            }
            Err(e) => Some(Err(at_line(
                e.position().map_or(fallback, |p| p.line()),
                format!("row does not parse: {e}"),
            ))),
        }
    }
}

/// How a table's header maps onto `T` (checked against its schema, module docs).
struct Layout<T> {
    joint_cols: Vec<usize>,
    fixed_header: csv::StringRecord,
    padded: usize,
    row: std::marker::PhantomData<fn() -> T>,
}

impl<T: Row> Layout<T> {
    /// The layout of `header`; `None` for an empty header (an empty file).
    fn of(header: &csv::StringRecord) -> Result<Option<Self>, TableError> {
        if header.is_empty() || (header.len() == 1 && header[0].is_empty()) {
            return Ok(None);
        }
        let joint_cols = joint_columns::<T>(header)?;
        let (fixed_header, padded) = fixed_columns::<T>(header, &joint_cols)?;
        Ok(Some(Self {
            joint_cols,
            fixed_header,
            padded: padded.len(),
            row: std::marker::PhantomData,
        }))
    }

    fn joints(&self) -> usize {
        self.joint_cols.len()
    }

    /// The row `record` (at `line`).
    fn decode(&self, record: &csv::StringRecord, line: u64) -> Result<T, TableError> {
        let mut fixed: csv::StringRecord = record
            .iter()
            .enumerate()
            .filter(|(i, _)| !self.joint_cols.contains(i))
            .map(|(_, c)| c)
            .collect();
        for _ in 0..self.padded {
            fixed.push_field("");
        }
        let mut row: T = fixed.deserialize(Some(&self.fixed_header)).map_err(|e| {
            let what = match e.kind() {
                csv::ErrorKind::Deserialize { err, .. } => format!("row does not parse: {err}"),
                _ => format!("row does not parse: {e}"),
            };
            at_line(line, what)
        })?;
        let cells: Vec<&str> = self.joint_cols.iter().map(|&i| &record[i]).collect();
        row.set_joints(joint_values::<T>(&cells, line)?);
        Ok(row)
    }
}

/// A problem at `line` of a table read from text (the file is added by the store,
/// `store::table::read`).
fn at_line(line: u64, what: String) -> TableError {
    TableError {
        path: None,
        line,
        what,
    }
}

/// The indices of the header's per-joint columns `<stem>_<k>`, which must be numbered 1..K in
/// order.
fn joint_columns<T: Row>(header: &csv::StringRecord) -> Result<Vec<usize>, TableError> {
    let joint_index = |h: &str| -> Option<usize> {
        let stem = T::JOINTS?;
        h.strip_prefix(stem)?
            .strip_prefix('_')?
            .parse::<usize>()
            .ok()
    };
    let joint_cols: Vec<usize> = (0..header.len())
        .filter(|&i| joint_index(&header[i]).is_some())
        .collect();
    for (k, &i) in joint_cols.iter().enumerate() {
        if joint_index(&header[i]) != Some(k + 1) {
            return Err(at_line(
                1,
                format!(
                    "per-joint column {} out of order (expected {}_{})",
                    &header[i],
                    T::JOINTS.unwrap_or_default(),
                    k + 1
                ),
            ));
        }
    }
    Ok(joint_cols)
}

/// The header's fixed columns (all but `joint_cols`), checked against `T`'s schema: every field
/// there, and no other. A field of a later version ([`Row::ADDED`]) that an older file lacks
/// is appended to the header and returned among the padded columns, read as empty cells.
fn fixed_columns<T: Row>(
    header: &csv::StringRecord,
    joint_cols: &[usize],
) -> Result<(csv::StringRecord, Vec<&'static str>), TableError> {
    let mut fixed_header: csv::StringRecord = header
        .iter()
        .enumerate()
        .filter(|(i, _)| !joint_cols.contains(i))
        .map(|(_, h)| h)
        .collect();
    let expected = fields::<T>();
    let missing: Vec<&str> = expected
        .iter()
        .copied()
        .filter(|c| !fixed_header.iter().any(|h| h == *c))
        .collect();
    let unknown: Vec<&str> = fixed_header
        .iter()
        .filter(|h| !expected.contains(h))
        .collect();
    // Optional columns of a later version that an older file lacks are read as empty cells.
    let padded: Vec<&str> = missing
        .iter()
        .copied()
        .filter(|c| T::ADDED.contains(c))
        .collect();
    let missing: Vec<&str> = missing
        .into_iter()
        .filter(|c| !T::ADDED.contains(c))
        .collect();
    if !missing.is_empty() || !unknown.is_empty() {
        let mut what =
            vec!["the header is not this version's schema (an old or a foreign file)".to_string()];
        if !missing.is_empty() {
            what.push(format!("missing columns: {}", missing.join(", ")));
        }
        if !unknown.is_empty() {
            what.push(format!("unknown columns: {}", unknown.join(", ")));
        }
        return Err(at_line(1, what.join("; ")));
    }
    for c in &padded {
        fixed_header.push_field(c);
    }
    Ok((fixed_header, padded))
}

/// The per-joint values of the row at `line` from its per-joint `cells`: the cells up to the
/// last non-empty one, each a number (filled from joint 1 without gaps).
fn joint_values<T: Row>(cells: &[&str], line: u64) -> Result<Vec<f64>, TableError> {
    let n = cells
        .iter()
        .rposition(|c| !c.is_empty())
        .map_or(0, |p| p + 1);
    cells[..n]
        .iter()
        .enumerate()
        .map(|(k, c)| {
            c.parse::<f64>().map_err(|_| {
                at_line(
                    line,
                    format!(
                        "row does not parse: {}_{} = {c:?} is not a number (per-joint \
                         columns are filled from joint 1 without gaps)",
                        T::JOINTS.unwrap_or_default(),
                        k + 1
                    ),
                )
            })
        })
        .collect()
}

/// The distinct values of `key` over `rows`, in the order they first appear (the papers of a
/// profile, the schemes of a cost measurement, the task sets of a leaderboard).
pub fn distinct<'a, T>(rows: &'a [T], key: impl Fn(&'a T) -> &'a str) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for r in rows {
        let k = key(r);
        if !out.contains(&k) {
            out.push(k);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    struct R {
        name: String,
        #[serde(skip)]
        drift: Vec<f64>,
        norm: Option<f64>,
    }

    impl Row for R {
        const JOINTS: Option<&'static str> = Some("drift");
        const JOINTS_BEFORE: &'static str = "norm";
        fn joints(&self) -> &[f64] {
            &self.drift
        }
        fn set_joints(&mut self, values: Vec<f64>) {
            self.drift = values;
        }
    }

    fn r(name: &str, drift: &[f64]) -> R {
        R {
            name: name.into(),
            drift: drift.to_vec(),
            norm: (!drift.is_empty()).then_some(1.5),
        }
    }

    #[test]
    fn distinct_keeps_the_first_appearance_order() {
        let rows = ["b", "a", "b", "c", "a"];
        assert_eq!(distinct(&rows, |r| r), ["b", "a", "c"]);
        assert!(distinct(&[] as &[&str], |r| r).is_empty());
    }

    #[test]
    fn per_joint_columns_follow_the_largest_joint_count_and_round_trip() {
        let rows = vec![
            r("five", &[1.0, -2.0, 3.0, 4.0, 0.1]),
            r("seven", &[1e-300, 2.0, 3.0, 4.0, 5.0, 6.0, -7.25]),
            r("failed", &[]),
        ];
        let bytes = to_csv(&rows).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(
            text.starts_with("name,drift_1,drift_2,drift_3,drift_4,drift_5,drift_6,drift_7,norm\n"),
            "{text}"
        );
        assert!(
            text.contains("\nfive,1.0,-2.0,3.0,4.0,0.1,,,1.5\n"),
            "{text}"
        );
        assert!(text.contains("\nfailed,,,,,,,,\n"), "{text}");
        assert_eq!(from_reader::<R, _>(bytes.as_slice()).unwrap(), rows);
        // No rows with joints: no per-joint columns.
        let text = String::from_utf8(to_csv(&[r("failed", &[])]).unwrap()).unwrap();
        assert!(text.starts_with("name,norm\n"), "{text}");
    }

    #[test]
    fn bad_headers_and_cells_are_errors_naming_the_line() {
        let e = from_reader::<R, _>("name,drift_2,norm\nx,1,2\n".as_bytes()).unwrap_err();
        assert!(
            e.to_string().contains("line 1") && e.what.contains("drift_2 out of order"),
            "{e}"
        );
        let e = from_reader::<R, _>("name,norm,extra\nx,1,2\n".as_bytes()).unwrap_err();
        assert!(e.what.contains("unknown columns: extra"), "{e}");
        let e = from_reader::<R, _>("name\nx\n".as_bytes()).unwrap_err();
        assert!(e.what.contains("missing columns: norm"), "{e}");
        let e = from_reader::<R, _>("name,drift_1,drift_2,norm\nx,1,2,3\ny,,2,3\n".as_bytes())
            .unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(e.what.contains("drift_1"), "{e}");
        let e = from_reader::<R, _>("name,drift_1,norm\nx,1,abc\n".as_bytes()).unwrap_err();
        assert_eq!(e.line, 2, "{e}");
    }
}
