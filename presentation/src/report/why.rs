//! "Why the numbers differ": per paper, the drift attribution of every run of the paper's
//! solver (`results/attribution.csv`), the tolerance ladder (`results/ladder.csv`) and the setup
//! inference (`results/inference.csv`, `results/inference-entries.csv`); and the section of
//! the group-code reference experiments. See `explain` for the mathematics; what is read from
//! the rows (the runs explained, the shares, the runs at MATLAB's default tolerances, the
//! solvers' spreads, the ladder's rungs) is the report model's
//! (`analysis::report_model::why`), built once per render: this module formats it.

use super::markdown::{percent, sci, sci_opt, Table, MISSING};
use analysis::drift_attribution::RunIds;
use analysis::inference_verdict::{FLAT, REPRODUCED, WEAK};
use analysis::papers::Papers;
use analysis::report_model::why::{AttributedRun, Attribution, Ladder, Why};
use analysis::report_model::Inference;
use analysis::GROUP_PAPER;
use records::inference::{self, EntryRow, InferenceRow, Integration, FAILED as FAILED_RESIDUAL};
use records::{AttributionRow, Component};
use records::{LadderMethod, LadderRow};
use std::fmt::Write as _;

/// The stored explanation results.
#[derive(Clone, Debug, Default)]
pub struct Explanations {
    pub ladder: Vec<LadderRow>,
    pub attribution: Vec<AttributionRow>,
    pub inference: Vec<InferenceRow>,
    pub entries: Vec<EntryRow>,
}

/// How the summary paragraph names a term of the sum.
fn described(c: Component) -> &'static str {
    match c {
        Component::Scheme => "the scheme itself (exact column, converged)",
        Component::NetworkLag => "the network's lag",
        Component::IntegrationError => "integration error",
        Component::SamplingGap => "the fixed-step loop's sampling gap",
        Component::StoppingRule => "the stopping rule",
        other => other.label(),
    }
}

/// How the front page's one line names a term of the sum.
fn brief(c: Component) -> &'static str {
    match c {
        Component::Scheme => "scheme",
        Component::NetworkLag => "lag",
        Component::IntegrationError => "integration",
        Component::SamplingGap => "sampling",
        Component::StoppingRule => "stopping rule",
        other => other.label(),
    }
}

/// "`experiment` variant / solver" of a run, by its labels (`key`, ids, when no row is found).
fn shown(row: Option<&AttributionRow>, key: RunIds) -> String {
    match row {
        Some(r) => format!("`{}` {} / {}", r.experiment, r.variant, r.solver),
        None => format!("`{}` {} / {}", key.0, key.1, key.2),
    }
}

/// "1.23e-3 (45 %)" of a component, or why it is missing.
fn cell(r: Option<&AttributionRow>) -> String {
    match r {
        None => MISSING.to_string(),
        Some(r) => match (r.drift_norm, r.share) {
            (Some(n), Some(s)) => format!("{} ({})", sci(n), percent(s, 0)),
            (Some(n), None) => sci(n),
            _ => format!("{MISSING} ({})", short(&r.note)),
        },
    }
}

fn short(s: &str) -> String {
    let s = s.trim();
    if s.chars().count() > 60 {
        format!("{}…", s.chars().take(60).collect::<String>())
    } else {
        s.to_string()
    }
}

/// The attribution table of one paper's runs: published norm, ours, and the "of which"
/// columns.
pub fn attribution_table(a: &Attribution) -> String {
    let networks = a.terms.contains(&Component::NetworkLag);
    let numerical = a.terms.contains(&Component::SamplingGap);
    let mut header = vec![
        "run (variant / solver)".to_string(),
        "paper ‖d‖".to_string(),
        "ours ‖d‖ (as run)".to_string(),
        "ours ‖d‖ at MATLAB's default tolerances".to_string(),
    ];
    header.extend(a.terms.iter().map(|s| format!("{} ‖·‖ (share)", s.label())));
    header.extend(a.switches.iter().map(|s| format!("{} ‖·‖", s.label())));
    header.push(match (networks, numerical) {
        (true, false) => "max pos. err: run / exact / converged net (m)".to_string(),
        (false, true) => "max pos. err: run / exact / converged method (m)".to_string(),
        _ => "max pos. err: run / exact / converged solver (m)".to_string(),
    });
    let mut t = Table::new(header);
    for run in &a.runs {
        t.push(attribution_row(run));
    }
    let mut out = t.without_empty_columns().render();
    out.push_str(&attribution_note(
        networks,
        numerical,
        !a.switches.is_empty(),
    ));
    out
}

