//! Growth exponents and crossovers of the cost against the number of joints
//! (`results/dof-cost.csv`, crate `records`'s `dof_cost`): the power law cost = c N^k fitted to
//! each (scheme, quantity, backend)'s measured medians, and where faer's dense LU overtakes
//! nalgebra's.

use records::dof_cost::{DofCostRow, Measurement, Quantity, RowKind, FAER, NALGEBRA};

/// A least-squares fit of cost = c N^k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerFit {
    /// The growth exponent k.
    pub k: f64,
    /// The factor c (the cost's unit).
    pub c: f64,
    /// Points fitted.
    pub points: usize,
}

/// Fits cost = c N^k to `(N, cost)` points by least squares on the logarithms:
/// with u = ln N and v = ln cost, the line v = ln c + k u minimising sum (v_i - ln c - k u_i)^2
/// has
///
/// ```text
/// k = sum (u_i - u_mean)(v_i - v_mean) / sum (u_i - u_mean)^2,   ln c = v_mean - k u_mean.
/// ```
///
/// So a relative error in each cost weighs the same at every N (the measurements' noise is
/// relative). Points with a non-positive or non-finite N or cost are left out; `None` with fewer
/// than two distinct N left.
pub fn fit_power_law(points: &[(f64, f64)]) -> Option<PowerFit> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, y)| n.is_finite() && y.is_finite() && *n > 0.0 && *y > 0.0)
        .map(|(n, y)| (n.ln(), y.ln()))
        .collect();
    let m = logs.len() as f64;
    let u_mean = logs.iter().map(|p| p.0).sum::<f64>() / m;
    let v_mean = logs.iter().map(|p| p.1).sum::<f64>() / m;
    let suu: f64 = logs.iter().map(|(u, _)| (u - u_mean).powi(2)).sum();
    let suv: f64 = logs.iter().map(|(u, v)| (u - u_mean) * (v - v_mean)).sum();
    if logs.len() < 2 || suu <= 0.0 {
        return None;
    }
    let k = suv / suu;
    Some(PowerFit {
        k,
        c: (v_mean - k * u_mean).exp(),
        points: logs.len(),
    })
}

/// One fit row per (scheme, quantity, backend) of the measured rows among `rows` with at least
/// two distinct N: the exponent of the medians ([`fit_power_law`]), in first-appearance order.
pub fn fit_rows(rows: &[DofCostRow]) -> Vec<DofCostRow> {
    let measured: Vec<&DofCostRow> = rows
        .iter()
        .filter(|r| r.kind == RowKind::Measured)
        .collect();
    let mut keys: Vec<(&str, Quantity, &str)> = Vec::new();
    for r in &measured {
        let key = (r.scheme.as_str(), r.quantity, r.backend.as_str());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .filter_map(|(scheme, quantity, backend)| {
            let members: Vec<&&DofCostRow> = measured
                .iter()
                .filter(|r| r.scheme == scheme && r.quantity == quantity && r.backend == backend)
                .collect();
            let points: Vec<(f64, f64)> = members
                .iter()
                .filter_map(|r| Some((r.n? as f64, r.median_us?)))
                .collect();
            let fit = fit_power_law(&points)?;
            let first = members[0];
            Some(DofCostRow {
                kind: RowKind::Fit,
                n: None,
                nx: None,
                n_eq: None,
                n_in: None,
                median_us: None,
                p95_us: None,
                samples: fit.points,
                exponent: Some(fit.k),
                factor_us: Some(fit.c),
                steps: None,
                rhs_evals: None,
                completed: None,
                ..(*first).clone()
            })
        })
        .collect()
}

/// Where faer's dense LU overtakes nalgebra's for one (scheme, quantity).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossover {
    /// The smallest measured N from which faer's median is below nalgebra's at this and every
    /// larger N measured on both (`None`: faer is slower at the largest N).
    pub n: Option<usize>,
    /// The size of the matrix factorised at that N: nx + n_eq for the KKT floor, the
    /// primal-dual network state nx + n_eq + n_in for the network Jacobian (LVI-PDNN's).
    pub lu_size: Option<usize>,
    /// nalgebra's median over faer's at the largest N measured on both, and that N.
    pub speedup_at_largest: f64,
    pub largest_n: usize,
}

