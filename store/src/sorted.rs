//! Rows in key order, streamed: a `runs.csv` read row by row ([`read_key_ordered`]), several
//! such sources merged into one key-ordered stream ([`KeyMerge`], a k-way merge), and the
//! latest row of each key kept ([`latest`]). What a shard's fold and a merge of shards hold is
//! then one row per source, whatever the number of runs: for S sources of R rows in all, a
//! merge costs O(R log S) time and O(S) rows of memory.
//!
//! Every `runs.csv` this program writes is in key order (`experiment`, `variant_id`,
//! `solver_id`, compared as strings), so reading one in key order checks, row by row and
//! without a set of the keys seen, that no run is listed twice: a row whose key is not greater
//! than the one above it is an error naming the file and the line.

use crate::error::RunsError;
use records::table::{self, Rows};
use records::RowsError;
use records::{check_run_names, RunRow};
use spec::RunKey;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::path::{Path, PathBuf};

/// A `runs.csv` read row by row in key order ([`read_key_ordered`]).
pub struct KeyOrdered {
    path: PathBuf,
    /// `None`: no file (no rows).
    rows: Option<Rows<RunRow, inputs::Capped>>,
    /// The key of the last row read.
    last: Option<RunKey>,
    /// The line of the next row (the header is line 1).
    line: usize,
}

/// Opens `path` (a `runs.csv`; absent: no rows) to be read row by row, through the one reader
/// (`owned_dir::open_file`): each row is checked as `read_runs` checks
/// it (the schema, the names) and for coming after the row above it in key order.
pub fn read_key_ordered(path: &Path) -> Result<KeyOrdered, RunsError> {
    let table_error = |error| RunsError::Table {
        path: path.to_path_buf(),
        error,
    };
    let rows = match crate::owned_dir::open_file(path) {
        Ok(file) => Some(table::rows(file).map_err(|e| {
            table_error(table::TableError {
                path: Some(path.to_path_buf()),
                ..e
            })
        })?),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => {
            return Err(table_error(table::TableError {
                path: Some(path.to_path_buf()),
                line: 0,
                what: format!("cannot read: {e}"),
            }))
        }
    };
    Ok(KeyOrdered {
        path: path.to_path_buf(),
        rows,
        last: None,
        line: 2,
    })
}

impl KeyOrdered {
    /// The per-joint columns of the file's header.
    pub fn joints(&self) -> usize {
        self.rows.as_ref().map_or(0, Rows::joints)
    }
}

impl Iterator for KeyOrdered {
    type Item = Result<RunRow, RunsError>;

    fn next(&mut self) -> Option<Self::Item> {
        let row = match self.rows.as_mut()?.next()? {
            Ok(row) => row,
            Err(error) => {
                self.rows = None;
                return Some(Err(RunsError::Table {
                    path: self.path.clone(),
                    error: table::TableError {
                        path: Some(self.path.clone()),
                        ..error
                    },
                }));
            }
        };
        let line = self.line;
        self.line += 1;
        let key = row.key();
        let checked = check_run_names(&row, line).and_then(|()| match &self.last {
            Some(before) if *before == key => Err(RowsError::Twice {
                line,
                key: key.to_string(),
                first: line - 1,
            }),
            Some(before) if *before > key => Err(RowsError::Unordered {
                line,
                key: key.to_string(),
                before: before.to_string(),
            }),
            _ => Ok(()),
        });
        if let Err(error) = checked {
            self.rows = None;
            return Some(Err(RunsError::Rows {
                path: self.path.clone(),
                error,
            }));
        }
        self.last = Some(key);
        Some(Ok(row))
    }
}

/// Key-ordered sources merged into one key-ordered stream of `(source index, row)`; rows of
/// equal keys come in the order of their sources. The first error of a source ends the
/// stream.
pub struct KeyMerge<I> {
    sources: Vec<I>,
    /// The next row of each source, taken from it.
    heads: Vec<Option<RunRow>>,
    /// The keys of the heads, smallest first (ties: the earlier source).
    order: BinaryHeap<Reverse<(RunKey, usize)>>,
    failed: bool,
}

impl<I, E> KeyMerge<I>
where
    I: Iterator<Item = Result<RunRow, E>>,
{
    /// The merge of `sources`, each in key order.
    pub fn new(sources: Vec<I>) -> Result<Self, E> {
        let mut merge = Self {
            heads: sources.iter().map(|_| None).collect(),
            order: BinaryHeap::with_capacity(sources.len()),
            sources,
            failed: false,
        };
        for i in 0..merge.sources.len() {
            merge.refill(i)?;
        }
        Ok(merge)
    }

    /// Takes the next row of source `i` as its head.
    fn refill(&mut self, i: usize) -> Result<(), E> {
        if let Some(row) = self.sources[i].next().transpose()? {
            self.order.push(Reverse((row.key(), i)));
            self.heads[i] = Some(row);
        }
        Ok(())
    }
}

