//! Incremental construction: the first tetrahedron, the stochastic visibility walk, and
//! Bowyer–Watson insertion (conflict region grown from the located tetrahedron, then starred from
//! the new vertex). All ids here are internal vertex ids (insertion order), except in the public
//! insertion methods (`insert`, `insert_batch`, ...), which hand out external ids.
//!
//! About 800 lines in one file on purpose: the walk, the conflict region and the starring work on
//! the triangulation's scratch buffers together, and the tagged variant of each step (symbolic
//! ties on planes) sits beside the plain one (`insert_vertex_with::<TAGGED>`).
use super::pred::{self, P};
use super::tags;
use super::tds::{facet_key, other_two, Tet, ID_MASK, INFINITE, IN_CAVITY, NONE, OUTSIDE};
use super::{key, norm, sort, Delaunay, FastHash, PointTags, VertexId};
use std::collections::HashMap;

/// Empty slot of the edge table (no edge has both endpoints equal to u32::MAX).
const EMPTY_EDGE: u64 = u64::MAX;

/// Hint the CPU to fetch a tetrahedron record we are about to read (the cavity search is bound by
/// cache misses on neighbouring records; issuing the four loads together overlaps them).
#[inline(always)]
fn prefetch(tets: &[Tet], t: u32) {
    #[cfg(target_arch = "x86_64")]
    if let Some(r) = tets.get(t as usize) {
        // SAFETY: prefetching is a hint and never faults; the pointer is in bounds anyway.
        unsafe {
            std::arch::x86_64::_mm_prefetch(
                r as *const Tet as *const i8,
                std::arch::x86_64::_MM_HINT_T0,
            )
        };
    }
}

/// Record `t`. The triangulation's invariants (checked by `is_valid` in tests) guarantee that every
/// neighbour id stored in a live record is a valid slot, so the hot loops skip bounds checks.
#[inline(always)]
fn tet(tets: &[Tet], t: u32) -> &Tet {
    debug_assert!((t as usize) < tets.len());
    // SAFETY: t is a neighbour or hint id of a valid triangulation, hence < tets.len().
    unsafe { tets.get_unchecked(t as usize) }
}

/// Mutable record `t` (same invariant as [`tet`]).
#[inline(always)]
fn tet_mut(tets: &mut [Tet], t: u32) -> &mut Tet {
    debug_assert!((t as usize) < tets.len());
    // SAFETY: as in `tet`.
    unsafe { tets.get_unchecked_mut(t as usize) }
}

/// Position of neighbour `t` in `tt`, ignoring the scratch marks.
#[inline(always)]
pub(super) fn index_of_neighbor_masked(tt: &Tet, t: u32) -> usize {
    let n = tt.n.map(|n| n & ID_MASK);
    if n[0] == t {
        0
    } else if n[1] == t {
        1
    } else if n[2] == t {
        2
    } else {
        debug_assert_eq!(n[3], t);
        3
    }
}

/// A facet of the conflict region: the new tetrahedron's vertices `v` (the cavity cell's with the
/// new vertex at position `i`), and the outside neighbour `nb`, whose facet `j` it is.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoundaryFacet {
    pub(super) v: [u32; 4],
    pub(super) nb: u32,
    pub(super) i: u8,
    pub(super) j: u8,
}

/// The rounded centroid of the positive tetrahedron `p` if it is strictly inside it (exact
/// orientations), else `None`: the centroid of a tetrahedron flat up to rounding (contour points
/// of one flat triangle of a sliced mesh, on several planes) can round out of it, and a point
/// outside the hull would make the star test refuse a valid cavity.
fn strictly_inner_point(p: [P; 4]) -> Option<P> {
    let c: P = std::array::from_fn(|k| 0.25 * (p[0][k] + p[1][k] + p[2][k] + p[3][k]));
    (0..4)
        .all(|i| {
            let mut r = p;
            r[i] = c;
            pred::orient(r[0], r[1], r[2], r[3]) > 0.0
        })
        .then_some(c)
}

