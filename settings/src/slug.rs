//! File-safe names: the one slug function every id derived from text goes through (solver ids,
//! variant ids not declared in a file, trace and figure names).

/// `text` as a slug: lower-case ASCII letters, digits and `.`; every other run of characters
/// becomes one `-`, and none leads or trails. Idempotent: `slug(slug(s)) == slug(s)`.
pub fn slug(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if c.is_ascii_alphanumeric() || c == '.' {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

/// Whether `text` is already a slug (what a declared id must be).
pub fn is_slug(text: &str) -> bool {
    !text.is_empty() && slug(text) == text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slugs_are_file_safe_and_idempotent() {
        assert_eq!(slug("VP-RNN-PF (sinh)"), "vp-rnn-pf-sinh");
        assert_eq!(slug("MVN [jaco2 hand centre]"), "mvn-jaco2-hand-centre");
        assert_eq!(slug("a=0.25, b"), "a-0.25-b");
        for s in ["VLTCO [star-lines]", "--x--", "ÄÖ 1"] {
            assert_eq!(slug(&slug(s)), slug(s));
        }
        assert!(is_slug("jia2019-clover"));
        assert!(!is_slug("VLTCO"));
        assert!(!is_slug(""));
        assert!(!is_slug("-a"));
    }
}
