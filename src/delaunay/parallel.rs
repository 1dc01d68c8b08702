//! Parallel bulk insertion (untagged construction only), after geogram's PDEL: the points of a BRIO
//! round (Hilbert-sorted, so contiguous chunks are spatial regions) are split into one chunk per
//! thread, and the threads insert into the one shared triangulation. A thread touches only the
//! tetrahedra it owns: every record it reads (walk, conflict test, neighbour of the cavity whose
//! adjacency it rewrites) is acquired first by a compare-and-swap on its owner byte. When a record is
//! owned by another thread, the insertion is undone before anything was written (only scratch marks),
//! the thread's records released, and the point is deferred to a sequential tail after the round.
//! Records are kept between insertions and released every `HOLD` insertions.
//!
//! The result is the Delaunay triangulation of the points under the symbolic perturbation, which
//! depends on the coordinates only (lexicographic order), never on insertion order: it is unique,
//! so the tetrahedra are the same as the sequential build's (slot numbers differ).
use super::insert::{index_of_neighbor_masked, BoundaryFacet};
use super::pred::{self, P};
use super::tds::{other_two, Tet, DEAD, ID_MASK, INFINITE, IN_CAVITY, NONE, OUTSIDE};
use super::Delaunay;
use std::sync::atomic::{AtomicU8, AtomicUsize, Ordering};

/// Rounds with fewer points than this are inserted sequentially.
pub(super) const MIN_ROUND: usize = 8192;

/// A thread keeps the records it acquired for this many insertions (most of what the next
/// insertions touch is then its own already: one compare-and-swap per record and period, not per
/// visit), then releases them all.
const HOLD: usize = 64;

/// Fresh slots are handed to the threads in blocks of this many.
const BLOCK: usize = 2048;

/// The triangulation shared by the threads of one round.
struct Shared<'a> {
    tets: *mut Tet,
    /// Slots `[0, cap)` may be written; `next` is the first never used.
    cap: usize,
    /// Slots below `old` existed before the round.
    old: usize,
    next: AtomicUsize,
    owner: Vec<AtomicU8>,
    pts: &'a [P],
    bounds: pred::Bounds,
}

// SAFETY: records are accessed only by the thread that owns them (owner byte acquired with
// Acquire ordering, released with Release), so no two threads access one record concurrently.
unsafe impl Sync for Shared<'_> {}

/// Why an insertion did not happen in the parallel phase.
enum Abort {
    /// A record was owned by another thread (or the hint was dead): defer the point.
    Busy,
    /// No slot left: defer this point and the rest of the chunk.
    Full,
}

/// One thread's state.
struct Worker {
    me: u8,
    held: Vec<u32>,
    cavity: Vec<u32>,
    boundary: Vec<BoundaryFacet>,
    outside: Vec<u32>,
    newt: Vec<u32>,
    edge_table: Vec<(u64, u32, u8)>,
    free: Vec<u32>,
    hint: u32,
    rng: u32,
    /// (internal id, internal id of the vertex at the same position).
    dropped: Vec<(u32, u32)>,
    deferred: Vec<u32>,
    /// Change in the number of finite tetrahedra.
    dfinite: isize,
    /// Unused slots of this thread's current block of fresh slots.
    block: (u32, u32),
}

impl Shared<'_> {
    #[inline(always)]
    fn rec(&self, t: u32) -> &Tet {
        debug_assert!((t as usize) < self.cap);
        // SAFETY: t < cap (a neighbour or slot id), and the caller owns record t.
        unsafe { &*self.tets.add(t as usize) }
    }
    #[inline(always)]
    #[allow(clippy::mut_from_ref)]
    fn rec_mut(&self, t: u32) -> &mut Tet {
        debug_assert!((t as usize) < self.cap);
        // SAFETY: as in `rec`; the owner is the only thread accessing the record.
        unsafe { &mut *self.tets.add(t as usize) }
    }
    #[inline(always)]
    fn pt(&self, v: u32) -> P {
        self.pts[v as usize]
    }
}

