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
//!
//! **Orientation convention.** Every finite tetrahedron `[p0,p1,p2,p3]` returned by
//! [`Delaunay::tet_vertices`] has positive volume: `(p1-p0)·((p2-p0)×(p3-p0)) > 0`, which is
//! `robust::orient3d(p0,p1,p2,p3) < 0` (see [`pred::orient`]).
//!
//! Design: flat arrays of tetrahedra (4 vertices, 4 neighbours, neighbour i opposite vertex i), a free
//! list, one infinite vertex [`INFINITE`] closing the hull (as in CGAL), Bowyer–Watson insertion with a
//! stochastic visibility walk, points inserted in BRIO + Hilbert order. Every decision is exact and
//! ties are broken by symbolic perturbation (see [`pred`]), so the result is a triangulation of the
//! Delaunay subdivision for any input, with no flat tetrahedron even for coplanar hull points.
pub mod gen;
#[allow(clippy::needless_range_loop)]
pub mod pred;
pub mod sort;
#[cfg(feature = "tetgen")]
pub mod tetgen;
mod validate;
pub mod xyz;

use pred::P;
use std::collections::HashMap;

pub type VertexId = u32;
pub type TetId = u32;

/// The vertex at infinity: every hull facet (a,b,c) carries an infinite tetrahedron (a,b,c,∞).
pub const INFINITE: VertexId = u32::MAX;
const NONE: u32 = u32::MAX;
const DEAD: u32 = u32::MAX - 1;

/// Where a query point lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// The point is exactly this vertex.
    Vertex(VertexId),
    /// The point is in this finite tetrahedron (closed: possibly on a facet or an edge of it).
    InTet(TetId),
    /// The point is strictly outside the convex hull, beyond the hull facet of this infinite tetrahedron.
    Outside(TetId),
    /// The triangulation has no tetrahedra yet (fewer than 4 affinely independent points).
    NoTets,
}

/// Exact 3D Delaunay triangulation.
#[derive(Clone, Debug)]
pub struct Delaunay {
    pts: Vec<P>,
    /// Per tetrahedron: vertices (or `INFINITE`), `DEAD` in slot 0 when freed.
    tv: Vec<[u32; 4]>,
    /// Per tetrahedron: neighbour opposite vertex i.
    tn: Vec<[u32; 4]>,
    free: Vec<u32>,
    /// One incident tetrahedron per vertex (NONE for merged duplicates / not yet triangulated).
    vtet: Vec<u32>,
    dups: Vec<(VertexId, VertexId)>,
    /// Affine dimension of the vertex set so far (-1 empty .. 3).
    dim: i8,
    /// While `dim < 3`: distinct vertices waiting for a full-dimensional simplex.
    pending: Vec<VertexId>,
    pending_keys: HashMap<[u64; 3], VertexId>,
    nfinite: usize,
    hint: u32,
    rng: u64,
    // Scratch buffers reused by every insertion.
    mark: Vec<u32>,
    stamp: u32,
    stack: Vec<u32>,
    cavity: Vec<u32>,
    boundary: Vec<(u32, u8)>,
    edges: HashMap<u64, (u32, u8)>,
}

impl Delaunay {
    /// Triangulates `points`; vertex ids are the input indices. Points at exactly the same position are
    /// merged (see [`Delaunay::duplicates`]). Fewer than 4 affinely independent points give no
    /// tetrahedra (see [`Delaunay::dimension`]). Non-finite coordinates are not allowed (use
    /// [`Delaunay::try_new`] to get an error instead of a panic).
    pub fn new(points: &[[f64; 3]]) -> Delaunay {
        Self::try_new(points).expect("Delaunay::new: non-finite coordinate")
    }

