//! The search behind the setup inference, independent of what one evaluation computes.
//!
//! # The problem
//!
//! Minimise objectives f_t(k, x) over a finite set of discrete combinations k = 0 .. K-1 and a
//! box of continuous coordinates x (each periodic or bounded). There is one joint objective
//! (t = joint: the whole table) and one per column (t = c: that column alone); one evaluation
//! at (k, x) yields all of them at once, so every evaluation informs every objective.
//!
//! # The stages
//!
//! 1. **Global:** every combination at G points of one Halton sequence over the box, the
//!    sequence dealt out in turn to the combinations (so the K G points all differ and
//!    cover the box K times more finely than G points would), plus the declared point.
//! 2. **Local:** Nelder-Mead (argmin) over x, k fixed, from the best few global points of each
//!    objective (distinct: another combination, or at least [`DISTINCT`] apart in the box's
//!    unit coordinates).
//! 3. **Profiles** of the joint optimum (k*, x*): for each coordinate j a grid of values v
//!    (with x*_j among them); at each v,
//!    p_j(v) = min over x_{-j} of f_joint(k*, x with x_j = v),
//!    by Nelder-Mead over the other coordinates, warm-started from the neighbouring grid
//!    point's optimum, walking outward from x*_j (the construction of a profile likelihood).
//!    With no iterations allowed, p_j is a slice (the others held at x*), and is labelled so.
//! 4. **Polish:** if a profile point beat (k*, x*), Nelder-Mead from it once more (so the
//!    profiles are those of (k*, x*), and the optimum reported may lie below them).
//!
//! Every evaluation of every stage passes through one `Tracker`, which keeps, per
//! combination and objective, the best point seen: the reported optimum of an objective is
//! the minimum over all evaluations, never only a stage's end point.

use argmin::core::{CostFunction, Error as ArgminError, Executor};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Two global points count as distinct starts when they are this far apart (Euclidean, in
/// the box's unit coordinates, periodic ones wrapped) or in different combinations.
pub const DISTINCT: f64 = 0.2;

/// One continuous coordinate of the search box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinate {
    pub name: &'static str,
    pub lo: f64,
    pub hi: f64,
    /// Periodic (hi is lo again) or bounded (values are clamped into [lo, hi]).
    pub periodic: bool,
    /// Grid points of its profile.
    pub grid: usize,
}

impl Coordinate {
    /// `x` in the box: wrapped if periodic, clamped if bounded.
    pub fn wrap(&self, x: f64) -> f64 {
        if self.periodic {
            self.lo + (x - self.lo).rem_euclid(self.hi - self.lo)
        } else {
            x.clamp(self.lo, self.hi)
        }
    }

    fn width(&self) -> f64 {
        self.hi - self.lo
    }

    /// The profile grid: evenly spaced, both ends included if bounded, hi left out if
    /// periodic (it is lo).
    pub fn grid_values(&self) -> Vec<f64> {
        let n = self.grid.max(2);
        let den = if self.periodic { n } else { n - 1 } as f64;
        (0..n)
            .map(|k| self.lo + self.width() * k as f64 / den)
            .collect()
    }

    /// Distance of two values in units of the box width (periodic ones the short way round).
    fn unit_distance(&self, a: f64, b: f64) -> f64 {
        let d = ((a - b) / self.width()).abs();
        if self.periodic {
            d.rem_euclid(1.0).min(1.0 - d.rem_euclid(1.0))
        } else {
            d
        }
    }
}

/// A point of the search: a discrete combination and the continuous coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub combo: usize,
    pub x: Vec<f64>,
}

/// Which objective.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The whole table.
    Joint,
    /// One column alone.
    Column(usize),
}

/// The objectives at one point.
#[derive(Clone, Debug, PartialEq)]
pub struct Scores {
    pub joint: f64,
    pub columns: Vec<f64>,
}

impl Scores {
    pub fn get(&self, t: Target) -> f64 {
        match t {
            Target::Joint => self.joint,
            Target::Column(c) => self.columns[c],
        }
    }
}