/// Coordinates of finite internal vertex `v` (< pts.len() by construction).
#[inline(always)]
fn pt(pts: &[P], v: u32) -> P {
    debug_assert!((v as usize) < pts.len());
    // SAFETY: finite vertex ids stored in live records are internal ids < pts.len().
    unsafe { *pts.get_unchecked(v as usize) }
}

#[inline]
pub(super) fn xorshift(mut x: u32) -> u32 {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    x
}

/// Stochastic visibility walk from `start` to a finite tetrahedron containing `q` (closed), or to the
/// infinite tetrahedron whose hull facet sees `q` strictly. Terminates with probability 1.
#[inline]
pub(super) fn walk(
    tets: &[Tet],
    pts: &[P],
    q: P,
    start: u32,
    rng: &mut u32,
    sb: &pred::Bounds,
) -> u32 {
    walk_with(tets, pts, q, start, rng, sb, |_, _| false)
}

/// [`walk`], never crossing the facet opposite `i` of a tetrahedron `v` when `degenerate(v, i)`
/// (the tagged walk: that facet and `q` are coplanar or collinear for the ideal points).
#[inline(always)]
fn walk_with(
    tets: &[Tet],
    pts: &[P],
    q: P,
    start: u32,
    rng: &mut u32,
    sb: &pred::Bounds,
    degenerate: impl Fn(&[u32; 4], usize) -> bool,
) -> u32 {
    let mut t = start;
    {
        let tt = &tets[t as usize];
        if tt.is_infinite() {
            t = tt.n[tt.index_of_vertex(INFINITE)];
        }
    }
    let mut prev = NONE;
    'outer: loop {
        *rng = xorshift(*rng);
        let tt = tet(tets, t);
        let p = [
            pt(pts, tt.v[0]),
            pt(pts, tt.v[1]),
            pt(pts, tt.v[2]),
            pt(pts, tt.v[3]),
        ];
        let r = (*rng >> 11) as usize;
        for k in 0..4 {
            let i = (r + k) & 3;
            let n = tt.n[i];
            if n == prev {
                continue;
            }
            let mut s = p;
            s[i] = q;
            if pred::orient_within(s[0], s[1], s[2], s[3], sb.orient) < 0.0 && !degenerate(&tt.v, i)
            {
                prev = t;
                t = n;
                if tet(tets, n).is_infinite() {
                    return t;
                }
                continue 'outer;
            }
        }
        return t;
    }
}

impl Delaunay {
    /// The first positive tetrahedron on internal vertices `v` and its four infinite neighbours.
    pub(super) fn build_first_tet(&mut self, mut v: [u32; 4]) {
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
        let ids: Vec<u32> = cells.iter().map(|c| self.tds.alloc(*c)).collect();
        for (c, &t) in cells.iter().zip(&ids) {
            for &w in c {
                if w != INFINITE {
                    self.vtet[w as usize] = t;
                }
            }
        }
        // adjacency by matching facets (only 5 cells)
        for &a in &ids {
            for i in 0..4 {
                let fa = facet_key(self.tds.tets[a as usize].v, i);
                for &b in &ids {
                    for j in 0..4 {
                        if a != b && facet_key(self.tds.tets[b as usize].v, j) == fa {
                            self.tds.tets[a as usize].n[i] = b;
                        }
                    }
                }
            }
        }
        self.nfinite = 1;
        self.hint = ids[0];
    }

    /// Perturbed conflict of tetrahedron `t` with point `q`. `t` itself carries no mark, its
    /// neighbours may.
    #[inline(always)]
    pub(super) fn conflict(&self, t: u32, q: P) -> bool {
        let tt = tet(&self.tds.tets, t);
        let v = tt.v;
        if !tt.is_infinite() {
            let p = |k: usize| pt(&self.pts, v[k]);
            return pred::conflict_finite([p(0), p(1), p(2), p(3)], q, &self.bounds);
        }
        self.conflict_infinite(t, q)
    }