impl Worker {
    fn new(me: u8, hint: u32, rng: u32) -> Worker {
        Worker {
            me,
            held: Vec::new(),
            cavity: Vec::new(),
            boundary: Vec::new(),
            outside: Vec::new(),
            newt: Vec::new(),
            edge_table: Vec::new(),
            free: Vec::new(),
            hint,
            rng,
            dropped: Vec::new(),
            deferred: Vec::new(),
            dfinite: 0,
            block: (0, 0),
        }
    }

    /// Acquires record `t` (true when this thread owns it, possibly already).
    #[inline(always)]
    fn acquire(&mut self, s: &Shared, t: u32) -> bool {
        let o = &s.owner[t as usize];
        let cur = o.load(Ordering::Relaxed);
        if cur == self.me {
            return true;
        }
        if cur != 0 {
            return false;
        }
        if o.compare_exchange(0, self.me, Ordering::Acquire, Ordering::Relaxed)
            .is_ok()
        {
            self.held.push(t);
            true
        } else {
            false
        }
    }

    fn release_all(&mut self, s: &Shared) {
        for &t in &self.held {
            s.owner[t as usize].store(0, Ordering::Release);
        }
        self.held.clear();
    }

    /// A slot for a new record with vertices `v`, acquired.
    fn alloc(&mut self, s: &Shared, v: [u32; 4]) -> Result<u32, Abort> {
        if let Some(t) = self.free.pop() {
            if self.acquire(s, t) {
                *s.rec_mut(t) = Tet { v, n: [NONE; 4] };
                return Ok(t);
            }
            // a stale hint of another thread holds it for a moment: keep it for later
            self.free.insert(0, t);
        }
        if self.block.0 == self.block.1 {
            // slots in blocks, so that one thread's records share no cache line with another's
            let b = s.next.fetch_add(BLOCK, Ordering::Relaxed);
            if b >= s.cap {
                return Err(Abort::Full);
            }
            self.block = (b as u32, (b + BLOCK).min(s.cap) as u32);
        }
        let t = self.block.0;
        self.block.0 += 1;
        let ok = self.acquire(s, t);
        debug_assert!(ok, "a fresh slot is reachable by nobody");
        *s.rec_mut(t) = Tet { v, n: [NONE; 4] };
        Ok(t)
    }

