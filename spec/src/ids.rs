//! Validated ids: [`ExperimentId`], [`VariantId`] and [`SolverId`], the three parts of a run's
//! key ([`crate::RunKey`]), and [`PaperId`], the paper an experiment file belongs to
//! (what the command line's `--paper` names).
//!
//! An id is a *slug* ([`settings::is_slug`]: lower-case ASCII letters, digits and `.`,
//! single `-` between them, none leading or trailing) that begins with a letter or digit and
//! holds no `..` (so that no id is `.` or `..` as a path component), of at most its kind's
//! length in bytes
//! ([`crate::MAX_EXPERIMENT_ID`], [`crate::MAX_VARIANT_LABEL`],
//! [`crate::MAX_SOLVER_LABEL`]). A slug has no `/`, `\`, `..`, markup or control
//! character, so an id can name a file under results/ and report/ and be shown as it is: the
//! checks of [`crate::check_name`] hold for every id by construction.
//!
//! The only ways to make an id are [`ExperimentId::new`] (and its siblings), which check, and
//! serde, which reads through the same check: a value of these types is valid, so the code that
//! holds one does not check again. Each derefs to `str` and compares with strings, for display
//! and lookups.

use crate::naming::{MAX_EXPERIMENT_ID, MAX_SOLVER_LABEL, MAX_VARIANT_LABEL};
use settings::{is_slug, slug};
use std::fmt;

/// Which kind of id an [`IdError`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IdKind {
    /// An experiment's id.
    Experiment,
    /// A variant's id.
    Variant,
    /// A solver's id.
    Solver,
    /// A paper's id.
    Paper,
}

impl IdKind {
    /// The kind's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            IdKind::Experiment => "experiment id",
            IdKind::Variant => "variant id",
            IdKind::Solver => "solver id",
            IdKind::Paper => "paper id",
        }
    }

    /// The longest id of this kind, in bytes.
    pub fn max_len(self) -> usize {
        match self {
            IdKind::Experiment | IdKind::Paper => MAX_EXPERIMENT_ID,
            IdKind::Variant => MAX_VARIANT_LABEL,
            IdKind::Solver => MAX_SOLVER_LABEL,
        }
    }
}

/// A text that is not a valid id of its kind: not a slug, or too long. The message names the
/// rule and suggests the slug of the text where there is one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum IdError {
    /// Not a slug, or one that begins with `.` or holds `..`.
    #[error("{} {} is not a slug (lower-case ASCII letters, digits and `.`, single `-` between them, beginning with a letter or digit, without `..`){}", kind.name(), settings::shown(text), suggest(text))]
    NotASlug {
        /// The id's kind.
        kind: IdKind,
        /// The text given.
        text: String,
    },
    /// Longer than its kind allows.
    #[error("{} {} is {len} bytes long; at most {} are allowed (ids name files under results/ and report/)", kind.name(), settings::shown(text), kind.max_len())]
    TooLong {
        /// The id's kind.
        kind: IdKind,
        /// The text given.
        text: String,
        /// Its length in bytes.
        len: usize,
    },
}

fn suggest(text: &str) -> String {
    let s = slug(&text.replace("..", "."));
    let s = s.trim_start_matches(['.', '-']);
    if s.is_empty() {
        String::new()
    } else {
        format!("; did you mean {}?", settings::shown(s))
    }
}

/// Whether `text` has the form of an id, whatever its length (module docs): what an id
/// declared in a file (an experiment's, a variant's, a paper's) must be.
pub fn is_id_form(text: &str) -> bool {
    is_slug(text) && text.starts_with(|c: char| c.is_ascii_alphanumeric()) && !text.contains("..")
}

