//! Our exact 3D Delaunay kernel. Contract used by the engines:
//! ```
//! use slice2solid::delaunay::Delaunay;
//! // the unit cube's corners (cospherical: the tie-breaking decides the diagonals), one duplicate
//! let mut points: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])
//!     .collect();
//! points.push([1.0, 1.0, 1.0]);
//! let mut dt = Delaunay::new(&points); // merged duplicates reported in dt.duplicates()
//! assert_eq!(dt.duplicates().len(), 1);
//! let v = dt.insert([0.5, 0.5, 0.5]); // more points later (conformity splitting)
//! assert_eq!(dt.point(v), [0.5, 0.5, 0.5]);
//! let volume: f64 = dt
//!     .tets() // finite, alive tetrahedra
//!     .map(|t| {
//!         let [a, b, c, d] = dt.tet_vertices(t).map(|v| dt.point(v)); // positively oriented
//!         let (u, v, w) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]], [d[0] - a[0], d[1] - a[1], d[2] - a[2]]);
//!         (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0
//!     })
//!     .sum();
//! assert!((volume - 1.0).abs() < 1e-12);
//! dt.is_valid().unwrap();
//! ```
//! Also `dt.tet_neighbors(t)` (neighbour i is opposite vertex i; infinite tets have a ghost vertex),
//! `dt.is_infinite(t)`, `dt.vertex_tets(v)`, `dt.locate(p)`.
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
//! Note: this is the opposite of the sign written in `mesh::TetMesh`'s doc comment ("orient3d > 0 in
//! robust's convention"); [`Delaunay::to_tet_mesh`] keeps the positive-volume order above.
//!
//! Lower dimensions: with fewer than 4 affinely independent points there are no tetrahedra;
//! [`Delaunay::dimension`] says -1, 0, 1 or 2, and inserting a point off their affine hull later
//! builds the 3D triangulation. Exact duplicates are merged: [`Delaunay::duplicates`] lists
//! (dropped, kept) pairs and [`Delaunay::canonical`] maps an id to the vertex that represents it.
//! Ids: tetrahedron ids are slots that are reused after insertions; hold them only between insertions.
//!
//! **Tagged construction** ([`Delaunay::try_new_tagged`], [`Delaunay::insert_tagged`]): points carry
//! the input planes they lie on, with exact uv in each plane's frame, and a global id
//! ([`PointTags`]). Decisions that are degenerate for the ideal points (exactly on their planes)
//! follow the line and plane rules of [`tags`]; the hull facets on a face plane are then the 2D
//! Delaunay triangulation of its points ([`plane2d`] is the reference), the same in every cell that
//! has those points, and no tetrahedron has four vertices on one plane. Circles are read on the 3D
//! positions through each plane's apex ([`PlaneApexes`], [`Delaunay::try_new_tagged_with`]), or in
//! uv for a plane without one (then the uv frame must be a similarity: orthonormal axes, one
//! scale); ties by a symbolic perturbation in the lexicographic order of the positions.
//! [`Delaunay::plane_hull_triangles`] gives the restriction.
//!
//! Layout: `tds` (flat records and free list), `insert` (walk, conflict region, starring, and the
//! public insertion methods), `query` (accessors, facets, edges, point location),
//! `parallel` (the multi-threaded bulk build of [`Delaunay::try_new_with_threads`], untagged only),
//! `pred` (filtered exact predicates and the perturbation), `sort` (BRIO + Hilbert), `validate`
//! (`is_valid`), `tags` (plane tags and their rules), `plane2d` (reference 2D Delaunay), `xyz`
//! (point files), `gen` (test point sets), `tetgen` (oracle, feature `tetgen`).
//!
//! Measured (release build, shared 2-core machine under load ~8, 10^6 points on 40 random planes,
//! 6,600,878 tetrahedra; 6 interleaved pairs): kernel time 0.81× that of CGAL 5.5's
//! `Delaunay_triangulation_3` (Epick, range insertion, g++ -O3) on the same points, median of the
//! per-pair ratios of thread CPU time (range 0.74–0.88; ours 4.74–5.24 s, CGAL 5.70–7.00 s), 0.82×
//! in wall time (range 0.74–0.97). Command: `S2S_TIME_XYZ=planes40_1000000.xyz cargo bench --bench
//! delaunay` against a CGAL program timing the same way (see `benches/delaunay.rs`); the CLI's
//! `seconds` against CGAL's wall time, 8 more pairs under load 4–8: median 0.87 (0.73–1.00). ~1.8× faster
//! than TetGen 1.5; ~390 bytes per point (peak RSS of the CLI). The hot path: static filter bounds
//! from the bounding box (`pred::Bounds`) before the semi-static ones, the insphere determinant in
//! two SSE2 lanes.
//!
//! Over 800 lines only with its unit tests (the test modules at the end); the code is shorter.
pub mod gen;
mod insert;
mod parallel;
pub mod plane2d;
#[allow(clippy::needless_range_loop)]
pub mod pred;
mod query;
pub mod sort;
pub mod tags;
mod tds;
#[cfg(feature = "tetgen")]
pub mod tetgen;
mod validate;
pub mod xyz;

