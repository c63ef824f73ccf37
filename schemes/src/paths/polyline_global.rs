//! Polylines run with one global time law over their arc length (the `star-lines` pentagram).
//!
//! With cumulative arc lengths sigma_k at the points P_k (zero-length segments dropped) and total
//! length L, the arc length travelled is sigma(t) = L s(t), s = phi / 2 pi = sin^2(pi t / (2T)). On
//! segment k (sigma_k <= sigma < sigma_{k+1}), with unit direction u_k = (P_{k+1} - P_k) / L_k:
//! r = P_k + u_k (sigma - sigma_k), rdot = u_k L sdot, rddot = u_k L sddot.
//! The speed L sdot is continuous, but the velocity turns abruptly at every corner (a delta in the
//! acceleration, which is not represented); at a corner instant the outgoing segment is used.
//! Corner k is passed at t = (2T / pi) asin(sqrt(sigma_k / L)).
//!
//! The pentagram: outer vertices V_k = c + R [sin(2 pi k/5), cos(2 pi k/5), 0], k = 0..4, with
//! c = r_start - R [0, 1, 0] so that V_0 = r_start, visited V0 V2 V4 V1 V3 V0.

use super::error::PathError;
use super::stroke::{polyline_segments, RawSegment};
use super::time_law::RestToRest;
use super::{Path, PathPoint};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// One straight piece of a [`GlobalPolyline`].
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    /// Arc length sigma_k at the piece's start.
    arc_start: f64,
    from: Vector3<f64>,
    /// Unit direction u_k.
    direction: Vector3<f64>,
}

/// A polyline travelled with the global sin^2 law over its whole arc length.
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalPolyline {
    law: RestToRest,
    length: f64,
    pieces: Vec<Piece>,
    /// Interior corner arc lengths sigma_1 .. sigma_{n-1}.
    corner_arcs: Vec<f64>,
    /// Interior corner instants.
    corner_times: Vec<f64>,
}

impl GlobalPolyline {
    /// The polyline through `points` in order, run in `duration` seconds.
    ///
    /// Repeated consecutive points are skipped. Errors if `duration` is not positive and finite,
    /// a point is not finite, or all points coincide.
    pub fn new(points: &[Vector3<f64>], duration: f64) -> Result<Self, PathError> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(PathError::NonPositiveDuration(duration));
        }
        let (raw, length) = polyline_segments(points)?;
        let mut pieces = Vec::with_capacity(raw.len());
        let mut arc_start = 0.0;
        for RawSegment {
            from,
            to,
            length: piece_length,
        } in raw
        {
            pieces.push(Piece {
                arc_start,
                from,
                direction: (to - from) / piece_length,
            });
            arc_start += piece_length;
        }
        let corner_arcs: Vec<f64> = pieces[1..].iter().map(|p| p.arc_start).collect();
        let corner_times = corner_arcs
            .iter()
            .map(|&sigma| 2.0 * duration / PI * (sigma / length).sqrt().asin())
            .collect();
        Ok(Self {
            law: RestToRest::new(duration),
            length,
            pieces,
            corner_arcs,
            corner_times,
        })
    }

    /// The straight-line pentagram of circumradius `radius` with its top vertex V_0 at `start`,
    /// tour V0 V2 V4 V1 V3 V0 in the base x-y plane.
    pub fn pentagram(start: Vector3<f64>, radius: f64, duration: f64) -> Result<Self, PathError> {
        let centre = start - Vector3::new(0.0, radius, 0.0);
        let vertex = |k: usize| {
            let (s, c) = (2.0 * PI * k as f64 / 5.0).sin_cos();
            centre + radius * Vector3::new(s, c, 0.0)
        };
        let tour = [start, vertex(2), vertex(4), vertex(1), vertex(3), start];
        Self::new(&tour, duration)
    }

    /// Total arc length L.
    pub fn length(&self) -> f64 {
        self.length
    }
}

impl Path for GlobalPolyline {
    fn duration(&self) -> f64 {
        self.law.duration()
    }

    fn at(&self, t: f64) -> PathPoint {
        let f = self.law.fraction(t).scaled(self.length);
        let piece = &self.pieces[self.corner_arcs.partition_point(|&a| a <= f.s)];
        PathPoint {
            r: piece.from + piece.direction * (f.s - piece.arc_start),
            rdot: piece.direction * f.sdot,
            rddot: piece.direction * f.sddot,
        }
    }

    fn breakpoints(&self) -> &[f64] {
        &self.corner_times
    }
}
