//! File-safe names: a run's slugs, shared by the experiment files' validation (two labels that
//! would share a file are an error), the traces and the figures.

/// Lower-case ASCII letters, digits and dashes.
pub fn slug(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        if c.is_ascii_alphanumeric() || c == '.' {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

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

/// Checks the three names of one run (experiment id, variant label, solver label).
pub fn check_run_names(experiment: &str, variant: &str, solver: &str) -> Result<(), NameError> {
    check_name(experiment, MAX_EXPERIMENT_ID)?;
    check_name(variant, MAX_VARIANT_LABEL)?;
    check_name(solver, MAX_SOLVER_LABEL)
}

/// `<variant-slug>__<solver-slug>`: a run's file stem inside its experiment's directory, shared
/// by the traces and the figures.
pub fn run_stem(variant: &str, solver: &str) -> String {
    format!("{}__{}", slug(variant), slug(solver))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsafe_empty_and_long_names_are_refused() {
        assert!(check_run_names("jia2019-clover", "VLTCO", "exact (Clarabel)").is_ok());
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
            check_run_names("e", &long, "s"),
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

    #[test]
    fn slugs_are_file_safe() {
        assert_eq!(slug("VP-RNN-PF (sinh)"), "vp-rnn-pf-sinh");
        assert_eq!(slug("exact (Clarabel)"), "exact-clarabel");
        assert_eq!(slug("MVN [jaco2 hand centre]"), "mvn-jaco2-hand-centre");
    }
}