    /// Like [`Delaunay::new`], but rejects non-finite coordinates with `Error::Input`.
    pub fn try_new(points: &[[f64; 3]]) -> crate::Result<Delaunay> {
        if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(crate::Error::input(
                format!("point {i}"),
                "non-finite coordinate",
            ));
        }
        let mut dt = Delaunay::empty();
        dt.pts = points.iter().map(|p| norm(*p)).collect();
        dt.vtet = vec![NONE; points.len()];
        // Merge exact duplicates first so that the kept vertex is the smallest index.
        let mut first: HashMap<[u64; 3], u32> = HashMap::with_capacity(points.len());
        let mut distinct = Vec::with_capacity(points.len());
        for (i, p) in dt.pts.iter().enumerate() {
            let key = [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()];
            match first.entry(key) {
                std::collections::hash_map::Entry::Occupied(e) => {
                    dt.dups.push((i as u32, *e.get()))
                }
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i as u32);
                    distinct.push(i as u32);
                }
            }
        }
        drop(first);
        let sub: Vec<P> = distinct.iter().map(|&i| dt.pts[i as usize]).collect();
        let order: Vec<u32> = sort::brio_order(&sub)
            .into_iter()
            .map(|k| distinct[k as usize])
            .collect();
        dt.bootstrap(&order);
        Ok(dt)
    }

    fn empty() -> Delaunay {
        Delaunay {
            pts: Vec::new(),
            tv: Vec::new(),
            tn: Vec::new(),
            free: Vec::new(),
            vtet: Vec::new(),
            dups: Vec::new(),
            dim: -1,
            pending: Vec::new(),
            pending_keys: HashMap::new(),
            nfinite: 0,
            hint: 0,
            rng: 0x9E37_79B9_7F4A_7C15,
            mark: Vec::new(),
            stamp: 0,
            stack: Vec::new(),
            cavity: Vec::new(),
            boundary: Vec::new(),
            edges: HashMap::new(),
        }
    }

    /// Inserts the vertices of `order` (ids already in `pts`): gathers them while the dimension is
    /// below 3, builds the first tetrahedron as soon as possible, then inserts the rest.
    fn bootstrap(&mut self, order: &[u32]) {
        let mut k = 0;
        while self.dim < 3 && k < order.len() {
            self.add_pending(order[k]);
            k += 1;
        }
        for &v in &order[k..] {
            self.insert_vertex(v);
        }
    }

    /// Lower-dimensional phase: keep distinct points, and start the 3D triangulation when the new
    /// point leaves the affine hull of the previous ones.
    fn add_pending(&mut self, v: u32) {
        let p = self.pts[v as usize];
        let key = [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()];
        if let Some(&w) = self.pending_keys.get(&key) {
            self.dups.push((v, w));
            return;
        }
        self.pending_keys.insert(key, v);
        self.pending.push(v);
        let pp = |i: usize| self.pts[self.pending[i] as usize];
        let n = self.pending.len();
        self.dim = match self.dim {
            -1 => 0,
            0 => 1,
            1 => {
                if pred::collinear(pp(0), pp(1), p) {
                    1
                } else {
                    // keep the basis points first: move v to position 2
                    self.pending.swap(2, n - 1);
                    2
                }
            }
            2 => {
                if pred::orient(pp(0), pp(1), pp(2), p) == 0.0 {
                    2
                } else {
                    self.pending.swap(3, n - 1);
                    3
                }
            }
            d => d,
        };
        if self.dim == 3 {
            self.build_first_tet();
            let rest: Vec<u32> = self.pending[4..].to_vec();
            self.pending.clear();
            self.pending_keys = HashMap::new();
            for v in rest {
                self.insert_vertex(v);
            }
        }
    }

    /// The first positive tetrahedron from pending[0..4] and its four infinite neighbours.
    fn build_first_tet(&mut self) {
        let mut v = [
            self.pending[0],
            self.pending[1],
            self.pending[2],
            self.pending[3],
        ];
        let p = |i: u32| self.pts[i as usize];
        if pred::orient(p(v[0]), p(v[1]), p(v[2]), p(v[3])) < 0.0 {
            v.swap(0, 1);
        }
        let mut cells = vec![v];
        for i in 0..4 {
            // replacing v[i] by ∞ flips the side, so swap two finite vertices to stay positive
            let mut c = v;
            c[i] = INFINITE;
            c.swap((i + 1) % 4, (i + 2) % 4);
            cells.push(c);
        }
        for c in &cells {
            let t = self.alloc(*c);
            for &w in c {
                if w != INFINITE {
                    self.vtet[w as usize] = t;
                }
            }
        }
        // adjacency by matching facets (only 5 cells)
        for a in 0..5u32 {
            for i in 0..4 {
                let fa = facet_key(self.tv[a as usize], i);
                for b in 0..5u32 {
                    if a == b {
                        continue;
                    }
                    for j in 0..4 {
                        if facet_key(self.tv[b as usize], j) == fa {
                            self.tn[a as usize][i] = b;
                        }
                    }
                }
            }
        }
        self.nfinite = 1;
        self.hint = 0;
    }

    fn alloc(&mut self, v: [u32; 4]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tv[t as usize] = v;
            self.tn[t as usize] = [NONE; 4];
            t
        } else {
            self.tv.push(v);
            self.tn.push([NONE; 4]);
            self.mark.push(0);
            (self.tv.len() - 1) as u32
        }
    }

    #[inline]
    fn next_rand(&mut self) -> u32 {
        // xorshift64*
        self.rng ^= self.rng >> 12;
        self.rng ^= self.rng << 25;
        self.rng ^= self.rng >> 27;
        (self.rng.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 32) as u32
    }

    #[inline]
    fn tet_points(&self, t: u32) -> [P; 4] {
        let v = self.tv[t as usize];
        let p = |w: u32| {
            if w == INFINITE {
                [0.0; 3]
            } else {
                self.pts[w as usize]
            }
        };
        [p(v[0]), p(v[1]), p(v[2]), p(v[3])]
    }

    #[inline]
    fn inf_index(&self, t: u32) -> Option<usize> {
        self.tv[t as usize].iter().position(|&w| w == INFINITE)
    }

    /// Stochastic visibility walk from `start` to the tetrahedron containing `q` (closed), or to the
    /// infinite tetrahedron whose hull facet sees `q` strictly.
    fn walk(&mut self, q: P, start: u32) -> u32 {
        let mut t = start;
        if let Some(k) = self.inf_index(t) {
            t = self.tn[t as usize][k];
        }
        let mut prev = NONE;
        'outer: loop {
            let r = self.next_rand() as usize;
            let v = self.tv[t as usize];
            let pts = self.tet_points(t);
            for k in 0..4 {
                let i = (r + k) & 3;
                let n = self.tn[t as usize][i];
                if n == prev {
                    continue;
                }
                let mut s = pts;
                s[i] = q;
                if pred::orient(s[0], s[1], s[2], s[3]) < 0.0 {
                    prev = t;
                    t = n;
                    if self.tv[t as usize].contains(&INFINITE) {
                        return t;
                    }
                    continue 'outer;
                }
            }
            let _ = v;
            return t;
        }
    }

    fn locate_internal(&mut self, q: P) -> Location {
        if self.dim < 3 {
            return Location::NoTets;
        }
        let mut start = self.hint;
        if self.tv[start as usize][0] == DEAD {
            start = (0..self.tv.len() as u32)
                .find(|&t| self.tv[t as usize][0] != DEAD)
                .unwrap();
        }
        let t = self.walk(q, start);
        if self.tv[t as usize].contains(&INFINITE) {
            return Location::Outside(t);
        }
        for &w in &self.tv[t as usize] {
            if self.pts[w as usize] == q {
                return Location::Vertex(w);
            }
        }
        Location::InTet(t)
    }

    /// Perturbed conflict of tetrahedron `t` with point `q`.
    #[inline]
    fn conflict(&self, t: u32, q: P) -> bool {
        let pts = self.tet_points(t);
        match self.inf_index(t) {
            None => pred::conflict_finite(pts, q),
            Some(k) => {
                let n = self.tn[t as usize][k];
                let nv = self.tv[n as usize];
                let j = (0..4).find(|&j| self.tn[n as usize][j] == t).unwrap();
                let d = self.pts[nv[j] as usize];
                pred::conflict_infinite(pts, k, d, q)
            }
        }
    }

    /// Inserts vertex `v` (already in `pts`) into the 3D triangulation; returns the id that represents
    /// its position (v, or the kept vertex when v is a duplicate).
    fn insert_vertex(&mut self, v: u32) -> u32 {
        let q = self.pts[v as usize];
        let t0 = match self.locate_internal(q) {
            Location::Vertex(w) => {
                self.dups.push((v, w));
                return w;
            }
            Location::InTet(t) | Location::Outside(t) => t,
            Location::NoTets => unreachable!(),
        };
        // Grow the conflict region (a ball, star-shaped from q under the perturbation).
        self.stamp = self.stamp.wrapping_add(2);
        if self.stamp < 2 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 2;
        }
        let cs = self.stamp;
        let ns = self.stamp + 1;
        let mut stack = std::mem::take(&mut self.stack);
        let mut cavity = std::mem::take(&mut self.cavity);
        let mut boundary = std::mem::take(&mut self.boundary);
        stack.clear();
        cavity.clear();
        boundary.clear();
        self.mark[t0 as usize] = cs;
        stack.push(t0);
        cavity.push(t0);
        while let Some(c) = stack.pop() {
            for i in 0..4 {
                let n = self.tn[c as usize][i];
                let m = self.mark[n as usize];
                if m == cs {
                    continue;
                }
                if m == ns {
                    boundary.push((c, i as u8));
                    continue;
                }
                if self.conflict(n, q) {
                    self.mark[n as usize] = cs;
                    stack.push(n);
                    cavity.push(n);
                } else {
                    self.mark[n as usize] = ns;
                    boundary.push((c, i as u8));
                }
            }
        }
        // Star the cavity boundary from v.
        self.edges.clear();
        let mut last = NONE;
        for &(c, i) in &boundary {
            let i = i as usize;
            let mut vs = self.tv[c as usize];
            vs[i] = v;
            let nb = self.tn[c as usize][i];
            let nt = self.alloc(vs);
            last = nt;
            self.tn[nt as usize][i] = nb;
            let j = (0..4).find(|&j| self.tn[nb as usize][j] == c).unwrap();
            self.tn[nb as usize][j] = nt;
            if !vs.contains(&INFINITE) {
                self.nfinite += 1;
            }
            for (j, &w) in vs.iter().enumerate() {
                if j != i {
                    let (a, b) = other_two(i, j);
                    let (x, y) = (vs[a].min(vs[b]), vs[a].max(vs[b]));
                    let key = ((x as u64) << 32) | y as u64;
                    if let Some((ot, oj)) = self.edges.remove(&key) {
                        self.tn[nt as usize][j] = ot;
                        self.tn[ot as usize][oj as usize] = nt;
                    } else {
                        self.edges.insert(key, (nt, j as u8));
                    }
                }
                if w != INFINITE {
                    self.vtet[w as usize] = nt;
                }
            }
        }
        debug_assert!(self.edges.is_empty());
        for &c in &cavity {
            if !self.tv[c as usize].contains(&INFINITE) {
                self.nfinite -= 1;
            }
            self.tv[c as usize][0] = DEAD;
            self.free.push(c);
        }
        self.hint = last;
        self.stack = stack;
        self.cavity = cavity;
        self.boundary = boundary;
        v
    }

    /// Pairs (dropped, kept) of vertices merged because they are at exactly the same position.
    pub fn duplicates(&self) -> &[(VertexId, VertexId)] {
        &self.dups
    }

    /// Inserts a point; returns its new id, or the id of the existing vertex at exactly that position.
    /// Panics on non-finite coordinates.
    pub fn insert(&mut self, p: [f64; 3]) -> VertexId {
        assert!(
            p.iter().all(|c| c.is_finite()),
            "Delaunay::insert: non-finite coordinate"
        );
        let v = self.pts.len() as u32;
        self.pts.push(norm(p));
        self.vtet.push(NONE);
        if self.dim < 3 {
            let before = self.dups.len();
            self.add_pending(v);
            if self.dups.len() > before && self.dups[before].0 == v {
                return self.dups[before].1;
            }
            return v;
        }
        self.insert_vertex(v)
    }

    /// Number of vertex ids handed out (including merged duplicates).
    pub fn num_vertices(&self) -> usize {
        self.pts.len()
    }

    pub fn point(&self, v: VertexId) -> [f64; 3] {
        self.pts[v as usize]
    }

    /// All points by id (merged duplicates included).
    pub fn points(&self) -> &[[f64; 3]] {
        &self.pts
    }

    /// Affine dimension of the points: -1 (none), 0, 1, 2 (no tetrahedra) or 3.
    pub fn dimension(&self) -> i8 {
        self.dim
    }

    /// Finite, alive tetrahedra.
    pub fn tets(&self) -> impl Iterator<Item = TetId> + '_ {
        (0..self.tv.len() as u32).filter(move |&t| {
            let v = &self.tv[t as usize];
            v[0] != DEAD && !v.contains(&INFINITE)
        })
    }

    /// All alive tetrahedra, infinite ones included.
    pub fn all_tets(&self) -> impl Iterator<Item = TetId> + '_ {
        (0..self.tv.len() as u32).filter(move |&t| self.tv[t as usize][0] != DEAD)
    }

    pub fn num_finite_tets(&self) -> usize {
        self.nfinite
    }

    /// Vertices of `t`; finite tetrahedra have positive volume (see the module doc). Infinite ones
    /// contain [`INFINITE`] and are positive when ∞ is replaced by a point beyond their hull facet.
    pub fn tet_vertices(&self, t: TetId) -> [VertexId; 4] {
        self.tv[t as usize]
    }

    /// Neighbour i is opposite vertex i (may be infinite).
    pub fn tet_neighbors(&self, t: TetId) -> [TetId; 4] {
        self.tn[t as usize]
    }

    pub fn is_infinite(&self, t: TetId) -> bool {
        self.tv[t as usize].contains(&INFINITE)
    }

    /// Finite tetrahedra incident to `v` (a merged duplicate answers for its kept vertex).
    #[allow(clippy::needless_range_loop)]
    pub fn vertex_tets(&self, v: VertexId) -> Vec<TetId> {
        let v = self.canonical(v);
        let t0 = match self.vtet.get(v as usize) {
            Some(&t) if t != NONE => t,
            _ => return Vec::new(),
        };
        let mut seen = vec![t0];
        let mut k = 0;
        while k < seen.len() {
            let t = seen[k];
            k += 1;
            let vs = self.tv[t as usize];
            for i in 0..4 {
                if vs[i] != v {
                    let n = self.tn[t as usize][i];
                    if !seen.contains(&n) {
                        seen.push(n);
                    }
                }
            }
        }
        seen.retain(|&t| !self.is_infinite(t));
        seen
    }

    /// The vertex kept for `v` (itself unless `v` was merged into another vertex).
    pub fn canonical(&self, v: VertexId) -> VertexId {
        self.dups
            .iter()
            .find(|d| d.0 == v)
            .map(|d| d.1)
            .unwrap_or(v)
    }

    /// Locates `p` (see [`Location`]).
    pub fn locate(&self, p: [f64; 3]) -> Location {
        let mut me = self.clone_walker();
        me.locate_internal(norm(p))
    }

    fn clone_walker(&self) -> Walker<'_> {
        Walker { dt: self }
    }

    /// Each triangle of the triangulation once, as (tet, i): the facet of finite tetrahedron `tet`
    /// opposite its vertex i (hull facets included, reported from their finite side).
    pub fn facets(&self) -> impl Iterator<Item = (TetId, u8)> + '_ {
        self.tets().flat_map(move |t| {
            (0..4u8).filter_map(move |i| {
                let n = self.tn[t as usize][i as usize];
                (self.is_infinite(n) || t < n).then_some((t, i))
            })
        })
    }

    /// The three vertices (a,b,c) of facet (t, i), counter-clockwise seen from vertex i, i.e.
    /// `pred::orient(a,b,c,v_i) > 0` (the normal (b-a)×(c-a) points into `t`).
    pub fn facet_vertices(&self, t: TetId, i: u8) -> [VertexId; 3] {
        let v = self.tv[t as usize];
        const F: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
        let f = F[i as usize];
        [v[f[0]], v[f[1]], v[f[2]]]
    }

    /// Every finite edge once, as (smaller id, larger id), sorted.
    pub fn edges(&self) -> Vec<[VertexId; 2]> {
        let mut e: Vec<[VertexId; 2]> = self
            .tets()
            .flat_map(|t| {
                let v = self.tv[t as usize];
                [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
                    .map(|(a, b)| [v[a].min(v[b]), v[a].max(v[b])])
            })
            .collect();
        e.sort_unstable();
        e.dedup();
        e
    }

    /// Finite tetrahedra as a mesh over all vertex ids (merged duplicates stay as unused vertices).
    pub fn to_tet_mesh(&self) -> crate::mesh::TetMesh {
        crate::mesh::TetMesh {
            vertices: self.pts.clone(),
            tets: self.tets().map(|t| self.tv[t as usize]).collect(),
        }
    }

    /// Checks every invariant; see `validate.rs`.
    pub fn is_valid(&self) -> Result<(), String> {
        validate::check(self)
    }

    /// Bytes held by the kernel's arrays (capacity).
    pub fn memory_bytes(&self) -> usize {
        self.pts.capacity() * 24
            + (self.tv.capacity() + self.tn.capacity()) * 16
            + self.mark.capacity() * 4
            + self.vtet.capacity() * 4
            + self.free.capacity() * 4
    }
}

