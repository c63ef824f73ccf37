//! The claims checklist: each paper's claims, as crate `analysis` evaluated them
//! ([`analysis::claim_verdict`]), rendered as Markdown.

use analysis::claim_verdict::Claim;

/// The checklist as Markdown.
pub fn checklist(claims: &[Claim]) -> String {
    let mut out = String::new();
    for c in claims {
        out.push_str(&format!(
            "- **{}** {} — {}\n",
            c.verdict.label(),
            c.statement,
            c.evidence
        ));
    }
    out
}