/// The [`Crossover`] of `quantity` for `scheme` among the measured rows: `None` when no N was
/// measured on both backends.
pub fn crossover(rows: &[DofCostRow], scheme: &str, quantity: Quantity) -> Option<Crossover> {
    let median = |backend: &str, n: usize| {
        rows.iter()
            .find(|r| {
                r.kind == RowKind::Measured
                    && r.scheme == scheme
                    && r.quantity == quantity
                    && r.backend == backend
                    && r.n == Some(n)
            })
            .and_then(|r| Some((r.median_us?, r)))
    };
    let mut ns: Vec<usize> = rows
        .iter()
        .filter(|r| r.kind == RowKind::Measured && r.scheme == scheme && r.quantity == quantity)
        .filter_map(|r| r.n)
        .collect();
    ns.sort_unstable();
    ns.dedup();
    // (N, nalgebra / faer, LU size) where both were measured, by increasing N.
    let both: Vec<(usize, f64, Option<usize>)> = ns
        .into_iter()
        .filter_map(|n| {
            let (nalgebra, row) = median(NALGEBRA, n)?;
            let (faer, _) = median(FAER, n)?;
            let kkt = row.nx.zip(row.n_eq).map(|(a, b)| a + b);
            let size = match quantity {
                Quantity::NetworkLu => kkt.zip(row.n_in).map(|(a, c)| a + c),
                _ => kkt,
            };
            Some((n, nalgebra / faer, size))
        })
        .collect();
    let &(largest_n, speedup_at_largest, _) = both.last()?;
    let from = both
        .iter()
        .rposition(|&(_, ratio, _)| ratio <= 1.0)
        .map_or(0, |i| i + 1);
    let first = both.get(from);
    Some(Crossover {
        n: first.map(|c| c.0),
        lu_size: first.and_then(|c| c.2),
        speedup_at_largest,
        largest_n,
    })
}