/// The attribution table's row of `run`: its labels, the paper's norm (`*`: derived from the
/// joints), ours as run and at MATLAB's default tolerances (× where that rung did not
/// finish), each of its columns (the sums' terms, then the switches), and the max position
/// errors of the run, the exact column and the converged solver.
fn attribution_row(run: &AttributedRun) -> Vec<String> {
    let paper_norm = run
        .published_norm
        .map(|(v, derived)| format!("{}{}", sci(v), if derived { "*" } else { "" }))
        .unwrap_or_else(|| MISSING.to_string());
    let mut row = vec![
        shown(run.run, run.key),
        paper_norm,
        sci_opt(run.run.and_then(|r| r.drift_norm)),
        match run.matlab_rung {
            Some(r) if r.completed() => sci_opt(r.drift_norm),
            Some(_) => "×".to_string(),
            None => MISSING.to_string(),
        },
    ];
    row.extend(run.columns.iter().map(|c| cell(*c)));
    let err = |r: Option<&AttributionRow>| sci_opt(r.and_then(|r| r.max_pos_err));
    row.push(format!(
        "{} / {} / {}",
        err(run.run),
        err(run.scheme),
        err(run.converged)
    ));
    row
}

/// What the attribution table's shares mean, for the sums it shows (a network's, a numerical
/// method's) and its "of which" columns (`switches`).
fn attribution_note(networks: bool, numerical: bool, switches: bool) -> String {
    let mut out = String::from("\nShares are |component| / |d_run|; ");
    if networks {
        out.push_str("for a network, scheme + network lag + integration error = the run's drift, joint by joint; ");
    }
    if numerical {
        out.push_str("for a numerical method in its fixed-step loop of step h, scheme + sampling gap + stopping rule = the run's drift, joint by joint (the sampling gap is the same loop at its finest stopping tolerance of the ladder against the exact column, the stopping rule the run against that loop); ");
    }
    out.push_str("the three need not add up in norm.");
    if networks {
        out.push_str(" The MATLAB-default column is the paper's solver integrated by ode15s's method at RelTol 1e-3 / AbsTol 1e-6, MATLAB's defaults, for the case that the papers' runs used them.");
    }
    if switches {
        out.push_str(" \"of which\" columns are the effect of switching one ingredient off with everything else held (they are part of the first three, not further terms).");
    }
    out.push_str(
        " \\* the paper prints no norm: the norm of its per-joint entries. Per-joint components: `results/attribution.csv`.\n",
    );
    out
}

/// The ladder of one paper's runs: digits shared with the converged drift at each rung.
pub fn ladder_table(l: &Ladder) -> String {
    let mut header = vec!["run".to_string()];
    header.extend(l.rungs.iter().map(|rung| {
        let m = rung.method;
        if m == LadderMethod::FixedStep {
            return format!("{m} |e| <= {}", short_tol(rung.rtol));
        }
        format!(
            "{m} {}/{}{}",
            short_tol(rung.rtol),
            short_tol(rung.atol),
            if rung.matlab { " (MATLAB default)" } else { "" }
        )
    }));
    let mut t = Table::new(header);
    for run in &l.runs {
        let r = run.first;
        let mut row = vec![format!("`{}` {} / {}", r.experiment, r.variant, r.solver)];
        row.extend(run.cells.iter().map(|c| rung_cell(*c)));
        t.push(row);
    }
    let mut out = t.without_empty_columns().render();
    out.push_str(
        "\nCells: significant digits the drift shares with the converged drift (\"ref\", the finest completed rung; -log10 of the relative change), **bold** at the run's own setting; × the rung did not finish (an explicit method on a stiff network, or the step cap). A published digit beyond the digits at the paper's setting (ode15s = bdf at RelTol 1e-6 / AbsTol 1e-8; MATLAB's default is 1e-3 / 1e-6) can be integration noise. A run with the group's MaxStep keeps it on every rung.",
    );
    if l.fixed_step {
        out.push_str(" A numerical method's rungs (fixed-step) are its loop at the run's own step h, each instant's iteration stopped at |e(U)|_2 <= the rung's tolerance: its digits at the paper's 1e-3 are those the stopping rule leaves (the sampling gap is in the attribution).");
    }
    out.push_str(" Every rung with its drifts, steps and wall time: `results/ladder.csv`.\n");
    out
}