/// What is searched: the combinations, the box, and one evaluation.
pub trait Objective: Sync {
    /// What an evaluation yields besides its scores (kept for the best points).
    type Detail: Clone + Send;
    fn combos(&self) -> usize;
    fn coordinates(&self) -> &[Coordinate];
    fn columns(&self) -> usize;
    /// The declared point (evaluated first, reported beside the optimum).
    fn declared(&self) -> Point;
    /// Evaluates a point whose coordinates are in the box.
    fn evaluate(&self, p: &Point) -> (Scores, Self::Detail);
}

/// The best point of one objective (within one combination).
#[derive(Clone, Debug)]
pub struct Best<D> {
    pub point: Point,
    pub scores: Scores,
    pub detail: D,
}

/// Per combination and objective (index 0 joint, 1 + c column c), the best point evaluated.
struct Tracker<D> {
    best: Vec<Vec<Option<Best<D>>>>,
}

impl<D: Clone> Tracker<D> {
    fn record(&mut self, p: &Point, s: &Scores, d: &D) {
        let slots = &mut self.best[p.combo];
        let targets =
            std::iter::once(Target::Joint).chain((0..s.columns.len()).map(Target::Column));
        for (slot, t) in slots.iter_mut().zip(targets) {
            if slot.as_ref().is_none_or(|b| s.get(t) < b.scores.get(t)) {
                *slot = Some(Best {
                    point: p.clone(),
                    scores: s.clone(),
                    detail: d.clone(),
                });
            }
        }
    }
}

/// Budget of one search.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Global points per combination.
    pub global_per_combo: usize,
    /// Nelder-Mead starts for the joint objective.
    pub joint_starts: usize,
    /// Nelder-Mead starts per column objective (0: columns only from the evaluations the
    /// other stages make).
    pub column_starts: usize,
    /// Nelder-Mead iterations per start.
    pub iterations: u64,
    /// Profiles of the joint optimum.
    pub profiles: bool,
    /// Nelder-Mead iterations per profile point (0: slices).
    pub profile_iterations: u64,
}

/// One point of a profile.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfilePoint {
    /// The profiled coordinate's value.
    pub value: f64,
    /// The point reached (the other coordinates re-fitted, or held for a slice).
    pub point: Point,
    pub scores: Scores,
}

/// The profile of one coordinate, ordered by value.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    pub coordinate: usize,
    /// The others re-fitted at each point (false: a slice).
    pub refitted: bool,
    pub points: Vec<ProfilePoint>,
}

/// A local search's end.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalOptimum {
    pub target: Target,
    pub point: Point,
    pub scores: Scores,
}

/// What a search finds.
#[derive(Clone, Debug)]
pub struct Outcome<D> {
    pub declared: Best<D>,
    /// Per combination, per objective (0 joint, 1 + c column c): the best evaluated.
    pub best: Vec<Vec<Option<Best<D>>>>,
    pub local: Vec<LocalOptimum>,
    pub profiles: Vec<Profile>,
    pub evaluations: usize,
}

fn slot(t: Target) -> usize {
    match t {
        Target::Joint => 0,
        Target::Column(c) => 1 + c,
    }
}

impl<D> Outcome<D> {
    /// The best evaluated point of objective `t` over the combinations `keep` admits.
    pub fn best_where(&self, t: Target, keep: impl Fn(usize) -> bool) -> Option<&Best<D>> {
        self.best
            .iter()
            .enumerate()
            .filter(|(k, _)| keep(*k))
            .filter_map(|(_, b)| b[slot(t)].as_ref())
            .min_by(|a, b| a.scores.get(t).total_cmp(&b.scores.get(t)))
    }

    /// The best evaluated point of objective `t` (every search evaluates the declared point).
    pub fn best(&self, t: Target) -> &Best<D> {
        self.best_where(t, |_| true)
            .expect("the declared point is always evaluated")
    }
}

/// A search in progress: the objective, the tracker and the evaluation count.
struct Search<'a, O: Objective> {
    objective: &'a O,
    tracker: Mutex<Tracker<O::Detail>>,
    evaluations: AtomicUsize,
}

