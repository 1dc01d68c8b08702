//! Contour edges that diagram points may not take away again (Ruppert's encroachment, in the
//! plane rule's 2D Delaunay triangulation of a face).
//!
//! A cell's diagram samples and their Steiner points go into its faces; one inside every empty
//! circle through a contour edge takes the edge out of the face's triangulation, and `conform`
//! splits the edge and runs both cells of the face again. Split at its midpoint, the halves were
//! taken away again by the next run's samples, round after round (a 40-plane fan of Elephant: 7
//! rounds, about half its cell time). So the pieces of a split edge (an edge with a conformity
//! Steiner point at an end) are guarded: a point inside the guard circle is not inserted. Edges
//! never taken away are not guarded: a sample near the contour is part of the diagram's sampling
//! and attaches the section to the cell; refusing every such sample (guarding all contour edges)
//! took 7 rounds to 2 but grew the flat zones by 20–60% (Horsers' area 230 → 364) and made four
//! odd inputs unclean (branch `guard-s35`).
use super::cell_input::{CellInput, IdMap};

/// Per grid cell, what lies in it (or reaches into it).
type Buckets<T> = IdMap<(i64, i64), Vec<T>>;

/// The grid cell of size `r` holding `q`.
pub(super) fn bucket(q: [f64; 2], r: f64) -> (i64, i64) {
    ((q[0] / r).floor() as i64, (q[1] / r).floor() as i64)
}

/// The contour edges of a face, each with one circle a new point may not go inside. Per edge `ab`
/// the guard is one circle through `a` and `b` that no point of the face is inside: the diametral
/// circle, or where a point of the face is inside that, the circle through it nearer to the
/// diametral one (every circle through `a`, `b` with its centre between the two is then empty). While no point goes inside that
/// circle, `ab` stays an edge; a refused point costs the diagram a sample near the contour.
pub(crate) struct ContourGuard {
    /// Bucket size.
    r: f64,
    /// Guard circles (centre, squared radius), in every bucket their square meets.
    discs: Buckets<([f64; 2], f64)>,
}

impl ContourGuard {
    /// The guard of slot `s`'s split contour edges (an end is a conformity Steiner point: the
    /// edge was taken away before) against the slot's points, bucketed at `r`.
    pub(crate) fn of_slot(input: &CellInput, s: usize, r: f64) -> ContourGuard {
        let slot = &input.slots[s];
        let split = |v: u32| {
            input
                .tags
                .get(v as usize)
                .is_some_and(|t| t.segment.is_some())
        };
        let points = (0..input.points.len())
            .filter(|&v| input.mask[v] >> s & 1 == 1)
            .map(|v| slot.uv[v]);
        let edges = (slot.contour_edges().iter())
            .filter(|&&(a, b)| split(a) || split(b))
            .map(|&(a, b)| [slot.uv[a as usize], slot.uv[b as usize]]);
        ContourGuard::of_points(r, points, edges)
    }

    /// The guard of the segments `edges` against `points` (the segments' ends among them),
    /// bucketed at `r`.
    pub(crate) fn of_points(
        r: f64,
        points: impl Iterator<Item = [f64; 2]>,
        edges: impl Iterator<Item = [[f64; 2]; 2]>,
    ) -> ContourGuard {
        let mut g = ContourGuard {
            r,
            discs: IdMap::default(),
        };
        let edges: Vec<[[f64; 2]; 2]> = edges.collect();
        // most faces have no split edge: no point is bucketed for them
        if edges.is_empty() || !(r > 0.0 && r.is_finite()) {
            return g;
        }
        let mut buckets: Buckets<[f64; 2]> = IdMap::default();
        for q in points.filter(|q| q.iter().all(|c| c.is_finite())) {
            buckets.entry(bucket(q, r)).or_default().push(q);
        }
        for [a, b] in edges {
            g.guard(a, b, &buckets);
        }
        g
    }

