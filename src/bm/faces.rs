//! The faces of a list of tetrahedra grouped by sorted key, without hashing: bucketed by their
//! smallest vertex (a counting sort), each bucket sorted by the other two. Building it and looking
//! faces up is several times faster than a hash map of the ~4 faces per tetrahedron of a whole
//! complex, which the assembly rebuilds many times.
use super::complex::outward_face;
use rayon::prelude::*;

/// Per face (sorted key): the tetrahedra that have it, in increasing index.
pub struct FaceTable {
    /// `keys[start[v]..start[v + 1]]`: the faces whose smallest vertex is `v` (the other two
    /// vertices, `k1 << 32 | k2`).
    start: Vec<u32>,
    keys: Vec<u64>,
    /// Per entry, `4 * tet + i`: the face is opposite local vertex `i` of tetrahedron `tet`.
    codes: Vec<u32>,
}

/// In [`FaceTable::neighbours`]: the face is on no other tetrahedron.
pub const NO_NEIGHBOUR: u32 = u32::MAX;
/// In [`FaceTable::neighbours`]: the face is on two or more other tetrahedra.
pub const MANY_NEIGHBOURS: u32 = u32::MAX - 1;

/// The four vertices in increasing order (a sorting network).
#[inline]
fn sorted4(mut t: [u32; 4]) -> [u32; 4] {
    for (a, b) in [(0, 1), (2, 3), (0, 2), (1, 3), (1, 2)] {
        if t[a] > t[b] {
            t.swap(a, b);
        }
    }
    t
}

impl FaceTable {
    /// The faces of `tets`, numbered in the order given.
    pub fn new(tets: &[[u32; 4]]) -> FaceTable {
        Self::of_lists(&[tets])
    }

    /// The faces of the concatenation of `lists`.
    pub fn of_lists(lists: &[&[[u32; 4]]]) -> FaceTable {
        let (n, n_codes) = sizes(lists);
        if Narrow::fits(n, n_codes) {
            Self::of_rows(bucketed::<Narrow>(lists, n))
        } else {
            Self::of_rows(bucketed::<Wide>(lists, n))
        }
    }

    fn of_rows<R: Row>((start, rows): (Vec<u32>, Vec<R>)) -> FaceTable {
        let keys = rows.iter().map(|r| r.key()).collect();
        let codes = rows.iter().map(|r| r.code()).collect();
        FaceTable { start, keys, codes }
    }

    /// The entries (codes `4 * tet + i`) of face `f` (a sorted key).
    pub fn codes(&self, f: &[u32; 3]) -> &[u32] {
        let Some(&lo) = self.start.get(f[0] as usize) else {
            return &[];
        };
        let (lo, hi) = (lo as usize, self.start[f[0] as usize + 1] as usize);
        let bucket = &self.keys[lo..hi];
        let k = (f[1] as u64) << 32 | f[2] as u64;
        let a = bucket.partition_point(|x| *x < k);
        let b = a + bucket[a..].partition_point(|x| *x == k);
        &self.codes[lo + a..lo + b]
    }