impl<O: Objective> Search<'_, O> {
    fn wrap(&self, combo: usize, x: &[f64]) -> Point {
        Point {
            combo,
            x: self
                .objective
                .coordinates()
                .iter()
                .zip(x)
                .map(|(c, v)| c.wrap(*v))
                .collect(),
        }
    }

    /// Evaluates (coordinates wrapped into the box) and records.
    fn eval(&self, combo: usize, x: &[f64]) -> (Point, Scores, O::Detail) {
        let p = self.wrap(combo, x);
        let (s, d) = self.objective.evaluate(&p);
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        self.tracker
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .record(&p, &s, &d);
        (p, s, d)
    }

    /// The best point of the joint objective evaluated so far.
    fn joint_best(&self) -> (Point, Scores) {
        let tracker = self.tracker.lock().unwrap_or_else(|e| e.into_inner());
        tracker
            .best
            .iter()
            .filter_map(|b| b[0].as_ref())
            .min_by(|a, b| a.scores.joint.total_cmp(&b.scores.joint))
            .map(|b| (b.point.clone(), b.scores.clone()))
            .expect("the declared point is recorded")
    }

    /// Nelder-Mead on objective `target` over the coordinates `free` from `start` (the other
    /// coordinates held); returns the best point it evaluated.
    fn nelder_mead(
        &self,
        start: &Point,
        free: &[usize],
        target: Target,
        iterations: u64,
    ) -> (Point, Scores) {
        let direct = |x: &[f64]| {
            let (p, s, _) = self.eval(start.combo, x);
            (p, s)
        };
        if free.is_empty() || iterations == 0 {
            return direct(&start.x);
        }
        let coords = self.objective.coordinates();
        let x0: Vec<f64> = free.iter().map(|&j| start.x[j]).collect();
        let mut simplex = vec![x0.clone()];
        for (i, &j) in free.iter().enumerate() {
            let mut v = x0.clone();
            // A tenth of the box, inward for a bounded coordinate at its upper end.
            let step = 0.1 * coords[j].width();
            v[i] += if !coords[j].periodic && v[i] + step > coords[j].hi {
                -step
            } else {
                step
            };
            simplex.push(v);
        }
        let cost = Local {
            search: self,
            start,
            free,
            target,
            seen: Mutex::new(None),
        };
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(1e-6)
            .expect("a non-negative tolerance");
        let result = Executor::new(cost, solver)
            .configure(|s| s.max_iters(iterations))
            .run();
        match result {
            Ok(r) => r
                .problem
                .problem
                .and_then(|c| c.seen.into_inner().unwrap_or_else(|e| e.into_inner()))
                .unwrap_or_else(|| direct(&start.x)),
            Err(_) => direct(&start.x),
        }
    }
}

/// The cost argmin's Nelder-Mead sees: objective `target` with the `free` coordinates of
/// `start` set from the vector; remembers the best point it evaluated.
struct Local<'a, 'b, O: Objective> {
    search: &'a Search<'b, O>,
    start: &'a Point,
    free: &'a [usize],
    target: Target,
    seen: Mutex<Option<(Point, Scores)>>,
}

impl<O: Objective> CostFunction for Local<'_, '_, O> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, v: &Self::Param) -> Result<f64, ArgminError> {
        let mut x = self.start.x.clone();
        for (&j, value) in self.free.iter().zip(v) {
            x[j] = *value;
        }
        let (p, s, _) = self.search.eval(self.start.combo, &x);
        let f = s.get(self.target);
        let mut seen = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        if seen.as_ref().is_none_or(|(_, b)| f < b.get(self.target)) {
            *seen = Some((p, s));
        }
        Ok(f)
    }
}

/// The k-th point (k >= 1) of the Halton sequence in `dims` dimensions (bases: the primes).
pub fn halton(k: usize, dims: usize) -> Vec<f64> {
    const PRIMES: [usize; 8] = [2, 3, 5, 7, 11, 13, 17, 19];
    PRIMES
        .iter()
        .take(dims)
        .map(|&b| {
            let (mut f, mut r, mut i) = (1.0, 0.0, k);
            while i > 0 {
                f /= b as f64;
                r += f * (i % b) as f64;
                i /= b;
            }
            r
        })
        .collect()
}