    /// The tags of the vertices of `v` (`None` for the infinite vertex); tagged triangulations only.
    #[inline(always)]
    fn tags_of(&self, v: [u32; 4]) -> [Option<tags::TaggedPoint<'_>>; 4] {
        v.map(|w| (w != INFINITE).then(|| (&self.tags[w as usize], self.pts[w as usize])))
    }

    /// Conflict of `t` with internal vertex `qv` at `q` in a tagged triangulation: the line and
    /// plane rules of [`tags`] where they apply (for infinite tetrahedra too: a query on a hull
    /// facet's plane is decided by the facet's circumcircle, never by the float side of the facet),
    /// else [`Delaunay::conflict`].
    #[inline]
    pub(super) fn conflict_tagged(&self, t: u32, qv: u32, q: P) -> bool {
        let v = tet(&self.tds.tets, t).v;
        match tags::conflict(self.tags_of(v), (&self.tags[qv as usize], q), &self.apexes) {
            Some(c) => c,
            None => self.conflict(t, q),
        }
    }

    /// A tetrahedron in conflict with internal vertex `qv` at `q` (tagged), or `Err(w)` when vertex
    /// `w` is at the same position. The walk does not cross tag-degenerate facets; when it ends
    /// in a tetrahedron that does not conflict (the float side of a facet disagrees with the tags,
    /// at ulp distances from a face plane), a breadth-first search from there finds one: the
    /// conflict region is non-empty (the tets on the plane's triangle or line segment containing
    /// `q`, or the float location, conflict) and is usually a few steps away. When nothing
    /// conflicts (the tag rules contradict the float geometry) the triangulation is marked
    /// inconsistent and `Err(qv)` returned: the point is refused.
    fn locate_tagged(&mut self, qv: u32, q: P) -> Result<u32, u32> {
        // An exact duplicate first, by the plain walk (it ends in a tetrahedron with the vertex
        // at q, as in the untagged kernel); the tagged walk may end away from it, and a duplicate
        // inserted as a new vertex would make a cavity that is not star-shaped.
        let plain = self.walk_from_hint(q);
        self.same_position(plain, q)?;
        let mut rng = self.rng;
        let (tets, pts, tags) = (&self.tds.tets, &self.pts, &self.tags);
        let qt = &tags[qv as usize];
        let t0 = walk_with(tets, pts, q, plain, &mut rng, &self.bounds, |v, i| {
            tags::walk_degenerate(v.map(|w| (w != INFINITE).then(|| &tags[w as usize])), i, qt)
        });
        self.rng = rng;
        self.same_position(t0, q)?;
        if self.conflict_tagged(t0, qv, q) {
            return Ok(t0);
        }
        self.stamp.resize(self.tds.tets.len(), 0);
        self.stamp_gen = self.stamp_gen.wrapping_add(1);
        if self.stamp_gen == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.stamp_gen = 1;
        }
        let mut queue = vec![t0];
        self.stamp[t0 as usize] = self.stamp_gen;
        let mut head = 0;
        while head < queue.len() {
            let c = queue[head];
            head += 1;
            for n in self.tds.tets[c as usize].n {
                if self.stamp[n as usize] == self.stamp_gen {
                    continue;
                }
                self.stamp[n as usize] = self.stamp_gen;
                self.same_position(n, q)?;
                if self.conflict_tagged(n, qv, q) {
                    return Ok(n);
                }
                queue.push(n);
            }
        }
        // the tag rules put q in conflict with nothing: inconsistent with the float geometry (as a
        // non-star cavity is); refuse the point rather than panic (`Delaunay::consistent` fails)
        self.inconsistent = true;
        Err(qv)
    }

    /// Tagged: whether every new finite tetrahedron would be positive; if not, the conflict rules
    /// were inconsistent across a cavity facet (an exact cosphericity across planes) and the
    /// triangulation records it (`Delaunay::consistent` then fails).
    ///
    /// A new infinite tetrahedron is checked through a point strictly inside the hull (the
    /// centroid of a finite tetrahedron outside the cavity): with it in the infinite vertex's
    /// place, the tetrahedron must be negative (the kernel's convention: the infinite vertex stands
    /// beyond its hull facet), i.e. its new hull facet has the solid on its inner side.
    fn cavity_is_star(&mut self, boundary: &[BoundaryFacet], outside: &[u32]) -> bool {
        // found at the first new hull facet (most cavities have none)
        let mut inner: Option<Option<P>> = None;
        for b in boundary {
            // a new hull facet may be flat (collinear on a hull plane, allowed by the
            // perturbation): only the wrong side is an error there; a finite tet must be positive
            let (p, infinite) = match b.v.iter().position(|&w| w == INFINITE) {
                None => (b.v.map(|w| self.pts[w as usize]), false),
                Some(k) => {
                    let inner = *inner.get_or_insert_with(|| {
                        outside
                            .iter()
                            .map(|&t| self.tds.tets[t as usize].v)
                            .filter(|v| !v.contains(&INFINITE))
                            .find_map(|v| strictly_inner_point(v.map(|w| self.pts[w as usize])))
                    });
                    let Some(c) = inner else { continue };
                    let p =
                        std::array::from_fn(|m| if m == k { c } else { self.pts[b.v[m] as usize] });
                    (p, true)
                }
            };
            let o = pred::orient(p[0], p[1], p[2], p[3]);
            let wrong = if infinite { o > 0.0 } else { o <= 0.0 };
            if wrong {
                self.inconsistent = true;
                return false;
            }
        }
        true
    }

    /// Whether the cavity is a ball that keeps every vertex: its boundary a closed 2-manifold (each
    /// edge on exactly two facets) of Euler characteristic 2, with every vertex of the cavity's
    /// tetrahedra on it. The star test decides the finite facets by orientation; hull facets (with
    /// the infinite vertex) it can only test against an inner point, so a tag-rule cavity that
    /// wraps around the hull can pass it and would be glued into a broken structure (seen on a
    /// fan's axis when the arrangement left near-duplicate points there: a segfault). Checked on
    /// every tagged insertion, not only where a tag rule decided part of the cavity: the float
    /// predicates give a ball on a triangulation that is Delaunay by them, and a tagged one is not
    /// (the rules decided earlier cavities), so a cavity of float decisions alone can be no ball
    /// either (generated odd input seed 3: a segfault in the next insertion). Combinatorial, so
    /// exact.
    fn cavity_is_ball(&mut self, boundary: &[BoundaryFacet], cavity: &[u32]) -> bool {
        // vertices by stamp (a fresh generation per test), edges counted in an open-addressing
        // table: linear in the cavity's size (this runs on most tagged insertions)
        self.vmark_gen = self.vmark_gen.wrapping_add(1);
        if self.vmark_gen == 0 {
            self.vmark.iter_mut().for_each(|m| *m = 0);
            self.vmark_gen = 1;
        }
        let gen = self.vmark_gen;
        if self.vmark.len() < self.pts.len() {
            self.vmark.resize(self.pts.len(), 0);
        }
        let bits = (usize::BITS - (6 * boundary.len()).leading_zeros()).max(4);
        let mut table = std::mem::take(&mut self.ball_edges);
        table.clear();
        table.resize(1 << bits, (u64::MAX, 0));
        let (mut verts, mut edges, mut infinite) = (0i64, 0i64, false);
        let mut manifold = true;
        'facets: for b in boundary {
            // the facet: the three vertices other than the new one (at `b.i`)
            let f: [u32; 3] = std::array::from_fn(|k| b.v[(b.i as usize + 1 + k) & 3]);
            for k in 0..3 {
                let w = f[k];
                if w == INFINITE {
                    verts += !infinite as i64;
                    infinite = true;
                } else if self.vmark[w as usize] != gen {
                    self.vmark[w as usize] = gen;
                    verts += 1;
                }
                let (x, y) = (w.min(f[(k + 1) % 3]), w.max(f[(k + 1) % 3]));
                let key = ((x as u64) << 32) | y as u64;
                let mut h = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize;
                loop {
                    let e = &mut table[h];
                    if e.0 == u64::MAX {
                        *e = (key, 1);
                        edges += 1;
                        break;
                    }
                    if e.0 == key {
                        e.1 += 1;
                        if e.1 > 2 {
                            manifold = false;
                            break 'facets;
                        }
                        break;
                    }
                    h = (h + 1) & ((1 << bits) - 1);
                }
            }
        }
        self.ball_edges = table;
        // each edge on exactly two facets: no count above two and 3F = 2E
        let manifold = manifold && 2 * edges == 3 * boundary.len() as i64;
        let euler = verts - edges + boundary.len() as i64;
        let keeps_vertices = || {
            cavity.iter().all(|&c| {
                self.tds.tets[c as usize].v.iter().all(|&w| {
                    if w == INFINITE {
                        infinite
                    } else {
                        self.vmark[w as usize] == gen
                    }
                })
            })
        };
        let ball = manifold && euler == 2 && keeps_vertices();
        if !ball {
            self.inconsistent = true;
        }
        ball
    }

    /// `Err(w)` when finite vertex `w` of `t` is at position `q`.
    #[inline]
    fn same_position(&self, t: u32, q: P) -> Result<(), u32> {
        match tet(&self.tds.tets, t)
            .v
            .into_iter()
            .find(|&w| w != INFINITE && self.pts[w as usize] == q)
        {
            Some(w) => Err(w),
            None => Ok(()),
        }
    }

    #[inline(never)]
    fn conflict_infinite(&self, t: u32, q: P) -> bool {
        let tt = &self.tds.tets[t as usize];
        let v = tt.v;
        let k = tt.index_of_vertex(INFINITE);
        let mut pts = [[0.0; 3]; 4];
        for m in 0..4 {
            if m != k {
                pts[m] = self.pts[v[m] as usize];
            }
        }
        let n = &self.tds.tets[(tt.n[k] & ID_MASK) as usize];
        let d = self.pts[n.v[index_of_neighbor_masked(n, t)] as usize];
        pred::conflict_infinite(pts, k, d, q, &self.bounds)
    }

    /// Locates internal point `q` from the hint.
    #[inline]
    pub(super) fn walk_from_hint(&mut self, q: P) -> u32 {
        let mut rng = self.rng;
        let t = walk(
            &self.tds.tets,
            &self.pts,
            q,
            self.hint,
            &mut rng,
            &self.bounds,
        );
        self.rng = rng;
        t
    }

    /// Inserts internal vertex `v` (already in `pts`) into the 3D triangulation. Returns `v`, or the
    /// internal id of the vertex already at that position (then nothing changed).
    pub(super) fn insert_vertex(&mut self, v: u32) -> u32 {
        if self.inconsistent {
            // a triangulation the tag rules could not keep valid takes no more points
            return v;
        }
        if self.tagged {
            self.insert_vertex_with::<true>(v)
        } else {
            self.insert_vertex_with::<false>(v)
        }
    }

    /// [`Delaunay::insert_vertex`], with the tag rules when `TAGGED` (a separate instance, so that
    /// the untagged hot loop is today's code).
    #[inline(always)]
    fn insert_vertex_with<const TAGGED: bool>(&mut self, v: u32) -> u32 {
        let q = self.pts[v as usize];
        let t0 = if TAGGED {
            match self.locate_tagged(v, q) {
                Ok(t) => t,
                Err(w) => return w,
            }
        } else {
            let t0 = self.walk_from_hint(q);
            if let Err(w) = self.same_position(t0, q) {
                return w;
            }
            t0
        };
        let tt = self.tds.tets[t0 as usize];
        // Grow the conflict region (a ball, star-shaped from q under the perturbation). Marks live in
        // the records (IN_CAVITY on n[0], OUTSIDE on n[1]); every boundary facet is recorded with
        // everything pass 1 needs, so that the cavity slots can be overwritten by new tetrahedra.
        let mut cavity = std::mem::take(&mut self.cavity);
        let mut boundary = std::mem::take(&mut self.boundary);
        let mut outside = std::mem::take(&mut self.outside);
        let mut newt = std::mem::take(&mut self.newt);
        cavity.clear();
        boundary.clear();
        outside.clear();
        newt.clear();
        let mut cavity_finite = 0usize;
        {
            let tets = &mut self.tds.tets;
            tets[t0 as usize].n[0] |= IN_CAVITY;
        }
        cavity_finite += !tt.is_infinite() as usize;
        for &n in &tt.n {
            prefetch(&self.tds.tets, n & ID_MASK);
        }
        cavity.push(t0);
        // Breadth-first: the cavity list is the queue, and the neighbours of a cell are prefetched
        // when it joins, so their records are on the way while earlier cells are processed.
        let mut head = 0;
        while head < cavity.len() {
            let c = cavity[head];
            head += 1;
            let ct = *tet(&self.tds.tets, c);
            let cn = ct.n.map(|n| n & ID_MASK);
            for (i, &n) in cn.iter().enumerate() {
                let nt = tet(&self.tds.tets, n);
                if nt.n[0] & IN_CAVITY != 0 {
                    continue;
                }
                if nt.n[1] & OUTSIDE == 0 {
                    let inside = if TAGGED {
                        self.conflict_tagged(n, v, q)
                    } else {
                        self.conflict(n, q)
                    };
                    if inside {
                        let nt = tet_mut(&mut self.tds.tets, n);
                        cavity_finite += !nt.is_infinite() as usize;
                        nt.n[0] |= IN_CAVITY;
                        let nn = nt.n;
                        for m in nn {
                            prefetch(&self.tds.tets, m & ID_MASK);
                        }
                        cavity.push(n);
                        continue;
                    }
                    tet_mut(&mut self.tds.tets, n).n[1] |= OUTSIDE;
                    outside.push(n);
                }
                let nt = tet(&self.tds.tets, n);
                // (built by selection: an indexed store followed by a wide load of the array
                // stalls store-to-load forwarding)
                let vs: [u32; 4] = std::array::from_fn(|k| if k == i { v } else { ct.v[k] });
                boundary.push(BoundaryFacet {
                    v: vs,
                    nb: n,
                    i: i as u8,
                    j: index_of_neighbor_masked(nt, c) as u8,
                });
            }
        }
        if TAGGED
            && (boundary.is_empty()
                || !self.cavity_is_star(&boundary, &outside)
                || !self.cavity_is_ball(&boundary, &cavity))
        {
            // leave the triangulation as it was (valid, without `v`): a non-star cavity, or one
            // that swallowed everything (tag rules contradicting the float predicates on a fan's
            // common line), would break the structure; the caller learns of it from
            // `Delaunay::consistent`
            for &c in &cavity {
                tet_mut(&mut self.tds.tets, c).n[0] &= ID_MASK;
            }
            for &n in &outside {
                tet_mut(&mut self.tds.tets, n).n[1] &= ID_MASK;
            }
            self.cavity = cavity;
            self.boundary = boundary;
            self.outside = outside;
            self.newt = newt;
            return v;
        }
        // Pass 1: one new tetrahedron per boundary facet (in the cavity's own slots first, they are
        // in cache), glued to the outside.
        let mut new_finite = 0usize;
        for (m, b) in boundary.iter().enumerate() {
            let nt = if m < cavity.len() {
                cavity[m]
            } else {
                self.tds.alloc(b.v)
            };
            newt.push(nt);
            let n: [u32; 4] = std::array::from_fn(|k| if k == b.i as usize { b.nb } else { NONE });
            *tet_mut(&mut self.tds.tets, nt) = Tet { v: b.v, n };
            tet_mut(&mut self.tds.tets, b.nb).n[b.j as usize] = nt;
            let rec = Tet { v: b.v, n };
            new_finite += !rec.is_infinite() as usize;
            if self.track_vtet {
                for &w in &b.v {
                    if w != INFINITE {
                        self.vtet[w as usize] = nt;
                    }
                }
            }
        }
        // A cavity always has fewer cells than boundary facets; keep the general case correct.
        for &c in cavity.iter().skip(boundary.len()) {
            self.tds.tets[c as usize].n[0] &= ID_MASK;
            self.tds.kill(c);
        }
        self.nfinite = self.nfinite + new_finite - cavity_finite;
        // Pass 2: glue the new tetrahedra to each other. Each edge {a,b} of the cavity boundary is
        // shared by exactly two boundary facets, whose new tetrahedra meet across the face {v,a,b}.
        self.glue_by_edge_table(&boundary, &newt);
        for &n in &outside {
            tet_mut(&mut self.tds.tets, n).n[1] &= ID_MASK;
        }
        self.hint = *newt.last().unwrap();
        self.cavity = cavity;
        self.boundary = boundary;
        self.outside = outside;
        self.newt = newt;
        v
    }

    /// Gluing through an open-addressing table keyed by the boundary edge (any cavity size).
    fn glue_by_edge_table(&mut self, boundary: &[BoundaryFacet], newt: &[u32]) {
        let bits = (usize::BITS - (4 * boundary.len()).leading_zeros()).max(4);
        let size = 1usize << bits;
        let mut table = std::mem::take(&mut self.edge_table);
        table.clear();
        table.resize(size, (EMPTY_EDGE, 0, 0));
        for (k, b) in boundary.iter().enumerate() {
            let nt = newt[k];
            let i = b.i as usize;
            let vs = b.v;
            for j in 0..4 {
                if j == i {
                    continue;
                }
                let (a, b) = other_two(i, j);
                let (x, y) = (vs[a].min(vs[b]), vs[a].max(vs[b]));
                let key = ((x as u64) << 32) | y as u64;
                let mut h = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize;
                loop {
                    let e = table[h];
                    if e.0 == EMPTY_EDGE {
                        table[h] = (key, nt, j as u8);
                        break;
                    }
                    if e.0 == key {
                        tet_mut(&mut self.tds.tets, nt).n[j] = e.1;
                        tet_mut(&mut self.tds.tets, e.1).n[e.2 as usize] = nt;
                        break;
                    }
                    h = (h + 1) & (size - 1);
                }
            }
        }
        self.edge_table = table;
    }
}

