//! A TOML error as the suite shows it: `toml`'s message and the line and column it points at,
//! never the source line that `toml`'s own `Display` quotes (a file linked to a secret would
//! otherwise print the secret).
//!
//! The message itself quotes the file where toml or serde name a key or a value (an unknown
//! field or variant, a duplicate key, a string of the wrong type), and they quote it as it is:
//! it is shown as every error shows a text from a file ([`settings::shown()`]: escaped, cut), and
//! what toml writes on several lines is put on one ([`shown_message`]).

// Through the parent module (this crate's root): robots/build.rs includes this file by path,
// with settings' `shown` module beside it in place of the crate.
use super::{is_control_or_format, shown, SHOWN_MAX_CHARS};
use serde::de::DeserializeOwned;
use std::fmt::Write;

/// The most characters of a message a [`TomlError`] keeps (past what its quoted texts are cut
/// to: a key with a backtick in it can leave text outside a quote).
pub const MAX_MESSAGE_CHARS: usize = 1024;

/// A TOML syntax or schema error: the message (which names at most the offending key or value)
/// and, when `toml` knows it, the 1-based line and column.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}{message}", at.map(|(line, column)| format!("line {line}, column {column}: ")).unwrap_or_default())]
pub struct TomlError {
    pub message: String,
    pub at: Option<(usize, usize)>,
}

impl TomlError {
    /// The error `error` of parsing `text`, placed by its span.
    pub fn new(error: &toml::de::Error, text: &str) -> Self {
        let at = error.span().map(|span| {
            let before = text.get(..span.start).unwrap_or(text);
            let line = before.matches('\n').count() + 1;
            let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            (line, column)
        });
        TomlError {
            message: shown_message(error.message()),
            at,
        }
    }
}

/// An error without a source text (deserializing a `toml::Value`): the message only.
impl From<toml::de::Error> for TomlError {
    fn from(error: toml::de::Error) -> Self {
        TomlError {
            message: shown_message(error.message()),
            at: None,
        }
    }
}

/// toml's or serde's `message` as a [`TomlError`] shows it: each text they quote in backticks
/// (`` unknown field `x` ``, `` duplicate key `x` ``) kept as it is when [`settings::shown`]
/// would show it unchanged, else shown by it (in double quotes, escaped, cut); each string
/// serde quotes (`string "..."`, already escaped) cut after [`SHOWN_MAX_CHARS`] characters as
/// `shown` cuts; any other control or format character escaped, a line break as `; `; and the
/// whole at most [`MAX_MESSAGE_CHARS`] characters.
pub fn shown_message(message: &str) -> String {
    const STRING: &str = "string \"";
    let message = message.trim_end();
    let mut out = String::with_capacity(message.len().min(4 * MAX_MESSAGE_CHARS));
    let mut i = 0;
    while i < message.len() {
        let rest = &message[i..];
        if let Some(end) = rest.strip_prefix('`').and_then(|r| r.find('`')) {
            let inner = &rest[1..1 + end];
            if format!("{inner:?}") == format!("\"{inner}\"")
                && inner.chars().count() <= SHOWN_MAX_CHARS
            {
                out.push_str(&rest[..end + 2]);
            } else {
                let _ = write!(out, "{}", shown(inner));
            }
            i += end + 2;
        } else if let Some((end, chars, cut)) = rest.strip_prefix(STRING).and_then(debug_quoted) {
            let body = &rest[STRING.len()..];
            match cut {
                None => out.push_str(&rest[..STRING.len() + end + 1]),
                Some(cut) => {
                    let _ = write!(
                        out,
                        "{STRING}{}\"... ({chars} characters, the first {SHOWN_MAX_CHARS} shown)",
                        &body[..cut]
                    );
                }
            }
            i += STRING.len() + end + 1;
        } else {
            let c = rest.chars().next().unwrap_or(' ');
            match c {
                '\n' => out.push_str("; "),
                c if is_control_or_format(c) => out.extend(c.escape_debug()),
                c => out.push(c),
            }
            i += c.len_utf8();
        }
        if out.len() > 4 * MAX_MESSAGE_CHARS {
            break;
        }
    }
    match out.char_indices().nth(MAX_MESSAGE_CHARS) {
        None => out,
        Some((cut, _)) => format!(
            "{}... (a message of {} characters, cut)",
            &out[..cut],
            message.chars().count()
        ),
    }
}

/// In `body`, the text of a string that `{:?}` escaped after its opening quote: the byte
/// index of its closing quote, the characters it stands for (an escape is one) and, when they
/// are more than [`SHOWN_MAX_CHARS`], the byte index after the last shown. `None` when no
/// closing quote follows.
fn debug_quoted(body: &str) -> Option<(usize, usize, Option<usize>)> {
    let mut chars = 0;
    let mut cut = None;
    let mut it = body.char_indices();
    while let Some((j, c)) = it.next() {
        if c == '"' {
            return Some((j, chars, cut.filter(|_| chars > SHOWN_MAX_CHARS)));
        }
        // An escape is one character: `\n`, `\"`, `\\` or `\u{..}`.
        if c == '\\' && it.next()?.1 == 'u' {
            it.by_ref().find(|&(_, c)| c == '}')?;
        }
        chars += 1;
        if chars == SHOWN_MAX_CHARS {
            cut = Some(it.clone().next().map_or(body.len(), |(k, _)| k));
        }
    }
    None
}