    /// Stochastic visibility walk (as `insert::walk`), acquiring every record it reads and
    /// releasing the ones it leaves.
    fn walk(&mut self, s: &Shared, q: P) -> Result<u32, Abort> {
        let mut t = self.start(s)?;
        if s.rec(t).is_infinite() {
            let tt = s.rec(t);
            let n = tt.n[tt.index_of_vertex(INFINITE)] & ID_MASK;
            if !self.acquire(s, n) {
                return Err(Abort::Busy);
            }
            t = n;
        }
        let mut prev = NONE;
        'outer: loop {
            self.rng = super::insert::xorshift(self.rng);
            let tt = *s.rec(t);
            let p = tt.v.map(|w| s.pt(w));
            let r = (self.rng >> 11) as usize;
            for k in 0..4 {
                let i = (r + k) & 3;
                let n = tt.n[i] & ID_MASK;
                if n == prev {
                    continue;
                }
                let mut sp = p;
                sp[i] = q;
                if pred::orient_within(sp[0], sp[1], sp[2], sp[3], s.bounds.orient) < 0.0 {
                    if !self.acquire(s, n) {
                        return Err(Abort::Busy);
                    }
                    prev = t;
                    t = n;
                    if s.rec(n).is_infinite() {
                        return Ok(t);
                    }
                    continue 'outer;
                }
            }
            return Ok(t);
        }
    }

    /// An acquired live record to start the walk from: the hint, else (it died in another thread's
    /// cavity) one of the previous insertion's new records, else a slot that existed before the
    /// round (always written: live or dead) chosen pseudo-randomly.
    fn start(&mut self, s: &Shared) -> Result<u32, Abort> {
        let h = self.hint;
        let n = self.newt.len();
        let old = |k: u32| ((h as u64 * 7919 + k as u64 * 104_729) % s.old as u64) as u32;
        for k in 0..(1 + n as u32 + 64) {
            let t = match k as usize {
                0 => h,
                m if m <= n => self.newt[m - 1],
                _ => old(k),
            };
            if self.acquire(s, t) && !s.rec(t).is_dead() {
                self.hint = t;
                return Ok(t);
            }
        }
        Err(Abort::Busy)
    }

    /// Conflict of owned record `t` with `q`; an infinite one needs its finite neighbour, acquired.
    #[inline(always)]
    fn conflict(&mut self, s: &Shared, t: u32, q: P) -> Result<bool, Abort> {
        let tt = *s.rec(t);
        if !tt.is_infinite() {
            let p = tt.v.map(|w| s.pt(w));
            return Ok(pred::conflict_finite(p, q, &s.bounds));
        }
        let k = tt.index_of_vertex(INFINITE);
        let nb = tt.n[k] & ID_MASK;
        if !self.acquire(s, nb) {
            return Err(Abort::Busy);
        }
        let p: [P; 4] = std::array::from_fn(|m| if m == k { [0.0; 3] } else { s.pt(tt.v[m]) });
        let n = s.rec(nb);
        let d = s.pt(n.v[index_of_neighbor_masked(n, t)]);
        Ok(pred::conflict_infinite(p, k, d, q, &s.bounds))
    }

    /// Clears the scratch marks of the cavity being grown and releases everything.
    fn undo(&mut self, s: &Shared) {
        for &c in &self.cavity {
            s.rec_mut(c).n[0] &= ID_MASK;
        }
        for &n in &self.outside {
            s.rec_mut(n).n[1] &= ID_MASK;
        }
        self.release_all(s);
    }

    /// Inserts internal vertex `v`; `Ok(w)` with `w != v` for a duplicate of `w`.
    fn insert(&mut self, s: &Shared, v: u32) -> Result<u32, Abort> {
        let q = s.pt(v);
        self.cavity.clear();
        self.boundary.clear();
        self.outside.clear();
        let r = self.walk(s, q).and_then(|t0| {
            if let Some(w) = s
                .rec(t0)
                .v
                .into_iter()
                .find(|&w| w != INFINITE && s.pt(w) == q)
            {
                return Ok(Some(w));
            }
            self.grow(s, t0, v, q).map(|_| None)
        });
        match r {
            Ok(Some(w)) => Ok(w),
            Ok(None) => {
                self.star(s)?;
                Ok(v)
            }
            Err(e) => {
                self.undo(s);
                Err(e)
            }
        }
    }

    /// Grows the conflict region of `q` from `t0` (as `insert_vertex_with`), acquiring each record.
    fn grow(&mut self, s: &Shared, t0: u32, v: u32, q: P) -> Result<(), Abort> {
        s.rec_mut(t0).n[0] |= IN_CAVITY;
        self.cavity.push(t0);
        let mut head = 0;
        while head < self.cavity.len() {
            let c = self.cavity[head];
            head += 1;
            let ct = *s.rec(c);
            let cn = ct.n.map(|n| n & ID_MASK);
            for (i, &n) in cn.iter().enumerate() {
                if !self.acquire(s, n) {
                    return Err(Abort::Busy);
                }
                let nt = s.rec(n);
                if nt.n[0] & IN_CAVITY != 0 {
                    continue;
                }
                if nt.n[1] & OUTSIDE == 0 {
                    if self.conflict(s, n, q)? {
                        s.rec_mut(n).n[0] |= IN_CAVITY;
                        self.cavity.push(n);
                        continue;
                    }
                    s.rec_mut(n).n[1] |= OUTSIDE;
                    self.outside.push(n);
                }
                let nt = s.rec(n);
                let vs: [u32; 4] = std::array::from_fn(|k| if k == i { v } else { ct.v[k] });
                self.boundary.push(BoundaryFacet {
                    v: vs,
                    nb: n,
                    i: i as u8,
                    j: index_of_neighbor_masked(nt, c) as u8,
                });
            }
        }
        Ok(())
    }

    /// Replaces the cavity by the star of the new vertex (every record involved is owned), then
    /// releases everything.
    fn star(&mut self, s: &Shared) -> Result<(), Abort> {
        // slots first: an allocation failure must leave the triangulation untouched
        self.newt.clear();
        let nb = self.boundary.len();
        for m in 0..nb {
            let t = if m < self.cavity.len() {
                self.cavity[m]
            } else {
                match self.alloc(s, self.boundary[m].v) {
                    Ok(t) => t,
                    Err(e) => {
                        for &t in &self.newt[self.cavity.len().min(self.newt.len())..] {
                            s.rec_mut(t).v[0] = DEAD;
                            self.free.push(t);
                        }
                        self.undo(s);
                        return Err(e);
                    }
                }
            };
            self.newt.push(t);
        }
        let cavity_finite = self
            .cavity
            .iter()
            .filter(|&&c| !s.rec(c).is_infinite())
            .count();
        let mut new_finite = 0;
        for (m, b) in self.boundary.iter().enumerate() {
            let nt = self.newt[m];
            let n: [u32; 4] = std::array::from_fn(|k| if k == b.i as usize { b.nb } else { NONE });
            *s.rec_mut(nt) = Tet { v: b.v, n };
            s.rec_mut(b.nb).n[b.j as usize] = nt;
            new_finite += !b.v.contains(&INFINITE) as usize;
        }
        for &c in self.cavity.iter().skip(nb) {
            s.rec_mut(c).v[0] = DEAD;
            s.rec_mut(c).n[0] &= ID_MASK;
            self.free.push(c);
        }
        self.dfinite += new_finite as isize - cavity_finite as isize;
        self.glue(s);
        for &n in &self.outside {
            s.rec_mut(n).n[1] &= ID_MASK;
        }
        self.hint = *self.newt.last().unwrap();
        Ok(())
    }

    /// Glues the new records to each other by their shared boundary edges (as `glue_by_edge_table`).
    fn glue(&mut self, s: &Shared) {
        let bits = (usize::BITS - (4 * self.boundary.len()).leading_zeros()).max(4);
        let size = 1usize << bits;
        let table = &mut self.edge_table;
        table.clear();
        table.resize(size, (u64::MAX, 0, 0));
        for (k, b) in self.boundary.iter().enumerate() {
            let nt = self.newt[k];
            let i = b.i as usize;
            for j in 0..4 {
                if j == i {
                    continue;
                }
                let (a, c) = other_two(i, j);
                let (x, y) = (b.v[a].min(b.v[c]), b.v[a].max(b.v[c]));
                let key = ((x as u64) << 32) | y as u64;
                let mut h = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize;
                loop {
                    let e = table[h];
                    if e.0 == u64::MAX {
                        table[h] = (key, nt, j as u8);
                        break;
                    }
                    if e.0 == key {
                        s.rec_mut(nt).n[j] = e.1;
                        s.rec_mut(e.1).n[e.2 as usize] = nt;
                        break;
                    }
                    h = (h + 1) & (size - 1);
                }
            }
        }
    }

    /// Inserts a chunk of internal vertices, deferring those that meet another thread.
    fn run(&mut self, s: &Shared, chunk: &[u32]) {
        for (k, &v) in chunk.iter().enumerate() {
            if k % HOLD == 0 {
                self.release_all(s);
            }
            match self.insert(s, v) {
                Ok(w) if w != v => self.dropped.push((v, w)),
                Ok(_) => {}
                Err(Abort::Busy) => self.deferred.push(v),
                Err(Abort::Full) => {
                    self.deferred.extend_from_slice(&chunk[k..]);
                    break;
                }
            }
        }
        self.release_all(s);
    }
}