/// The public insertion: one point, or a batch in BRIO order with the ids of insertion in order.
impl Delaunay {
    /// Inserts a point; returns its new id, or the id of the existing vertex at exactly that position
    /// (the new id is then recorded in [`Delaunay::duplicates`]). Panics on non-finite coordinates.
    pub fn insert(&mut self, p: [f64; 3]) -> VertexId {
        assert!(
            p.iter().all(|c| c.is_finite()),
            "Delaunay::insert: non-finite coordinate"
        );
        self.insert_tagged_unchecked(p, PointTags::none())
    }

    /// Inserts a point lying on the planes of `tags` (as [`Delaunay::insert`]; on a triangulation
    /// built by [`Delaunay::new`] the tags are ignored). Panics on non-finite coordinates or bad tags.
    /// After it, [`Delaunay::consistent`] says whether the triangulation can be trusted.
    pub fn insert_tagged(&mut self, p: [f64; 3], tags: &PointTags) -> VertexId {
        assert!(
            p.iter().all(|c| c.is_finite()),
            "Delaunay::insert_tagged: non-finite coordinate"
        );
        let t = tags
            .normalized()
            .expect("Delaunay::insert_tagged: bad tags");
        self.insert_tagged_unchecked(p, t)
    }

    fn insert_tagged_unchecked(&mut self, p: [f64; 3], tags: PointTags) -> VertexId {
        let e = self.int.len() as u32;
        self.int.push(NONE);
        match self.place(e, norm(p), tags) {
            Some(kept) => {
                self.dups.push((e, kept));
                kept
            }
            None => e,
        }
    }

