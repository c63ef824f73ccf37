//! The claims checklist: every claim of docs/experiments.md evaluated from the stored runs.
//!
//! A claim is PASS or FAIL with the measured numbers as evidence, or N/A when the suite does
//! not measure what it is about (or its runs are missing). Verdicts refer to the paper's own
//! solver; the exact (Clarabel) numbers are given beside it. Thresholds are stated in each
//! claim: "<<" means at least [`MUCH`] times smaller.

use super::cost::{evaluation_ratio, slowdown};
use super::markdown::sci;
use records::index::{completed, failed_at, Runs, EXACT};
use records::paper_values::PaperValue;
use records::runs::RunRow;

/// "a << b" means a * MUCH <= b.
pub const MUCH: f64 = 10.0;

/// The outcome of one claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    Pass,
    Fail,
    NotApplicable,
}

impl Verdict {
    /// `PASS`, `FAIL` or `N/A`.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Fail => "FAIL",
            Verdict::NotApplicable => "N/A",
        }
    }
}

/// One evaluated claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// A few words, used in the verdict paragraph.
    pub short: String,
    /// The claim as tested, with its threshold.
    pub statement: String,
    pub verdict: Verdict,
    /// The measured numbers (or why the claim could not be evaluated).
    pub evidence: String,
}

/// Evaluates a claim: `Ok((holds, evidence))`, or `Err(why)` for N/A.
fn check(
    short: &str,
    statement: &str,
    eval: impl FnOnce() -> Result<(bool, String), String>,
) -> Claim {
    let (verdict, evidence) = match eval() {
        Ok((true, e)) => (Verdict::Pass, e),
        Ok((false, e)) => (Verdict::Fail, e),
        Err(e) => (Verdict::NotApplicable, e),
    };
    Claim {
        short: short.to_string(),
        statement: statement.to_string(),
        verdict,
        evidence,
    }
}

/// The claims of one paper (`values` gives the published compute times zhong2021's claim
/// compares with).
pub fn evaluate(paper: &str, runs: &Runs, values: &[PaperValue]) -> Vec<Claim> {
    match paper {
        "jia2019" => jia2019(runs),
        "zhang2018" => zhang2018(runs),
        "zhong2021" => zhong2021(runs, values),
        "kong2019" => kong2019(runs),
        _ => Vec::new(),
    }
}

/// A metric that must exist (a completed run's drift, a measured error).
fn value(r: &RunRow, v: Option<f64>, what: &str) -> Result<f64, String> {
    v.ok_or_else(|| {
        format!(
            "{} / {} / {}: no {what} ({})",
            r.experiment,
            r.variant,
            r.solver,
            if completed(r) {
                "not measured".to_string()
            } else {
                failed_at(r)
            }
        )
    })
}

/// "label value (exact value)" for one metric of the paper's solver and the exact column.
fn with_exact(runs: &Runs, r: &RunRow, v: impl Fn(&RunRow) -> Option<f64>) -> String {
    let exact = runs
        .find(&r.experiment, &r.variant, EXACT)
        .and_then(&v)
        .map(|e| format!(" (exact {})", sci(e)))
        .unwrap_or_default();
    format!(
        "{} {}{exact}",
        r.variant,
        v(r).map(sci).unwrap_or_else(|| failed_at(r))
    )
}

