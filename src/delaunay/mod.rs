//! Our exact 3D Delaunay kernel. Contract used by the engines:
//! ```ignore
//! let mut dt = Delaunay::new(&points);          // merged duplicates reported in dt.duplicates()
//! dt.insert(p) -> VertexId                      // more points later (conformity splitting)
//! dt.tets() -> impl Iterator<Item = TetId>      // finite, alive tetrahedra
//! dt.tet_vertices(t) -> [VertexId; 4]           // positively oriented
//! dt.tet_neighbors(t) -> [TetId; 4]             // neighbour i is opposite vertex i (infinite tets have a ghost vertex)
//! dt.is_infinite(t), dt.point(v), dt.vertex_tets(v), dt.locate(p)
//! ```
//! Vertex ids are the input indices (0..n) for `new`, then increasing for `insert`.
