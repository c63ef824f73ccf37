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

/// `<variant-slug>__<solver-slug>`: a run's file stem inside its experiment's directory, shared
/// by the traces and the figures.
pub fn run_stem(variant: &str, solver: &str) -> String {
    format!("{}__{}", slug(variant), slug(solver))
}

#[cfg(test)]
mod tests {
    use super::slug;

    #[test]
    fn slugs_are_file_safe() {
        assert_eq!(slug("VP-RNN-PF (sinh)"), "vp-rnn-pf-sinh");
        assert_eq!(slug("exact (Clarabel)"), "exact-clarabel");
        assert_eq!(slug("MVN [jaco2 hand centre]"), "mvn-jaco2-hand-centre");
    }
}
