//! Split points kept apart. The refinements (`singular`'s growth, `slab`) put a point on an edge
//! at a set distance from one end. Edges from one vertex to a cluster of near-duplicate vertices
//! (a contour jittering within 1e-7, a tiny section), or from such a cluster to one vertex, or to
//! the split points of an earlier round, point nearly the same way, and points at one distance
//! along them are near-duplicates: 1e-11 apart on the generated inputs, far below what tools that
//! weld vertices (trimesh: about 1e-8) keep apart, and the walls between them nearly coplanar
//! slivers. So a point that would crowd another moves along its edge, first by a few percent of
//! its distance, then by finer steps of a few gaps, until it clears them.
use crate::fxhash::FxHashMap;

/// Split points keep at least this fraction of their distance along the edge (a growth distance
/// or a slab's thickness, 1e-3 of the diagonal: 1e-8 of the diagonal) from each other.
pub const MIN_GAP: f64 = 1e-5;

/// Slab points keep at least this fraction of the slab's thickness (1e-7 of the diagonal at the
/// usual 1e-3) from each other: a hundred times the distance at which `check` calls two triangles
/// one double sheet (1e-9 of the diagonal). At `MIN_GAP`, two slab points of odd076 on edges from
/// one zone vertex to two apexes nearly in line were 4e-8 of the diagonal apart, and the needle
/// triangles from them to the far end of their zone lay on each other within that distance.
pub const SLAB_GAP: f64 = 1e-4;

/// On an edge shorter than the gap over this, the gap is this fraction of the edge: near-duplicate
/// points come from long edges converging at a core, not from a contour drawn at a far smaller
/// scale than the diagonal, whose own vertices are that close.
const SHORT_EDGE: f64 = 1e-2;

/// Factors of the distance tried first, in order: near-parallel edges then part along their length.
const STAGGER: [f64; 5] = [1.0, 1.01, 0.99, 1.02, 0.98];

/// Where those are all crowded (a bundle of edges to a cluster, grown along round after round),
/// finer steps of three gaps each, alternately up and down, as far as `FINE_RANGE` of the distance.
const FINE_STEPS: usize = 200;
const FINE_RANGE: f64 = 0.1;

/// How a point of each refinement is spaced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rule {
    /// A growth's point: crowded by its own core's points only, it may move nearer or farther
    /// (any point near its core does).
    Growth,
    /// A slab's point: crowded by every point of the slabs, it moves only farther, unless its
    /// distance was capped at the middle of the edge (a slab keeps at least its thickness).
    Slab,
}

/// Points kept apart by at least `gap`: a grid of cells of that size. Each point has an owner (a
/// growth's core vertex); a point may be crowded by its owner's points only, or by all.
pub struct Spaced {
    gap: f64,
    cells: FxHashMap<[i64; 3], Vec<([f64; 3], u32)>>,
}

impl Spaced {
    pub fn new(gap: f64, points: &[([f64; 3], u32)]) -> Spaced {
        let mut s = Spaced {
            gap,
            cells: FxHashMap::default(),
        };
        for &(p, owner) in points {
            s.insert(p, owner);
        }
        s
    }

    fn cell(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|x| (x / self.gap).floor() as i64)
    }

    pub fn insert(&mut self, p: [f64; 3], owner: u32) {
        let c = self.cell(p);
        self.cells.entry(c).or_default().push((p, owner));
    }

    /// Whether a point (of `owner`, or of anyone where `None`) lies closer than `gap` (at most
    /// the grid's) to `p` (one equal to it too).
    pub fn crowds(&self, p: [f64; 3], owner: Option<u32>, gap: f64) -> bool {
        let c = self.cell(p);
        let g2 = gap.min(self.gap).powi(2);
        (0..27).any(|i| {
            let k = [i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1];
            let key = [c[0] + k[0], c[1] + k[1], c[2] + k[2]];
            self.cells.get(&key).is_some_and(|ps| {
                ps.iter().any(|&(q, qo)| {
                    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                    owner.is_none_or(|o| o == qo) && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < g2
                })
            })
        })
    }

    /// The point on the edge from `p` to `q` at the fraction `fraction(1)` of it, at most a
    /// half, moved along the edge (`fraction(k)` for the factors `k` tried, as `rule` allows)
    /// where it would crowd a point; recorded as `owner`'s. Where every place tried is crowded,
    /// the one at `fraction(1)`. Returns the point and the fraction it is at.
    pub fn place(
        &mut self,
        [p, q]: [[f64; 3]; 2],
        fraction: impl Fn(f64) -> f64,
        rule: Rule,
        owner: u32,
    ) -> ([f64; 3], f64) {
        let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        // capped at the middle, the point is staggered nearer: where edges are capped (edges to
        // the previous round's split points are as long as the distance), moving the distance
        // alone would move nothing
        let base = fraction(1.0);
        let capped = base >= 0.5;
        let at = |k: f64| {
            let s = if capped { 0.5 * k } else { fraction(k) };
            let allowed = s <= 0.5 && (rule == Rule::Growth || capped || k >= 1.0);
            allowed.then_some(([p[0] + s * d[0], p[1] + s * d[1], p[2] + s * d[2]], s))
        };
        let crowded_by = match rule {
            Rule::Growth => Some(owner),
            Rule::Slab => None,
        };
        // short edges (a contour at a far smaller scale) are dense by nature
        let gap = (SHORT_EDGE * len).min(self.gap);
        let placed = factors(3.0 * gap / (base.min(0.5) * len))
            .filter_map(at)
            .find(|&(y, _)| !self.crowds(y, crowded_by, gap))
            .unwrap_or_else(|| at(1.0).expect("at most halfway"));
        self.insert(placed.0, owner);
        placed
    }
}