use pred::P;
use std::collections::HashMap;
pub use tags::{PlaneApexes, PointTags, MAX_PLANES};
pub use tds::INFINITE;
use tds::{Tds, NONE};

pub type VertexId = u32;
pub type TetId = u32;

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
///
/// Internally vertices are numbered in insertion order (BRIO + Hilbert), so that the coordinates
/// of neighbouring vertices are close in memory; the public API speaks external ids (input indices).
#[derive(Clone, Debug)]
pub struct Delaunay {
    /// Coordinates by internal id.
    pts: Vec<P>,
    /// Internal id → external id.
    ext: Vec<u32>,
    /// External id → internal id (a merged duplicate maps to its kept vertex).
    int: Vec<u32>,
    tds: Tds,
    /// One incident tetrahedron per internal vertex (NONE while not triangulated).
    vtet: Vec<u32>,
    /// (dropped, kept) external ids.
    dups: Vec<(VertexId, VertexId)>,
    /// Affine dimension of the vertex set so far (-1 empty .. 3).
    dim: i8,
    /// While `dim < 3`: distinct internal vertices waiting for a full-dimensional simplex.
    pending: Vec<u32>,
    pending_keys: HashMap<[u64; 3], u32, FastHash>,
    nfinite: usize,
    hint: u32,
    rng: u32,
    // Scratch buffers reused by every insertion.
    cavity: Vec<u32>,
    boundary: Vec<insert::BoundaryFacet>,
    outside: Vec<u32>,
    newt: Vec<u32>,
    edge_table: Vec<(u64, u32, u8)>,
    /// Bounding box of every point in `pts` and the static filter bounds it gives (predicates on
    /// points inside the box only).
    lo: P,
    hi: P,
    bounds: pred::Bounds,
    /// Whether insertions keep `vtet` up to date (off during the bulk build, which rebuilds it once).
    track_vtet: bool,
    /// Built by [`Delaunay::try_new_tagged`]: the tag rules of [`tags`] apply, `tags` is filled.
    tagged: bool,
    /// Plane tags by internal id (empty when not `tagged`).
    tags: Vec<PointTags>,
    /// The planes' apexes for the plane rule (empty: decided in uv).
    apexes: PlaneApexes,
    /// A tagged insertion met a cavity that is not star-shaped (an exact cosphericity across
    /// planes the tag rules cannot decide, see `tags`): the triangulation is not to be trusted.
    inconsistent: bool,
    /// Visit stamps of the tagged locate's fallback search (by tetrahedron slot).
    stamp: Vec<u32>,
    stamp_gen: u32,
    /// Scratch of the cavity's ball test: vertex stamps (by internal id) and an edge count table.
    vmark: Vec<u32>,
    vmark_gen: u32,
    ball_edges: Vec<(u64, u8)>,
    /// Points the parallel bulk build deferred to a sequential tail.
    parallel_deferred: usize,
}

