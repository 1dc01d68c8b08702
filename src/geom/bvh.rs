//! A bounding volume hierarchy of axis-aligned boxes (median split on the longest axis of the
//! centroids, leaves of at most `LEAF` items). Generic over what the boxes bound: triangles for
//! self-intersection and ray queries, points for nearest-sample queries.
//!
//! Boxes are built from the exact input coordinates with `min`/`max` (no rounding), so closed box
//! overlap is a conservative filter for exact predicates.

#![allow(clippy::needless_range_loop)] // small fixed-size coordinate loops read better indexed
use smallvec::SmallVec;

const LEAF: usize = 4;
/// Subtrees larger than this are built in parallel (rayon::join) and spliced.
const PAR_BUILD: usize = 1 << 15;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    pub fn of_points(points: &[[f64; 3]]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for p in points {
            b.add_point(*p);
        }
        b
    }

    pub fn add_point(&mut self, p: [f64; 3]) {
        for k in 0..3 {
            self.lo[k] = self.lo[k].min(p[k]);
            self.hi[k] = self.hi[k].max(p[k]);
        }
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        let mut b = *self;
        for k in 0..3 {
            b.lo[k] = b.lo[k].min(o.lo[k]);
            b.hi[k] = b.hi[k].max(o.hi[k]);
        }
        b
    }

    /// Closed overlap (touching boxes overlap).
    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    /// Squared distance from `p` to the box (0 inside).
    #[inline]
    pub fn dist2(&self, p: [f64; 3]) -> f64 {
        let mut d = 0.0;
        for k in 0..3 {
            let e = (self.lo[k] - p[k]).max(0.0).max(p[k] - self.hi[k]);
            d += e * e;
        }
        d
    }

    /// The box grown by `d` on every side.
    pub fn grown(&self, d: f64) -> Aabb {
        Aabb {
            lo: self.lo.map(|x| x - d),
            hi: self.hi.map(|x| x + d),
        }
    }

    pub fn diagonal(&self) -> f64 {
        (0..3)
            .map(|k| (self.hi[k] - self.lo[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    fn centroid(&self) -> [f64; 3] {
        [
            0.5 * (self.lo[0] + self.hi[0]),
            0.5 * (self.lo[1] + self.hi[1]),
            0.5 * (self.lo[2] + self.hi[2]),
        ]
    }
}

#[derive(Clone, Debug)]
struct Node {
    bb: Aabb,
    /// Leaf: first index into `items`; inner: index of the right child (left child is the next node).
    first_or_right: u32,
    /// Number of items of a leaf, 0 for an inner node.
    count: u32,
}

/// The hierarchy. `items` holds the item ids (indices into the caller's array) in leaf order.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
    items: Vec<u32>,
    boxes: Vec<Aabb>,
}

impl Bvh {
    /// Build over `boxes` (item `i` is bounded by `boxes[i]`).
    pub fn build(boxes: Vec<Aabb>) -> Bvh {
        let mut items: Vec<u32> = (0..boxes.len() as u32).collect();
        let centroids: Vec<[f64; 3]> = boxes.iter().map(Aabb::centroid).collect();
        let nodes = if boxes.is_empty() {
            Vec::new()
        } else {
            build_par(&boxes, &centroids, &mut items, 0)
        };
        Bvh {
            nodes,
            items,
            boxes,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map(|n| n.bb).unwrap_or(Aabb::EMPTY)
    }

    pub fn item_box(&self, i: u32) -> &Aabb {
        &self.boxes[i as usize]
    }

    /// Call `f` for every item whose box passes `test`, descending only into nodes whose box passes.
    #[inline]
    pub fn visit(&self, test: impl Fn(&Aabb) -> bool, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack: SmallVec<[u32; 64]> = SmallVec::new();
        stack.push(0);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if !test(&node.bb) {
                continue;
            }
            if node.count > 0 {
                let s = node.first_or_right as usize;
                for &it in &self.items[s..s + node.count as usize] {
                    if test(&self.boxes[it as usize]) {
                        f(it);
                    }
                }
            } else {
                stack.push(node.first_or_right);
                stack.push(n + 1);
            }
        }
    }

    /// Items whose box overlaps `bb` (closed).
    pub fn for_each_overlap(&self, bb: &Aabb, f: impl FnMut(u32)) {
        self.visit(|b| b.overlaps(bb), f)
    }

    /// The item minimising `dist2(item)` (a squared distance from `p` that is never below the squared
    /// distance from `p` to the item's box), with that squared distance. `None` when empty.
    pub fn nearest(&self, p: [f64; 3], dist2: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best = (u32::MAX, f64::INFINITY);
        let mut stack: SmallVec<[(u32, f64); 64]> = SmallVec::new();
        stack.push((0, self.nodes[0].bb.dist2(p)));
        while let Some((n, d)) = stack.pop() {
            if d >= best.1 {
                continue;
            }
            let node = &self.nodes[n as usize];
            if node.count > 0 {
                let s = node.first_or_right as usize;
                for &it in &self.items[s..s + node.count as usize] {
                    if self.boxes[it as usize].dist2(p) < best.1 {
                        let di = dist2(it);
                        if di < best.1 {
                            best = (it, di);
                        }
                    }
                }
            } else {
                let (l, r) = (n + 1, node.first_or_right);
                let dl = self.nodes[l as usize].bb.dist2(p);
                let dr = self.nodes[r as usize].bb.dist2(p);
                // Push the farther child first so the nearer one is explored first.
                if dl < dr {
                    stack.push((r, dr));
                    stack.push((l, dl));
                } else {
                    stack.push((l, dl));
                    stack.push((r, dr));
                }
            }
        }
        (best.0 != u32::MAX).then_some(best)
    }
}

/// Split `items` at the median centroid along the longest axis of the centroids' box.
fn split(bb_items: &[u32], centroids: &[[f64; 3]]) -> usize {
    let mut cb = Aabb::EMPTY;
    for &i in bb_items {
        cb.add_point(centroids[i as usize]);
    }
    (0..3)
        .max_by(|&a, &b| (cb.hi[a] - cb.lo[a]).total_cmp(&(cb.hi[b] - cb.lo[b])))
        .unwrap_or(0)
}

/// Build a subtree as its own node array (root first, child links relative to it); large subtrees
/// build their two halves in parallel and splice them.
fn build_par(
    boxes: &[Aabb],
    centroids: &[[f64; 3]],
    items: &mut [u32],
    offset: usize,
) -> Vec<Node> {
    if items.len() < PAR_BUILD {
        let mut nodes = Vec::with_capacity(2 * items.len() / LEAF + 1);
        build_rec(boxes, centroids, items, offset, &mut nodes);
        return nodes;
    }
    let axis = split(items, centroids);
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&a, &b| {
        centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
    });
    let (left, right) = items.split_at_mut(mid);
    let (ln, rn) = rayon::join(
        || build_par(boxes, centroids, left, offset),
        || build_par(boxes, centroids, right, offset + mid),
    );
    let mut nodes = Vec::with_capacity(1 + ln.len() + rn.len());
    nodes.push(Node {
        bb: ln[0].bb.union(&rn[0].bb),
        first_or_right: (1 + ln.len()) as u32,
        count: 0,
    });
    let shift = |mut n: Node, by: usize| {
        if n.count == 0 {
            n.first_or_right += by as u32;
        }
        n
    };
    nodes.extend(ln.iter().cloned().map(|n| shift(n, 1)));
    let by = 1 + ln.len();
    nodes.extend(rn.into_iter().map(|n| shift(n, by)));
    nodes
}

fn build_rec(
    boxes: &[Aabb],
    centroids: &[[f64; 3]],
    items: &mut [u32],
    offset: usize,
    nodes: &mut Vec<Node>,
) -> u32 {
    let me = nodes.len() as u32;
    let mut bb = Aabb::EMPTY;
    for &i in items.iter() {
        bb = bb.union(&boxes[i as usize]);
    }
    if items.len() <= LEAF {
        nodes.push(Node {
            bb,
            first_or_right: offset as u32,
            count: items.len() as u32,
        });
        return me;
    }
    nodes.push(Node {
        bb,
        first_or_right: 0,
        count: 0,
    });
    let axis = split(items, centroids);
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&a, &b| {
        centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
    });
    let (left, right) = items.split_at_mut(mid);
    build_rec(boxes, centroids, left, offset, nodes);
    let r = build_rec(boxes, centroids, right, offset + mid, nodes);
    nodes[me as usize].first_or_right = r;
    me
}

