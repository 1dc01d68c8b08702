//! A plain tetrahedral complex in local vertex ids: tetrahedra, face neighbours and vertex stars.
//! Built from any list of positively oriented tetrahedra (the Delaunay kernel's finite tets, or a
//! hand-built complex in tests), so the pruning code does not depend on the kernel's internals.
use super::cell_input::IdMap;

pub const NONE: u32 = u32::MAX;

/// The six edges of a tetrahedron as local index pairs; edge `k` is opposite edge `5 - k`.
pub const TET_EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

#[derive(Clone, Debug, Default)]
pub struct Complex {
    pub tets: Vec<[u32; 4]>,
    /// Neighbour across the face opposite vertex `i`, `NONE` on the hull.
    pub nbr: Vec<[u32; 4]>,
    /// Tetrahedra incident to each vertex.
    pub star: Vec<Vec<u32>>,
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
        let mut star = vec![Vec::new(); n_vertices];
        for (ti, t) in tets.iter().enumerate() {
            for &v in t {
                star[v as usize].push(ti as u32);
            }
        }
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
    }
}