impl Delaunay {
    /// Triangulates `points`; vertex ids are the input indices. Points at exactly the same position are
    /// merged (see [`Delaunay::duplicates`]; the first occurrence is kept). Fewer than 4 affinely
    /// independent points give no tetrahedra (see [`Delaunay::dimension`]). Panics on non-finite
    /// coordinates (use [`Delaunay::try_new`] to get an error instead).
    pub fn new(points: &[[f64; 3]]) -> Delaunay {
        Self::try_new(points).expect("Delaunay::new: non-finite coordinate")
    }

    /// Like [`Delaunay::new`], but rejects non-finite coordinates with `Error::Input`.
    pub fn try_new(points: &[[f64; 3]]) -> crate::Result<Delaunay> {
        Self::try_new_with_threads(points, 1)
    }

    /// [`Delaunay::try_new`] with at most `threads` threads: rounds of the insertion order with
    /// many points (8192 or more) are inserted in parallel (see `parallel`; rayon tasks, so it
    /// nests in a rayon pool). The triangulation is the same for every thread count, but the
    /// tetrahedron slots (the order of [`Delaunay::tets`]) depend on the threads' timing when
    /// `threads > 1`: [`Delaunay::try_new`] stays sequential so that the engines' results are
    /// reproducible run to run.
    pub fn try_new_with_threads(points: &[[f64; 3]], threads: usize) -> crate::Result<Delaunay> {
        check_finite(points)?;
        Ok(Self::build(points, None, threads.clamp(1, 64)))
    }

    /// Points the parallel build deferred to its sequential tails (they met another thread).
    pub fn parallel_deferred(&self) -> usize {
        self.parallel_deferred
    }

    /// Triangulates `points` lying on input planes given by `tags` (one per point, same order;
    /// [`PointTags::none`] for a point on no plane). Decisions that are degenerate for the ideal
    /// points (the points exactly on their planes, which floats are not for oblique planes) follow
    /// the plane and line rules of [`tags`]: the triangles whose vertices share a plane and that
    /// are hull facets are, by construction, the 2D Delaunay triangulation of that plane's points
    /// (here in its uv, ties in the lexicographic order of the positions: the same in every cell
    /// that has those points; the engine passes apexes, [`Delaunay::try_new_tagged_with`]), and no tetrahedron has
    /// four vertices on one plane or three on one line of two planes. Merged duplicates keep the
    /// first occurrence's tags. Errors on non-finite input, a length mismatch or bad tags.
    pub fn try_new_tagged(points: &[[f64; 3]], tags: &[PointTags]) -> crate::Result<Delaunay> {
        Self::try_new_tagged_with(points, tags, &PlaneApexes::default())
    }

    /// [`Delaunay::try_new_tagged`] with the plane rule decided through each plane's apex (see
    /// [`PlaneApexes`]) on the points' 3D positions, for the planes that have one.
    pub fn try_new_tagged_with(
        points: &[[f64; 3]],
        tags: &[PointTags],
        apexes: &PlaneApexes,
    ) -> crate::Result<Delaunay> {
        check_finite(points)?;
        if tags.len() != points.len() {
            return Err(crate::Error::input(
                "tags",
                format!("{} tags for {} points", tags.len(), points.len()),
            ));
        }
        let tags = tags
            .iter()
            .enumerate()
            .map(|(i, t)| {
                t.normalized()
                    .map_err(|e| crate::Error::input(format!("tags of point {i}"), e))
            })
            .collect::<crate::Result<Vec<_>>>()?;
        let dt = Self::build(points, Some((&tags, apexes)), 1);
        dt.consistent()?;
        Ok(dt)
    }

    /// `Err` when a tagged insertion met a cavity that is not star-shaped: rather than hand out a
    /// triangulation with inverted tetrahedra, the caller learns that this input needs the exact
    /// (ideal-point) predicates the tag rules do not have.
    pub fn consistent(&self) -> crate::Result<()> {
        if self.inconsistent {
            return Err(crate::Error::input(
                "tagged points",
                "an exact cosphericity across planes that the plane rules cannot decide (a cavity was not star-shaped)",
            ));
        }
        Ok(())
    }