/// A rung's cell of the ladder: the digits it shares with the converged drift (bold at the
/// run's own setting), "ref" for the converged rung, × for one that did not finish.
fn rung_cell(r: Option<&LadderRow>) -> String {
    match r {
        None => MISSING.to_string(),
        Some(r) if r.reference => "ref".to_string(),
        Some(r) if !r.completed() => "×".to_string(),
        Some(r) => {
            let d = r
                .stable_digits
                .map(|d| format!("{d:.1}"))
                .unwrap_or_default();
            if r.as_run {
                format!("**{d}**")
            } else {
                d
            }
        }
    }
}

/// A tolerance with no decimals, as the ladder's headers show it (`1e-6`).
fn short_tol(v: f64) -> String {
    format!("{v:.0e}")
}

/// The inference of one paper's tables.
pub fn inference_section(paper: &str, x: &Explanations, inferred: &[Inference]) -> String {
    let rows: Vec<&InferenceRow> = x.inference.iter().filter(|r| r.paper == paper).collect();
    if rows.is_empty() {
        return format!(
            "No setup inference stored for {paper}: run `cargo run --release -p reproduce -- infer {paper}`.\n"
        );
    }
    let mut out = String::new();
    for inference in inferred.iter().filter(|i| i.paper == paper) {
        let of_table: Vec<&InferenceRow> = rows
            .iter()
            .copied()
            .filter(|r| r.table == inference.table)
            .collect();
        out.push_str(&table_inference(inference, &of_table, x));
    }
    let _ = writeln!(
        out,
        "A column or table counts as reproduced when its relative residual ‖d − d_paper‖ / ‖d_paper‖ is at most {}; the table residual is the root mean square of the column residuals, so every column weighs alike whatever its magnitude. A column fitted alone has as many entries as the arm has joints against up to five continuous parameters and the discrete ones: a close column fit is weak evidence by itself; one setup that explains every column of a table is the stronger test. A profile is flat when its largest residual is below {}x its smallest, weakly determined below {}x. Every evaluated setup's residuals: `results/inference.csv`; the entries of the declared, joint and column fits: `results/inference-entries.csv`.",
        percent(REPRODUCED, 0),
        FLAT,
        WEAK
    );
    out
}

/// The inference of one published table (its rows `of_table`): the verdicts, the search, the
/// setups found, each hypothesis's best, the profiles and the per-entry residuals; empty
/// without a verdict or without the declared and the inferred setup.
fn table_inference(inference: &Inference, of_table: &[&InferenceRow], x: &Explanations) -> String {
    let (paper, table) = (inference.paper, inference.table);
    let Some(verdicts) = &inference.verdicts else {
        return String::new();
    };
    let find = |kind: &str, objective: &str| {
        of_table
            .iter()
            .copied()
            .find(|r| r.kind == kind && r.objective == objective)
    };
    let (Some(declared), Some(best)) = (
        find(inference::DECLARED, inference::TABLE),
        find(inference::BEST, inference::TABLE),
    ) else {
        return String::new();
    };
    let mut out = String::new();
    let _ = writeln!(out, "**{table}.**\n");
    for v in verdicts {
        let _ = writeln!(out, "- {v}");
    }
    let column_starts = of_table
        .iter()
        .any(|r| r.kind == inference::LOCAL && r.objective != inference::TABLE);
    let profiled = of_table.iter().any(|r| r.profile().is_some());
    let _ = writeln!(
        out,
        "\nSearch: {} evaluations in {:.0} s (a Halton sample of the continuous parameters for every discrete combination, then Nelder-Mead from the best few of the whole table{}{}); every optimum below is the best of all evaluations.\n",
        best.evaluations,
        best.wall_s,
        if column_starts { " and of each column alone" } else { "" },
        if profiled {
            ", then the profiles, and Nelder-Mead once more from a profile point that beat the optimum, if one did"
        } else {
            ""
        }
    );
    let columns: Vec<&str> = of_table
        .iter()
        .filter(|r| r.kind == inference::BEST && r.objective != inference::TABLE)
        .map(|r| r.objective.as_str())
        .collect();
    let mut setups = vec![
        ("declared".to_string(), declared),
        (
            "inferred setup (fitted to the paper): whole table".to_string(),
            best,
        ),
    ];
    for c in &columns {
        if let Some(r) = find(inference::BEST, c) {
            setups.push((
                format!("inferred setup (fitted to the paper): {c} alone"),
                r,
            ));
        }
    }
    out.push_str(&setups_table(&setups));
    out.push_str(&hypotheses_table(of_table, &columns));
    out.push_str(&profiles_list(inference, of_table));
    out.push_str(&entries_table(paper, table, x));
    out.push('\n');
    out
}