    /// The tetrahedra that have face `f` (a sorted key), in increasing index.
    pub fn owners(&self, f: &[u32; 3]) -> impl ExactSizeIterator<Item = u32> + Clone + '_ {
        self.codes(f).iter().map(|c| c >> 2)
    }

    /// Per tetrahedron (of `n_tets`) and local face `i`: the other tetrahedron with that face,
    /// [`NO_NEIGHBOUR`] when none, [`MANY_NEIGHBOURS`] when several (overlapping tetrahedra:
    /// look them up with [`FaceTable::owners`]). Walks through K read this in O(1) instead of a
    /// search per step.
    pub fn neighbours(&self, n_tets: usize) -> Vec<[u32; 4]> {
        let mut out = vec![[NO_NEIGHBOUR; 4]; n_tets];
        self.for_each_face(|codes| match *codes {
            [a, b] => {
                out[(a >> 2) as usize][(a & 3) as usize] = b >> 2;
                out[(b >> 2) as usize][(b & 3) as usize] = a >> 2;
            }
            [_] => {}
            _ => {
                for &c in codes {
                    out[(c >> 2) as usize][(c & 3) as usize] = MANY_NEIGHBOURS;
                }
            }
        });
        out
    }

    /// The tetrahedron across face `i` of `tets[t]` that passes `ok`, read from `neighbours`
    /// (this table's [`FaceTable::neighbours`] of `tets`); where several overlap there, the first
    /// by index.
    pub fn across(
        &self,
        tets: &[[u32; 4]],
        neighbours: &[[u32; 4]],
        t: usize,
        i: usize,
        ok: impl Fn(usize) -> bool,
    ) -> Option<usize> {
        match neighbours[t][i] {
            NO_NEIGHBOUR => None,
            MANY_NEIGHBOURS => {
                let mut f = outward_face(&tets[t], i);
                f.sort_unstable();
                (self.owners(&f).map(|o| o as usize)).find(|&o| o != t && ok(o))
            }
            o => Some(o as usize).filter(|&o| ok(o)),
        }
    }

    /// Calls `f` with the entries (codes) of every face, in increasing key.
    pub fn for_each_face(&self, mut f: impl FnMut(&[u32])) {
        for v in 0..self.start.len().saturating_sub(1) {
            let (lo, hi) = (self.start[v] as usize, self.start[v + 1] as usize);
            let mut i = lo;
            while i < hi {
                let mut j = i + 1;
                while j < hi && self.keys[j] == self.keys[i] {
                    j += 1;
                }
                f(&self.codes[i..j]);
                i = j;
            }
        }
    }
}

/// One face in [`bucketed`]'s buckets: its two larger vertices and its code `4 * tet + i`, packed
/// in one integer whose order is (key, code), so that each bucket sorts as plain integers.
trait Row: Copy + Ord + Send + Sync + Default {
    fn pack(k1: u32, k2: u32, code: u32) -> Self;
    /// The two larger vertices `k1 << 32 | k2`.
    fn key(self) -> u64;
    fn code(self) -> u32;
}

/// 64 bits: vertices below 2^20 and codes below 2^24 (four million tetrahedra), the usual case;
/// half the bytes of [`Wide`] to scatter and sort.
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Narrow(u64);

impl Narrow {
    const VERTEX_BITS: u32 = 20;
    const CODE_BITS: u32 = 24;
    fn fits(n_vertices: usize, n_codes: usize) -> bool {
        n_vertices <= 1 << Self::VERTEX_BITS && n_codes <= 1 << Self::CODE_BITS
    }
}

impl Row for Narrow {
    #[inline]
    fn pack(k1: u32, k2: u32, code: u32) -> Self {
        let (v, c) = (Self::VERTEX_BITS, Self::CODE_BITS);
        Narrow((k1 as u64) << (v + c) | (k2 as u64) << c | code as u64)
    }
    #[inline]
    fn key(self) -> u64 {
        let k = self.0 >> Self::CODE_BITS;
        (k >> Self::VERTEX_BITS) << 32 | (k & ((1 << Self::VERTEX_BITS) - 1))
    }
    #[inline]
    fn code(self) -> u32 {
        (self.0 & ((1 << Self::CODE_BITS) - 1)) as u32
    }
}

/// 128 bits: any input.
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Wide(u128);

impl Row for Wide {
    #[inline]
    fn pack(k1: u32, k2: u32, code: u32) -> Self {
        Wide((k1 as u128) << 64 | (k2 as u128) << 32 | code as u128)
    }
    #[inline]
    fn key(self) -> u64 {
        (self.0 >> 32) as u64
    }
    #[inline]
    fn code(self) -> u32 {
        self.0 as u32
    }
}

