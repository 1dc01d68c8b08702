//! The edges of a list of tetrahedra numbered without hashing, as `faces` numbers their faces:
//! bucketed by their smaller vertex (a counting sort), each bucket sorted by the larger one.
//! Walks through a whole complex that count per edge (thinning, growth through the dual
//! complex) index arrays by these numbers instead of hashing six edges per tetrahedron.
use super::complex::TET_EDGES;
use super::faces::{for_ranges, sort_small};

/// Per tetrahedron, the number of each of its six edges (in `TET_EDGES` order); equal edges have
/// equal numbers, `0..count`.
pub struct EdgeTable {
    pub of_tet: Vec<[u32; 6]>,
    pub count: usize,
    /// The numbers of the edges whose smaller vertex is `v`: `start[v]..start[v + 1]`, in
    /// increasing larger vertex (`larger`, per number).
    start: Vec<u32>,
    larger: Vec<u32>,
}

impl EdgeTable {
    pub fn new(tets: &[[u32; 4]]) -> EdgeTable {
        let n = tets.iter().flatten().max().map_or(0, |&v| v as usize + 1);
        let mut start = vec![0u32; n + 1];
        for t in tets {
            for (a, b) in TET_EDGES {
                start[t[a].min(t[b]) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        // per edge: its larger vertex and its code `6 * tet + e`, one integer per row
        let mut next = start.clone();
        let mut rows = vec![0u64; start[n] as usize];
        for (ti, t) in tets.iter().enumerate() {
            for (e, (a, b)) in TET_EDGES.into_iter().enumerate() {
                let slot = &mut next[t[a].min(t[b]) as usize];
                rows[*slot as usize] = (t[a].max(t[b]) as u64) << 32 | (6 * ti + e) as u64;
                *slot += 1;
            }
        }
        for_ranges(&start, &mut rows, |start, rows, lo| {
            for b in start.windows(2) {
                sort_small(&mut rows[(b[0] - lo) as usize..(b[1] - lo) as usize]);
            }
        });
        let mut of_tet = vec![[0u32; 6]; tets.len()];
        let (mut count, mut first, mut larger) = (0usize, Vec::with_capacity(n + 1), Vec::new());
        for b in start.windows(2) {
            first.push(count as u32);
            for run in rows[b[0] as usize..b[1] as usize].chunk_by(|x, y| x >> 32 == y >> 32) {
                for &r in run {
                    let code = r as u32 as usize;
                    of_tet[code / 6][code % 6] = count as u32;
                }
                larger.push((run[0] >> 32) as u32);
                count += 1;
            }
        }
        first.push(count as u32);
        EdgeTable {
            of_tet,
            count,
            start: first,
            larger,
        }
    }

    /// The number of edge ab, if a tetrahedron has it.
    pub fn id(&self, a: u32, b: u32) -> Option<u32> {
        let (lo, hi) = (a.min(b) as usize, a.max(b));
        let range = self.start.get(lo..lo + 2)?;
        let bucket = &self.larger[range[0] as usize..range[1] as usize];
        let i = bucket.binary_search(&hi).ok()?;
        Some(range[0] + i as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_edges_have_equal_numbers() {
        let tets = [[0, 1, 2, 3], [4, 1, 2, 3], [3, 2, 1, 5]];
        let table = EdgeTable::new(&tets);
        // 6 + 3 new for the second (4 with 1, 2, 3) + 3 for the third (5 with 1, 2, 3)
        assert_eq!(table.count, 12);
        assert_eq!(table.id(3, 0), Some(table.of_tet[0][2]));
        assert_eq!(table.id(5, 2), table.id(2, 5));
        assert!(table.id(5, 2).is_some());
        assert_eq!(table.id(4, 5), None);
        assert_eq!(table.id(0, 9), None);
        assert_eq!(table.id(9, 10), None);
        for (s, a) in tets.iter().enumerate() {
            for (t, b) in tets.iter().enumerate() {
                for (i, &(p, q)) in TET_EDGES.iter().enumerate() {
                    for (j, &(r, u)) in TET_EDGES.iter().enumerate() {
                        let same =
                            (a[p].min(a[q]), a[p].max(a[q])) == (b[r].min(b[u]), b[r].max(b[u]));
                        let ids = table.of_tet[s][i] == table.of_tet[t][j];
                        assert_eq!(same, ids, "tetrahedra {s} and {t}, edges {i} and {j}");
                    }
                }
            }
        }
    }
}
