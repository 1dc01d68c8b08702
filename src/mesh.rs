//! Plain mesh containers shared by I/O, the engines and the evaluation tools.
use serde::{Deserialize, Serialize};

/// A triangle surface. Triangles are counter-clockwise seen from outside when the mesh is a solid's boundary.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TriMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

/// A tetrahedral mesh. Tetrahedra have positive volume: (b−a)·((c−a)×(d−a)) > 0, i.e. `robust::orient3d(a,b,c,d) < 0`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TetMesh {
    pub vertices: Vec<[f64; 3]>,
    pub tets: Vec<[u32; 4]>,
}