    /// The bulk build of [`Delaunay::try_new`] / [`Delaunay::try_new_tagged`] on checked input.
    fn build(
        points: &[[f64; 3]],
        tags: Option<(&[PointTags], &PlaneApexes)>,
        threads: usize,
    ) -> Delaunay {
        let mut dt = Delaunay::empty();
        let order = sort::brio_order(points);
        dt.pts = order.iter().map(|&k| norm(points[k as usize])).collect();
        if let Some((tags, apexes)) = tags {
            dt.tagged = true;
            dt.tags = order.iter().map(|&k| tags[k as usize].clone()).collect();
            dt.apexes = apexes.clone();
        }
        for p in points {
            dt.lo = std::array::from_fn(|k| dt.lo[k].min(p[k]));
            dt.hi = std::array::from_fn(|k| dt.hi[k].max(p[k]));
        }
        dt.bounds = pred::Bounds::for_extent(pred::Bounds::extent(dt.lo, dt.hi));
        dt.ext = order;
        dt.vtet = vec![NONE; dt.pts.len()];
        // About 6.7 tetrahedra per point for most inputs: reserve once instead of regrowing
        // (each regrowth copies the whole array and faults in fresh pages).
        let expect = dt.pts.len() * 7 + 64;
        dt.tds.tets.reserve(expect);
        dt.track_vtet = false;
        // Exact duplicates are found by the insertion itself (the located tetrahedron has a vertex
        // at the same position) and merged afterwards: no hash table over all points.
        let mut dropped: Vec<(u32, u32)> = Vec::new();
        let rounds = sort::brio_rounds(dt.pts.len());
        for r in rounds.windows(2) {
            let (a, b) = (r[0] as u32, r[1] as u32);
            if threads > 1
                && tags.is_none()
                && dt.dim == 3
                && (b - a) as usize >= parallel::MIN_ROUND
            {
                dropped.extend(dt.insert_round_parallel(a..b, threads));
                continue;
            }
            for k in a..b {
                let w = if dt.dim < 3 {
                    dt.add_pending(k)
                } else {
                    dt.insert_vertex(k)
                };
                if w != k {
                    dropped.push((k, w));
                }
            }
        }
        dropped.sort_unstable();
        dt.int = vec![NONE; points.len()];
        if !dropped.is_empty() {
            dt.merge_duplicates(&dropped);
        }
        for (k, &e) in dt.ext.iter().enumerate() {
            dt.int[e as usize] = k as u32;
        }
        for &(d, kept) in &dt.dups {
            dt.int[d as usize] = dt.int[kept as usize];
        }
        dt.vtet = vec![NONE; dt.pts.len()];
        dt.track_vtet = true;
        if dt.dim == 3 {
            for t in 0..dt.tds.tets.len() as u32 {
                let tt = &dt.tds.tets[t as usize];
                if !tt.is_dead() {
                    for w in tt.v {
                        if w != INFINITE {
                            dt.vtet[w as usize] = t;
                        }
                    }
                }
            }
        }
        dt
    }

    /// After the bulk build: `dropped` lists (internal id never triangulated, internal id of the
    /// vertex at the same position). Each merged group is represented by its smallest external id
    /// (as if duplicates had been removed before the build), the dropped ids are recorded in `dups`
    /// (sorted) and the internal ids are compacted.
    fn merge_duplicates(&mut self, dropped: &[(u32, u32)]) {
        let ext0 = self.ext.clone();
        for &(k, w) in dropped {
            let e = &mut self.ext[w as usize];
            *e = (*e).min(ext0[k as usize]);
        }
        for &(k, w) in dropped {
            let kept = self.ext[w as usize];
            for e in [ext0[k as usize], ext0[w as usize]] {
                if e != kept {
                    self.dups.push((e, kept));
                }
            }
        }
        self.dups.sort_unstable();
        self.dups.dedup();
        let mut hole = vec![false; self.pts.len()];
        for &(k, _) in dropped {
            hole[k as usize] = true;
        }
        let mut newid = vec![NONE; self.pts.len()];
        let mut m = 0u32;
        for (k, h) in hole.iter().enumerate() {
            if !h {
                newid[k] = m;
                self.pts[m as usize] = self.pts[k];
                self.ext[m as usize] = self.ext[k];
                if self.tagged {
                    self.tags.swap(m as usize, k);
                }
                m += 1;
            }
        }
        self.pts.truncate(m as usize);
        self.ext.truncate(m as usize);
        if self.tagged {
            self.tags.truncate(m as usize);
        }
        let map = |w: u32| if w == INFINITE { w } else { newid[w as usize] };
        for t in self.tds.tets.iter_mut() {
            if !t.is_dead() {
                t.v = t.v.map(map);
            }
        }
        for w in self.pending.iter_mut() {
            *w = map(*w);
        }
        for w in self.pending_keys.values_mut() {
            *w = map(*w);
        }
    }