/// Read-only locate: the walk needs a random source, so it runs on a throw-away state.
struct Walker<'a> {
    dt: &'a Delaunay,
}

impl Walker<'_> {
    fn locate_internal(&mut self, q: P) -> Location {
        let dt = self.dt;
        if dt.dim < 3 {
            return Location::NoTets;
        }
        let mut t = if dt.tv[dt.hint as usize][0] != DEAD {
            dt.hint
        } else {
            dt.all_tets().next().unwrap()
        };
        if let Some(k) = dt.inf_index(t) {
            t = dt.tn[t as usize][k];
        }
        let mut rng: u32 = 0x1234_5678;
        let mut prev = NONE;
        'outer: loop {
            rng ^= rng << 13;
            rng ^= rng >> 17;
            rng ^= rng << 5;
            let pts = dt.tet_points(t);
            for k in 0..4 {
                let i = (rng as usize + k) & 3;
                let n = dt.tn[t as usize][i];
                if n == prev {
                    continue;
                }
                let mut s = pts;
                s[i] = q;
                if pred::orient(s[0], s[1], s[2], s[3]) < 0.0 {
                    prev = t;
                    t = n;
                    if dt.is_infinite(t) {
                        return Location::Outside(t);
                    }
                    continue 'outer;
                }
            }
            break;
        }
        for &w in &dt.tv[t as usize] {
            if dt.pts[w as usize] == q {
                return Location::Vertex(w);
            }
        }
        Location::InTet(t)
    }
}

