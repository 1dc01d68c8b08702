//! A plain tetrahedral complex in local vertex ids: tetrahedra, face neighbours and vertex stars.
//! Built from any list of positively oriented tetrahedra (the Delaunay kernel's finite tets, or a
//! hand-built complex in tests), so the pruning code does not depend on the kernel's internals.
//! [`Complex::from_delaunay`] builds the same complex from the kernel's own adjacency (no facet
//! hashing).
use super::cell_input::IdMap;
use crate::delaunay::Delaunay;
use crate::mesh::Stars;

pub const NONE: u32 = u32::MAX;

/// The six edges of a tetrahedron as local index pairs; edge `k` is opposite edge `5 - k`.
pub const TET_EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

#[derive(Clone, Debug, Default)]
pub struct Complex {
    pub tets: Vec<[u32; 4]>,
    /// Neighbour across the face opposite vertex `i`, `NONE` on the hull.
    pub nbr: Vec<[u32; 4]>,
    /// Tetrahedra incident to each vertex.
    pub star: Stars,
}

/// Face opposite local vertex `i`, oriented outward for a positively oriented tetrahedron.
pub fn outward_face(t: &[u32; 4], i: usize) -> [u32; 3] {
    match i {
        0 => [t[1], t[3], t[2]],
        1 => [t[0], t[2], t[3]],
        2 => [t[0], t[3], t[1]],
        _ => [t[0], t[1], t[2]],
    }
}