    /// A copy without the scratch buffers of insertion (cavity, gluing and search tables, visit
    /// stamps by slot and vertex), which are rebuilt on demand: a stored triangulation that will
    /// take more points later (a cell's run start; a thousand-frame sweep keeps one per cell)
    /// holds only the triangulation.
    pub fn clone_compact(&self) -> Delaunay {
        // every field named, so that a field added later is sorted here as kept or scratch
        let Delaunay {
            pts,
            ext,
            int,
            tds,
            vtet,
            dups,
            dim,
            pending,
            pending_keys,
            nfinite,
            hint,
            rng,
            cavity: _,
            boundary: _,
            outside: _,
            newt: _,
            edge_table: _,
            lo,
            hi,
            bounds,
            track_vtet,
            tagged,
            tags,
            apexes,
            inconsistent,
            stamp: _,
            stamp_gen,
            vmark: _,
            vmark_gen,
            ball_edges: _,
            parallel_deferred,
        } = self;
        Delaunay {
            pts: pts.clone(),
            ext: ext.clone(),
            int: int.clone(),
            tds: tds.clone(),
            vtet: vtet.clone(),
            dups: dups.clone(),
            dim: *dim,
            pending: pending.clone(),
            pending_keys: pending_keys.clone(),
            nfinite: *nfinite,
            hint: *hint,
            rng: *rng,
            lo: *lo,
            hi: *hi,
            bounds: *bounds,
            track_vtet: *track_vtet,
            tagged: *tagged,
            tags: tags.clone(),
            apexes: apexes.clone(),
            inconsistent: *inconsistent,
            stamp_gen: *stamp_gen,
            vmark_gen: *vmark_gen,
            parallel_deferred: *parallel_deferred,
            ..Delaunay::empty()
        }
    }

    fn empty() -> Delaunay {
        Delaunay {
            pts: Vec::new(),
            ext: Vec::new(),
            int: Vec::new(),
            tds: Tds::default(),
            vtet: Vec::new(),
            dups: Vec::new(),
            dim: -1,
            pending: Vec::new(),
            pending_keys: HashMap::default(),
            nfinite: 0,
            hint: 0,
            rng: 0x9E37_79B9,
            cavity: Vec::new(),
            boundary: Vec::new(),
            outside: Vec::new(),
            newt: Vec::new(),
            edge_table: Vec::new(),
            tagged: false,
            tags: Vec::new(),
            apexes: PlaneApexes::default(),
            inconsistent: false,
            stamp: Vec::new(),
            stamp_gen: 0,
            vmark: Vec::new(),
            vmark_gen: 0,
            ball_edges: Vec::new(),
            parallel_deferred: 0,
            lo: [f64::INFINITY; 3],
            hi: [f64::NEG_INFINITY; 3],
            bounds: pred::Bounds::NONE,
            track_vtet: true,
        }
    }

    /// Grows the bounding box to `p` (and the static filter bounds with it).
    fn cover(&mut self, p: P) {
        if (0..3).all(|k| self.lo[k] <= p[k] && p[k] <= self.hi[k]) {
            return;
        }
        self.lo = std::array::from_fn(|k| self.lo[k].min(p[k]));
        self.hi = std::array::from_fn(|k| self.hi[k].max(p[k]));
        self.bounds = pred::Bounds::for_extent(pred::Bounds::extent(self.lo, self.hi));
    }