    /// Inserts the (normalised) point of external id `e`, whose `int` slot exists. Returns the kept
    /// vertex's external id when a vertex is already at that position (nothing is added then).
    fn place(&mut self, e: u32, p: P, tags: PointTags) -> Option<VertexId> {
        let k = self.pts.len() as u32;
        self.cover(p);
        self.pts.push(p);
        if self.tagged {
            self.tags.push(tags);
        }
        self.ext.push(e);
        self.vtet.push(NONE);
        self.int[e as usize] = k;
        let w = if self.dim < 3 {
            self.add_pending(k)
        } else {
            self.insert_vertex(k)
        };
        if w == k {
            return None;
        }
        self.pts.pop();
        self.ext.pop();
        self.vtet.pop();
        if self.tagged {
            self.tags.pop();
        }
        self.int[e as usize] = w;
        Some(self.ext[w as usize])
    }

    /// Inserts `points` as [`Delaunay::insert`] would one after the other (the same ids, the same
    /// merged duplicates, the same triangulation: it is unique for a point set under the
    /// perturbation), but in BRIO order, which for a cell's diagram samples (given row by row of a
    /// grid) makes fewer and smaller conflict regions. Returns each point's id (the kept vertex's
    /// for a duplicate). Panics on non-finite coordinates.
    pub fn insert_batch(&mut self, points: &[[f64; 3]]) -> Vec<VertexId> {
        self.insert_batch_with(points, None)
    }

