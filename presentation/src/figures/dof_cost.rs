//! The cost against the number of joints of one scheme (`results/dof-cost.csv`): the median
//! cost of each per-call quantity (top) and of each whole run (bottom) against N, both axes
//! logarithmic, so a power law c N^k is a straight line of slope k; the legend gives each
//! quantity's fitted k. The dense LU quantities are drawn once per backend: nalgebra in the
//! quantity's colour, faer in the light shade of the same hue.

use super::layout::{Area, Body, Figure};
use super::legend::{self, Arrangement, Entry};
use super::panels::{LogLogPanel, Series};
use super::style::{colour, light, LEGEND_LINE_WIDTH};
use crate::error::FigureError;
use plotters::prelude::*;
use records::dof_cost::DofCostRow;
use records::dof_cost::Quantity;

/// Width of the legend column on the right (px).
const LEGEND_WIDTH: u32 = 360;

/// File name of a scheme's figure inside `report/figures/`.
pub fn file_name(scheme: &str) -> String {
    format!("dof-cost__{scheme}.svg")
}

/// A quantity as the report and the figure name it (`network` is the network's name).
pub fn quantity_label(quantity: Quantity, network: &str) -> String {
    match quantity {
        Quantity::SchemeBuild => "scheme build (QP assembly)".to_string(),
        Quantity::NetworkRhs => format!("{network} RHS"),
        Quantity::NetworkJacobian => format!("{network} Jacobian"),
        Quantity::NetworkLu => format!("{network} Jacobian's LU"),
        Quantity::ExactActiveSet => "exact: active set, hot-started".to_string(),
        Quantity::ExactClarabel => "exact: Clarabel".to_string(),
        Quantity::KktFloor => "dense KKT floor (one LU)".to_string(),
        Quantity::RunExact => "whole run, exact column".to_string(),
        Quantity::RunNetwork => format!("whole run, {network}"),
    }
}

/// What the figure draws under its title: the two panels on the left, the legend on the right.
pub struct DofCostBody {
    entries: Vec<Entry>,
    calls: LogLogPanel,
    runs: LogLogPanel,
}

impl Body for DofCostBody {
    fn draw<DB: DrawingBackend>(&self, area: &Area<DB>) -> Result<(), FigureError> {
        let (width, _) = area.dim_in_pixel();
        let (plots, legend_area) = area.split_horizontally(width.saturating_sub(LEGEND_WIDTH));
        legend::draw(&legend_area, &self.entries, Arrangement::Column)?;
        let (top, bottom) = plots.split_vertically(plots.dim_in_pixel().1 * 3 / 5);
        self.calls.draw(&top)?;
        self.runs.draw(&bottom)
    }
}

/// The figure of one scheme; `rows` are that scheme's rows of `dof-cost.csv` (measured and
/// fitted). Quantity k (in [`Quantity::ALL`] order) is drawn in colour k on nalgebra and in
/// its light shade (`style::light`) on faer.
pub fn figure(scheme: &str, rows: &[&DofCostRow]) -> Figure<DofCostBody> {
    let mut entries = Vec::new();
    let mut calls = Vec::new();
    let mut runs = Vec::new();
    for (k, quantity) in Quantity::ALL.into_iter().enumerate() {
        let backends = records::dof_cost::backends(rows.iter().copied(), quantity);
        for (b, backend) in backends.iter().enumerate() {
            let of_series = |r: &&&DofCostRow| r.quantity == quantity && r.backend == *backend;
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| !r.is_fit() && of_series(r))
                .filter_map(|r| Some((r.n? as f64, r.median_us?)))
                .collect();
            if points.is_empty() {
                continue;
            }
            let network = rows
                .iter()
                .find(of_series)
                .map_or("", |r| r.network.as_str());
            let exponent = rows
                .iter()
                .find(|r| r.is_fit() && of_series(r))
                .and_then(|r| r.exponent)
                .map_or(String::new(), |e| format!(" (k = {e:.2})"));
            let on = match backends[..] {
                [_] => String::new(),
                _ => format!(", {backend}"),
            };
            let colour = if b == 0 { colour(k) } else { light(colour(k)) };
            entries.push(Entry {
                style: colour.stroke_width(LEGEND_LINE_WIDTH),
                label: format!("{}{on}{exponent}", quantity_label(quantity, network)),
            });
            let series = Series { colour, points };
            if quantity.is_run() {
                runs.push(series);
            } else {
                calls.push(series);
            }
        }
    }
    let scheme_name = rows.first().map_or("", |r| r.scheme_name.as_str());
    Figure {
        title: format!(
            "{scheme} {scheme_name} on nlink-N: median cost against the number of joints"
        ),
        body: DofCostBody {
            entries,
            calls: LogLogPanel {
                caption: "(a) one call at the sampled states".to_string(),
                x_desc: "joints N".to_string(),
                y_desc: "median per call (us)".to_string(),
                series: calls,
                marks: false,
            },
            runs: LogLogPanel {
                caption: "(b) one whole run".to_string(),
                x_desc: "joints N".to_string(),
                y_desc: "median per run (us)".to_string(),
                series: runs,
                marks: false,
            },
        },
    }
}