/// -0.0 → 0.0 so that equal points have equal bits.
#[inline]
fn norm(p: P) -> P {
    [p[0] + 0.0, p[1] + 0.0, p[2] + 0.0]
}

/// The two positions of 0..4 other than i and j.
#[inline]
fn other_two(i: usize, j: usize) -> (usize, usize) {
    let mut r = [0usize; 2];
    let mut k = 0;
    for m in 0..4 {
        if m != i && m != j {
            r[k] = m;
            k += 1;
        }
    }
    (r[0], r[1])
}

fn facet_key(v: [u32; 4], i: usize) -> [u32; 3] {
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
    use rand::{Rng, SeedableRng};

    fn rng() -> rand_chacha::ChaCha8Rng {
        rand_chacha::ChaCha8Rng::seed_from_u64(7)
    }

    #[test]
    fn random_points_valid() {
        let mut r = rng();
        let pts: Vec<[f64; 3]> = (0..2000).map(|_| [r.gen(), r.gen(), r.gen()]).collect();
        let dt = Delaunay::new(&pts);
        dt.is_valid().unwrap();
        assert_eq!(dt.dimension(), 3);
        assert!(dt.num_finite_tets() > 2000);
        for (t, i) in dt.facets().take(100) {
            let [a, b, c] = dt.facet_vertices(t, i).map(|w| dt.point(w));
            let d = dt.point(dt.tet_vertices(t)[i as usize]);
            assert!(pred::orient(a, b, c, d) > 0.0);
        }
        assert!(dt.edges().len() > 2000);
        for (k, p) in pts.iter().enumerate().take(50) {
            assert_eq!(dt.locate(*p), Location::Vertex(k as u32));
            let t = *dt.vertex_tets(k as u32).first().unwrap();
            assert!(dt.tet_vertices(t).contains(&(k as u32)));
        }
        match dt.locate([0.5, 0.5, 0.5]) {
            Location::InTet(t) => assert!(!dt.is_infinite(t)),
            l => panic!("{l:?}"),
        }
        assert!(matches!(dt.locate([2.0, 0.5, 0.5]), Location::Outside(_)));
    }

    #[test]
    fn lattice_valid() {
        let mut pts = Vec::new();
        for x in 0..6 {
            for y in 0..6 {
                for z in 0..6 {
                    pts.push([x as f64, y as f64, z as f64]);
                }
            }
        }
        let dt = Delaunay::new(&pts);
        dt.is_valid().unwrap();
        // volume of the 5^3 cube
        let vol: f64 = dt
            .tets()
            .map(|t| {
                let v = dt.tet_vertices(t).map(|w| dt.point(w));
                pred::orient(v[0], v[1], v[2], v[3]) / 6.0
            })
            .sum();
        assert!((vol - 125.0).abs() < 1e-9, "{vol}");
    }

    #[test]
    fn low_dimensions_and_duplicates() {
        let dt = Delaunay::new(&[]);
        assert_eq!(dt.dimension(), -1);
        let dt = Delaunay::new(&[[0.0; 3], [0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]);
        assert_eq!(dt.dimension(), 1);
        assert_eq!(dt.duplicates(), &[(1, 0)]);
        let plane: Vec<[f64; 3]> = (0..50)
            .map(|i| [(i % 7) as f64, (i / 7) as f64, 0.0])
            .collect();
        let mut dt = Delaunay::new(&plane);
        assert_eq!(dt.dimension(), 2);
        assert_eq!(dt.num_finite_tets(), 0);
        dt.is_valid().unwrap();
        let v = dt.insert([1.0, 1.0, 1.0]);
        assert_eq!(v, 50);
        assert_eq!(dt.dimension(), 3);
        dt.is_valid().unwrap();
        assert_eq!(dt.insert([1.0, 1.0, 1.0]), 50);
        assert_eq!(dt.insert([2.0, 1.0, 0.0]), 9);
        assert!(!dt.vertex_tets(3).is_empty());
        dt.is_valid().unwrap();
    }
}

#[cfg(test)]
mod degenerate_tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn volume(dt: &Delaunay) -> f64 {
        dt.tets()
            .map(|t| {
                let v = dt.tet_vertices(t).map(|w| dt.point(w));
                pred::orient(v[0], v[1], v[2], v[3]) / 6.0
            })
            .sum()
    }

    #[test]
    fn cube_faces_and_circles() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut pts = Vec::new();
        for _ in 0..3000 {
            let f = r.gen_range(0..6);
            let (a, b): (f64, f64) = (r.gen(), r.gen());
            let c = if f % 2 == 0 { 0.0 } else { 1.0 };
            pts.push(match f / 2 {
                0 => [c, a, b],
                1 => [a, c, b],
                _ => [a, b, c],
            });
        }
        for k in 0..8 {
            pts.push([(k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64]);
        }
        let dt = Delaunay::new(&pts);
        dt.is_valid().unwrap();
        assert!((volume(&dt) - 1.0).abs() < 1e-9);
        // circles on parallel planes: thousands of cocircular points
        let mut pts = Vec::new();
        for z in 0..5 {
            for i in 0..64 {
                let a = i as f64 * std::f64::consts::TAU / 64.0;
                pts.push([a.cos(), a.sin(), z as f64]);
                pts.push([
                    (a.cos() * 4.0).round() / 4.0,
                    (a.sin() * 4.0).round() / 4.0,
                    z as f64 + 0.5,
                ]);
            }
        }
        let dt = Delaunay::new(&pts);
        dt.is_valid().unwrap();
    }
}

