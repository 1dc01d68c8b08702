//! Triangulation data structure: tetrahedra in one flat array (4 vertices + 4 neighbours, 32 bytes,
//! neighbour i opposite vertex i), a free list of dead slots. The two scratch marks of an insertion
//! live in the top bits of `n[0]` and `n[1]` (no side array: testing a mark reads the record the
//! conflict test needs anyway, one cache miss instead of two).
//! Purely combinatorial; geometry lives in `pred` and `insert`.

/// Vertex id of the point at infinity (internal and external).
pub const INFINITE: u32 = u32::MAX;
/// "No tetrahedron".
pub const NONE: u32 = u32::MAX;
/// Marks a freed slot in `v[0]`.
pub const DEAD: u32 = u32::MAX - 1;

#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct Tet {
    pub v: [u32; 4],
    pub n: [u32; 4],
}

impl Tet {
    #[inline]
    pub fn is_infinite(&self) -> bool {
        (self.v[0] == INFINITE)
            | (self.v[1] == INFINITE)
            | (self.v[2] == INFINITE)
            | (self.v[3] == INFINITE)
    }
    #[inline]
    pub fn is_dead(&self) -> bool {
        self.v[0] == DEAD
    }
    #[inline]
    pub fn index_of_vertex(&self, w: u32) -> usize {
        if self.v[0] == w {
            0
        } else if self.v[1] == w {
            1
        } else if self.v[2] == w {
            2
        } else {
            debug_assert_eq!(self.v[3], w);
            3
        }
    }
    #[inline]
    pub fn index_of_neighbor(&self, t: u32) -> usize {
        if self.n[0] == t {
            0
        } else if self.n[1] == t {
            1
        } else if self.n[2] == t {
            2
        } else {
            debug_assert_eq!(self.n[3], t);
            3
        }
    }
}

#[derive(Clone, Debug, Default)]
pub struct Tds {
    pub tets: Vec<Tet>,
    pub free: Vec<u32>,
}

/// Scratch mark on `n[0]`: the slot is in the conflict region of the current insertion.
pub const IN_CAVITY: u32 = 1 << 31;
/// Scratch mark on `n[1]`: the slot was tested and is not in conflict.
pub const OUTSIDE: u32 = 1 << 31;
/// Mask of a neighbour id without marks (tetrahedron ids stay below 2^31, see `alloc`).
pub const ID_MASK: u32 = !(1 << 31);

impl Tds {
    #[inline]
    pub fn alloc(&mut self, v: [u32; 4]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tets[t as usize] = Tet { v, n: [NONE; 4] };
            t
        } else {
            self.push(v)
        }
    }

    /// A fresh slot at the end of the array.
    #[inline]
    pub fn push(&mut self, v: [u32; 4]) -> u32 {
        let t = self.tets.len() as u32;
        // Ids must leave the top bit free for the scratch marks (2^31 tets would be 64 GiB).
        assert!(t < ID_MASK, "more than 2^31 tetrahedra");
        self.tets.push(Tet { v, n: [NONE; 4] });
        t
    }

    #[inline]
    pub fn kill(&mut self, t: u32) {
        self.tets[t as usize].v[0] = DEAD;
        self.free.push(t);
    }

    pub fn bytes(&self) -> usize {
        self.tets.capacity() * std::mem::size_of::<Tet>() + self.free.capacity() * 4
    }
}

/// The two positions of 0..4 other than i and j.
#[inline]
pub fn other_two(i: usize, j: usize) -> (usize, usize) {
    const T: [[(u8, u8); 4]; 4] = [
        [(2, 3), (2, 3), (1, 3), (1, 2)],
        [(2, 3), (0, 3), (0, 3), (0, 2)],
        [(1, 3), (0, 3), (0, 1), (0, 1)],
        [(1, 2), (0, 2), (0, 1), (0, 1)],
    ];
    let (a, b) = T[i][j];
    (a as usize, b as usize)
}

/// Sorted vertex triple of facet i of `v` (for matching facets).
pub fn facet_key(v: [u32; 4], i: usize) -> [u32; 3] {
    let mut f = [0u32; 3];
    let mut k = 0;
    for (m, &w) in v.iter().enumerate() {
        if m != i {
            f[k] = w;
            k += 1;
        }
    }
    f.sort_unstable();
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn other_two_table() {
        for i in 0..4 {
            for j in 0..4 {
                if i == j {
                    continue;
                }
                let (a, b) = other_two(i, j);
                assert!(a < b && a != i && a != j && b != i && b != j);
            }
        }
    }
}
