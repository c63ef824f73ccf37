//! Latency percentiles of a run's ticks.

use records::percentile;
use serde::Serialize;

/// p50, p99 and max of a set of durations, in microseconds (the workspace's percentile, `records::percentile`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Latency {
    pub p50_us: f64,
    pub p99_us: f64,
    pub max_us: f64,
}

impl Latency {
    /// The percentiles of `samples_us` (sorted in place); zeros when empty.
    pub fn of(samples_us: &mut [f64]) -> Self {
        if samples_us.is_empty() {
            return Latency::default();
        }
        samples_us.sort_by(f64::total_cmp);
        Latency {
            p50_us: percentile(samples_us, 0.50),
            p99_us: percentile(samples_us, 0.99),
            max_us: samples_us[samples_us.len() - 1],
        }
    }
}