    /// Lower-dimensional phase: keep distinct points, and start the 3D triangulation when internal
    /// vertex `v` leaves the affine hull of the previous ones. Returns `v`, or the internal id of the
    /// pending vertex at the same position.
    fn add_pending(&mut self, v: u32) -> u32 {
        let p = self.pts[v as usize];
        if let Some(&w) = self.pending_keys.get(&key(p)) {
            return w;
        }
        self.pending_keys.insert(key(p), v);
        self.pending.push(v);
        let pp = |i: usize| self.pts[self.pending[i] as usize];
        let n = self.pending.len();
        self.dim = match self.dim {
            -1 => 0,
            0 => 1,
            1 => {
                if pred::collinear(pp(0), pp(1), p)
                    || self.tag_collinear(self.pending[0], self.pending[1], v)
                {
                    1
                } else {
                    // keep the basis points first
                    self.pending.swap(2, n - 1);
                    2
                }
            }
            2 => {
                if pred::orient(pp(0), pp(1), pp(2), p) == 0.0
                    || self.tag_degenerate([self.pending[0], self.pending[1], self.pending[2], v])
                {
                    2
                } else {
                    self.pending.swap(3, n - 1);
                    3
                }
            }
            d => d,
        };
        if self.dim == 3 {
            let pend = std::mem::take(&mut self.pending);
            self.pending_keys = HashMap::default();
            self.build_first_tet([pend[0], pend[1], pend[2], pend[3]]);
            for &w in &pend[4..] {
                self.insert_vertex(w);
            }
        }
        v
    }

    /// Three internal vertices on one line by their tags (always false when untagged).
    fn tag_collinear(&self, a: u32, b: u32, c: u32) -> bool {
        self.tagged && {
            let t = |w: u32| &self.tags[w as usize];
            tags::on_one_line(t(a), t(b), t(c))
        }
    }

    /// Four internal vertices degenerate by their tags (see [`tags::degenerate`]).
    fn tag_degenerate(&self, v: [u32; 4]) -> bool {
        self.tagged && tags::degenerate(v.map(|w| &self.tags[w as usize]))
    }
}

/// A multiplicative hasher for coordinate bit patterns (SipHash is needlessly slow here, and
/// inputs are not adversarial).
#[derive(Clone, Copy, Default)]
struct FastHash;
impl std::hash::BuildHasher for FastHash {
    type Hasher = FastHasher;
    fn build_hasher(&self) -> FastHasher {
        FastHasher(0)
    }
}
struct FastHasher(u64);
impl std::hash::Hasher for FastHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(23) ^ x).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// `Error::Input` naming the first point with a non-finite coordinate.
fn check_finite(points: &[[f64; 3]]) -> crate::Result<()> {
    match points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        Some(i) => Err(crate::Error::input(
            format!("point {i}"),
            "non-finite coordinate",
        )),
        None => Ok(()),
    }
}

/// -0.0 → 0.0 so that equal points have equal bits.
#[inline]
fn norm(p: P) -> P {
    [p[0] + 0.0, p[1] + 0.0, p[2] + 0.0]
}

