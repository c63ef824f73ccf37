//! How an error shows a text it was given: the one way every error of the workspace quotes a
//! value from a user's file or from the command line (a robot's name, a kind, a method, a key,
//! an id, a label).
//!
//! A file can hold any text, and an error that printed it as it is would let the file drive
//! the terminal it is read on: an escape sequence clears or recolours the screen or sets its
//! title, a carriage return or line feed fakes a line of output, a bidi override reverses what
//! follows it, and a megabyte-long name is printed whole. [`shown`] quotes the text instead:
//!
//! - in double quotes, every character that is not plainly visible escaped as Rust's `{:?}`
//!   escapes it: control characters (`\n`, `\r`, `\t`, `\u{1b}`, `\u{85}`, ...), Unicode format
//!   characters (bidi controls such as `\u{202e}`, zero-width characters, `\u{feff}`), the line
//!   and paragraph separators (`\u{2028}`, `\u{2029}`), spaces other than `' '`, combining marks
//!   and unassigned code points; `"` and `\` as `\"` and `\\`;
//! - cut after its first [`SHOWN_MAX_CHARS`] characters, with a marker that says how long it
//!   was: `"xxxx…"... (1000000 characters, the first 128 shown)`.
//!
//! A text that is plain and short is shown as `"text"`, as the messages always quoted it.
//!
//! The rule of what a label or id may hold ([`is_control_or_format`]) and what a text shown in
//! listings and the report may hold ([`is_one_line`]) are here too, beside the way errors show
//! a text that breaks them.

use std::fmt;

/// The most characters of a text an error shows ([`shown`]): enough for every valid id and
/// label whole (the longest, a variant's label, is at most 100 bytes: `spec::MAX_VARIANT_LABEL`),
/// so that only a text that breaks a rule is ever cut.
pub const SHOWN_MAX_CHARS: usize = 128;

/// `text` as an error shows it (module docs): quoted, escaped, at most [`SHOWN_MAX_CHARS`]
/// characters of it with its length when it is longer.
///
/// ```
/// use settings::shown;
///
/// assert_eq!(shown("jaco2").to_string(), "\"jaco2\"");
/// assert_eq!(shown("x\u{1b}[2J\r\n").to_string(), "\"x\\u{1b}[2J\\r\\n\"");
/// assert_eq!(
///     shown(&"a".repeat(200)).to_string(),
///     format!("\"{}\"... (200 characters, the first 128 shown)", "a".repeat(128))
/// );
/// ```
pub fn shown(text: &str) -> Shown<'_> {
    Shown(text)
}

/// A text as an error shows it ([`shown`]); its `Display` writes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shown<'a>(&'a str);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0.char_indices().nth(SHOWN_MAX_CHARS) {
            None => write!(f, "{:?}", self.0),
            Some((cut, _)) => write!(
                f,
                "{:?}... ({} characters, the first {SHOWN_MAX_CHARS} shown)",
                &self.0[..cut],
                self.0.chars().count()
            ),
        }
    }
}

/// Whether `c` is a control or formatting character, what no label, id or one-line text may
/// hold: a control character (Unicode category Cc: C0, DEL, C1 such as `\u{85}`), a format
/// character (Cf: the bidi controls `\u{202a}`..`\u{202e}` and `\u{2066}`..`\u{2069}`, the
/// marks `\u{200e}`, `\u{200f}` and `\u{61c}`, zero-width characters, `\u{feff}`, the soft
/// hyphen, tags, ...) or a line or paragraph separator (`\u{2028}`, `\u{2029}`).
pub fn is_control_or_format(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{ad}'
                | '\u{600}'..='\u{605}'
                | '\u{61c}'
                | '\u{6dd}'
                | '\u{70f}'
                | '\u{890}'..='\u{891}'
                | '\u{8e2}'
                | '\u{180e}'
                | '\u{200b}'..='\u{200f}'
                | '\u{2028}'..='\u{202e}'
                | '\u{2060}'..='\u{2064}'
                | '\u{2066}'..='\u{206f}'
                | '\u{feff}'
                | '\u{fff9}'..='\u{fffb}'
                | '\u{110bd}'
                | '\u{110cd}'
                | '\u{13430}'..='\u{1343f}'
                | '\u{1bca0}'..='\u{1bca3}'
                | '\u{1d173}'..='\u{1d17a}'
                | '\u{e0001}'
                | '\u{e0020}'..='\u{e007f}'
        )
}

