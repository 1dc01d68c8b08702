//! Incremental construction: the first tetrahedron, the stochastic visibility walk, and
//! Bowyer–Watson insertion (conflict region grown from the located tetrahedron, then starred from
//! the new vertex). All ids here are internal vertex ids (insertion order).
use super::pred::{self, P};
use super::tds::{facet_key, other_two, Tet, INFINITE, IN_CAVITY, NONE, OUTSIDE};
use super::Delaunay;

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

/// Coordinates of finite internal vertex `v` (< pts.len() by construction).
#[inline(always)]
fn pt(pts: &[P], v: u32) -> P {
    debug_assert!((v as usize) < pts.len());
    // SAFETY: finite vertex ids stored in live records are internal ids < pts.len().
    unsafe { *pts.get_unchecked(v as usize) }
}

#[inline]
fn xorshift(mut x: u32) -> u32 {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    x
}

/// Stochastic visibility walk from `start` to a finite tetrahedron containing `q` (closed), or to the
/// infinite tetrahedron whose hull facet sees `q` strictly. Terminates with probability 1.
#[inline]
pub(super) fn walk(tets: &[Tet], pts: &[P], q: P, start: u32, rng: &mut u32) -> u32 {
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
            if pred::orient(s[0], s[1], s[2], s[3]) < 0.0 {
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

    /// Perturbed conflict of tetrahedron `t` with point `q`.
    #[inline]
    pub(super) fn conflict(&self, t: u32, q: P) -> bool {
        let tt = tet(&self.tds.tets, t);
        let v = tt.v;
        if !tt.is_infinite() {
            let p = |k: usize| pt(&self.pts, v[k]);
            return pred::conflict_finite([p(0), p(1), p(2), p(3)], q);
        }
        let k = tt.index_of_vertex(INFINITE);
        let mut pts = [[0.0; 3]; 4];
        for m in 0..4 {
            if m != k {
                pts[m] = self.pts[v[m] as usize];
            }
        }
        let n = &self.tds.tets[tt.n[k] as usize];
        let d = self.pts[n.v[n.index_of_neighbor(t)] as usize];
        pred::conflict_infinite(pts, k, d, q)
    }

    /// Locates internal point `q` from the hint.
    #[inline]
    pub(super) fn walk_from_hint(&mut self, q: P) -> u32 {
        let mut rng = self.rng;
        let t = walk(&self.tds.tets, &self.pts, q, self.hint, &mut rng);
        self.rng = rng;
        t
    }

    /// Inserts internal vertex `v` (already in `pts`) into the 3D triangulation. Returns `v`, or the
    /// internal id of the vertex already at that position (then nothing changed).
    pub(super) fn insert_vertex(&mut self, v: u32) -> u32 {
        let q = self.pts[v as usize];
        let t0 = self.walk_from_hint(q);
        let tt = self.tds.tets[t0 as usize];
        if !tt.is_infinite() {
            for w in tt.v {
                if self.pts[w as usize] == q {
                    return w;
                }
            }
        }
        // Grow the conflict region (a ball, star-shaped from q under the perturbation).
        let mut stack = std::mem::take(&mut self.stack);
        let mut cavity = std::mem::take(&mut self.cavity);
        let mut boundary = std::mem::take(&mut self.boundary);
        let mut outside = std::mem::take(&mut self.outside);
        let mut newt = std::mem::take(&mut self.newt);
        stack.clear();
        cavity.clear();
        boundary.clear();
        outside.clear();
        newt.clear();
        self.tds.flags[t0 as usize] = IN_CAVITY;
        stack.push(t0);
        cavity.push(t0);
        while let Some(c) = stack.pop() {
            let cn = tet(&self.tds.tets, c).n;
            for &n in &cn {
                prefetch(&self.tds.tets, n);
            }
            for (i, &n) in cn.iter().enumerate() {
                let f = self.tds.flags[n as usize];
                if f & IN_CAVITY != 0 {
                    continue;
                }
                if f & OUTSIDE == 0 {
                    if self.conflict(n, q) {
                        self.tds.flags[n as usize] = IN_CAVITY;
                        stack.push(n);
                        cavity.push(n);
                        continue;
                    }
                    self.tds.flags[n as usize] = OUTSIDE;
                    outside.push(n);
                }
                boundary.push((c, i as u8));
            }
        }
        // Pass 1: one new tetrahedron per boundary facet, glued to the outside; the dead cavity cell
        // remembers it in its neighbour slot.
        for &(c, i) in &boundary {
            let i = i as usize;
            let ct = &self.tds.tets[c as usize];
            let mut vs = ct.v;
            vs[i] = v;
            let nb = ct.n[i];
            let nt = self.tds.alloc(vs);
            newt.push(nt);
            self.tds.tets[nt as usize].n[i] = nb;
            let nbt = &mut self.tds.tets[nb as usize];
            let j = nbt.index_of_neighbor(c);
            nbt.n[j] = nt;
            self.tds.tets[c as usize].n[i] = nt;
            let finite = !self.tds.tets[nt as usize].is_infinite();
            if self.track_vtet {
                for &w in &vs {
                    if w != INFINITE {
                        self.vtet[w as usize] = nt;
                    }
                }
            }
            self.nfinite += finite as usize;
        }
        // Pass 2: glue the new tetrahedra to each other. The neighbour of new tet (c,i) across its
        // face {v,a,b} comes from the other boundary facet on edge ab: turn around ab inside the
        // cavity, starting from c.
        for (k, &(c, i)) in boundary.iter().enumerate() {
            let nt = newt[k];
            let i = i as usize;
            let vs = self.tds.tets[nt as usize].v;
            for j in 0..4 {
                if j == i || self.tds.tets[nt as usize].n[j] != NONE {
                    continue;
                }
                let (a, b) = other_two(i, j);
                let (va, vb) = (vs[a], vs[b]);
                let mut cur = c;
                let mut f = j;
                loop {
                    let ct = &self.tds.tets[cur as usize];
                    let cv = ct.v;
                    // the vertex of cur's face f other than a and b
                    let (x, y) = other_two(f, cv.iter().position(|&w| w == va).unwrap());
                    let wpos = if cv[x] == vb { y } else { x };
                    let n = ct.n[f];
                    if self.tds.flags[n as usize] & IN_CAVITY != 0 {
                        f = self.tds.tets[n as usize].index_of_vertex(cv[wpos]);
                        cur = n;
                    } else {
                        self.tds.tets[nt as usize].n[j] = n;
                        self.tds.tets[n as usize].n[wpos] = nt;
                        break;
                    }
                }
            }
        }
        for &c in &cavity {
            self.tds.flags[c as usize] = 0;
            if !self.tds.tets[c as usize].is_infinite() {
                self.nfinite -= 1;
            }
            self.tds.kill(c);
        }
        for &n in &outside {
            self.tds.flags[n as usize] = 0;
        }
        self.hint = *newt.last().unwrap();
        self.stack = stack;
        self.cavity = cavity;
        self.boundary = boundary;
        self.outside = outside;
        self.newt = newt;
        v
    }
}
