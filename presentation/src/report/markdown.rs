//! Markdown building blocks: the report's number formats and a pipe-table builder.
//!
//! Every measured number is printed with three significant digits in scientific notation
//! ([`sci`]), so that columns of very different magnitudes stay comparable at a glance and
//! the output is byte-stable. A fraction is shown as a percentage ([`percent`]), seconds as
//! minutes ([`minutes`]) and a ratio to the best with three significant digits ([`times`]):
//! units of display, the only arithmetic of the report's pages (what is shown is computed in
//! crate `analysis`).

/// The placeholder for a number that does not exist (not measured, not printed by the paper).
pub const MISSING: &str = "—";

pub use analysis::sci;

/// [`sci`] of an optional number, [`MISSING`] when absent.
pub fn sci_opt(v: Option<f64>) -> String {
    v.map(sci).unwrap_or_else(|| MISSING.to_string())
}

/// A fraction as a percentage with `decimals` decimals: `percent(0.25, 1)` is `25.0 %`.
pub fn percent(fraction: f64, decimals: usize) -> String {
    format!("{:.*} %", decimals, 100.0 * fraction)
}

/// Seconds as minutes with one decimal: `minutes(90.0)` is `1.5`.
pub fn minutes(seconds: f64) -> String {
    format!("{:.1}", seconds / 60.0)
}

/// A ratio to the best with three significant digits (`1.00`, `12.3`, `456`), scientific
/// outside [1, 1000).
pub fn times(v: f64) -> String {
    if v.is_finite() && (1.0..1000.0).contains(&v) {
        let decimals = 2 - v.log10().floor() as usize;
        format!("{v:.decimals$}")
    } else {
        sci(v)
    }
}

/// A Markdown pipe table.
#[derive(Clone, Debug)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column headers and no rows.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Self {
        Table {
            header: header.into_iter().map(Into::into).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row (one cell per header column).
    pub fn push<S: Into<String>>(&mut self, row: impl IntoIterator<Item = S>) {
        let row: Vec<String> = row.into_iter().map(Into::into).collect();
        debug_assert_eq!(
            row.len(),
            self.header.len(),
            "row width differs from the header"
        );
        self.rows.push(row);
    }

    /// True when the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Removes the columns (other than the first) whose cells are all [`MISSING`].
    pub fn without_empty_columns(self) -> Self {
        let keep: Vec<bool> = (0..self.header.len())
            .map(|c| c == 0 || self.rows.iter().any(|r| r[c] != MISSING))
            .collect();
        let pick = |cells: Vec<String>| {
            cells
                .into_iter()
                .zip(&keep)
                .filter(|(_, k)| **k)
                .map(|(c, _)| c)
                .collect()
        };
        Table {
            header: pick(self.header),
            rows: self.rows.into_iter().map(pick).collect(),
        }
    }

    /// The table as Markdown, ending with a newline. A table wider than [`MAX_COLUMNS`] is
    /// rendered as several tables of at most that many columns, each repeating the first
    /// column (the rows' labels), the columns shared out evenly and kept in order.
    pub fn render(&self) -> String {
        let data = self.header.len().saturating_sub(1);
        let parts = data.div_ceil(MAX_COLUMNS - 1).max(1);
        if parts == 1 {
            return self.render_columns(&(0..self.header.len()).collect::<Vec<_>>());
        }
        let per = data.div_ceil(parts);
        (0..parts)
            .map(|p| {
                let columns: Vec<usize> = std::iter::once(0)
                    .chain(1 + p * per..(1 + (p + 1) * per).min(1 + data))
                    .collect();
                self.render_columns(&columns)
            })
            .collect::<Vec<_>>()
            .join("\n*(continued)*\n\n")
    }

    /// The table restricted to `columns` (indices, in order), as Markdown.
    fn render_columns(&self, columns: &[usize]) -> String {
        let pick = |cells: &[String]| -> Vec<String> {
            columns.iter().map(|&c| cells[c].clone()).collect()
        };
        let line = |cells: &[String]| {
            format!(
                "| {} |\n",
                cells
                    .iter()
                    .map(|c| escape(c))
                    .collect::<Vec<_>>()
                    .join(" | ")
            )
        };
        let mut out = line(&pick(&self.header));
        out.push_str(&format!("|{}\n", "---|".repeat(columns.len())));
        for r in &self.rows {
            out.push_str(&line(&pick(r)));
        }
        out
    }
}

