//! Queries of a triangulation: vertices and their tags, tetrahedra, facets and edges, point
//! location, the tet mesh, validity and memory.
use super::tds::NONE;
use super::{
    insert, norm, pred, validate, Delaunay, Location, PointTags, TetId, VertexId, INFINITE,
};

impl Delaunay {
    /// Pairs (dropped, kept) of vertices merged because they are at exactly the same position.
    pub fn duplicates(&self) -> &[(VertexId, VertexId)] {
        &self.dups
    }

    /// Number of vertex ids handed out (including merged duplicates).
    pub fn num_vertices(&self) -> usize {
        self.int.len()
    }

    pub fn point(&self, v: VertexId) -> [f64; 3] {
        self.pts[self.int[v as usize] as usize]
    }

    /// The tags of vertex `v` (`None` on a triangulation built untagged).
    pub fn point_tags(&self, v: VertexId) -> Option<&PointTags> {
        self.tagged
            .then(|| &self.tags[self.int[v as usize] as usize])
    }

    /// Whether the triangulation was built by [`Delaunay::try_new_tagged`].
    pub fn is_tagged(&self) -> bool {
        self.tagged
    }

    /// The hull facets whose three vertices lie on `plane` (tagged triangulations; empty otherwise),
    /// as vertex triples ordered as [`Delaunay::facet_vertices`]: the restriction of the
    /// triangulation to a face plane of the point set, which the tag rules make the 2D Delaunay
    /// triangulation of the plane's points.
    pub fn plane_hull_triangles(&self, plane: u32) -> Vec<[VertexId; 3]> {
        if !self.tagged {
            return Vec::new();
        }
        self.facets()
            .filter(|&(t, i)| self.is_infinite(self.tds.tets[t as usize].n[i as usize]))
            .map(|(t, i)| self.facet_vertices(t, i))
            .filter(|f| {
                f.iter()
                    .all(|&w| self.tags[self.int[w as usize] as usize].on(plane))
            })
            .collect()
    }

    /// Affine dimension of the points: -1 (none), 0, 1, 2 (no tetrahedra) or 3.
    pub fn dimension(&self) -> i8 {
        self.dim
    }

