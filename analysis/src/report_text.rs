//! What a text of `papers/` that reaches the report must be: one line. The report puts titles,
//! citations and claims into headings, table cells and list items, which a line break or other
//! control character would end (a claim's text would become a heading of its own).

/// Whether `text` is one line: no line break, control or formatting character. The rule is
/// crate settings', which the experiment files' `title` and `paper_output` follow too.
pub use settings::is_one_line;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_break_or_control_character_ends_one_line() {
        assert!(is_one_line("Jia & Li, “Drift-free…”, 2019"));
        assert!(!is_one_line("a\n## Summary") && !is_one_line("a\rb"));
        // A bidi override would reverse what follows it; a line separator breaks the line.
        assert!(!is_one_line("Jia \u{202e}9102") && !is_one_line("a\u{2028}b"));
    }
}
