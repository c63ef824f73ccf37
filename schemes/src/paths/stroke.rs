//! Stroke paths: polylines with a rest-to-rest move on every segment.
//!
//! For points P_0 .. P_n (zero-length segments dropped) with lengths L_k = |P_{k+1} - P_k|,
//! segment k lasts Delta_k = T L_k / sum(L) and starts at t_k = sum_{j<k} Delta_j. On it
//! r(t) = P_k + (P_{k+1} - P_k) s_k(t - t_k) with s_k(tau) = sin^2(pi tau / (2 Delta_k)), so
//! rdot = (P_{k+1} - P_k) sdot_k and rddot = (P_{k+1} - P_k) sddot_k. Every segment reaches the same
//! peak speed (pi / 2) sum(L) / T at its middle, the velocity is zero (hence continuous) at every
//! corner, and the acceleration jumps there from -(pi^2 / 2 Delta_k^2)(P_{k+1} - P_k) to
//! +(pi^2 / 2 Delta_{k+1}^2)(P_{k+2} - P_{k+1}). At a corner instant the outgoing segment is used.

use super::time_law::RestToRest;
use super::{Path, PathPoint};
use nalgebra::Vector3;
use spec::PathError;

/// Relative length below which a segment counts as zero-length (a repeated point) and is dropped.
pub(crate) const ZERO_LENGTH: f64 = 1e-12;

/// A straight polyline segment of positive length.
pub(crate) struct RawSegment {
    pub(crate) from: Vector3<f64>,
    pub(crate) to: Vector3<f64>,
    pub(crate) length: f64,
}

/// The non-degenerate segments of a polyline, with their total length.
///
/// Segments shorter than [`ZERO_LENGTH`] times the total length are skipped; the next segment
/// then starts where the skipped one started, so the polyline stays connected.
pub(crate) fn polyline_segments(
    points: &[Vector3<f64>],
) -> Result<(Vec<RawSegment>, f64), PathError> {
    if points.iter().any(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(PathError::NonFinitePoint);
    }
    let raw_total: f64 = points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    if raw_total.is_nan() || raw_total <= 0.0 {
        return Err(PathError::DegeneratePolyline);
    }
    let mut segments = Vec::with_capacity(points.len().saturating_sub(1));
    let mut from = points[0];
    for &to in &points[1..] {
        let length = (to - from).norm();
        if length > ZERO_LENGTH * raw_total {
            segments.push(RawSegment { from, to, length });
            from = to;
        }
    }
    let total = segments.iter().map(|s| s.length).sum();
    Ok((segments, total))
}

/// One rest-to-rest segment of a [`StrokePath`].
#[derive(Clone, Debug, PartialEq)]
pub struct StrokeSegment {
    /// Start time t_k.
    pub start_time: f64,
    /// Segment point P_k.
    pub from: Vector3<f64>,
    /// Segment point P_{k+1}.
    pub to: Vector3<f64>,
    /// Length L_k = |P_{k+1} - P_k| > 0.
    pub length: f64,
    /// The sin^2 law over Delta_k.
    law: RestToRest,
}

impl StrokeSegment {
    /// Duration Delta_k.
    pub fn duration(&self) -> f64 {
        self.law.duration()
    }
}

/// A polyline drawn stroke by stroke, resting at every corner.
#[derive(Clone, Debug, PartialEq)]
pub struct StrokePath {
    duration: f64,
    segments: Vec<StrokeSegment>,
    /// Interior corner instants t_1 .. t_{n-1}.
    corners: Vec<f64>,
}

impl StrokePath {
    /// The polyline through `points` in order, drawn in `duration` seconds.
    ///
    /// Repeated consecutive points are skipped. Errors if `duration` is not positive and finite,
    /// a point is not finite, or all points coincide.
    pub fn new(points: &[Vector3<f64>], duration: f64) -> Result<Self, PathError> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(PathError::NonPositiveDuration(duration));
        }
        let (raw, total) = polyline_segments(points)?;
        let mut segments = Vec::with_capacity(raw.len());
        let mut start_time = 0.0;
        for RawSegment { from, to, length } in raw {
            let delta = duration * length / total;
            segments.push(StrokeSegment {
                start_time,
                from,
                to,
                length,
                law: RestToRest::new(delta),
            });
            start_time += delta;
        }
        // The last segment ends at T exactly (the running sum may be off by rounding).
        let last = segments
            .last_mut()
            .expect("polyline_segments returns at least one segment");
        last.law = RestToRest::new(duration - last.start_time);
        let corners = segments[1..].iter().map(|s| s.start_time).collect();
        Ok(Self {
            duration,
            segments,
            corners,
        })
    }

    /// The kong2019 eq. (21) triangle with side `side`: (0,0) -> (side/2, side sqrt3/2) -> (side, 0)
    /// -> (0,0) in the base x-y plane relative to `start`; equal sides, so T/3 per side.
    pub fn triangle(start: Vector3<f64>, side: f64, duration: f64) -> Result<Self, PathError> {
        let apex = Vector3::new(0.5 * side, 0.5 * 3f64.sqrt() * side, 0.0);
        let right = Vector3::new(side, 0.0, 0.0);
        Self::new(&[start, start + apex, start + right, start], duration)
    }

    /// The segments in drawing order.
    pub fn segments(&self) -> &[StrokeSegment] {
        &self.segments
    }
}

impl Path for StrokePath {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn at(&self, t: f64) -> PathPoint {
        // The segment with the largest start time <= t (the first one for t < 0).
        let k = self.corners.partition_point(|&c| c <= t);
        let seg = &self.segments[k];
        let f = seg.law.fraction(t - seg.start_time);
        let d = seg.to - seg.from;
        PathPoint {
            r: seg.from + d * f.s,
            rdot: d * f.sdot,
            rddot: d * f.sddot,
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.corners
    }
}