#[cfg(test)]
mod timing {
    /// `cargo test --lib delaunay::timing -- --ignored --nocapture` (profile test, opt-level 2).
    #[test]
    #[ignore]
    fn timing() {
        let n: usize = std::env::var("S2S_N")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(100_000);
        for (name, pts) in [
            ("uniform", super::gen::uniform(n, 1)),
            ("planes40", super::gen::on_planes(n, 40, 1)),
        ] {
            let t = std::time::Instant::now();
            let dt = super::Delaunay::new(&pts);
            eprintln!(
                "{name} {n}: {:.3} s, {} tets",
                t.elapsed().as_secs_f64(),
                dt.num_finite_tets()
            );
        }
    }
}

#[cfg(test)]
mod timing_degenerate {
    #[test]
    #[ignore]
    fn timing_degenerate() {
        for (name, pts) in [
            ("circles", super::gen::circles(10, 200)),
            ("circles6", super::gen::circles(6, 100)),
            ("polytope", super::gen::polytope_faces(5000, 30, 5)),
        ] {
            let t = std::time::Instant::now();
            let dt = super::Delaunay::new(&pts);
            eprintln!(
                "{name}: {:.3} s, {} tets",
                t.elapsed().as_secs_f64(),
                dt.num_finite_tets()
            );
            let t = std::time::Instant::now();
            dt.is_valid().unwrap();
            eprintln!("valid {name}: {:.3} s", t.elapsed().as_secs_f64());
        }
    }
}
