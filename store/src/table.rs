//! Tables of rows read from the store's files: the bytes through the one reader
//! ([`crate::read_owned_file`]), the rows parsed by their schema ([`records::table`]), any
//! problem a [`TableError`] naming the file.

use records::table::{from_reader, Row, TableError};
use std::path::Path;

/// Reads a table of `T` from `path` (errors name it), through the one reader
/// ([`crate::read_owned_file`]).
pub fn read<T: Row>(path: &Path) -> Result<Vec<T>, TableError> {
    read_with(path, |bytes| from_reader(bytes))
}

/// Reads a table of `T` from `path` like [`read`], an absent file as no rows (a results file
/// the reproduction has not written yet).
pub fn read_if_present<T: Row>(path: &Path) -> Result<Vec<T>, TableError> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    read(path)
}

/// The rows `parse` makes of the bytes of `path`, read through the one reader; an error names
/// `path`.
pub(crate) fn read_with<T>(
    path: &Path,
    parse: impl FnOnce(&[u8]) -> Result<Vec<T>, TableError>,
) -> Result<Vec<T>, TableError> {
    let bytes = crate::owned_dir::read_file(path).map_err(|e| TableError {
        path: Some(path.to_path_buf()),
        line: 0,
        what: format!("cannot read: {e}"),
    })?;
    parse(bytes.as_slice()).map_err(|e| TableError {
        path: Some(path.to_path_buf()),
        ..e
    })
}
