//! File-safe names: a run's slugs, shared by the experiment files' validation (two labels that
//! would share a file are an error), the traces and the figures.

pub use settings::slug;
use settings::{is_control_or_format, shown};

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
    /// The name holds a control or formatting character ([`settings::is_control_or_format`]:
    /// a line break, an escape, a bidi override, a zero-width or separator character).
    #[error("{} must hold no control or formatting characters (it holds {found:?}; names are shown in listings, in the terminal and in report/)", shown(name))]
    ControlOrFormat {
        /// The name.
        name: String,
        /// The first such character.
        found: char,
    },
    /// The name holds `/`, `\` or `..`.
    #[error(
        "{} must not contain `/`, `\\` or `..` (it names files under results/ and report/)",
        shown(name)
    )]
    Unsafe {
        /// The name.
        name: String,
    },
    /// The name's slug is empty: it has no ASCII letter or digit.
    #[error(
        "{} needs at least one ASCII letter or digit (it names files under results/ and report/)",
        shown(name)
    )]
    Empty {
        /// The name.
        name: String,
    },
    /// The name holds HTML or a Markdown link ([`has_markup`]).
    #[error("{} must not contain HTML (`<` before a letter, `/`, `!` or `?`) or a Markdown link (`](`): labels are shown as they are in report/", shown(name))]
    Markup {
        /// The name.
        name: String,
    },
    /// The name is longer than its kind allows.
    #[error("{} is {len} bytes long; at most {max} are allowed (it names files under results/ and report/, whose names are limited to {MAX_FILE_NAME} bytes)", shown(name))]
    TooLong {
        /// The name.
        name: String,
        /// Its length (bytes).
        len: usize,
        /// The longest allowed (bytes), e.g. [`MAX_VARIANT_LABEL`].
        max: usize,
    },
}

/// Checks that `name` (an id or a label) can name a file or directory under results/ and
/// report/ and be shown as it is: no control or formatting character
/// ([`settings::is_control_or_format`]), no `/`, `\` or `..`, not empty once slugged, at most
/// `max` bytes; and that the report's tables can show it as it is ([`has_markup`]).
pub fn check_name(name: &str, max: usize) -> Result<(), NameError> {
    if let Some(found) = name.chars().find(|&c| is_control_or_format(c)) {
        return Err(NameError::ControlOrFormat {
            name: name.into(),
            found,
        });
    }
    if name.contains('/') || name.contains('\\') || name.contains("..") {
        return Err(NameError::Unsafe { name: name.into() });
    }
    if has_markup(name) {
        return Err(NameError::Markup { name: name.into() });
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

/// Whether `text` holds what Markdown would not show as text in a table cell: an HTML tag,
/// comment or autolink (`<` before an ASCII letter, `/`, `!` or `?`) or a link or image
/// (`](`). A bare `<` (as in `|e| <= 0.001`), brackets and emphasis characters stay text.
pub fn has_markup(text: &str) -> bool {
    text.contains("](")
        || text
            .as_bytes()
            .windows(2)
            .any(|w| w[0] == b'<' && (w[1].is_ascii_alphabetic() || b"/!?".contains(&w[1])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsafe_empty_and_long_names_are_refused() {
        assert!(check_name("VLTCO [star-lines]", MAX_VARIANT_LABEL).is_ok());
        for bad in ["../x", "a/b", "a\\b", ".."] {
            assert!(
                matches!(check_name(bad, 64), Err(NameError::Unsafe { .. })),
                "{bad:?}"
            );
        }
        assert!(matches!(
            check_name("(( ))", 64),
            Err(NameError::Empty { .. })
        ));
        for bad in [
            "Z <img src=x onerror=alert(1)>",
            "a <td> b",
            "<!-- c -->",
            "[x](javascript:alert(1))",
            "<https:example.org>",
        ] {
            assert!(
                matches!(check_name(bad, 64), Err(NameError::Markup { .. })),
                "{bad:?}"
            );
        }
        for good in [
            "94LVI (|e| <= 0.001)",
            "ZNN (eq. 22) [start on theta*0]",
            "a < b",
        ] {
            assert!(check_name(good, MAX_VARIANT_LABEL).is_ok(), "{good:?}");
        }
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

    #[test]
    fn control_and_formatting_characters_are_refused_by_their_own_rule() {
        for (bad, found) in [
            ("a\u{7}b", '\u{7}'),
            ("a\tb", '\t'),
            ("a\nb", '\n'),
            ("a\u{85}b", '\u{85}'),
            ("abc\u{202e}fed", '\u{202e}'),
            ("a\u{2028}b", '\u{2028}'),
            ("zero\u{200b}width", '\u{200b}'),
            ("x\u{1b}[2J/..", '\u{1b}'),
        ] {
            let e = check_name(bad, 64).unwrap_err();
            assert_eq!(
                e,
                NameError::ControlOrFormat {
                    name: bad.into(),
                    found
                }
            );
            let shown = e.to_string();
            assert!(
                shown.contains("no control or formatting characters")
                    && shown.contains(&format!("{found:?}"))
                    && !shown.contains("`/`"),
                "{shown}"
            );
            assert!(!shown.chars().any(is_control_or_format), "{shown:?}");
        }
        // The separators keep their own message, the name shown escaped.
        let e = check_name("a/b", 64).unwrap_err().to_string();
        assert!(e.starts_with("\"a/b\" must not contain `/`"), "{e}");
    }

    #[test]
    fn a_long_name_is_shown_cut() {
        let long = "x".repeat(1_000_000);
        let e = check_name(&long, MAX_VARIANT_LABEL)
            .unwrap_err()
            .to_string();
        assert!(e.len() < 500, "{} bytes", e.len());
        assert!(
            e.contains("(1000000 characters, the first 128 shown) is 1000000 bytes long"),
            "{e}"
        );
        // Every name a rule allows is shown whole.
        assert!(
            MAX_VARIANT_LABEL
                .max(MAX_SOLVER_LABEL)
                .max(MAX_EXPERIMENT_ID)
                <= settings::SHOWN_MAX_CHARS
        );
    }
}