    /// [`Delaunay::insert_batch`] of points lying on the planes of `tags` (one per point; ignored on
    /// a triangulation built untagged). Panics on non-finite coordinates, a length mismatch or bad
    /// tags. After it, [`Delaunay::consistent`] says whether the triangulation can be trusted.
    pub fn insert_batch_tagged(
        &mut self,
        points: &[[f64; 3]],
        tags: &[PointTags],
    ) -> Vec<VertexId> {
        assert_eq!(
            tags.len(),
            points.len(),
            "Delaunay::insert_batch_tagged: one tag set per point"
        );
        self.insert_batch_with(points, Some(tags))
    }

    fn insert_batch_with(
        &mut self,
        points: &[[f64; 3]],
        tags: Option<&[PointTags]>,
    ) -> Vec<VertexId> {
        assert!(
            points.iter().all(|p| p.iter().all(|c| c.is_finite())),
            "Delaunay::insert_batch: non-finite coordinate"
        );
        let e0 = self.int.len() as u32;
        // a repeated position within the batch maps to its first occurrence (as in order)
        let mut first: HashMap<[u64; 3], u32, FastHash> = HashMap::default();
        let same_as: Vec<u32> = (0..points.len() as u32)
            .map(|i| *first.entry(key(norm(points[i as usize]))).or_insert(i))
            .collect();
        self.int.resize(e0 as usize + points.len(), NONE);
        let mut new_dups = Vec::new();
        for i in sort::brio_order(points) {
            if same_as[i as usize] != i {
                continue;
            }
            let e = e0 + i;
            // a kept vertex is an earlier one (never of this batch: those are at distinct positions)
            let t = match tags {
                Some(tags) if self.tagged => tags[i as usize]
                    .normalized()
                    .expect("Delaunay::insert_batch_tagged: bad tags"),
                _ => PointTags::none(),
            };
            if let Some(kept) = self.place(e, norm(points[i as usize]), t) {
                new_dups.push((e, kept));
            }
        }
        for (i, &j) in same_as.iter().enumerate() {
            if j != i as u32 {
                let w = self.int[(e0 + j) as usize];
                self.int[e0 as usize + i] = w;
                new_dups.push((e0 + i as u32, self.ext[w as usize]));
            }
        }
        new_dups.sort_unstable();
        self.dups.extend(new_dups);
        (e0..e0 + points.len() as u32)
            .map(|e| self.canonical(e))
            .collect()
    }
}
