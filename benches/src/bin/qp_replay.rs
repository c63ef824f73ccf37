//! Replays recorded QPs to the suite's active set (`records::qp_replay` says what and why):
//! `qp_replay QPS_FILE OUT_DIR [REPEATS]` reads the QPs `benches/qp_replay/record.py` wrote,
//! solves the whole sequence `REPEATS` times (default 20) warm (each solve hot-started from the
//! previous QP's working set) and cold (an empty working set), every answer certified, and
//! writes `OUT_DIR/suite-x.txt` (one line per QP: the answer x) and `OUT_DIR/suite-times.csv`
//! (start, mean and 95th percentile over the QPs of each QP's median microseconds).
//!
//! The QP file holds, per QP, a line `qp nx n_eq n_in` and then one line per field, the field
//! name first: `P` (row-major), `q`, `A` (row-major), `b`, `G` (row-major), `h`, `lower`,
//! `upper` (`inf` and `-inf` for absent bounds), as `qp::Qp` states the problem.

use nalgebra::{DMatrix, DVector};
use qp::Qp;
use solvers::{ActiveSetSolution, ActiveSetSolver, WorkingSet};
use std::io::Write;
use std::time::Instant;

fn fail(msg: impl std::fmt::Display) -> ! {
    eprintln!("qp_replay: {msg}");
    std::process::exit(2)
}

/// The QPs of `text` (module docs).
fn parse(text: &str) -> Vec<Qp> {
    let mut lines = text.lines().enumerate();
    let mut qps = Vec::new();
    while let Some((i, head)) = lines.next() {
        let sizes: Vec<usize> = head
            .strip_prefix("qp ")
            .unwrap_or_else(|| fail(format!("line {}: expected `qp nx n_eq n_in`", i + 1)))
            .split_whitespace()
            .map(|s| {
                s.parse()
                    .unwrap_or_else(|_| fail(format!("line {}: a size", i + 1)))
            })
            .collect();
        let [nx, ne, ni] = sizes[..] else {
            fail(format!("line {}: three sizes", i + 1))
        };
        let mut field = |name: &str, len: usize| -> Vec<f64> {
            let (j, line) = lines
                .next()
                .unwrap_or_else(|| fail(format!("the file ends before field {name}")));
            let mut words = line.split_whitespace();
            if words.next() != Some(name) {
                fail(format!("line {}: expected field {name}", j + 1));
            }
            let v: Vec<f64> = words
                .map(|w| {
                    w.parse()
                        .unwrap_or_else(|_| fail(format!("line {}: {w}", j + 1)))
                })
                .collect();
            if v.len() != len {
                fail(format!(
                    "line {}: {name} has {} numbers, not {len}",
                    j + 1,
                    v.len()
                ));
            }
            v
        };
        let p = DMatrix::from_row_slice(nx, nx, &field("P", nx * nx));
        let q = DVector::from_vec(field("q", nx));
        let a = DMatrix::from_row_slice(ne, nx, &field("A", ne * nx));
        let b = DVector::from_vec(field("b", ne));
        let g = DMatrix::from_row_slice(ni, nx, &field("G", ni * nx));
        let h = DVector::from_vec(field("h", ni));
        let lower = DVector::from_vec(field("lower", nx));
        let upper = DVector::from_vec(field("upper", nx));
        qps.push(Qp {
            p,
            q,
            a,
            b,
            g,
            h,
            lower,
            upper,
        });
    }
    qps
}

/// The mean and the 95th percentile of `medians` (microseconds).
fn summary(medians: &mut [f64]) -> (f64, f64) {
    let mean = medians.iter().sum::<f64>() / medians.len() as f64;
    medians.sort_by(f64::total_cmp);
    let p95 = medians[((medians.len() - 1) as f64 * 0.95).round() as usize];
    (mean, p95)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(file), Some(out)) = (args.get(1), args.get(2)) else {
        fail("usage: qp_replay QPS_FILE OUT_DIR [REPEATS]")
    };
    let repeats: usize = args.get(3).map_or(20, |r| {
        r.parse().unwrap_or_else(|_| fail("REPEATS is a count"))
    });
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| fail(format!("{file}: {e}")));
    let qps = parse(&text);
    if qps.is_empty() {
        fail(format!("{file}: no QP"));
    }
    let max = qps
        .iter()
        .map(Qp::dims)
        .max_by_key(|d| d.nx + d.n_eq + d.n_in)
        .unwrap();
    let mut solver = ActiveSetSolver::new(max);
    let mut sol = ActiveSetSolution::zeros(qps[0].dims());
    let mut prev = WorkingSet::with_capacity(max.nx + max.n_in);
    let per_qp = || vec![Vec::with_capacity(repeats); qps.len()];
    let mut times: [Vec<Vec<f64>>; 2] = [per_qp(), per_qp()];
    let mut answers: Vec<DVector<f64>> = Vec::with_capacity(qps.len());
    for rep in 0..repeats {
        for (start, warm) in [(0, true), (1, false)] {
            prev.clear();
            for (k, qp) in qps.iter().enumerate() {
                let from = (warm && k > 0).then_some(&prev);
                let t0 = Instant::now();
                solver
                    .solve_into(qp, from, &mut sol)
                    .unwrap_or_else(|e| fail(format!("QP {k}: {e}")));
                times[start][k].push(t0.elapsed().as_secs_f64() * 1e6);
                prev.clone_from(&sol.working_set);
                if rep == 0 && start == 0 {
                    answers.push(sol.x.clone());
                }
            }
        }
    }
    std::fs::create_dir_all(out).unwrap_or_else(|e| fail(format!("{out}: {e}")));
    let mut x = std::fs::File::create(format!("{out}/suite-x.txt")).unwrap_or_else(|e| fail(e));
    for a in &answers {
        let line: Vec<String> = a.iter().map(|v| format!("{v:e}")).collect();
        writeln!(x, "{}", line.join(" ")).unwrap_or_else(|e| fail(e));
    }
    let mut csv = String::from("start,mean_us,p95_us,qps,repeats\n");
    for (start, name) in [(0, "warm"), (1, "cold")] {
        let mut medians: Vec<f64> = times[start]
            .iter_mut()
            .map(|t| {
                t.sort_by(f64::total_cmp);
                t[t.len() / 2]
            })
            .collect();
        let (mean, p95) = summary(&mut medians);
        csv.push_str(&format!("{name},{mean},{p95},{},{repeats}\n", qps.len()));
    }
    std::fs::write(format!("{out}/suite-times.csv"), csv).unwrap_or_else(|e| fail(e));
    eprintln!("replayed {} QPs x {repeats} to the active set", qps.len());
}