/// Whether `text` is one line, what a text shown in listings and the report must be (a
/// paper's title and citation, a claim, an experiment file's `title` and `paper_output`): no
/// line break, control or formatting character ([`is_control_or_format`]: a line break would
/// end the heading, table cell or list item it is put in, an escape sequence would drive the
/// terminal `list` prints it on, a bidi override would reverse the text after it).
pub fn is_one_line(text: &str) -> bool {
    !text.chars().any(is_control_or_format)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The hostile texts a file can hold: escape sequences, a fake line, OSC, BEL, C1, bidi
    /// and format characters, the separators.
    fn hostile() -> Vec<String> {
        [
            "x\u{1b}[2J\u{1b}[31mRED\r\nfake: all good",
            "P\u{1b}]0;pwned\u{7}\u{1b}[31mX",
            "a\u{85}b",
            "abc\u{202e}fed",
            "a\u{2028}b\u{2029}c",
            "zero\u{200b}width\u{feff}",
            "\u{2066}isolate\u{2069}",
            "del\u{7f}",
            "tab\there",
            "tag\u{e0041}",
        ]
        .map(String::from)
        .to_vec()
    }

    #[test]
    fn a_hostile_text_is_shown_without_its_control_or_format_characters() {
        for text in hostile() {
            let s = shown(&text).to_string();
            assert!(
                !s.chars().any(is_control_or_format),
                "{s:?} still holds a control or format character"
            );
            assert!(s.starts_with('"') && s.ends_with('"'), "{s}");
        }
        assert_eq!(
            shown("x\u{1b}[2J\r\n\u{202e}\u{2028}\u{85}").to_string(),
            r#""x\u{1b}[2J\r\n\u{202e}\u{2028}\u{85}""#
        );
    }

    #[test]
    fn a_plain_text_is_quoted_as_it_is() {
        for text in [
            "jaco2-pen",
            "VP-RNN-PF (sinh)",
            "Jia & Li, “Drift-free…”",
            "日本",
        ] {
            assert_eq!(shown(text).to_string(), format!("\"{text}\""));
        }
        assert_eq!(shown("say \"hi\"").to_string(), r#""say \"hi\"""#);
    }

    #[test]
    fn a_long_text_is_cut_with_its_length() {
        let exact = "é".repeat(SHOWN_MAX_CHARS);
        assert_eq!(shown(&exact).to_string(), format!("\"{exact}\""));
        let long = format!("{}\u{1b}", "n".repeat(1_000_000));
        let s = shown(&long).to_string();
        assert_eq!(
            s,
            format!(
                "\"{}\"... (1000001 characters, the first 128 shown)",
                "n".repeat(SHOWN_MAX_CHARS)
            )
        );
        // Cut by characters, never inside one.
        let wide = "日".repeat(SHOWN_MAX_CHARS + 1);
        assert!(shown(&wide)
            .to_string()
            .starts_with(&format!("\"{}\"...", "日".repeat(SHOWN_MAX_CHARS))));
    }

    #[test]
    fn control_and_format_characters_are_told_apart_from_text() {
        for c in [
            '\u{0}',
            '\u{7}',
            '\t',
            '\n',
            '\r',
            '\u{1b}',
            '\u{7f}',
            '\u{85}',
            '\u{9b}',
            '\u{ad}',
            '\u{61c}',
            '\u{200b}',
            '\u{200d}',
            '\u{200e}',
            '\u{200f}',
            '\u{2028}',
            '\u{2029}',
            '\u{202a}',
            '\u{202e}',
            '\u{2066}',
            '\u{2069}',
            '\u{feff}',
            '\u{e0041}',
        ] {
            assert!(is_control_or_format(c), "{c:?}");
        }
        for c in [
            'a', ' ', '-', '.', '(', 'é', '“', '…', '日', '\u{a0}', '\u{2030}', '\u{2070}',
        ] {
            assert!(!is_control_or_format(c), "{c:?}");
        }
    }

    #[test]
    fn one_line_is_no_control_character() {
        assert!(is_one_line("Jia & Li, “Drift-free…”, 2019"));
        for bad in ["a\n## Summary", "a\rb", "T\u{1b}[2J", "P\u{7}", "a\u{85}b"] {
            assert!(!is_one_line(bad), "{bad:?}");
        }
    }
}