/// The setups (label, row) of a table's inference: each setup's parameters and residuals.
fn setups_table(setups: &[(String, &InferenceRow)]) -> String {
    let mut t = Table::new([
        "setup",
        "robot",
        "drift computed by",
        "rotation (rad)",
        "tilt x / y (rad)",
        "phase",
        "size factor",
        "reversed",
        "RMP reading",
        "rel. residual (of what it is fitted to)",
        "table residual",
        "max entry error",
        "signs as the paper",
    ]);
    for (label, r) in setups {
        t.push([
            label.clone(),
            r.robot.clone(),
            integration_words(r.integration).to_string(),
            format!("{:.3}", r.rotation),
            format!("{:.3} / {:.3}", r.tilt_x, r.tilt_y),
            format!("{:.3}", r.phase),
            format!("{:.3}", r.scale_factor),
            r.reverse.to_string(),
            r.rmp.label().to_string(),
            residual(r.rel_residual),
            residual(r.table_residual),
            sci_opt(r.max_entry_error),
            match (r.signs_matched, r.entries) {
                (Some(s), Some(n)) => format!("{s} of {n}"),
                _ => MISSING.to_string(),
            },
        ]);
    }
    t.render()
}

/// The profiles of a table's inference, when it has any: the figure and, per profiled
/// parameter, its points and verdict.
fn profiles_list(inference: &Inference, of_table: &[&InferenceRow]) -> String {
    let (paper, table) = (inference.paper, inference.table);
    let mut out = String::new();
    let profiles: Vec<&InferenceRow> = of_table
        .iter()
        .copied()
        .filter(|r| r.profile().is_some())
        .collect();
    if !profiles.is_empty() {
        let _ = writeln!(
            out,
            "\n![{paper} {table}: inference profiles](figures/{})",
            crate::figures::profile::file_name(paper, table)
        );
        out.push_str(
            "\nProfiles of the whole-table optimum (each point: the best table residual with that parameter held at the value; \"re-fitted\": the other continuous parameters re-fitted there by Nelder-Mead, warm-started from the neighbouring point; \"slice\": held at the optimum). They are taken at the optimum of the global and local stages; where a profile point beat it, Nelder-Mead went on from there, and the optimum reported (marked in the figure) can lie below the profiles:\n\n",
        );
        for &(name, refitted, decided) in &inference.profiles {
            let along: Vec<&&InferenceRow> = profiles
                .iter()
                .filter(|r| r.profile() == Some((name, refitted)))
                .collect();
            let pts: Vec<String> = along
                .iter()
                .map(|r| {
                    let v = r.parameter(name);
                    if r.rel_residual >= FAILED_RESIDUAL {
                        format!("{v:.2} → failed (a run of the table failed)")
                    } else {
                        format!("{v:.2} → {}", sci(r.rel_residual))
                    }
                })
                .collect();
            let _ = writeln!(
                out,
                "- {name} ({}): {} ({})",
                if refitted { "re-fitted" } else { "slice" },
                pts.join(", "),
                decided
            );
        }
    }
    out
}