/// Per face of the tetrahedra of `lists` (concatenated), bucketed by its smallest vertex `v` at
/// `rows[start[v]..start[v + 1]]` (a counting sort, then small sorts): its other two vertices
/// and its code, as a [`Row`]. Equal faces are adjacent in their bucket, in increasing code.
fn bucketed<R: Row>(lists: &[&[[u32; 4]]], n: usize) -> (Vec<u32>, Vec<R>) {
    let all = || lists.iter().flat_map(|l| l.iter());
    let mut start = vec![0u32; n + 1];
    for t in all() {
        // three faces have the smallest vertex, the one opposite it the second smallest
        let s = sorted4(*t);
        start[s[0] as usize + 1] += 3;
        start[s[1] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut next = start.clone();
    let mut rows: Vec<R> = vec![R::default(); start[n] as usize];
    for (ti, t) in all().enumerate() {
        // the sorted key of the face opposite i: the sorted tetrahedron without t[i]
        let s = sorted4(*t);
        for (i, &x) in t.iter().enumerate() {
            let j = s.iter().position(|&v| v == x).unwrap_or(0);
            let k: [u32; 3] = std::array::from_fn(|m| s[m + (m >= j) as usize]);
            let slot = &mut next[k[0] as usize];
            rows[*slot as usize] = R::pack(k[1], k[2], 4 * ti as u32 + i as u32);
            *slot += 1;
        }
    }
    for_ranges(&start, &mut rows, |start, rows, lo| {
        for b in start.windows(2) {
            sort_small(&mut rows[(b[0] - lo) as usize..(b[1] - lo) as usize]);
        }
    });
    (start, rows)
}

/// The number of vertices of `lists` (one more than the largest) and of their faces' codes.
fn sizes(lists: &[&[[u32; 4]]]) -> (usize, usize) {
    let all = || lists.iter().flat_map(|l| l.iter());
    let n = all().flatten().max().map_or(0, |&v| v as usize + 1);
    (n, 4 * lists.iter().map(|l| l.len()).sum::<usize>())
}

/// Vertices per range of buckets handed to one thread.
const RANGE: usize = 1 << 13;

/// Calls `f` on consecutive ranges of buckets in parallel: with the range's `start` entries (one
/// more than its buckets), its rows, and the index of its first row.
pub(super) fn for_ranges<T: Send>(
    start: &[u32],
    rows: &mut [T],
    f: impl Fn(&[u32], &mut [T], u32) + Sync,
) {
    let n = start.len().saturating_sub(1);
    let mut parts = Vec::with_capacity(n / RANGE + 1);
    let mut rest = rows;
    for lo in (0..n).step_by(RANGE) {
        let hi = (lo + RANGE).min(n);
        let (head, tail) = rest.split_at_mut((start[hi] - start[lo]) as usize);
        parts.push((&start[lo..=hi], head));
        rest = tail;
    }
    parts.into_par_iter().for_each(|(s, rows)| f(s, rows, s[0]));
}

/// The triangles of `tets` with exactly one tetrahedron, oriented outward from it (unsorted).
pub fn boundary(tets: &[[u32; 4]]) -> Vec<[u32; 3]> {
    let (n, n_codes) = sizes(&[tets]);
    if Narrow::fits(n, n_codes) {
        boundary_of_rows(tets, bucketed::<Narrow>(&[tets], n))
    } else {
        boundary_of_rows(tets, bucketed::<Wide>(&[tets], n))
    }
}

fn boundary_of_rows<R: Row>(tets: &[[u32; 4]], (start, rows): (Vec<u32>, Vec<R>)) -> Vec<[u32; 3]> {
    // ranges of buckets in parallel, concatenated in order
    let n = start.len().saturating_sub(1);
    let parts: Vec<Vec<[u32; 3]>> = (0..n.div_ceil(RANGE))
        .into_par_iter()
        .map(|r| {
            let mut out = Vec::new();
            for b in start[r * RANGE..=((r + 1) * RANGE).min(n)].windows(2) {
                // equal faces are adjacent in their bucket
                let bucket = &rows[b[0] as usize..b[1] as usize];
                for run in bucket.chunk_by(|x, y| x.key() == y.key()) {
                    if let [r] = run {
                        let c = r.code();
                        out.push(outward_face(&tets[(c >> 2) as usize], (c & 3) as usize));
                    }
                }
            }
            out
        })
        .collect();
    parts.concat()
}

/// Insertion sort for the small buckets (a dozen rows on average), the library sort otherwise.
pub(super) fn sort_small<T: Ord + Copy>(rows: &mut [T]) {
    if rows.len() > 32 {
        rows.sort_unstable();
        return;
    }
    for i in 1..rows.len() {
        let x = rows[i];
        let mut j = i;
        while j > 0 && rows[j - 1] > x {
            rows[j] = rows[j - 1];
            j -= 1;
        }
        rows[j] = x;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_match_the_owners_of_each_face() {
        // two tetrahedra sharing face 1-2-3, a third sharing 0-1-2 with the first, and a copy
        // of the second overlapping it (face 1-2-3 then has three owners)
        let tets = [[0, 1, 2, 3], [4, 1, 2, 3], [5, 0, 1, 2], [4, 3, 2, 1]];
        let table = FaceTable::new(&tets);
        let n = table.neighbours(tets.len());
        for (t, (tet, got)) in tets.iter().zip(&n).enumerate() {
            for (i, &got) in got.iter().enumerate() {
                let mut f = outward_face(tet, i);
                f.sort_unstable();
                let others: Vec<u32> = table.owners(&f).filter(|&o| o != t as u32).collect();
                let want = match others[..] {
                    [] => NO_NEIGHBOUR,
                    [o] => o,
                    _ => MANY_NEIGHBOURS,
                };
                assert_eq!(got, want, "tetrahedron {t} face {i}");
                // `across` reads the same: the first other owner, where several overlap
                let first = others.first().map(|&o| o as usize);
                assert_eq!(table.across(&tets, &n, t, i, |_| true), first);
            }
        }
        assert_eq!(n[0][0], MANY_NEIGHBOURS);
        assert_eq!(n[0][3], 2);
        assert_eq!(n[2][0], 0);
    }

    /// The narrow rows hold what the wide ones hold, up to their largest vertex and code.
    #[test]
    fn narrow_rows_round_trip_to_their_bounds() {
        let (v, c) = ((1 << Narrow::VERTEX_BITS) - 1, (1 << Narrow::CODE_BITS) - 1);
        for (k1, k2, code) in [(0, 1, 0), (7, 9, 12), (v - 1, v, c), (v, v, c)] {
            let (n, w) = (Narrow::pack(k1, k2, code), Wide::pack(k1, k2, code));
            assert_eq!((n.key(), n.code()), (w.key(), w.code()));
            assert_eq!(n.key(), (k1 as u64) << 32 | k2 as u64);
        }
        assert!(Narrow::pack(3, 5, 9) < Narrow::pack(3, 6, 0));
        assert!(Narrow::pack(3, 6, 0) < Narrow::pack(3, 6, 1));
        assert!(Narrow::fits(1 << 20, 1 << 24) && !Narrow::fits((1 << 20) + 1, 4));
    }

    /// Both row widths bucket the same faces in the same order (pseudo-random tetrahedra, with
    /// repeated faces).
    #[test]
    fn narrow_and_wide_rows_give_the_same_table() {
        let mut x = 12345u64;
        let mut next = |m: u64| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((x >> 33) % m) as u32
        };
        let tets: Vec<[u32; 4]> = (0..2000)
            .map(|_| {
                let a = next(300);
                [a, a + 1 + next(5), a + 7 + next(3), a + 11 + next(2)]
            })
            .collect();
        let n = sizes(&[&tets]).0;
        let narrow = FaceTable::of_rows(bucketed::<Narrow>(&[&tets], n));
        let wide = FaceTable::of_rows(bucketed::<Wide>(&[&tets], n));
        assert_eq!(
            (&narrow.start, &narrow.keys, &narrow.codes),
            (&wide.start, &wide.keys, &wide.codes)
        );
        let b = boundary(&tets);
        let wide_b = boundary_of_rows(&tets, bucketed::<Wide>(&[&tets], n));
        assert_eq!(b, wide_b);
        assert!(!b.is_empty() && b.len() < 4 * tets.len());
    }
}