/// The rows of a measurement: every measured row, then the fits.
pub fn rows(
    measurements: &[Measurement],
    machine: &str,
    cores: usize,
    git_rev: &str,
) -> Vec<DofCostRow> {
    let mut rows: Vec<DofCostRow> = measurements
        .iter()
        .map(|m| DofCostRow::measured(m, machine, cores, git_rev))
        .collect();
    let fits = fit_rows(&rows);
    rows.extend(fits);
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use records::dof_cost::{backends, RunCounts, SchemeKind, Summary};
    use store::dof_cost::{read, write};
    fn measurement(n: usize, quantity: Quantity, median_us: f64) -> Measurement {
        on(NALGEBRA, n, quantity, median_us)
    }

    fn on(backend: &str, n: usize, quantity: Quantity, median_us: f64) -> Measurement {
        Measurement {
            backend: backend.to_string(),
            scheme: SchemeKind::Vltco,
            scheme_name: "VLTCO".into(),
            network: "LVI-PDNN".into(),
            n,
            nx: n + 1,
            n_eq: 3,
            n_in: 2 * n,
            quantity,
            summary: Summary {
                median_us,
                p95_us: 1.25 * median_us,
                samples: 150,
            },
            run: quantity.is_run().then_some(RunCounts {
                steps: 100 * n,
                rhs_evals: 700 * n,
                completed: true,
            }),
        }
    }

    #[test]
    fn the_csv_round_trips_with_its_fits() {
        let mut ms = Vec::new();
        for n in [3, 6, 12, 30] {
            ms.push(measurement(
                n,
                Quantity::ExactClarabel,
                2.0 * (n * n) as f64,
            ));
            ms.push(measurement(n, Quantity::RunExact, 1e3 * n as f64));
        }
        let rows = rows(&ms, "Test CPU @ 1 GHz", 2, "abc123");
        assert_eq!(rows.len(), 8 + 2);
        let fit = rows
            .iter()
            .find(|r| r.is_fit() && r.quantity == Quantity::ExactClarabel)
            .unwrap();
        assert!((fit.exponent.unwrap() - 2.0).abs() < 1e-12, "{fit:?}");
        assert_eq!((fit.samples, fit.n, fit.median_us), (4, None, None));
        let run = rows
            .iter()
            .find(|r| r.quantity == Quantity::RunExact)
            .unwrap();
        assert_eq!((run.steps, run.completed), (Some(300), Some(true)));

        let bytes = records::table::to_csv(&rows).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        assert!(
            text.starts_with("scheme,scheme_name,network,quantity,backend,kind,n,"),
            "{text}"
        );
        let back: Vec<DofCostRow> = records::table::from_reader(bytes.as_slice()).unwrap();
        assert_eq!(back, rows);

        let dir = inputs::Scratch::dir("dof-cost");
        assert!(read(&dir).unwrap().is_empty());
        write(&dir, &rows).unwrap();
        assert_eq!(read(&dir).unwrap(), rows);
    }

    #[test]
    fn each_backend_gets_its_own_fit_and_rows_round_trip() {
        let mut ms = Vec::new();
        for n in [3, 30, 100, 200] {
            let n3 = (n * n * n) as f64;
            ms.push(on(NALGEBRA, n, Quantity::KktFloor, 0.01 * n3));
            ms.push(on(FAER, n, Quantity::KktFloor, 5.0 * (n * n) as f64));
        }
        let rows = rows(&ms, "Test CPU", 2, "abc123");
        let fit = |backend: &str| {
            rows.iter()
                .find(|r| r.is_fit() && r.backend == backend)
                .and_then(|r| r.exponent)
                .unwrap()
        };
        assert!((fit("nalgebra") - 3.0).abs() < 1e-12);
        assert!((fit("faer") - 2.0).abs() < 1e-12);
        let back: Vec<DofCostRow> =
            records::table::from_reader(records::table::to_csv(&rows).unwrap().as_slice()).unwrap();
        assert_eq!(back, rows);
        assert_eq!(back.iter().filter(|r| r.backend == "faer").count(), 4 + 1);
        assert_eq!(backends(&rows, Quantity::KktFloor), [NALGEBRA, FAER]);
        assert_eq!(
            backends(rows.iter().rev(), Quantity::KktFloor),
            [NALGEBRA, FAER]
        );
        assert!(backends(&rows, Quantity::NetworkRhs).is_empty());
    }

    #[test]
    fn the_fit_recovers_an_exact_power_law() {
        let sizes = [3.0, 5.0, 7.0, 30.0, 100.0, 200.0];
        let points: Vec<(f64, f64)> = sizes.iter().map(|&n| (n, 3.0 * n * n)).collect();
        let fit = fit_power_law(&points).unwrap();
        assert!((fit.k - 2.0).abs() < 1e-12, "{fit:?}");
        assert!((fit.c - 3.0).abs() < 1e-10, "{fit:?}");
        assert_eq!(fit.points, sizes.len());
        // With a deterministic relative noise of up to +-10 %: within 0.1 of the exponent.
        let noisy: Vec<(f64, f64)> = sizes
            .iter()
            .enumerate()
            .map(|(i, &n)| (n, 0.5 * n.powf(1.5) * (1.0 + 0.1 * (i as f64 * 2.3).sin())))
            .collect();
        assert!((fit_power_law(&noisy).unwrap().k - 1.5).abs() < 0.1);
    }

    #[test]
    fn the_fit_needs_two_distinct_positive_points() {
        assert!(fit_power_law(&[]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (3.0, 2.0)]).is_none());
        assert!(fit_power_law(&[(3.0, 1.0), (6.0, 0.0), (f64::NAN, 1.0)]).is_none());
        let fit = fit_power_law(&[(3.0, 1.0), (6.0, 2.0), (9.0, -1.0)]).unwrap();
        assert_eq!(fit.points, 2);
        assert!((fit.k - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_crossover_is_where_faer_stays_ahead() {
        // faer slower at 3 and 10, ahead at 30, behind at 50 (noise), ahead from 100 on.
        let mut ms = Vec::new();
        for (n, nalgebra, faer) in [
            (3, 1.0, 2.0),
            (10, 3.0, 4.0),
            (30, 9.0, 8.0),
            (50, 20.0, 21.0),
            (100, 90.0, 30.0),
            (200, 700.0, 100.0),
        ] {
            ms.push(on(NALGEBRA, n, Quantity::KktFloor, nalgebra));
            ms.push(on(FAER, n, Quantity::KktFloor, faer));
        }
        let rows = rows(&ms, "Test CPU", 2, "abc123");
        let c = crossover(&rows, "vltco", Quantity::KktFloor).unwrap();
        assert_eq!((c.n, c.lu_size, c.largest_n), (Some(100), Some(104), 200));
        assert!((c.speedup_at_largest - 7.0).abs() < 1e-12);
        assert!(crossover(&rows, "vltco", Quantity::NetworkLu).is_none());
        let slower: Vec<_> = ms.iter().filter(|m| m.n < 30).cloned().collect();
        let c = crossover(
            &super::rows(&slower, "Test CPU", 2, "abc"),
            "vltco",
            Quantity::KktFloor,
        );
        assert_eq!(c.map(|c| c.n), Some(None));
    }
}