/// The per-entry residuals of the inferred setup of the whole table (ours / paper per joint
/// and column), when stored.
fn entries_table(paper: &str, table: &str, x: &Explanations) -> String {
    let mut out = String::new();
    let entries: Vec<&EntryRow> = x
        .entries
        .iter()
        .filter(|e| e.paper == paper && e.table == table && e.setup == inference::BEST)
        .collect();
    if !entries.is_empty() {
        out.push_str(
            "\nPer-entry residuals of the inferred setup of the whole table (ours / paper):\n\n",
        );
        let mut columns: Vec<&str> = entries.iter().map(|e| e.column.as_str()).collect();
        columns.dedup();
        let n = entries.iter().map(|e| e.joint).max().unwrap_or(0);
        let mut header = vec!["column".to_string()];
        header.extend((1..=n).map(|j| format!("θ{j}")));
        let mut t = Table::new(header);
        for c in columns {
            let mut row = vec![c.to_string()];
            for j in 1..=n {
                row.push(
                    entries
                        .iter()
                        .find(|e| e.column == c && e.joint == j)
                        .map(|e| {
                            format!(
                                "{} / {}{}",
                                sci(e.ours),
                                sci(e.paper_value),
                                if e.sign_matched { "" } else { " (sign)" }
                            )
                        })
                        .unwrap_or_else(|| MISSING.to_string()),
                );
            }
            t.push(row);
        }
        out.push_str(&t.render());
    }
    out
}

/// A residual, or "failed" for the penalty of a setup whose run failed.
fn residual(r: f64) -> String {
    if r >= FAILED_RESIDUAL {
        "failed".to_string()
    } else {
        sci(r)
    }
}

fn integration_words(i: Integration) -> &'static str {
    match i {
        Integration::Exact => "exact column",
        Integration::NetworkMatlabDefault => "network, MATLAB defaults",
        Integration::NetworkStated => "network, stated tolerances",
    }
}

/// The best of each hypothesis (robot x how the drift is computed): the whole table and each
/// column alone; empty with a single hypothesis.
fn hypotheses_table(rows: &[&InferenceRow], columns: &[&str]) -> String {
    let hyp: Vec<&&InferenceRow> = rows
        .iter()
        .filter(|r| r.kind == inference::HYPOTHESIS)
        .collect();
    let mut keys: Vec<(&str, Integration)> = Vec::new();
    for r in &hyp {
        if !keys.contains(&(r.robot.as_str(), r.integration)) {
            keys.push((r.robot.as_str(), r.integration));
        }
    }
    if keys.len() < 2 {
        return String::new();
    }
    let mut header = vec![
        "hypothesis (robot, drift computed by)".to_string(),
        "best table residual".to_string(),
    ];
    header.extend(columns.iter().map(|c| format!("best {c} alone")));
    let mut t = Table::new(header);
    for (robot, integration) in keys {
        let cell = |objective: &str| {
            hyp.iter()
                .find(|r| {
                    r.robot == robot && r.integration == integration && r.objective == objective
                })
                .map_or(MISSING.to_string(), |r| residual(r.rel_residual))
        };
        let mut row = vec![
            format!("{robot}, {}", integration_words(integration)),
            cell(inference::TABLE),
        ];
        row.extend(columns.iter().map(|c| cell(c)));
        t.push(row);
    }
    let mut out = String::from(
        "\nThe best of each discrete hypothesis (the pose re-fitted under each; relative residuals):\n\n",
    );
    out.push_str(&t.render());
    out
}

