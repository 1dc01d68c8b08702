//! Delaunay conformity of the contour edges, shared across cells.
//!
//! A contour edge lies on one face (two cells) or on an arrangement edge (up to four cells). When a
//! cell's triangulation misses it, it is split at its midpoint by a Steiner point: one *global* vertex
//! (in the pool, tagged with the planes common to the edge's endpoints), so every cell sharing the
//! edge sees the same split. Splits are kept in a map keyed by the (global) edge; face boundary loops
//! are re-expanded through it, and the cells whose faces changed are re-triangulated, until no cell
//! misses an edge.
use crate::arrangement::{Arrangement, VertexPool};
use smallvec::SmallVec;
use std::collections::HashMap;

#[derive(Clone, Debug, Default)]
pub struct Splits {
    pub mid: HashMap<(u32, u32), u32>,
}

impl Splits {
    /// Split global edge (a,b) at its midpoint (once); returns the Steiner vertex.
    pub fn split(&mut self, pool: &mut VertexPool, a: u32, b: u32) -> u32 {
        let k = super::cell_input::edge_key(a, b);
        if let Some(&m) = self.mid.get(&k) {
            return m;
        }
        let (ta, tb) = (&pool.tags[a as usize], &pool.tags[b as usize]);
        let mut tags: SmallVec<[u32; 3]> = SmallVec::new();
        let mut uv: SmallVec<[[f64; 2]; 3]> = SmallVec::new();
        for (i, &p) in ta.iter().enumerate() {
            if let Some(j) = tb.iter().position(|&q| q == p) {
                let (x, y) = (pool.uv[a as usize][i], pool.uv[b as usize][j]);
                tags.push(p);
                uv.push([0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])]);
            }
        }
        let (pa, pb) = (pool.positions[a as usize], pool.positions[b as usize]);
        let m = pool.positions.len() as u32;
        pool.positions.push([
            0.5 * (pa[0] + pb[0]),
            0.5 * (pa[1] + pb[1]),
            0.5 * (pa[2] + pb[2]),
        ]);
        pool.tags.push(tags);
        pool.uv.push(uv);
        pool.on_segment.insert(m, segment_of(pool, a, b));
        self.mid.insert(k, m);
        m
    }

    /// A loop of global ids with every split edge replaced by its (recursively split) halves.
    pub fn expand(&self, l: &[u32]) -> Vec<u32> {
        let mut out = Vec::with_capacity(l.len());
        for i in 0..l.len() {
            self.push_edge(l[i], l[(i + 1) % l.len()], &mut out);
        }
        out
    }

    fn push_edge(&self, a: u32, b: u32, out: &mut Vec<u32>) {
        // iterative in-order expansion: emit a, then the split points between a and b
        let mut stack = vec![(a, b)];
        while let Some((x, y)) = stack.pop() {
            match self.mid.get(&super::cell_input::edge_key(x, y)) {
                Some(&m) => {
                    stack.push((m, y));
                    stack.push((x, m));
                }
                None => out.push(x),
            }
        }
    }
}

/// The contour edge that edge (a, b) is a part of: the segment a split point of either end lies
/// on when the other end is on it too, else (a, b) itself.
fn segment_of(pool: &VertexPool, a: u32, b: u32) -> [u32; 2] {
    let on = |v: u32, s: &[u32; 2]| s.contains(&v) || pool.on_segment.get(&v) == Some(s);
    for v in [a, b] {
        if let Some(s) = pool.on_segment.get(&v) {
            if on(a, s) && on(b, s) {
                return *s;
            }
        }
    }
    [a.min(b), a.max(b)]
}

/// Boundary loops (outer and holes) of every face, global ids, splits applied.
pub fn face_loops(arr: &Arrangement, splits: &Splits) -> Vec<Vec<Vec<u32>>> {
    use rayon::prelude::*;
    // a dense sweep has most of a million faces, every round
    arr.faces
        .par_iter()
        .map(|f| {
            f.pieces
                .iter()
                .flat_map(|p| std::iter::once(&p.outer).chain(p.holes.iter()))
                .filter(|l| l.len() >= 3)
                .map(|l| splits.expand(l))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use smallvec::smallvec;
    #[test]
    fn split_and_expand() {
        let mut pool = VertexPool::default();
        for (p, uv) in [
            ([0.0, 0.0, 0.0], [0.0, 0.0]),
            ([2.0, 0.0, 0.0], [2.0, 0.0]),
            ([0.0, 2.0, 0.0], [0.0, 2.0]),
        ] {
            pool.positions.push(p);
            pool.tags.push(smallvec![3]);
            pool.uv.push(smallvec![uv]);
        }
        let mut s = Splits::default();
        let m = s.split(&mut pool, 1, 0);
        assert_eq!(m, 3);
        assert_eq!(pool.positions[3], [1.0, 0.0, 0.0]);
        assert_eq!(pool.uv[3][0], [1.0, 0.0]);
        let m2 = s.split(&mut pool, 0, 3);
        assert_eq!(s.expand(&[0, 1, 2]), vec![0, m2, 3, 1, 2]);
        assert_eq!(s.split(&mut pool, 0, 1), 3);
        // both split points lie on the contour edge (0, 1)
        assert_eq!(pool.on_segment[&3], [0, 1]);
        assert_eq!(pool.on_segment[&m2], [0, 1]);
    }
}
