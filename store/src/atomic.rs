//! The atomic write every file of the store goes through: to a temporary file whose name says
//! it is the program's own ([`TMP_PREFIX`]), then renamed over the target, a
//! [`crate::kill_point`] after the rename. An interrupted write leaves the old file or the new
//! one, never half of one; [`crate::results_dir::remove_own_tmp`] clears a killed writer's
//! temporary files.

use std::path::Path;

/// The start of every temporary file name the program writes: `.driftbench-tmp.<pid>.<counter>.
/// <name>` for an atomic write of `<name>`, `.driftbench-tmp.<pid>.probe` for a writability
/// probe. Only names of this exact shape are the program's own
/// ([`crate::results_dir::is_own_tmp`]); a user's `notes.2024.12.tmp` never is.
pub const TMP_PREFIX: &str = ".driftbench-tmp.";

/// Writes `bytes` to `path` atomically: to a temporary file unique to this call (`TMP_PREFIX`,
/// the process id and a counter, so concurrent writers of the same file never share one), then
/// renamed over `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// [`write_atomic`] of what `write` writes, streamed through a buffer: a file far larger than
/// memory (a merged `runs.csv`) is written row by row. Nothing replaces `path` unless `write`
/// succeeds (its temporary file is removed).
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    use std::io::Write as _;
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let tmp = tmp_path(path);
    let written = std::fs::File::create(&tmp).and_then(|file| {
        let mut out = std::io::BufWriter::with_capacity(64 * 1024, file);
        write(&mut out)?;
        out.flush()
    });
    written
        .and_then(|()| std::fs::rename(&tmp, path))
        .inspect_err(|_| {
            let _ = std::fs::remove_file(&tmp);
        })?;
    crate::kill_point::passed();
    Ok(())
}

/// A temporary file's path for `path`, unique to this call: `.driftbench-tmp.<pid>.<counter>.
/// <name>` beside it ([`TMP_PREFIX`]). An atomic write writes there before its rename; the
/// manifest's spills (`crate::tracked_dir`) stay there until dropped.
pub fn tmp_path(path: &Path) -> std::path::PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let mut name = std::ffi::OsString::from(format!(
        "{TMP_PREFIX}{}.{}.",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    name.push(path.file_name().unwrap_or_default());
    path.with_file_name(name)
}
