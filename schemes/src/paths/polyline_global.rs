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
//!
//! **Phase** ([`shift_closed_loop`]). A phase p in [0, 1) starts the closed tour at arc length
//! sigma0 = p L instead of at P_0: with Q the tour's point at sigma0 (on segment k), the tour
//! Q P_{k+1} ... P_n (= P_0) P_1 ... P_k Q is translated by P_0 - Q so that it still starts and
//! ends at r_start, and is then run with the one global law as above. The same figure is drawn
//! from another of its points; P_0 becomes an interior corner and Q, where the tour now joins,
//! is passed at rest.

use super::stroke::{polyline_segments, RawSegment};
use super::time_law::RestToRest;
use super::{Path, PathPoint};
use nalgebra::Vector3;
use spec::PathError;
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
        Self::new(&pentagram_tour(start, radius), duration)
    }

    /// [`GlobalPolyline::pentagram`] started a fraction `phase` of its arc length further along
    /// the tour (see [`shift_closed_loop`]), still starting and ending at `start`. `phase` = 0
    /// gives the unshifted pentagram.
    pub fn pentagram_with_phase(
        start: Vector3<f64>,
        radius: f64,
        duration: f64,
        phase: f64,
    ) -> Result<Self, PathError> {
        Self::new(
            &shift_closed_loop(&pentagram_tour(start, radius), phase)?,
            duration,
        )
    }

    /// Total arc length L.
    pub fn length(&self) -> f64 {
        self.length
    }
}

/// The pentagram tour V0 V2 V4 V1 V3 V0 with V0 = `start`.
fn pentagram_tour(start: Vector3<f64>, radius: f64) -> [Vector3<f64>; 6] {
    let centre = start - Vector3::new(0.0, radius, 0.0);
    let vertex = |k: usize| {
        let (s, c) = (2.0 * PI * k as f64 / 5.0).sin_cos();
        centre + radius * Vector3::new(s, c, 0.0)
    };
    [start, vertex(2), vertex(4), vertex(1), vertex(3), start]
}

/// The closed tour `points` (first = last) started at arc length `phase` L instead of at its
/// first point, translated so that it still starts and ends at `points[0]` (module docs).
///
/// Errors if `phase` is not in [0, 1), the tour is not closed, a point is not finite or the
/// tour has no length.
pub fn shift_closed_loop(
    points: &[Vector3<f64>],
    phase: f64,
) -> Result<Vec<Vector3<f64>>, PathError> {
    if !(0.0..1.0).contains(&phase) {
        return Err(PathError::PhaseOutOfRange(phase));
    }
    if points.iter().any(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(PathError::NonFinitePoint);
    }
    let (first, last) = match (points.first(), points.last()) {
        (Some(&f), Some(&l)) => (f, l),
        _ => return Err(PathError::DegeneratePolyline),
    };
    if first != last {
        return Err(PathError::PhaseNotSupported("an open polyline".into()));
    }
    let total: f64 = points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    if total.is_nan() || total <= 0.0 {
        return Err(PathError::DegeneratePolyline);
    }
    let sigma0 = phase * total;
    // Segment k holding sigma0 (the last one if rounding runs past the end).
    let mut k = points.len() - 2;
    let mut q = last;
    let mut arc = 0.0;
    for (i, w) in points.windows(2).enumerate() {
        let len = (w[1] - w[0]).norm();
        if arc + len > sigma0 && len > 0.0 {
            k = i;
            q = w[0] + (w[1] - w[0]) * ((sigma0 - arc) / len);
            break;
        }
        arc += len;
    }
    let shift = first - q;
    let mut tour = Vec::with_capacity(points.len() + 2);
    tour.push(q);
    tour.extend(&points[k + 1..]);
    tour.extend(&points[1..=k]);
    tour.push(q);
    for p in &mut tour {
        *p += shift;
    }
    // The ends are the start point exactly (not up to the rounding of q + (first - q)).
    let n = tour.len();
    tour[0] = first;
    tour[n - 1] = first;
    Ok(tour)
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