    /// Guard the segment `ab` against the bucketed `points`.
    fn guard(&mut self, a: [f64; 2], b: [f64; 2], points: &Buckets<[f64; 2]>) {
        let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = (dx * dx + dy * dy).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return;
        }
        let (half2, rr) = (0.25 * len * len, 0.5 * len);
        // an edge far longer than the buckets (a face clipped along a long line) stays unguarded:
        // refusing every point of its circle would leave much of the face unsampled
        let Some((lo, hi)) = self.span(m, rr, 256) else {
            return;
        };
        // circle(t): centre m + t n, through a and b; a point (x, y) in the frame (m; u, n) is
        // inside iff 2 y t > x² + y² − |ab|²/4, so points of either side inside the diametral
        // circle (t = 0) bound the empty circles' t from that side
        let (u, n) = ([dx / len, dy / len], [-dy / len, dx / len]);
        let (mut t_lo, mut t_hi) = (0.0f64, 0.0f64);
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                for q in points.get(&(x, y)).into_iter().flatten() {
                    let d = [q[0] - m[0], q[1] - m[1]];
                    let (px, py) = (d[0] * u[0] + d[1] * u[1], d[0] * n[0] + d[1] * n[1]);
                    let k = px * px + py * py - half2;
                    // a and b themselves (and points on the circle) are ties, not inside
                    if k >= -1e-12 * half2 || py == 0.0 {
                        continue;
                    }
                    let t = k / (2.0 * py);
                    if py < 0.0 {
                        t_lo = t_lo.max(t);
                    } else {
                        t_hi = t_hi.min(t);
                    }
                }
            }
        }
        // both sides inside: no empty circle through a and b, the edge is no Delaunay edge now
        // and no guard keeps it
        if t_lo > 0.0 && t_hi < 0.0 {
            return;
        }
        let t = if t_lo > 0.0 { t_lo } else { t_hi };
        let c = [m[0] + t * n[0], m[1] + t * n[1]];
        // a hair widened: on the circle is a tie of four cocircular points, which the kernel's
        // perturbation decides either way
        let r2 = (half2 + t * t) * (1.0 + 1e-9);
        let Some((lo, hi)) = self.span(c, r2.sqrt(), 1024) else {
            return;
        };
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                self.discs.entry((x, y)).or_default().push((c, r2));
            }
        }
    }

    /// The first and last bucket of the square around the circle (centre `c`, radius `rad`), if it
    /// spans at most `most` buckets.
    fn span(&self, c: [f64; 2], rad: f64, most: i64) -> Option<((i64, i64), (i64, i64))> {
        let lo = bucket([c[0] - rad, c[1] - rad], self.r);
        let hi = bucket([c[0] + rad, c[1] + rad], self.r);
        ((hi.0 - lo.0 + 1).saturating_mul(hi.1 - lo.1 + 1) <= most).then_some((lo, hi))
    }

    /// Whether no edge is guarded (every one too long for the buckets, or no Delaunay edge).
    #[cfg(test)]
    fn is_empty(&self) -> bool {
        self.discs.is_empty()
    }

    /// Whether `q` is inside (or on) the guard circle of a contour edge.
    pub(crate) fn encroaches(&self, q: [f64; 2]) -> bool {
        self.discs.get(&bucket(q, self.r)).is_some_and(|l| {
            l.iter()
                .any(|&(c, r2)| (q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2) <= r2)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::cutting::tests::circle;

    /// Delaunay edges of `points` (spade, exact predicates), as index pairs.
    fn delaunay_edges(points: &[[f64; 2]]) -> (Vec<(usize, usize)>, usize) {
        use spade::{DelaunayTriangulation, Point2, Triangulation};
        let mut dt: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
        let ids: Vec<_> = (points.iter())
            .map(|p| dt.insert(Point2::new(p[0], p[1])).expect("finite point"))
            .collect();
        let index: std::collections::HashMap<_, usize> =
            ids.iter().enumerate().map(|(i, &h)| (h, i)).collect();
        let edges = (dt.undirected_edges())
            .map(|e| {
                let [a, b] = e.vertices().map(|v| index[&v.fix()]);
                (a.min(b), a.max(b))
            })
            .collect();
        (edges, dt.num_vertices())
    }

    fn guard_of(points: &[[f64; 2]], edges: &[(usize, usize)], r: f64) -> ContourGuard {
        ContourGuard::of_points(
            r,
            points.iter().copied(),
            edges.iter().map(|&(a, b)| [points[a], points[b]]),
        )
    }

    /// A point in the diametral circle of an edge with nothing else near is refused, one just
    /// outside it is not; with a point of the face inside the diametral circle on one side, the
    /// guard is the larger circle through it, and refuses a point of the other side outside the
    /// diametral circle that would take the edge away (the plane rule's 2D Delaunay edge).
    #[test]
    fn the_guard_is_an_empty_circle_through_the_edge() {
        let (a, b) = ([0.0, 0.0], [1.0, 0.0]);
        let g = guard_of(&[a, b], &[(0, 1)], 0.25);
        assert!(g.encroaches([0.5, 0.49]));
        assert!(!g.encroaches([0.5, 0.51]));
        assert!(!g.encroaches([0.5, -0.51]));
        // d below inside the diametral circle: the empty circles through a, b bulge upwards
        let d = [0.5, -0.3];
        let g = guard_of(&[a, b, d], &[(0, 1)], 0.25);
        // circle through a, b, d: centre (0.5, t) with 0.25 + t² = (t + 0.3)², t = 0.2667
        assert!(g.encroaches([0.5, 0.8]));
        assert!(!g.encroaches([0.5, 0.85]));
        // and the edge is lost to that point without the guard (spade's triangulation)
        let (edges, _) = delaunay_edges(&[a, b, d, [0.5, 0.8]]);
        assert!(!edges.contains(&(0, 1)));
        let (edges, _) = delaunay_edges(&[a, b, d, [0.5, 0.85]]);
        assert!(edges.contains(&(0, 1)));
        // a point inside the diametral circle on both sides: no empty circle, no guard
        let g = guard_of(&[a, b, d, [0.5, 0.3]], &[(0, 1)], 0.25);
        assert!(!g.encroaches([0.5, 0.1]));
        // an edge far longer than the buckets stays unguarded
        let g = guard_of(&[a, b], &[(0, 1)], 0.01);
        assert!(!g.encroaches([0.5, 0.1]));
    }

    /// On a ring of contour points and a grid of candidates, the guard keeps every ring edge and
    /// refuses only candidates near the ring (most of the grid inside goes in), where without it
    /// candidates take ring edges away.
    #[test]
    fn the_guard_refuses_only_near_the_contour() {
        let ring = circle(0.0, 0.0, 1.0, 24);
        let edges: Vec<(usize, usize)> = (0..24)
            .map(|i| (i.min((i + 1) % 24), i.max((i + 1) % 24)))
            .collect();
        let g = guard_of(&ring, &edges, 0.13);
        let grid: Vec<[f64; 2]> = (0..41)
            .flat_map(|i| (0..41).map(move |j| [-1.0 + 0.05 * i as f64, -1.0 + 0.05 * j as f64]))
            .filter(|q| q[0] * q[0] + q[1] * q[1] < 1.0)
            .collect();
        let kept: Vec<[f64; 2]> = grid.iter().copied().filter(|&q| !g.encroaches(q)).collect();
        assert!(
            kept.len() * 10 > grid.len() * 8,
            "{} of {}",
            kept.len(),
            grid.len()
        );
        let with = |pts: &[[f64; 2]]| {
            let mut all = ring.clone();
            all.extend_from_slice(pts);
            delaunay_edges(&all).0
        };
        let after = with(&kept);
        assert!(edges.iter().all(|e| after.contains(e)));
        let unguarded = with(&grid);
        assert!(edges.iter().any(|e| !unguarded.contains(e)));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
        /// Every guarded Delaunay edge of a point set stays a Delaunay edge whatever points the
        /// guard lets in (spade's exact triangulation decides); an edge too long for the
        /// buckets is not guarded, and may go.
        #[test]
        fn guarded_edges_stay_delaunay_edges(
            points in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 8..40),
            every in 2usize..5,
            extra in proptest::collection::vec((-0.2f64..1.2, -0.2f64..1.2), 50..150),
        ) {
            // jittered by a hash of the index: the shrunk inputs stay in general position
            let jitter = |i: usize, k: f64| {
                let h = |c: f64| 0.01 * ((i as f64 * 12.9898 + k + c).sin() * 43_758.545_3).fract();
                [h(0.0), h(78.233)]
            };
            let points: Vec<[f64; 2]> = (points.iter().enumerate())
                .map(|(i, &(x, y))| [x + jitter(i, 0.0)[0], y + jitter(i, 0.0)[1]])
                .collect();
            let extra: Vec<[f64; 2]> = (extra.iter().enumerate())
                .map(|(i, &(x, y))| [x + jitter(i, 0.5)[0], y + jitter(i, 0.5)[1]])
                .collect();
            let (edges, n) = delaunay_edges(&points);
            proptest::prop_assume!(n == points.len());
            let guarded: Vec<(usize, usize)> = edges.iter().copied().step_by(every).collect();
            let g = guard_of(&points, &guarded, 0.05);
            let mut all = points.clone();
            all.extend(extra.iter().copied().filter(|&q| !g.encroaches(q)));
            let (after, _) = delaunay_edges(&all);
            // the edges the guard keeps: not those too long for its buckets
            for e in guarded.iter().filter(|&&e| !guard_of(&points, &[e], 0.05).is_empty()) {
                proptest::prop_assert!(after.contains(e), "edge {:?} lost", e);
            }
        }
    }
}