/// `toml::from_str`, its error a [`TomlError`].
pub fn from_str<T: DeserializeOwned>(text: &str) -> Result<T, TomlError> {
    toml::from_str(text).map_err(|e| TomlError::new(&e, text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct File {
        title: String,
    }

    #[test]
    fn errors_name_the_line_and_column_without_the_source_line() {
        let secret = "CANARY_SECRET_1234";
        let e = from_str::<File>(&format!("title = \"x\"\n{secret} = 1\n")).unwrap_err();
        assert_eq!(e.at, Some((2, 1)), "{e}");
        let shown = e.to_string();
        assert!(shown.starts_with("line 2, column 1: "), "{shown}");
        assert!(shown.contains("unknown field"), "{shown}");
        // The offending token may be named; the rest of the file never is.
        let e = from_str::<File>(&format!("title = \"x\"\nnot toml {secret}\n")).unwrap_err();
        let shown = e.to_string();
        assert!(!shown.contains(secret) && !shown.contains('|'), "{shown}");
        assert_eq!(e.at.map(|a| a.0), Some(2), "{shown}");
        let plain: TomlError = toml::from_str::<File>("").unwrap_err().into();
        assert_eq!(plain.at, None);
        assert!(
            plain.to_string().contains("missing field `title`"),
            "{plain}"
        );
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Kinds {
        kind: Kind,
        count: Option<u32>,
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(rename_all = "lowercase")]
    enum Kind {
        Znn,
    }

    /// What toml's message would print raw: ESC, CR/LF, BEL, OSC, C1, bidi and separators.
    const HOSTILE: &str = "\\u001b[2J\\u001b]0;pwned\\u0007\\r\\nfake\\u0085\\u202e\\u2028";

    fn shown_error(text: &str) -> String {
        let e = from_str::<Kinds>(text).unwrap_err();
        let shown = e.to_string();
        assert!(
            !shown.chars().any(is_control_or_format),
            "{text:?}: {shown:?}"
        );
        shown
    }

    #[test]
    fn the_keys_and_values_a_message_quotes_are_escaped() {
        let variant = shown_error(&format!("kind = \"{HOSTILE}\"\n"));
        assert!(
            variant.contains(r#"unknown variant "\u{1b}[2J\u{1b}]0;pwned\u{7}\r\nfake\u{85}\u{202e}\u{2028}", expected `znn`"#),
            "{variant}"
        );
        let field = shown_error(&format!("kind = \"znn\"\n\"{HOSTILE}\" = 1\n"));
        assert!(field.contains("unknown field \"\\u{1b}[2J"), "{field}");
        assert!(field.contains("expected `kind` or `count`"), "{field}");
        let twice = shown_error(&format!("\"{HOSTILE}\" = 1\n\"{HOSTILE}\" = 2\n"));
        assert!(twice.contains("duplicate key \"\\u{1b}[2J"), "{twice}");
        // serde quotes a string of the wrong type escaped; a key with a backtick leaves text
        // outside any quote, escaped all the same.
        let typed = shown_error(&format!("kind = \"znn\"\ncount = \"{HOSTILE}\"\n"));
        assert!(
            typed.contains("invalid type: string \"\\u{1b}[2J"),
            "{typed}"
        );
        let tick = shown_error(&format!("kind = \"znn\"\n\"a`{HOSTILE}\" = 1\n"));
        assert!(tick.contains("unknown field `a`\\u{1b}[2J"), "{tick}");
        // Plain names are quoted as toml quotes them.
        let plain = shown_error("kind = \"lvi\"\n");
        assert!(
            plain.ends_with("unknown variant `lvi`, expected `znn`"),
            "{plain}"
        );
    }

    #[test]
    fn a_long_key_or_value_is_cut() {
        let long = "x".repeat(1_000_000);
        for text in [
            format!("kind = \"{long}\"\n"),
            format!("kind = \"znn\"\n{long} = 1\n"),
            format!("kind = \"znn\"\ncount = \"{long}\"\n"),
            format!("kind = \"znn\"\n\"a`{long}\" = 1\n"),
        ] {
            let shown = shown_error(&text);
            assert!(shown.len() < 2 * MAX_MESSAGE_CHARS, "{} bytes", shown.len());
            assert!(
                shown.contains("1000000 characters, the first 128 shown")
                    || shown.contains("characters, cut)"),
                "{shown}"
            );
        }
        let e = shown_error(&format!(
            "kind = \"znn\"\ncount = \"{}\\u001b\"\n",
            "y".repeat(134)
        ));
        assert!(
            e.contains(&format!(
                "string \"{}\"... (135 characters, the first 128 shown)",
                "y".repeat(128)
            )),
            "{e}"
        );
    }
}