/// The whole "Why the numbers differ" subsection of one paper (its model, `why`).
pub fn section(why: &Why, (x, inferred): (&Explanations, &[Inference]), papers: &Papers) -> String {
    let paper = why.paper;
    let attribution = why
        .attribution
        .as_ref()
        .map_or_else(String::new, attribution_table);
    let ladder = why.ladder.as_ref().map_or_else(String::new, ladder_table);
    if attribution.is_empty() && ladder.is_empty() {
        return String::new();
    }
    let mut out = String::from("\n### Why the numbers differ\n\n");
    if paper == GROUP_PAPER {
        out.push_str(&summary(why, inferred));
    }
    if !attribution.is_empty() {
        out.push_str("\n#### Drift attribution\n\n");
        out.push_str(&attribution);
    }
    if !ladder.is_empty() {
        out.push_str("\n#### Tolerance ladder\n\n");
        out.push_str(&ladder);
    }
    let has_tables = analysis::papers::table_ids(&papers.values)
        .iter()
        .any(|(p, _)| p == paper);
    if has_tables {
        out.push_str("\n#### Setup inference\n\n");
        out.push_str(&inference_section(paper, x, inferred));
    }
    out
}

/// `lo % to hi %` of a share's range, or [`MISSING`].
fn range(v: Option<(f64, f64)>) -> String {
    match v {
        Some((lo, hi)) => format!("{} to {}", percent(lo, 3), percent(hi, 3)),
        None => MISSING.to_string(),
    }
}

/// Why a paper's drifts are what they are, in one line (the front page): the share of the
/// drift that the scheme, the lag and integration error carry over its explained runs; empty
/// where none was explained.
pub fn one_line(why: &Why) -> String {
    let Some(a) = &why.attribution else {
        return String::new();
    };
    let parts: Vec<String> = a
        .shares
        .iter()
        .map(|(c, v)| format!("{} {}", brief(*c), range(*v)))
        .collect();
    format!("{} of the drift", parts.join(", "))
}

/// One paragraph (placed after the verdict): which share of the drift each ingredient carries,
/// across the paper's runs, how far apart several solvers of one scheme are (the paper's and
/// ours), what MATLAB's default tolerances would change (the model's, `why`), and what the
/// setup inference found (`inferred`); empty without explanations.
pub fn summary(why: &Why, inferred: &[Inference]) -> String {
    let paper = why.paper;
    let Some(a) = &why.attribution else {
        return String::new();
    };
    let shares = &a.shares;
    let rest: Vec<String> = shares
        .iter()
        .filter(|(c, _)| *c != Component::Scheme)
        .map(|(c, v)| format!("{} {}", described(*c), range(*v)))
        .collect();
    let scheme = shares
        .iter()
        .find(|(c, _)| *c == Component::Scheme)
        .map_or(MISSING.to_string(), |(_, v)| range(*v));
    let mut out = format!(
        "\n**Why** (see \"Why the numbers differ\" below). Over {} runs of {}, {} carries {scheme} of the drift (|d_exact| / |d_run|), {}.",
        a.runs.len(),
        if paper == GROUP_PAPER {
            "the group's network"
        } else {
            "the paper's solver"
        },
        described(Component::Scheme),
        match rest.split_last() {
            Some((last, [])) => last.clone(),
            Some((last, init)) => format!("{} and {last}", init.join(", ")),
            None => String::new(),
        }
    );
    for s in &a.spreads {
        out.push_str(&format!(
            " On `{}` {} the paper's {} solvers' drift norms span a factor {:.1}, ours {:.2}: one scheme, so solvers that converge cannot differ by more than their lag.",
            s.experiment, s.variant, s.columns, s.theirs, s.ours
        ));
    }
    if let Some(m) = a.matlab {
        out.push_str(&format!(
            " Integrated at MATLAB's default tolerances (RelTol 1e-3, AbsTol 1e-6) instead of the stated 1e-6 / 1e-8, the same runs drift {} to {} times as much; the paper's norm is nearer that value than the converged one in {} of {} columns.",
            sci(m.lo),
            sci(m.hi),
            m.nearer_matlab,
            m.compared
        ));
    }
    out.push_str(&inference_verdicts(paper, inferred));
    out.push('\n');
    out
}

/// The last verdict of each of `paper`'s inferred tables (of `inferred`), as sentences of
/// the summary.
fn inference_verdicts(paper: &str, inferred: &[Inference]) -> String {
    let mut out = String::new();
    for i in inferred.iter().filter(|i| i.paper == paper) {
        if let Some(v) = i.verdicts.as_ref().and_then(|v| v.last()) {
            out.push_str(&format!(" {}: {v}", i.table));
        }
    }
    out
}