fn key3(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// `t` rotated by an even permutation (keeping its orientation) so that t[0] is its smallest vertex
/// and t[1] the smallest of the other three; with `pos[k]`, the position in `t` of the result's
/// vertex k.
pub fn canonical_tet(t: [u32; 4]) -> ([u32; 4], [u8; 4]) {
    let p = |m: [usize; 4]| (m.map(|i| t[i]), m.map(|i| i as u8));
    let [a, b, c, d] = t;
    let m = if a <= b.min(c).min(d) {
        [0, 1, 2, 3]
    } else if b <= c.min(d) {
        [1, 0, 3, 2]
    } else if c <= d {
        [2, 3, 0, 1]
    } else {
        [3, 2, 1, 0]
    };
    let [b, c, d] = [t[m[1]], t[m[2]], t[m[3]]];
    if b <= c.min(d) {
        p(m)
    } else if c <= d {
        p([m[0], m[2], m[3], m[1]])
    } else {
        p([m[0], m[3], m[1], m[2]])
    }
}

impl Complex {
    pub fn new(n_vertices: usize, tets: Vec<[u32; 4]>) -> Complex {
        let mut nbr = vec![[NONE; 4]; tets.len()];
        let mut open: IdMap<[u32; 3], (u32, u8)> =
            IdMap::with_capacity_and_hasher(tets.len() * 2, Default::default());
        for (ti, t) in tets.iter().enumerate() {
            for i in 0..4 {
                let k = key3(outward_face(t, i));
                if let Some((tj, j)) = open.remove(&k) {
                    nbr[ti][i] = tj;
                    nbr[tj as usize][j as usize] = ti as u32;
                } else {
                    open.insert(k, (ti as u32, i as u8));
                }
            }
        }
        let star = Stars::new(n_vertices, &tets);
        Complex { tets, nbr, star }
    }

    /// `Complex::new(n_vertices, finite_tets(dt))` (see `cell::finite_tets`: tets positively
    /// oriented in `robust`'s convention, canonically rotated, sorted), with the neighbours read from
    /// the kernel instead of matched by hashing facets.
    pub fn from_delaunay(n_vertices: usize, dt: &Delaunay) -> Complex {
        // (canonical tet, kernel slot, kernel position of each of its vertices)
        let rows: Vec<([u32; 4], u32, [u8; 4])> = dt
            .tets()
            .map(|t| {
                let v = dt.tet_vertices(t);
                // the kernel's positive volume is robust's negative orientation: swap two vertices
                let (c, pos) = canonical_tet([v[0], v[1], v[3], v[2]]);
                (c, t, pos.map(|k| [0u8, 1, 3, 2][k as usize]))
            })
            .collect();
        // Sorted by canonical tet: counting sort on the first (smallest) vertex, then each bucket
        // (a few tets) by the rest; tets are distinct, so the order is unique.
        let nv = rows.iter().map(|r| r.0[0] as usize + 1).max().unwrap_or(0);
        let mut start = vec![0u32; nv + 1];
        for r in &rows {
            start[r.0[0] as usize + 1] += 1;
        }
        for v in 0..nv {
            start[v + 1] += start[v];
        }
        let mut order = vec![0u32; rows.len()];
        let mut next = start.clone();
        for (k, r) in rows.iter().enumerate() {
            let v = r.0[0] as usize;
            order[next[v] as usize] = k as u32;
            next[v] += 1;
        }
        for v in 0..nv {
            order[start[v] as usize..start[v + 1] as usize]
                .sort_unstable_by_key(|&k| rows[k as usize].0);
        }
        let rows: Vec<([u32; 4], u32, [u8; 4])> = order.iter().map(|&k| rows[k as usize]).collect();
        // kernel slot → index here (NONE for infinite and dead slots)
        let mut rank = vec![NONE; dt.num_tet_slots()];
        for (k, r) in rows.iter().enumerate() {
            rank[r.1 as usize] = k as u32;
        }
        let nbr = rows
            .iter()
            .map(|&(_, t, pos)| {
                let n = dt.tet_neighbors(t);
                pos.map(|p| rank[n[p as usize] as usize])
            })
            .collect();
        let tets: Vec<[u32; 4]> = rows.into_iter().map(|r| r.0).collect();
        let star = Stars::new(n_vertices, &tets);
        Complex { tets, nbr, star }
    }

    pub fn len(&self) -> usize {
        self.tets.len()
    }

    pub fn is_empty(&self) -> bool {
        self.tets.is_empty()
    }

    /// Local index (0..4) of vertex `v` in tet `t`.
    pub fn index_of(&self, t: u32, v: u32) -> Option<usize> {
        self.tets[t as usize].iter().position(|&w| w == v)
    }

    /// Local index in `n` of the vertex opposite the face shared with `t`.
    pub fn back_index(&self, n: u32, t: u32) -> usize {
        self.nbr[n as usize]
            .iter()
            .position(|&w| w == t)
            .expect("neighbour relation is symmetric")
    }

    /// True when some tetrahedron accepted by `alive` contains both `a` and `b`.
    pub fn has_edge(&self, a: u32, b: u32, alive: impl Fn(u32) -> bool) -> bool {
        self.star[a as usize]
            .iter()
            .any(|&t| alive(t) && self.tets[t as usize].contains(&b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn neighbours_are_found() {
        // two tets sharing face (0,1,2)
        let c = Complex::new(5, vec![[0, 1, 2, 3], [0, 2, 1, 4]]);
        assert_eq!(c.nbr[0][3], 1);
        assert_eq!(c.nbr[1][3], 0);
        assert_eq!(c.nbr[0][0], NONE);
        assert_eq!(c.back_index(1, 0), 3);
        assert!(c.has_edge(3, 0, |_| true));
        assert!(!c.has_edge(3, 4, |_| true));
        assert_eq!(c.star.len(), 5);
        assert_eq!(&c.star[0], &[0, 1]);
        assert_eq!(&c.star[4], &[1]);
    }

    #[test]
    fn canonical_rotation_is_even_and_tracks_positions() {
        for t in [
            [0, 1, 2, 3],
            [3, 2, 1, 0],
            [2, 0, 3, 1],
            [1, 3, 0, 2],
            [3, 1, 2, 0],
        ] {
            let (c, pos) = canonical_tet(t);
            assert_eq!(c[0], *t.iter().min().unwrap());
            assert!(c[1] < c[2] && c[1] < c[3]);
            assert_eq!(pos.map(|p| t[p as usize]), c);
            // even permutation: an even number of inversions
            let inv = (0..4)
                .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                .filter(|&(i, j)| pos[i] > pos[j])
                .count();
            assert_eq!(inv % 2, 0, "{t:?}");
        }
    }

    #[test]
    fn from_delaunay_equals_the_hashed_complex() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        // points on the faces of a tilted box (coplanar groups, as in a cell), then insertions
        let mut pts: Vec<[f64; 3]> = (0..300)
            .map(|k| {
                let (a, b): (f64, f64) = (r.gen(), r.gen());
                let c = (k % 2) as f64;
                let p = match k % 6 / 2 {
                    0 => [c, a, b],
                    1 => [a, c, b],
                    _ => [a, b, c],
                };
                [p[0] + 0.3 * p[1], p[1] - 0.2 * p[2], p[2] + 0.1 * p[0]]
            })
            .collect();
        let mut dt = Delaunay::new(&pts);
        for _ in 0..50 {
            let p = [r.gen(), r.gen(), 0.5];
            pts.push(p);
            dt.insert(p);
        }
        let a = Complex::from_delaunay(pts.len(), &dt);
        let b = Complex::new(pts.len(), crate::bm::cell::finite_tets(&dt));
        assert!(a.len() > 300);
        assert_eq!(a.tets, b.tets);
        assert_eq!(a.nbr, b.nbr);
        for v in 0..pts.len() {
            assert_eq!(&a.star[v], &b.star[v]);
        }
    }
}
