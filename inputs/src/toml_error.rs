//! A TOML error as the suite shows it: `toml`'s message and the line and column it points at,
//! never the source line that `toml`'s own `Display` quotes (a file linked to a secret would
//! otherwise print the secret).

use serde::de::DeserializeOwned;

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
            message: error.message().trim_end().to_string(),
            at,
        }
    }
}

/// An error without a source text (deserializing a `toml::Value`): the message only.
impl From<toml::de::Error> for TomlError {
    fn from(error: toml::de::Error) -> Self {
        TomlError {
            message: error.message().trim_end().to_string(),
            at: None,
        }
    }
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
}