    /// Finite, alive tetrahedra.
    pub fn tets(&self) -> impl Iterator<Item = TetId> + '_ {
        (0..self.tds.tets.len() as u32).filter(move |&t| {
            let tt = &self.tds.tets[t as usize];
            !tt.is_dead() && !tt.is_infinite()
        })
    }

    /// All alive tetrahedra, infinite ones included.
    pub fn all_tets(&self) -> impl Iterator<Item = TetId> + '_ {
        (0..self.tds.tets.len() as u32).filter(move |&t| !self.tds.tets[t as usize].is_dead())
    }

    pub fn num_finite_tets(&self) -> usize {
        self.nfinite
    }

    /// Number of tetrahedron slots: every [`TetId`] (alive or dead, finite or infinite) is below it,
    /// so arrays indexed by tetrahedron can be sized by it.
    pub fn num_tet_slots(&self) -> usize {
        self.tds.tets.len()
    }

    /// Vertices of `t`; finite tetrahedra have positive volume (see the module doc). Infinite ones
    /// contain [`INFINITE`] and are positive when ∞ is replaced by a point beyond their hull facet.
    #[inline]
    pub fn tet_vertices(&self, t: TetId) -> [VertexId; 4] {
        self.tds.tets[t as usize].v.map(|w| self.external(w))
    }

    #[inline]
    pub(super) fn external(&self, w: u32) -> u32 {
        if w == INFINITE {
            INFINITE
        } else {
            self.ext[w as usize]
        }
    }

    /// Neighbour i is opposite vertex i (may be infinite).
    #[inline]
    pub fn tet_neighbors(&self, t: TetId) -> [TetId; 4] {
        self.tds.tets[t as usize].n
    }

    #[inline]
    pub fn is_infinite(&self, t: TetId) -> bool {
        self.tds.tets[t as usize].is_infinite()
    }

    /// Finite tetrahedra incident to `v` (a merged duplicate answers for its kept vertex).
    pub fn vertex_tets(&self, v: VertexId) -> Vec<TetId> {
        let Some(&w) = self.int.get(v as usize) else {
            return Vec::new();
        };
        let t0 = self.vtet[w as usize];
        if t0 == NONE {
            return Vec::new();
        }
        let mut seen = vec![t0];
        let mut k = 0;
        while k < seen.len() {
            let tt = &self.tds.tets[seen[k] as usize];
            k += 1;
            for i in 0..4 {
                if tt.v[i] != w && !seen.contains(&tt.n[i]) {
                    seen.push(tt.n[i]);
                }
            }
        }
        seen.retain(|&t| !self.is_infinite(t));
        seen
    }

    /// The vertex kept for `v` (itself unless `v` was merged into another vertex).
    pub fn canonical(&self, v: VertexId) -> VertexId {
        self.ext[self.int[v as usize] as usize]
    }

    /// Locates `p` (see [`Location`]).
    pub fn locate(&self, p: [f64; 3]) -> Location {
        if self.dim < 3 {
            return Location::NoTets;
        }
        let q = norm(p);
        let mut rng = 0x1234_5678;
        // the query may lie outside the box of the vertices: bounds for both
        let (mut lo, mut hi) = (self.lo, self.hi);
        for k in 0..3 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
        let sb = pred::Bounds::for_extent(pred::Bounds::extent(lo, hi));
        let t = insert::walk(&self.tds.tets, &self.pts, q, self.hint, &mut rng, &sb);
        let tt = &self.tds.tets[t as usize];
        if tt.is_infinite() {
            return Location::Outside(t);
        }
        for w in tt.v {
            if self.pts[w as usize] == q {
                return Location::Vertex(self.ext[w as usize]);
            }
        }
        Location::InTet(t)
    }

    /// Each triangle of the triangulation once, as (tet, i): the facet of finite tetrahedron `tet`
    /// opposite its vertex i (hull facets included, reported from their finite side).
    pub fn facets(&self) -> impl Iterator<Item = (TetId, u8)> + '_ {
        self.tets().flat_map(move |t| {
            (0..4u8).filter_map(move |i| {
                let n = self.tds.tets[t as usize].n[i as usize];
                (self.is_infinite(n) || t < n).then_some((t, i))
            })
        })
    }

    /// The three vertices (a,b,c) of facet (t, i), counter-clockwise seen from vertex i, i.e.
    /// `pred::orient(a,b,c,v_i) > 0` (the normal (b-a)×(c-a) points into `t`).
    pub fn facet_vertices(&self, t: TetId, i: u8) -> [VertexId; 3] {
        let v = self.tet_vertices(t);
        const F: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
        let f = F[i as usize];
        [v[f[0]], v[f[1]], v[f[2]]]
    }

    /// Every finite edge once, as (smaller id, larger id), sorted.
    pub fn edges(&self) -> Vec<[VertexId; 2]> {
        let mut e: Vec<[VertexId; 2]> = self
            .tets()
            .flat_map(|t| {
                let v = self.tet_vertices(t);
                [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
                    .map(|(a, b)| [v[a].min(v[b]), v[a].max(v[b])])
            })
            .collect();
        e.sort_unstable();
        e.dedup();
        e
    }

    /// Finite tetrahedra as a mesh over all external vertex ids (merged duplicates stay as unused
    /// vertices), positively oriented as [`Delaunay::tet_vertices`].
    pub fn to_tet_mesh(&self) -> crate::mesh::TetMesh {
        crate::mesh::TetMesh {
            vertices: (0..self.int.len() as u32).map(|v| self.point(v)).collect(),
            tets: self.tets().map(|t| self.tet_vertices(t)).collect(),
        }
    }

    /// Checks every invariant exactly (see `validate.rs`): adjacency symmetry, positive orientation,
    /// local Delaunay property of every facet (exact and perturbed), hull convexity, vertex coverage.
    pub fn is_valid(&self) -> Result<(), String> {
        validate::check(self)
    }

    /// Bytes held by the kernel's arrays (capacity).
    pub fn memory_bytes(&self) -> usize {
        self.pts.capacity() * 24
            + (self.ext.capacity() + self.int.capacity() + self.vtet.capacity()) * 4
            + self.tds.bytes()
    }
}
