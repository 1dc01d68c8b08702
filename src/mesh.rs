//! Plain mesh containers shared by I/O, the engines and the evaluation tools.
use serde::{Deserialize, Serialize};

/// A triangle surface. Triangles are counter-clockwise seen from outside when the mesh is a solid's boundary.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TriMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// The triangles `tris` over `positions`, keeping only the vertices they use, in increasing
    /// index.
    pub fn with_used_vertices(positions: &[[f64; 3]], tris: &[[u32; 3]]) -> TriMesh {
        let mut used = vec![false; positions.len()];
        for &v in tris.iter().flatten() {
            used[v as usize] = true;
        }
        let mut index = vec![u32::MAX; positions.len()];
        let mut vertices = Vec::new();
        for (v, _) in used.iter().enumerate().filter(|(_, &u)| u) {
            index[v] = vertices.len() as u32;
            vertices.push(positions[v]);
        }
        TriMesh {
            vertices,
            triangles: tris.iter().map(|t| t.map(|v| index[v as usize])).collect(),
        }
    }

    /// Why this mesh cannot be measured, if it cannot: a triangle index past the vertices or a
    /// coordinate that is not finite (meshes made by callers, e.g. from arrays, not read from files).
    pub fn problem(&self) -> Option<String> {
        let n = self.vertices.len();
        if let Some(i) = self
            .vertices
            .iter()
            .position(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Some(format!("vertex {i} has a coordinate that is not finite"));
        }
        self.triangles
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= n))
            .map(|i| format!("triangle {i} has a vertex index out of range ({n} vertices)"))
    }
}

/// A tetrahedral mesh. Tetrahedra have positive volume: (b−a)·((c−a)×(d−a)) > 0, i.e. `robust::orient3d(a,b,c,d) < 0`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TetMesh {
    pub vertices: Vec<[f64; 3]>,
    pub tets: Vec<[u32; 4]>,
}

/// An element index stored in [`Stars`] (`u32` for compact tables, `usize` where callers index).
pub trait StarIndex: Copy + Default {
    fn from_index(i: usize) -> Self;
}

impl StarIndex for u32 {
    fn from_index(i: usize) -> u32 {
        i as u32
    }
}

impl StarIndex for usize {
    fn from_index(i: usize) -> usize {
        i
    }
}

/// The elements (triangles, tetrahedra) incident to each vertex, ascending, in one array:
/// `stars[v]` is a slice. An element with a repeated vertex is listed once per corner there.
#[derive(Clone, Debug, Default)]
pub struct Stars<I = u32> {
    /// `items[start[v]..start[v + 1]]` is vertex v's star.
    start: Vec<usize>,
    items: Vec<I>,
}

impl<I: StarIndex> Stars<I> {
    /// The stars of `n_vertices` vertices in `elements` (every vertex id below `n_vertices`).
    pub fn new<const K: usize>(n_vertices: usize, elements: &[[u32; K]]) -> Stars<I> {
        Self::new_where(n_vertices, elements, |_| true)
    }

    /// [`Stars::new`] over the elements whose index passes `keep`.
    pub fn new_where<const K: usize>(
        n_vertices: usize,
        elements: &[[u32; K]],
        keep: impl Fn(usize) -> bool,
    ) -> Stars<I> {
        let mut start = vec![0usize; n_vertices + 1];
        for (i, e) in elements.iter().enumerate() {
            if keep(i) {
                for &v in e {
                    start[v as usize + 1] += 1;
                }
            }
        }
        for v in 0..n_vertices {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut items = vec![I::default(); start[n_vertices]];
        for (i, e) in elements.iter().enumerate() {
            if keep(i) {
                for &v in e {
                    items[fill[v as usize]] = I::from_index(i);
                    fill[v as usize] += 1;
                }
            }
        }
        Stars { start, items }
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<I> std::ops::Index<usize> for Stars<I> {
    type Output = [I];
    fn index(&self, v: usize) -> &[I] {
        &self.items[self.start[v]..self.start[v + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stars_list_incident_elements_ascending() {
        let tris = [[0u32, 1, 2], [2, 1, 3], [3, 3, 0]];
        let s: Stars<usize> = Stars::new(5, &tris);
        assert_eq!(s.len(), 5);
        assert_eq!(&s[0], &[0, 2]);
        assert_eq!(&s[1], &[0, 1]);
        assert_eq!(&s[3], &[1, 2, 2]);
        assert!(s[4].is_empty());
        let kept: Stars<u32> = Stars::new_where(5, &tris, |i| i != 1);
        assert_eq!(&kept[1], &[0]);
        assert_eq!(&kept[3], &[2, 2]);
    }
}