impl<I, E> Iterator for KeyMerge<I>
where
    I: Iterator<Item = Result<RunRow, E>>,
{
    type Item = Result<(usize, RunRow), E>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let Reverse((_, i)) = self.order.pop()?;
        let row = self.heads[i].take()?;
        if let Err(e) = self.refill(i) {
            self.failed = true;
            return Some(Err(e));
        }
        Some(Ok((i, row)))
    }
}

/// Of each run key of a key-ordered stream of `(source, row)` ([`KeyMerge`]), the row of the
/// last source that has it: a fresh row replaces a stored one. `superseded` is told each row
/// replaced.
pub fn latest<E>(
    merged: impl Iterator<Item = Result<(usize, RunRow), E>>,
    mut superseded: impl FnMut(&RunRow),
) -> impl Iterator<Item = Result<(usize, RunRow), E>> {
    let mut merged = merged.peekable();
    std::iter::from_fn(move || {
        let (mut source, mut row) = match merged.next()? {
            Ok(item) => item,
            Err(e) => return Some(Err(e)),
        };
        while let Some(Ok((_, next))) = merged.peek() {
            if next.key() != row.key() {
                break;
            }
            let Some(Ok((s, next))) = merged.next() else {
                break;
            };
            superseded(&row);
            (source, row) = (s, next);
        }
        Some(Ok((source, row)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use spec::SolverKind;

    fn row(variant: &str, git_rev: &str) -> RunRow {
        RunRow {
            git_rev: git_rev.into(),
            ..RunRow::blank(
                &RunKey::from_ids("exp", variant, "exact").unwrap(),
                SolverKind::Exact,
            )
        }
    }

    fn source(rows: Vec<RunRow>) -> std::vec::IntoIter<Result<RunRow, ()>> {
        rows.into_iter().map(Ok).collect::<Vec<_>>().into_iter()
    }

    /// Three sources merged in key order; on equal keys the later source's row is kept and the
    /// earlier one said superseded.
    #[test]
    fn merged_in_key_order_and_the_later_source_wins() {
        let stored = source(vec![row("a", "old"), row("c", "old"), row("e", "old")]);
        let fresh = source(vec![row("b", "new"), row("c", "new")]);
        let more = source(vec![row("d", "new"), row("f", "new")]);
        let merge = KeyMerge::new(vec![stored, fresh, more]).unwrap();
        let mut replaced = Vec::new();
        let got: Vec<(usize, String, String)> = latest(merge, |r| replaced.push(r.variant.clone()))
            .map(|r| r.unwrap())
            .map(|(s, r)| (s, r.variant, r.git_rev))
            .collect();
        let want = [
            (0, "a", "old"),
            (1, "b", "new"),
            (1, "c", "new"),
            (2, "d", "new"),
            (0, "e", "old"),
            (2, "f", "new"),
        ];
        assert_eq!(got, want.map(|(s, v, g)| (s, v.to_string(), g.to_string())));
        assert_eq!(replaced, ["c"]);
    }

    /// A runs.csv out of key order, or with a run twice, is refused naming the line.
    #[test]
    fn a_file_out_of_order_or_with_a_run_twice_is_refused() {
        let dir = inputs::Scratch::dir("sorted");
        let path = dir.join("runs.csv");
        let write = |rows: &[RunRow]| {
            let mut w = csv::Writer::from_writer(Vec::new());
            w.write_record(table::header::<RunRow>(0)).unwrap();
            for r in rows {
                w.write_record(table::record(r, 0).unwrap()).unwrap();
            }
            std::fs::write(&path, w.into_inner().unwrap()).unwrap();
        };
        write(&[row("a", "r"), row("b", "r")]);
        let read: Vec<RunRow> = read_key_ordered(&path)
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(read.len(), 2);
        for (rows, want) in [
            (
                vec![row("b", "r"), row("a", "r")],
                "line 3: the run exp / a / exact comes after exp / b / exact",
            ),
            (
                vec![row("a", "r"), row("a", "r")],
                "line 3: the run exp / a / exact is listed twice",
            ),
        ] {
            write(&rows);
            let e = read_key_ordered(&path)
                .unwrap()
                .collect::<Result<Vec<_>, _>>()
                .unwrap_err();
            assert!(e.to_string().contains(want), "{e}");
            assert!(e.to_string().contains("runs.csv"), "{e}");
        }
        assert_eq!(
            read_key_ordered(&dir.join("absent.csv")).unwrap().count(),
            0
        );
    }
}