/// Checks `text` as an id of `kind` (module docs).
fn check(kind: IdKind, text: &str) -> Result<(), IdError> {
    if !is_id_form(text) {
        return Err(IdError::NotASlug {
            kind,
            text: text.to_string(),
        });
    }
    if text.len() > kind.max_len() {
        return Err(IdError::TooLong {
            kind,
            text: text.to_string(),
            len: text.len(),
        });
    }
    Ok(())
}

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident, $kind:expr) => {
        $(#[$doc])*
        #[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
        #[serde(try_from = "String", into = "String")]
        pub struct $name(String);

        impl $name {
            /// `text` as an id, if it is one (module docs).
            pub fn new(text: impl Into<String>) -> Result<Self, IdError> {
                let text = text.into();
                check($kind, &text)?;
                Ok(Self(text))
            }

            /// The id's text.
            pub fn as_str(&self) -> &str {
                &self.0
            }
        }

        impl TryFrom<String> for $name {
            type Error = IdError;
            fn try_from(text: String) -> Result<Self, IdError> {
                Self::new(text)
            }
        }

        impl TryFrom<&str> for $name {
            type Error = IdError;
            fn try_from(text: &str) -> Result<Self, IdError> {
                Self::new(text)
            }
        }

        impl std::str::FromStr for $name {
            type Err = IdError;
            fn from_str(text: &str) -> Result<Self, IdError> {
                Self::new(text)
            }
        }

        impl From<$name> for String {
            fn from(id: $name) -> String {
                id.0
            }
        }

        impl std::ops::Deref for $name {
            type Target = str;
            fn deref(&self) -> &str {
                &self.0
            }
        }

        impl AsRef<str> for $name {
            fn as_ref(&self) -> &str {
                &self.0
            }
        }

        impl AsRef<std::path::Path> for $name {
            /// An id is a file or directory name under results/ and report/.
            fn as_ref(&self) -> &std::path::Path {
                std::path::Path::new(&self.0)
            }
        }

        impl std::borrow::Borrow<str> for $name {
            fn borrow(&self) -> &str {
                &self.0
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(&self.0)
            }
        }

        impl PartialEq<str> for $name {
            fn eq(&self, other: &str) -> bool {
                self.0 == other
            }
        }

        impl PartialEq<&str> for $name {
            fn eq(&self, other: &&str) -> bool {
                self.0 == *other
            }
        }

        impl PartialEq<String> for $name {
            fn eq(&self, other: &String) -> bool {
                &self.0 == other
            }
        }

        impl PartialEq<$name> for str {
            fn eq(&self, other: &$name) -> bool {
                self == other.0
            }
        }

        impl PartialEq<$name> for &str {
            fn eq(&self, other: &$name) -> bool {
                *self == other.0
            }
        }

        impl PartialEq<$name> for String {
            fn eq(&self, other: &$name) -> bool {
                *self == other.0
            }
        }
    };
}

id_type!(
    /// An experiment's id (`[[experiment]] id`), e.g. `jia2019-clover`.
    ExperimentId,
    IdKind::Experiment
);
id_type!(
    /// A variant's id (`[[experiment.variant]] id`, or the slug of its label), e.g. `vltco`.
    VariantId,
    IdKind::Variant
);
id_type!(
    /// A paper's id (an experiment file's `paper`), e.g. `jia2019`, `group`, `cross`.
    PaperId,
    IdKind::Paper
);
id_type!(
    /// A solver's id (`exact`, a network's [`settings::SolverSpec::id`], a
    /// numerical method's or a scored trajectory's), e.g. `lvi-pdnn`.
    SolverId,
    IdKind::Solver
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slugs_within_their_length_are_ids_and_nothing_else_is() {
        assert_eq!(
            ExperimentId::new("jia2019-clover").unwrap(),
            "jia2019-clover"
        );
        assert!(SolverId::new("group-znn-gamma-500-nu-2500-perturbed-as-1.5").is_ok());
        for bad in [
            "", "VLTCO", "a b", "-a", "a--b", "../x", "a/b", "x<y", "é", "a\n",
        ] {
            assert!(VariantId::new(bad).is_err(), "accepted {bad:?}");
        }
        let long = "a".repeat(MAX_EXPERIMENT_ID + 1);
        assert!(matches!(
            ExperimentId::new(long.clone()),
            Err(IdError::TooLong { len, .. }) if len == MAX_EXPERIMENT_ID + 1
        ));
        assert!(VariantId::new(long).is_ok(), "variant ids may be longer");
        assert!(SolverId::new("s".repeat(MAX_SOLVER_LABEL + 1)).is_err());
        assert_eq!(PaperId::new("kong2019").unwrap(), "kong2019");
        let err = PaperId::new("Kong2019").unwrap_err();
        assert!(
            err.to_string()
                .starts_with("paper id \"Kong2019\" is not a slug"),
            "{err}"
        );
    }

    #[test]
    fn every_id_can_name_a_file() {
        for text in ["a", "jia2019-clover", "x.1-y", "0"] {
            let id = VariantId::new(text).unwrap();
            assert!(
                crate::naming::check_name(&id, MAX_VARIANT_LABEL).is_ok(),
                "{id}"
            );
        }
    }

    #[test]
    fn serde_reads_through_the_check_and_messages_suggest_a_slug() {
        #[derive(serde::Deserialize)]
        struct Row {
            id: SolverId,
        }
        let ok: Row = toml::from_str("id = \"lvi-pdnn\"").unwrap();
        assert_eq!(ok.id.as_str(), "lvi-pdnn");
        let err = toml::from_str::<Row>("id = \"LVI PDNN\"").err().unwrap();
        assert!(
            err.to_string().contains("did you mean \"lvi-pdnn\""),
            "{err}"
        );
    }
}
