//! File-safe names: a run's slugs, shared by the experiment files' validation (two labels that
//! would share a file are an error), the traces and the figures.

pub use schemes::slug::slug;

/// Longest experiment id (and paper id), in bytes.
pub const MAX_EXPERIMENT_ID: usize = 64;
/// Longest variant label, in bytes.
pub const MAX_VARIANT_LABEL: usize = 100;
/// Longest solver label, in bytes.
pub const MAX_SOLVER_LABEL: usize = 80;
/// The longest file name any id leads to is a figure's,
/// `<experiment>__<variant>__<solver>.svg`: with the limits above at most 64 + 2 + 100 + 2 +
/// 80 + 4 = 252 bytes, within the 255 that common file systems allow (slugs are never longer
/// than the text they come from).
pub const MAX_FILE_NAME: usize = 255;

/// Why an id or label cannot name a file.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NameError {
    #[error(
        "\"{name}\" must not contain `/`, `\\` or `..` (it names files under results/ and report/)"
    )]
    Unsafe { name: String },
    #[error("\"{name}\" needs at least one ASCII letter or digit (it names files under results/ and report/)")]
    Empty { name: String },
    #[error("\"{}...\" is {len} bytes long; at most {max} are allowed (it names files under results/ and report/, whose names are limited to {MAX_FILE_NAME} bytes)", name.chars().take(40).collect::<String>())]
    TooLong {
        name: String,
        len: usize,
        max: usize,
    },
}

/// Checks that `name` (an id or a label) can name a file or directory under results/ and
/// report/: no `/`, `\` or `..`, no control characters, not empty once slugged, at most `max`
/// bytes.
pub fn check_name(name: &str, max: usize) -> Result<(), NameError> {
    if name.contains('/')
        || name.contains('\\')
        || name.contains("..")
        || name.contains(char::is_control)
    {
        return Err(NameError::Unsafe { name: name.into() });
    }
    if slug(name).is_empty() {
        return Err(NameError::Empty { name: name.into() });
    }
    if name.len() > max {
        return Err(NameError::TooLong {
            name: name.into(),
            len: name.len(),
            max,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsafe_empty_and_long_names_are_refused() {
        assert!(check_name("VLTCO [star-lines]", MAX_VARIANT_LABEL).is_ok());
        for bad in ["../x", "a/b", "a\\b", "..", "a\nb"] {
            assert!(
                matches!(check_name(bad, 64), Err(NameError::Unsafe { .. })),
                "{bad:?}"
            );
        }
        assert!(matches!(
            check_name("(( ))", 64),
            Err(NameError::Empty { .. })
        ));
        let long = "x".repeat(MAX_VARIANT_LABEL + 1);
        assert!(matches!(
            check_name(&long, MAX_VARIANT_LABEL),
            Err(NameError::TooLong { len: 101, .. })
        ));
        let longest = format!(
            "{}__{}__{}.svg",
            "e".repeat(MAX_EXPERIMENT_ID),
            "v".repeat(MAX_VARIANT_LABEL),
            "s".repeat(MAX_SOLVER_LABEL)
        );
        assert!(longest.len() <= MAX_FILE_NAME);
    }
}