/// The most columns a rendered table has (the first, the rows' labels, included): wider
/// tables are split ([`Table::render`]) so that a page reads on a screen.
pub const MAX_COLUMNS: usize = 12;

/// Text from an input (a paper's title, citation, claim, a published table's names and notes)
/// as Markdown that shows it literally and carries no HTML: `&`, `<` and `>` become entities,
/// the characters that open Markdown's emphasis, code, links, headings and strike-through
/// (`\`, `` ` ``, `*`, `_`, `[`, `]`, `#`, `~`) are backslash-escaped, and a line break or other
/// control character becomes a space, so the text can neither end the line, heading or list
/// item it is in nor open a link or a tag. (`|` is left to [`Table`], which escapes it in cells;
/// outside a table it is text.) The one escaping function of the report.
pub fn text(input: &str) -> String {
    let mut out = String::with_capacity(input.len());
    for c in input.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\\' | '`' | '*' | '_' | '[' | ']' | '#' | '~' => {
                out.push('\\');
                out.push(c);
            }
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A cell made safe for a pipe table, whatever it holds: `|` escaped, a line break or other
/// control character a space, the `<` that would open HTML (before an ASCII letter, `/`, `!` or
/// `?`) an entity, and the `(` of a link whose target has a URL scheme (`[x](javascript:...)`)
/// escaped, so no cell ends its row, carries a tag or links off the report. (The report's own
/// cells link only to its pages and figures by relative paths, and hold no HTML; text from a
/// file goes through [`text`] besides.)
fn escape(cell: &str) -> String {
    let mut out = String::with_capacity(cell.len());
    for (i, c) in cell.char_indices() {
        let rest = &cell[i + c.len_utf8()..];
        match c {
            '|' => out.push_str("\\|"),
            '<' if rest.starts_with(|n: char| n.is_ascii_alphabetic() || "/!?".contains(n)) => {
                out.push_str("&lt;")
            }
            '(' if cell[..i].ends_with(']') && has_scheme(rest) => out.push_str("\\("),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// Whether a link target starts with a URL scheme (`javascript:`, `data:`, `https:`): an ASCII
/// letter, then letters, digits, `+`, `-` or `.`, then `:`.
fn has_scheme(target: &str) -> bool {
    let t = target.trim_start();
    let end = t
        .find(|c: char| !(c.is_ascii_alphanumeric() || "+-.".contains(c)))
        .unwrap_or(t.len());
    t.starts_with(|c: char| c.is_ascii_alphabetic()) && t[end..].starts_with(':')
}

/// A cell for `metric` of `r`: the number, or why there is none (a failed run has no drift).
pub fn metric_cell(r: &records::RunRow, name: &str) -> String {
    match records::index::metric(r, name) {
        Some(v) => sci(v),
        None if !records::index::completed(r) => records::index::failed_at(r),
        None => MISSING.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wide_table_is_split_keeping_its_label_column_and_every_cell() {
        let header: Vec<String> = (0..25).map(|c| format!("h{c}")).collect();
        let mut t = Table::new(header);
        t.push((0..25).map(|c| format!("r{c}")));
        let out = t.render();
        let widths: Vec<usize> = out
            .lines()
            .filter(|l| l.starts_with("| h0 "))
            .map(|l| l.matches(" | ").count() + 1)
            .collect();
        assert_eq!(
            widths,
            [9, 9, 9],
            "24 data columns in three tables of 8 + the label"
        );
        for c in 0..25 {
            assert!(out.contains(&format!("| r{c} ")) || out.contains(&format!("| r{c} |")));
        }
        assert_eq!(
            out.matches("| r0 |").count(),
            3,
            "the label column in every part"
        );
        let mut narrow = Table::new(["a", "b"]);
        narrow.push(["1", "2"]);
        assert_eq!(narrow.render(), "| a | b |\n|---|---|\n| 1 | 2 |\n");
    }

    #[test]
    fn input_text_shows_literally_without_html_links_or_line_breaks() {
        assert_eq!(text("plain text, 1e-4 (m)"), "plain text, 1e-4 (m)");
        assert_eq!(
            text("a\n## Summary\r<script>x & y</script>"),
            "a \\#\\# Summary &lt;script&gt;x &amp; y&lt;/script&gt;"
        );
        assert_eq!(
            text("[click](javascript:alert(1))"),
            "\\[click\\](javascript:alert(1))"
        );
        assert_eq!(
            text("θ*0, theta_4, `x`, ~~s~~, \\"),
            "θ\\*0, theta\\_4, \\`x\\`, \\~\\~s\\~\\~, \\\\"
        );
        let mut t = Table::new(["a", "b"]);
        t.push([text("x | y"), text("<img src=x onerror=alert(1)>")]);
        let md = t.render();
        assert_eq!(
            md.lines().nth(2),
            Some("| x \\| y | &lt;img src=x onerror=alert(1)&gt; |")
        );
    }

    /// Every cell, whatever table it comes from (the Python leaderboard's names were escaped
    /// for `|` only): no tag, no link off the report, no line break; the report's own cells
    /// (relative links, `<=`, code) as they were.
    #[test]
    fn every_cell_is_escaped_for_a_table() {
        let mut t = Table::new(["a"]);
        for cell in [
            "<img src=x onerror=alert(1)>",
            "[x](javascript:alert(1))",
            "[x]( data:text/html,1)",
            "a\nb\r|c",
            "</td><!-- -->",
            "[figure](figures/a__b__c.svg)",
            "94LVI (|e| <= 0.001)",
            "`code` [T2](paper-jia2019.md#t2)",
        ] {
            t.push([cell]);
        }
        let md = t.render();
        let rows: Vec<&str> = md.lines().skip(2).collect();
        assert_eq!(
            rows,
            [
                "| &lt;img src=x onerror=alert(1)> |",
                "| [x]\\(javascript:alert(1)) |",
                "| [x]\\( data:text/html,1) |",
                "| a b \\|c |",
                "| &lt;/td>&lt;!-- --> |",
                "| [figure](figures/a__b__c.svg) |",
                "| 94LVI (\\|e\\| <= 0.001) |",
                "| `code` [T2](paper-jia2019.md#t2) |",
            ]
        );
    }

    #[test]
    fn three_significant_digits() {
        assert_eq!(sci(-0.00012345), "-1.23e-4");
        assert_eq!(sci(1.0), "1.00e0");
        assert_eq!(sci_opt(None), MISSING);
        assert_eq!(
            (times(1.0), times(12.34), times(456.7)),
            ("1.00".into(), "12.3".into(), "457".into())
        );
        assert_eq!(times(1234.0), "1.23e3");
    }

    #[test]
    fn units_of_display() {
        assert_eq!(percent(0.25, 1), "25.0 %");
        assert_eq!(percent(0.123456, 3), "12.346 %");
        assert_eq!(percent(1.0, 0), "100 %");
        assert_eq!(minutes(90.0), "1.5");
    }

    #[test]
    fn empty_columns_are_dropped_and_pipes_escaped() {
        let mut t = Table::new(["a", "b", "c"]);
        t.push(["x|y", MISSING, "1"]);
        assert_eq!(
            t.without_empty_columns().render(),
            "| a | c |\n|---|---|\n| x\\|y | 1 |\n"
        );
    }
}