/// Up to `n` of `evaluated`, best first for objective `t`, pairwise distinct (see
/// [`DISTINCT`]).
fn distinct_starts(
    evaluated: &[(Point, Scores)],
    coords: &[Coordinate],
    t: Target,
    n: usize,
) -> Vec<Point> {
    let mut order: Vec<&(Point, Scores)> = evaluated.iter().collect();
    order.sort_by(|a, b| a.1.get(t).total_cmp(&b.1.get(t)));
    let mut out: Vec<Point> = Vec::new();
    for (p, _) in order {
        if out.len() >= n {
            break;
        }
        let far = |q: &Point| {
            q.combo != p.combo
                || coords
                    .iter()
                    .zip(p.x.iter().zip(&q.x))
                    .map(|(c, (a, b))| c.unit_distance(*a, *b).powi(2))
                    .sum::<f64>()
                    .sqrt()
                    >= DISTINCT
        };
        if out.iter().all(far) {
            out.push(p.clone());
        }
    }
    out
}

/// Runs the three stages (see the module doc) on `objective`.
pub fn search<O: Objective>(objective: &O, budget: Budget) -> Outcome<O::Detail> {
    let coords = objective.coordinates();
    let dims = coords.len();
    let s = Search {
        objective,
        tracker: Mutex::new(Tracker {
            best: vec![vec![None; 1 + objective.columns()]; objective.combos()],
        }),
        evaluations: AtomicUsize::new(0),
    };
    let declared = {
        let d = objective.declared();
        let (point, scores, detail) = s.eval(d.combo, &d.x);
        Best {
            point,
            scores,
            detail,
        }
    };
    // 1. Global.
    let combos = objective.combos();
    let mut grid: Vec<Point> = (0..combos)
        .flat_map(|combo| {
            (0..budget.global_per_combo).map(move |k| Point {
                combo,
                x: halton(1 + k * combos + combo, dims)
                    .iter()
                    .zip(coords)
                    .map(|(u, c)| c.lo + u * c.width())
                    .collect(),
            })
        })
        .collect();
    grid.push(declared.point.clone());
    let mut evaluated: Vec<(Point, Scores)> = grid
        .par_iter()
        .map(|p| {
            let (p, sc, _) = s.eval(p.combo, &p.x);
            (p, sc)
        })
        .collect();
    evaluated.push((declared.point.clone(), declared.scores.clone()));
    // 2. Local.
    let all: Vec<usize> = (0..dims).collect();
    let mut starts: Vec<(Target, Point)> =
        distinct_starts(&evaluated, coords, Target::Joint, budget.joint_starts)
            .into_iter()
            .map(|p| (Target::Joint, p))
            .collect();
    for c in 0..objective.columns() {
        starts.extend(
            distinct_starts(&evaluated, coords, Target::Column(c), budget.column_starts)
                .into_iter()
                .map(|p| (Target::Column(c), p)),
        );
    }
    let local: Vec<LocalOptimum> = starts
        .par_iter()
        .map(|(t, p)| {
            let (point, scores) = s.nelder_mead(p, &all, *t, budget.iterations);
            LocalOptimum {
                target: *t,
                point,
                scores,
            }
        })
        .collect();
    // 3. Profiles of the joint optimum so far.
    let mut local = local;
    let profiles = if budget.profiles && dims > 0 {
        let best = s.joint_best();
        let profiles = profiles(&s, &best, budget.profile_iterations);
        // 4. A profile point that beat the optimum is a start the local stage missed.
        let after = s.joint_best();
        if after.1.joint < best.1.joint {
            let (point, scores) = s.nelder_mead(&after.0, &all, Target::Joint, budget.iterations);
            local.push(LocalOptimum {
                target: Target::Joint,
                point,
                scores,
            });
        }
        profiles
    } else {
        Vec::new()
    };
    let tracker = s.tracker.into_inner().unwrap_or_else(|e| e.into_inner());
    Outcome {
        declared,
        best: tracker.best,
        local,
        profiles,
        evaluations: s.evaluations.into_inner(),
    }
}