/// Boxes of the triangles of a mesh.
pub fn triangle_boxes(vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> Vec<Aabb> {
    triangles
        .iter()
        .map(|t| {
            Aabb::of_points(&[
                vertices[t[0] as usize],
                vertices[t[1] as usize],
                vertices[t[2] as usize],
            ])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn overlap_and_nearest_match_brute_force() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let pts: Vec<[f64; 3]> = (0..2000)
            .map(|_| [rng.gen(), rng.gen(), rng.gen()])
            .collect();
        let bvh = Bvh::build(pts.iter().map(|&p| Aabb::of_points(&[p])).collect());
        for _ in 0..50 {
            let q: [f64; 3] = [rng.gen(), rng.gen(), rng.gen()];
            let d2 = |i: u32| {
                let p = pts[i as usize];
                (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
            };
            let (bi, bd) = bvh.nearest(q, d2).unwrap();
            let brute = (0..pts.len() as u32)
                .min_by(|&a, &b| d2(a).total_cmp(&d2(b)))
                .unwrap();
            assert_eq!(bd, d2(brute));
            assert_eq!(d2(bi), d2(brute));
            let bb = Aabb {
                lo: [q[0] - 0.1, q[1] - 0.1, q[2] - 0.1],
                hi: [q[0] + 0.1, q[1] + 0.1, q[2] + 0.1],
            };
            let mut got = vec![];
            bvh.for_each_overlap(&bb, |i| got.push(i));
            got.sort();
            let want: Vec<u32> = (0..pts.len() as u32)
                .filter(|&i| Aabb::of_points(&[pts[i as usize]]).overlaps(&bb))
                .collect();
            assert_eq!(got, want);
        }
    }
}