#[inline]
fn key(p: P) -> [u64; 3] {
    [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()]
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
    fn duplicates_keep_the_first_occurrence() {
        let mut r = rng();
        let base: Vec<[f64; 3]> = (0..200).map(|_| [r.gen(), r.gen(), r.gen()]).collect();
        let pts: Vec<[f64; 3]> = (0..1000).map(|_| base[r.gen_range(0..200)]).collect();
        let dt = Delaunay::new(&pts);
        dt.is_valid().unwrap();
        let mut expect = Vec::new();
        for (i, p) in pts.iter().enumerate() {
            let first = pts.iter().position(|q| q == p).unwrap() as u32;
            if first != i as u32 {
                expect.push((i as u32, first));
            }
            assert_eq!(dt.canonical(i as u32), first);
            assert_eq!(dt.point(i as u32), *p);
            assert_eq!(dt.locate(*p), Location::Vertex(first));
        }
        assert_eq!(dt.duplicates(), &expect[..]);
        let used: std::collections::HashSet<u32> =
            dt.tets().flat_map(|t| dt.tet_vertices(t)).collect();
        assert_eq!(used.len(), pts.len() - expect.len());
        assert!(expect.iter().all(|&(d, _)| !used.contains(&d)));
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

    #[test]
    fn batch_insertion_matches_insertion_in_order() {
        let mut r = rng();
        let base: Vec<[f64; 3]> = (0..300)
            .map(|k| {
                let (a, b): (f64, f64) = (r.gen(), r.gen());
                [a, b, (k % 3) as f64 * 0.5 + 0.1 * a]
            })
            .collect();
        // new points on the same planes, an exact duplicate of an old point and repeats in the batch
        let mut batch: Vec<[f64; 3]> = (0..200)
            .map(|k| {
                let (a, b): (f64, f64) = (r.gen(), r.gen());
                [a, b, (k % 3) as f64 * 0.5 + 0.1 * a]
            })
            .collect();
        batch[17] = base[5];
        batch[40] = batch[3];
        batch[41] = batch[3];
        let mut one = Delaunay::new(&base);
        let ids_one: Vec<u32> = batch.iter().map(|&p| one.insert(p)).collect();
        let mut all = Delaunay::new(&base);
        let ids_all = all.insert_batch(&batch);
        all.is_valid().unwrap();
        assert_eq!(ids_one, ids_all);
        assert_eq!(ids_all[17], 5);
        assert_eq!(ids_all[41], 303);
        assert_eq!(one.duplicates(), all.duplicates());
        let tets = |dt: &Delaunay| {
            let mut t: Vec<[u32; 4]> = dt
                .tets()
                .map(|t| {
                    let mut v = dt.tet_vertices(t);
                    v.sort_unstable();
                    v
                })
                .collect();
            t.sort_unstable();
            t
        };
        assert_eq!(tets(&one), tets(&all));
        for v in 0..one.num_vertices() as u32 {
            assert_eq!(one.canonical(v), all.canonical(v));
            assert_eq!(one.point(v), all.point(v));
        }
    }
}

#[cfg(test)]
mod tagged_tests {
    use super::*;

    /// A square on an oblique plane (exactly cocircular in uv, not exactly coplanar in floats) with
    /// an apex on either side: both pyramids take the same diagonal (the gid tie-break), no flat tet.
    #[test]
    fn square_on_oblique_plane_same_diagonal_both_sides() {
        let u = [0.6, 0.48, 0.64];
        let v = [-0.8, 0.36, 0.48];
        let o = [0.1, 0.2, 0.3];
        let n = [0.0, -0.8, 0.6];
        let at = |s: f64, t: f64, h: f64| -> [f64; 3] {
            std::array::from_fn(|k| o[k] + s * u[k] + t * v[k] + h * n[k])
        };
        let sq = [[0.1, 0.3], [0.7, 0.3], [0.7, 0.9], [0.1, 0.9]];
        for gids in [[4u64, 1, 3, 2], [1, 2, 3, 4], [9, 7, 8, 6]] {
            let mut diag = Vec::new();
            for h in [1.0, -1.0] {
                let mut pts: Vec<[f64; 3]> = sq.iter().map(|q| at(q[0], q[1], 0.0)).collect();
                pts.push(at(0.4, 0.6, h));
                let mut tags: Vec<PointTags> = (0..4)
                    .map(|i| PointTags::new(gids[i], &[(7, sq[i])]))
                    .collect();
                tags.push(PointTags::none());
                let dt = Delaunay::try_new_tagged(&pts, &tags).unwrap();
                dt.is_valid().unwrap();
                assert_eq!(dt.num_finite_tets(), 2);
                let mut f: Vec<[u32; 3]> = dt
                    .plane_hull_triangles(7)
                    .into_iter()
                    .map(|mut t| {
                        t.sort_unstable();
                        t
                    })
                    .collect();
                f.sort_unstable();
                diag.push(f);
            }
            assert_eq!(diag[0], diag[1], "gids {gids:?}");
        }
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