/// The factors of the distance tried: `STAGGER`, then steps of `fine` (a fraction of the
/// distance) alternately up and down.
fn factors(fine: f64) -> impl Iterator<Item = f64> {
    let fine = (1..=FINE_STEPS)
        .flat_map(move |m| [1.0 + m as f64 * fine, 1.0 - m as f64 * fine])
        .take_while(|k| (k - 1.0).abs() <= FINE_RANGE);
    STAGGER.into_iter().chain(fine)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
        (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
    }

    /// Whether `x` lies on the segment from `p` to `q` up to rounding.
    fn on_segment(x: [f64; 3], p: [f64; 3], q: [f64; 3]) -> bool {
        (dist(p, x) + dist(x, q) - dist(p, q)).abs() < 1e-12
    }

    /// A cluster of `n` far vertices 1e-9 apart around (1, 0, 0).
    fn cluster(n: usize) -> Vec<[f64; 3]> {
        (0..n)
            .map(|i| [1.0, 1e-9 * i as f64, 1e-9 * (i % 3) as f64])
            .collect()
    }

    #[test]
    fn edges_capped_at_their_middle_still_part() {
        // growth towards the previous round's points: every edge shorter than twice the distance,
        // so every point is at a middle; 30 near-parallel edges (more than the coarse factors)
        let (core, distance) = ([0.0; 3], 2.0);
        let mut spaced = Spaced::new(MIN_GAP * distance, &[]);
        let mut placed = Vec::new();
        for q in cluster(30) {
            let (x, s) = spaced.place([core, q], |k| k * distance / 1.0, Rule::Growth, 0);
            assert!((0.5 * (1.0 - FINE_RANGE)..=0.5).contains(&s), "{s}");
            assert!(on_segment(x, core, q));
            placed.push(x);
        }
        for (i, a) in placed.iter().enumerate() {
            for b in &placed[i + 1..] {
                assert!(
                    dist(*a, *b) >= MIN_GAP * distance * (1.0 - 1e-9),
                    "{a:?} {b:?}"
                );
            }
        }
    }

    #[test]
    fn a_slab_point_moves_only_farther_unless_capped() {
        let (zone_vertex, thickness) = ([0.0; 3], 1e-3);
        let mut spaced = Spaced::new(MIN_GAP * thickness, &[]);
        for q in cluster(12) {
            let (x, s) = spaced.place([zone_vertex, q], |k| k * thickness, Rule::Slab, 7);
            assert!(s >= thickness && on_segment(x, zone_vertex, q), "{s}");
        }
        // capped: half the apex's height at most, so nearer
        let mut spaced = Spaced::new(MIN_GAP * thickness, &[]);
        let near_apex = [[2e-3, 0.0, 0.0], [2e-3, 1e-12, 0.0]];
        let (_, s0) = spaced.place([zone_vertex, near_apex[0]], |k| k, Rule::Slab, 8);
        let (_, s1) = spaced.place([zone_vertex, near_apex[1]], |k| k, Rule::Slab, 8);
        assert_eq!(s0, 0.5);
        assert!(s1 < 0.5, "{s1}");
    }

    #[test]
    fn points_of_other_owners_crowd_only_when_asked() {
        let mut spaced = Spaced::new(1e-3, &[([0.0, 0.0, 0.0], 1)]);
        assert!(!spaced.crowds([1e-4, 0.0, 0.0], Some(2), 1e-3));
        assert!(spaced.crowds([1e-4, 0.0, 0.0], Some(1), 1e-3));
        assert!(spaced.crowds([1e-4, 0.0, 0.0], None, 1e-3));
        spaced.insert([1.0, 0.0, 0.0], 2);
        assert!(spaced.crowds([1.0, 1e-4, 0.0], None, 1e-3));
    }
}