/// The run of `runs` (a filtered set) with the largest value of `v`, and that value.
fn worst<'a>(
    rows: impl Iterator<Item = &'a RunRow>,
    v: impl Fn(&RunRow) -> Option<f64>,
) -> Option<(&'a RunRow, f64)> {
    rows.filter_map(|r| v(r).map(|x| (r, x)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// `rows`, or an error when there are none (the claim is then N/A).
fn nonempty(rows: Vec<&RunRow>) -> Result<Vec<&RunRow>, String> {
    if rows.is_empty() {
        Err("no such runs".to_string())
    } else {
        Ok(rows)
    }
}

/// "experiment / variant / solver".
fn name(r: &RunRow) -> String {
    format!("{} / {} / {}", r.experiment, r.variant, r.solver)
}

const JIA_POS_ERR: f64 = 1e-4;
const LIMIT_TOL: f64 = 1e-9;

/// jia2019: drift ordering, position error, joint limits, MVN's velocity, the model check.
pub fn jia2019(runs: &Runs) -> Vec<Claim> {
    let clover = |variant: &str| {
        runs.need("jia2019-clover", variant, "LVI-PDNN")
            .map_err(|e| e.to_string())
    };
    let drift = |r: &RunRow| value(r, r.drift_norm, "drift");
    vec![
        check("drift(VLTCO) << drift(MVN-INVM)", "clover, LVI-PDNN: ‖drift‖ of VLTCO at least 10x smaller than MVN-INVM's", || {
            let (v, i) = (clover("VLTCO")?, clover("MVN-INVM")?);
            let (dv, di) = (drift(v)?, drift(i)?);
            Ok((dv * MUCH <= di, format!("{}; {}; MVN-INVM/VLTCO = {}", with_exact(runs, v, |r| r.drift_norm), with_exact(runs, i, |r| r.drift_norm), sci(di / dv))))
        }),
        check("drift(MVN-INVM) < drift(MVN)", "clover, LVI-PDNN: ‖drift‖ of MVN-INVM smaller than MVN's", || {
            let (i, m) = (clover("MVN-INVM")?, clover("MVN")?);
            let (di, dm) = (drift(i)?, drift(m)?);
            Ok((di < dm, format!("{}; {}; MVN-INVM/MVN = {}", with_exact(runs, i, |r| r.drift_norm), with_exact(runs, m, |r| r.drift_norm), sci(di / dm))))
        }),
        check("position error < 1e-4 m", "max position error below 1e-4 m in every jia2019 run (all variants and solvers)", || {
            let (r, e) = worst(runs.of_paper("jia2019"), |r| r.max_pos_err).ok_or("no jia2019 run measured a position error")?;
            Ok((e < JIA_POS_ERR, format!("largest: {} in {}", sci(e), name(r))))
        }),
        check("joints inside their limits", "every jia2019 run: min joint-angle margin >= 0 and min joint-velocity margin >= -1e-9 rad/s", || {
            let (ra, a) = worst(runs.of_paper("jia2019"), |r| r.theta_margin.map(|m| -m)).ok_or("no margins measured")?;
            let (rv, v) = worst(runs.of_paper("jia2019"), |r| r.thetadot_margin.map(|m| -m)).ok_or("no margins measured")?;
            Ok((-a >= 0.0 && -v >= -LIMIT_TOL, format!("min angle margin {} rad ({}); min velocity margin {} rad/s ({})", sci(-a), name(ra), sci(-v), name(rv))))
        }),
        check(
            "MVN's θ̇ stays inside ±1.5 rad/s",
            "MVN (jaco2-pen) keeps every joint velocity inside its bound (>= -1e-9 rad/s margin): the bounds are QP constraints, so the paper's θ̇1 crossing of -1.5 rad/s at t = 2.23 s cannot occur",
            || {
                let m = clover("MVN")?;
                let margin = value(m, m.thetadot_margin, "velocity margin")?;
                Ok((margin >= -LIMIT_TOL, format!("min velocity margin (all joints, so θ̇1 included): {} rad/s; peak |θ̇| {} rad/s", with_exact(runs, m, |r| r.thetadot_margin), sci(value(m, m.peak_thetadot, "peak")?))))
            },
        ),
        check("jaco2-hand leaves joint 6 still", "MVN, exact: |θ6(T) − θ6(0)| on jaco2-hand at most 1e-3 x that on jaco2-pen (joint 6 cannot move a tool point on its axis)", || {
            let hand = runs.need("jia2019-clover", "MVN [jaco2-hand]", EXACT).map_err(|e| e.to_string())?;
            let pen = runs.need("jia2019-clover", "MVN", EXACT).map_err(|e| e.to_string())?;
            let (h, p) = (value(hand, hand.drift.get(5).copied(), "θ6 drift")?.abs(), value(pen, pen.drift.get(5).copied(), "θ6 drift")?.abs());
            Ok((h <= 1e-3 * p, format!("|θ6 drift|: jaco2-hand {}, jaco2-pen {}", sci(h), sci(p))))
        }),
    ]
}

const SMALL_DRIFT: f64 = 1e-2;
const TRACKING: f64 = 1e-3;

/// zhang2018: MTN diverges, HL-JDF returns, FP-CDNN breaks under perturbation, VP-CDNN does not.
pub fn zhang2018(runs: &Runs) -> Vec<Claim> {
    let select = |exp_suffix: &'static str, variant: &'static str, solver: &'static str| {
        runs.of_paper("zhang2018")
            .filter(move |r| {
                r.experiment.ends_with(exp_suffix)
                    && r.variant.starts_with(variant)
                    && r.solver.starts_with(solver)
            })
            .collect::<Vec<_>>()
    };
    let peaks = |r: &RunRow| {
        format!(
            "{}: {}, peak |θ̇| {}, |θ̈| {}, |τ| {}",
            r.experiment.trim_start_matches("zhang2018-"),
            if completed(r) {
                format!("drift {}", r.drift_norm.map(sci).unwrap_or_default())
            } else {
                failed_at(r)
            },
            r.peak_thetadot.map(sci).unwrap_or_default(),
            r.peak_thetaddot.map(sci).unwrap_or_default(),
            r.peak_torque.map(sci).unwrap_or_default()
        )
    };
    let returns = |r: &RunRow| completed(r) && r.drift_norm.is_some_and(|d| d < SMALL_DRIFT);
    vec![
        check("MTN diverges", "MTN (zeta = 0), FP-CDNN and exact: the run fails or a joint exceeds its 1.5 rad/s bound", || {
            let rows = nonempty(select("-scheme", "MTN", ""))?;
            let ok = rows.iter().all(|r| !completed(r) || r.thetadot_margin.is_some_and(|m| m < 0.0));
            Ok((ok, rows.iter().map(|r| format!("{} ({})", peaks(r), r.solver)).collect::<Vec<_>>().join("; ")))
        }),
        check("HL-JDF returns to θ0 smoothly", "HL-JDF (zeta = 0.6), FP-CDNN: completes with ‖drift‖ < 1e-2 rad and every joint velocity inside its bound", || {
            let rows = nonempty(select("-scheme", "HL-JDF", "FP-CDNN"))?;
            let ok = rows.iter().all(|r| returns(r) && r.thetadot_margin.is_some_and(|m| m >= 0.0));
            Ok((ok, rows.iter().map(|r| peaks(r)).collect::<Vec<_>>().join("; ")))
        }),
        check("perturbed FP-CDNN fails", "perturbed FP-CDNN: fails, or its max position error or drift is at least 10x VP-CDNN's", || {
            let fp = nonempty(select("-robust", "HL-JDF", "FP-CDNN"))?;
            let mut ok = true;
            let mut ev = Vec::new();
            for f in fp {
                let vp = runs.of_experiment(&f.experiment).find(|r| r.solver.starts_with("VP-CDNN")).ok_or("no VP-CDNN run beside it")?;
                let much = |a: Option<f64>, b: Option<f64>| a.zip(b).is_some_and(|(a, b)| a >= MUCH * b);
                ok &= !completed(f) || much(f.max_pos_err, vp.max_pos_err) || much(f.drift_norm, vp.drift_norm);
                ev.push(format!("{}, max position error {} m (VP-CDNN {} m)", peaks(f), f.max_pos_err.map(sci).unwrap_or_default(), vp.max_pos_err.map(sci).unwrap_or_default()));
            }
            Ok((ok, ev.join("; ")))
        }),
        check("perturbed VP-CDNN returns to θ0", "perturbed VP-CDNN: completes with ‖drift‖ < 1e-2 rad", || {
            let rows = nonempty(select("-robust", "HL-JDF", "VP-CDNN"))?;
            Ok((rows.iter().all(|r| returns(r)), rows.iter().map(|r| peaks(r)).collect::<Vec<_>>().join("; ")))
        }),
        check("perturbed VP-CDNN tracks the path", "perturbed VP-CDNN: max position error below 1e-3 m over the whole run", || {
            let rows = nonempty(select("-robust", "HL-JDF", "VP-CDNN"))?;
            let ok = rows.iter().all(|r| r.max_pos_err.is_some_and(|e| e < TRACKING));
            let ev = rows.iter().map(|r| format!("{}: max {} m, final {} m", r.experiment.trim_start_matches("zhang2018-"), r.max_pos_err.map(sci).unwrap_or_default(), r.final_pos_err.map(sci).unwrap_or_default()));
            Ok((ok, ev.collect::<Vec<_>>().join("; ")))
        }),
    ]
}

/// zhong2021's experiments and the compute-time ratio S-LVI-PDNN / VP-RNN-PF the paper reports
/// (about 2x on the clover, 7x on "dai").
const ZHONG: &[(&str, f64)] = &[
    ("zhong2021-clover-a", 2.0),
    ("zhong2021-clover-b", 2.0),
    ("zhong2021-dai", 7.0),
];

/// zhong2021: VP-RNN-PF drifts less, tracks better, and is faster than S-LVI-PDNN.
pub fn zhong2021(runs: &Runs, values: &[PaperValue]) -> Vec<Claim> {
    let mut claims = Vec::new();
    for &(exp, target) in ZHONG {
        let short = exp.trim_start_matches("zhong2021-");
        let split = || -> Result<(Vec<&RunRow>, &RunRow), String> {
            let vp: Vec<&RunRow> = runs
                .of_experiment(exp)
                .filter(|r| r.solver.starts_with("VP-RNN-PF"))
                .collect();
            let s = runs
                .of_experiment(exp)
                .find(|r| r.solver == "S-LVI-PDNN")
                .ok_or(format!("no S-LVI-PDNN run on {exp}"))?;
            if vp.is_empty() {
                return Err(format!("no VP-RNN-PF run on {exp}"));
            }
            Ok((vp, s))
        };
        let compare =
            |what: &str, v: fn(&RunRow) -> Option<f64>| -> Result<(bool, String), String> {
                let (vp, s) = split()?;
                let sv = value(s, v(s), what)?;
                let vps: Vec<(&RunRow, f64)> = vp
                    .iter()
                    .map(|r| value(r, v(r), what).map(|x| (*r, x)))
                    .collect::<Result<_, _>>()?;
                let ev = vps
                    .iter()
                    .map(|(r, x)| format!("{} {}", r.solver, sci(*x)))
                    .collect::<Vec<_>>()
                    .join(", ");
                let exact = runs
                    .find(exp, &s.variant, EXACT)
                    .and_then(v)
                    .map(|e| format!("; exact {}", sci(e)))
                    .unwrap_or_default();
                Ok((
                    vps.iter().all(|(_, x)| *x < sv),
                    format!("{ev}; S-LVI-PDNN {}{exact}", sci(sv)),
                ))
            };
        claims.push(check(
            &format!("{short}: VP-RNN-PF drifts less"),
            &format!("{exp}: every VP-RNN-PF variant's ‖drift‖ below S-LVI-PDNN's"),
            || compare("drift", |r| r.drift_norm),
        ));
        claims.push(check(
            &format!("{short}: VP-RNN-PF tracks better"),
            &format!("{exp}: every VP-RNN-PF variant's max position error below S-LVI-PDNN's"),
            || compare("position error", |r| r.max_pos_err),
        ));
        claims.push(check(
            &format!("{short}: S-LVI-PDNN ~{target}x slower"),
            &format!("{exp}: S-LVI-PDNN's right-hand-side evaluations / mean VP-RNN-PF's (a deterministic cost, the same on every machine) within a factor 2 of {target} (the paper's ~{target}x in MATLAB seconds)"),
            || {
                let ours = evaluation_ratio(runs, exp).ok_or("evaluation counts missing")?;
                let s = slowdown(runs, values, exp);
                let paper = s.paper.map(|p| format!("; paper, MATLAB seconds: {}", sci(p))).unwrap_or_default();
                let timing = s.ours.map(|t| format!("; ours in simulation seconds {} (timing, varies by machine)", sci(t))).unwrap_or_default();
                Ok((ours >= target / 2.0 && ours <= target * 2.0, format!("ours, evaluations: {}{paper}{timing}", sci(ours))))
            },
        ));
    }
    claims
}

const KONG_RETURN: f64 = 1e-4;
const KONG_FINAL_ERR: f64 = 2.4e-4;
const FT: &str = "finite-time (eq. 14)";
const ZN: &str = "ZNN (eq. 22)";
const ON_REF: &str = " [start on theta*0]";
/// kong2019 Fig 9: ‖Wy − v‖ reaches ~2e-4 within 1 s.
const KONG_SETTLE_ERR: f64 = 2e-4;

/// kong2019: finite-time drift vs ZNN drift, return to theta*0, final position error.
pub fn kong2019(runs: &Runs) -> Vec<Claim> {
    let ratio_claim = |exp: &str, suffix: &str| -> Result<(f64, f64, String), String> {
        let ft = runs
            .need(exp, &format!("{FT}{suffix}"), "FTNN")
            .map_err(|e| e.to_string())?;
        let zn = runs
            .need(exp, &format!("{ZN}{suffix}"), "ZNN")
            .map_err(|e| e.to_string())?;
        let (a, b) = (
            value(ft, ft.drift_ref_norm, "drift")?,
            value(zn, zn.drift_ref_norm, "drift")?,
        );
        Ok((
            a,
            b,
            format!(
                "{}: FTNN {}, ZNN {} (ZNN/FTNN {}; exact: {} vs {})",
                exp.trim_start_matches("kong2019-"),
                sci(a),
                sci(b),
                sci(b / a),
                with_exact(runs, ft, |r| r.drift_ref_norm),
                with_exact(runs, zn, |r| r.drift_ref_norm)
            ),
        ))
    };
    let deviated = ["kong2019-circle", "kong2019-triangle"];
    vec![
        check("finite-time drift << ZNN drift (start on θ*0)", "circle, both started on θ*0 (Table 3's setting): ‖θ(T) − θ*0‖ of FTNN at least 10x smaller than ZNN's", || {
            let (a, b, ev) = ratio_claim("kong2019-circle", ON_REF)?;
            Ok((a * MUCH <= b, ev))
        }),
        check("finite-time drift << ZNN drift (deviated start)", "circle and triangle, started 0.5 rad off θ*0 on joint 5: ‖θ(T) − θ*0‖ of FTNN at least 10x smaller than ZNN's", || {
            let all: Vec<(f64, f64, String)> = deviated.iter().map(|e| ratio_claim(e, "")).collect::<Result<_, _>>()?;
            Ok((all.iter().all(|(a, b, _)| a * MUCH <= *b), all.into_iter().map(|(_, _, e)| e).collect::<Vec<_>>().join("; ")))
        }),
        check("joints return to θ*0", "FTNN from the deviated start (circle, triangle): ‖θ(T) − θ*0‖ < 1e-4 rad", || {
            let rows: Vec<&RunRow> = deviated.iter().map(|e| runs.need(e, FT, "FTNN").map_err(|e| e.to_string())).collect::<Result<_, _>>()?;
            let vals: Vec<f64> = rows.iter().map(|r| value(r, r.drift_ref_norm, "drift")).collect::<Result<_, _>>()?;
            let ev = rows.iter().zip(&vals).map(|(r, v)| format!("{}: {} (‖θ(T) − θ(0)‖ {})", r.experiment.trim_start_matches("kong2019-"), sci(*v), r.drift_norm.map(sci).unwrap_or_default()));
            Ok((vals.iter().all(|v| *v < KONG_RETURN), ev.collect::<Vec<_>>().join("; ")))
        }),
        check("final position error < 2.4e-4 m", "every FTNN run: position error at t = T below 2.4e-4 m", || {
            let (r, e) = worst(runs.of_paper("kong2019").filter(|r| r.solver == "FTNN"), |r| r.final_pos_err).ok_or("no FTNN run")?;
            Ok((e < KONG_FINAL_ERR, format!("largest: {} m in {}", sci(e), name(r))))
        }),
        check("‖Wy − v‖ settles to ~2e-4 within 1 s", "every FTNN run on the circle: the network's error norm ‖Wy − v‖ stays below 2x 2e-4 after t = 1 s (Fig 9)", || {
            let rows: Vec<&RunRow> = runs.of_experiment("kong2019-circle").filter(|r| r.solver == "FTNN").collect();
            if rows.is_empty() {
                return Err("no FTNN run on the circle".to_string());
            }
            let vals: Vec<f64> = rows.iter().map(|r| value(r, r.net_error_max_after_1s, "network error")).collect::<Result<_, _>>()?;
            let ev = rows.iter().zip(&vals).map(|(r, v)| format!("{}: max after 1 s {}, at T {}", r.variant, sci(*v), r.net_error_final.map(sci).unwrap_or_default()));
            Ok((vals.iter().all(|v| *v <= 2.0 * KONG_SETTLE_ERR), ev.collect::<Vec<_>>().join("; ")))
        }),
    ]
}

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