/// The profiles of every coordinate at `best` (module doc, stage 3).
fn profiles<O: Objective>(
    s: &Search<'_, O>,
    best: &(Point, Scores),
    iterations: u64,
) -> Vec<Profile> {
    let coords = s.objective.coordinates();
    // Chains: per coordinate, the grid values above x*_j (ascending) and below (descending).
    let chains: Vec<(usize, Vec<f64>)> = coords
        .iter()
        .enumerate()
        .flat_map(|(j, c)| {
            let at = best.0.x[j];
            let values = c.grid_values();
            let up: Vec<f64> = values.iter().copied().filter(|v| *v > at).collect();
            let mut down: Vec<f64> = values.iter().copied().filter(|v| *v < at).collect();
            down.reverse();
            [(j, up), (j, down)]
        })
        .collect();
    let walked: Vec<(usize, Vec<ProfilePoint>)> = chains
        .par_iter()
        .map(|(j, values)| {
            let others: Vec<usize> = (0..coords.len()).filter(|k| k != j).collect();
            let mut from = best.0.clone();
            let mut out = Vec::new();
            for &v in values {
                from.x[*j] = v;
                let (point, scores) = s.nelder_mead(&from, &others, Target::Joint, iterations);
                // Warm start of the next grid value: this one's optimum.
                from = point.clone();
                out.push(ProfilePoint {
                    value: v,
                    point,
                    scores,
                });
            }
            (*j, out)
        })
        .collect();
    (0..coords.len())
        .map(|j| {
            let mut points: Vec<ProfilePoint> = walked
                .iter()
                .filter(|(k, _)| *k == j)
                .flat_map(|(_, p)| p.iter().cloned())
                .collect();
            points.push(ProfilePoint {
                value: best.0.x[j],
                point: best.0.clone(),
                scores: best.1.clone(),
            });
            points.sort_by(|a, b| a.value.total_cmp(&b.value));
            Profile {
                coordinate: j,
                refitted: iterations > 0 && coords.len() > 1,
                points,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two combinations over [0, 1) (periodic) x [-1, 1]: combination 0 has a wide shallow
    /// basin (0.5 at A) and a narrower one (0.3 at C); combination 1 a shallow one (0.6 at A)
    /// and the global minimum (0.02 at B). Column 0 is the joint objective shifted by 0.01;
    /// column 1 has its own minimum (0.1 at D in combination 0). Every evaluation is logged.
    struct TwoBasins {
        coords: Vec<Coordinate>,
        log: Mutex<Vec<(Point, Scores)>>,
    }

    const A: [f64; 2] = [0.2, -0.5];
    const B: [f64; 2] = [0.7, 0.6];
    const C: [f64; 2] = [0.45, 0.1];
    const D: [f64; 2] = [0.85, -0.7];

    fn sq(x: &[f64], c: [f64; 2]) -> f64 {
        (x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2)
    }

    impl TwoBasins {
        fn new() -> Self {
            Self {
                coords: vec![
                    Coordinate {
                        name: "u",
                        lo: 0.0,
                        hi: 1.0,
                        periodic: true,
                        grid: 8,
                    },
                    Coordinate {
                        name: "v",
                        lo: -1.0,
                        hi: 1.0,
                        periodic: false,
                        grid: 9,
                    },
                ],
                log: Mutex::new(Vec::new()),
            }
        }
    }

    impl Objective for TwoBasins {
        type Detail = ();
        fn combos(&self) -> usize {
            2
        }
        fn coordinates(&self) -> &[Coordinate] {
            &self.coords
        }
        fn columns(&self) -> usize {
            2
        }
        fn declared(&self) -> Point {
            Point {
                combo: 0,
                x: vec![0.0, 0.0],
            }
        }
        fn evaluate(&self, p: &Point) -> (Scores, ()) {
            let x = &p.x;
            let joint = match p.combo {
                0 => (0.5 + sq(x, A)).min(0.3 + 20.0 * sq(x, C)),
                _ => (0.6 + sq(x, A)).min(0.02 + 5.0 * sq(x, B)),
            };
            let own = if p.combo == 0 {
                0.1 + 3.0 * sq(x, D)
            } else {
                1.0
            };
            let s = Scores {
                joint,
                columns: vec![joint + 0.01, own],
            };
            self.log.lock().unwrap().push((p.clone(), s.clone()));
            (s, ())
        }
    }

    fn budget() -> Budget {
        Budget {
            global_per_combo: 32,
            joint_starts: 3,
            column_starts: 2,
            iterations: 80,
            profiles: true,
            profile_iterations: 30,
        }
    }

    #[test]
    fn nelder_mead_from_the_declared_point_alone_stays_in_a_local_basin() {
        // The premise of the global stage: a local search from the declared point does not
        // reach the global minimum of this objective.
        let o = TwoBasins::new();
        let s = Search {
            objective: &o,
            tracker: Mutex::new(Tracker {
                best: vec![vec![None; 3]; 2],
            }),
            evaluations: AtomicUsize::new(0),
        };
        let (_, scores) = s.nelder_mead(&o.declared(), &[0, 1], Target::Joint, 200);
        assert!(scores.joint > 0.25, "{}", scores.joint);
    }

    #[test]
    fn the_search_finds_the_global_minimum_of_two_basins() {
        let o = TwoBasins::new();
        let out = search(&o, budget());
        let best = out.best(Target::Joint);
        assert_eq!(best.point.combo, 1);
        assert!((best.scores.joint - 0.02).abs() < 1e-4, "{:?}", best);
        assert!(sq(&best.point.x, B).sqrt() < 0.01, "{:?}", best.point);
        // Column 1 alone has its optimum elsewhere (combination 0, at D).
        let own = out.best(Target::Column(1));
        assert_eq!(own.point.combo, 0);
        assert!((own.scores.columns[1] - 0.1).abs() < 1e-4, "{:?}", own);
    }

    #[test]
    fn the_reported_best_is_the_minimum_over_every_evaluation() {
        let o = TwoBasins::new();
        let out = search(&o, budget());
        let log = o.log.lock().unwrap();
        assert_eq!(log.len(), out.evaluations);
        for t in [Target::Joint, Target::Column(0), Target::Column(1)] {
            let min = log
                .iter()
                .map(|(_, s)| s.get(t))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(out.best(t).scores.get(t), min, "{t:?}");
        }
        // Per combination too.
        for k in 0..2 {
            let min = log
                .iter()
                .filter(|(p, _)| p.combo == k)
                .map(|(_, s)| s.joint)
                .fold(f64::INFINITY, f64::min);
            assert_eq!(
                out.best_where(Target::Joint, |c| c == k)
                    .unwrap()
                    .scores
                    .joint,
                min
            );
        }
    }

    #[test]
    fn re_fitted_profiles_lie_on_or_below_slices_and_touch_the_optimum() {
        let o = TwoBasins::new();
        let out = search(&o, budget());
        let best = out.best(Target::Joint).scores.joint;
        let sliced = search(
            &TwoBasins::new(),
            Budget {
                profile_iterations: 0,
                ..budget()
            },
        );
        for (p, q) in out.profiles.iter().zip(&sliced.profiles) {
            assert!(p.refitted && !q.refitted);
            assert_eq!(p.points.len(), o.coords[p.coordinate].grid + 1);
            let min = p
                .points
                .iter()
                .map(|q| q.scores.joint)
                .fold(f64::INFINITY, f64::min);
            assert_eq!(min, best);
            for (a, b) in p.points.iter().zip(&q.points) {
                assert_eq!(a.value, b.value);
                assert!(a.scores.joint <= b.scores.joint + 1e-12);
                assert_eq!(a.point.x[p.coordinate], a.value);
            }
        }
        // Away from B along v the slice climbs steeply, the re-fitted profile (u free) less.
        let v = &out.profiles[1].points;
        let w = &sliced.profiles[1].points;
        assert!(v[0].scores.joint < w[0].scores.joint);
    }

    #[test]
    fn halton_points_fill_the_unit_box() {
        let pts: Vec<Vec<f64>> = (1..=64).map(|k| halton(k, 3)).collect();
        assert_eq!(halton(1, 2), vec![0.5, 1.0 / 3.0]);
        for d in 0..3 {
            let low = pts.iter().filter(|p| p[d] < 0.5).count();
            assert!(
                (28..=36).contains(&low),
                "dimension {d}: {low} of 64 below 0.5"
            );
        }
    }
}