impl Delaunay {
    /// Inserts internal vertices `range` (one BRIO round, Hilbert-sorted) with `threads` threads,
    /// then the deferred ones sequentially. Needs `dim == 3`, untagged, `track_vtet` off. Returns
    /// the (dropped, kept) pairs of duplicates found.
    pub(super) fn insert_round_parallel(
        &mut self,
        range: std::ops::Range<u32>,
        threads: usize,
    ) -> Vec<(u32, u32)> {
        debug_assert!(self.dim == 3 && !self.tagged && !self.track_vtet);
        let m = (range.end - range.start) as usize;
        let len = self.tds.tets.len();
        // about 6.75 new tetrahedra per point; more than that defers the rest to the tail
        let cap = (len + 7 * m + m / 4 + 4096).max(self.tds.tets.capacity());
        assert!(cap < ID_MASK as usize, "more than 2^31 tetrahedra");
        self.tds.tets.reserve_exact(cap - len);
        let verts: Vec<u32> = range.collect();
        let chunk = m.div_ceil(threads);
        // each thread starts at a tetrahedron near its chunk's first point (a walk from the hint)
        let starts: Vec<u32> = verts
            .chunks(chunk)
            .map(|c| self.walk_from_hint(self.pts[c[0] as usize]))
            .collect();
        let mut workers: Vec<Worker> = starts
            .iter()
            .enumerate()
            .map(|(k, &h)| Worker::new(k as u8 + 1, h, 0x9E37_79B9 ^ (k as u32 * 0x85EB_CA6B)))
            .collect();
        workers[0].free = std::mem::take(&mut self.tds.free);
        let shared = Shared {
            tets: self.tds.tets.as_mut_ptr(),
            cap,
            old: len,
            next: AtomicUsize::new(len),
            owner: (0..cap).map(|_| AtomicU8::new(0)).collect(),
            pts: &self.pts,
            bounds: self.bounds,
        };
        rayon::scope(|sc| {
            for (w, c) in workers.iter_mut().zip(verts.chunks(chunk)) {
                let sh = &shared;
                sc.spawn(move |_| w.run(sh, c));
            }
        });
        let used = shared.next.load(Ordering::Relaxed).min(cap);
        for w in &mut workers {
            // the unused rest of a block: dead records on the free list
            for t in w.block.0..w.block.1 {
                *shared.rec_mut(t) = Tet {
                    v: [DEAD; 4],
                    n: [NONE; 4],
                };
                w.free.push(t);
            }
        }
        drop(shared);
        // SAFETY: every slot below `used` was written, by `alloc` (fresh slots are written at once)
        // or above (the unused rest of each block); capacity is at least cap.
        unsafe { self.tds.tets.set_len(used) };
        let mut dropped = Vec::new();
        let mut deferred = Vec::new();
        for w in &mut workers {
            self.tds.free.append(&mut w.free);
            self.nfinite = (self.nfinite as isize + w.dfinite) as usize;
            dropped.append(&mut w.dropped);
            deferred.append(&mut w.deferred);
        }
        self.hint = workers
            .iter()
            .map(|w| w.hint)
            .find(|&h| !self.tds.tets[h as usize].is_dead())
            .unwrap_or_else(|| self.any_live_tet());
        self.parallel_deferred += deferred.len();
        for v in deferred {
            let w = self.insert_vertex(v);
            if w != v {
                dropped.push((v, w));
            }
        }
        dropped
    }

    /// Some live tetrahedron (the hint after a round whose workers' hints all died).
    fn any_live_tet(&self) -> u32 {
        self.tds.tets.iter().position(|t| !t.is_dead()).unwrap() as u32
    }
}
