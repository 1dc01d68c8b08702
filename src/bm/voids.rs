//! Voids that no section witnesses: connected regions of unkept tetrahedra enclosed by K (every
//! face of the region is shared with another of its tetrahedra or with a kept one), which never
//! reach a section plane outside its section. Pruning and growth leave such bubbles between the
//! planes (each an extra component of ∂K with negative volume); no section says the solid is empty
//! there, so K takes them in. Combinatorial throughout: a face lies on a plane when its three
//! vertices share that plane's tag, and it is inside the section when it is one of the section
//! triangles (`Triangulation::internal`, refined with the complex).
//!
//! A region is left alone when one of its faces lies on a plane outside the section there (the
//! section witnesses the empty space: a hole, the outside of a contour) or has no tetrahedron on
//! its other side (the region reaches the space outside every cell's triangulation, or a face the
//! two cells triangulate differently: conservative).
use super::faces::FaceTable;
use super::refine::{key3, on_a_plane, Triangulation};
use crate::mesh::Stars;

/// What filling did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VoidStats {
    pub voids_filled: u64,
    pub tets_filled: u64,
}

/// Fill every enclosed, unwitnessed void of `k` (moved from `fillable`/`external` into `kept`).
pub fn fill(k: &mut Triangulation) -> VoidStats {
    let unkept: Vec<[u32; 4]> = k
        .fillable
        .iter()
        .chain(k.external.iter())
        .copied()
        .collect();
    let faces = FaceTable::new(&unkept);
    let regions = regions(&unkept, &faces);
    // kept tetrahedra by vertex: is there one on the other side of a face?
    let kept_star = Stars::<u32>::new(k.positions.len(), k.kept);
    let kept_on = |f: &[u32; 3]| {
        kept_star[f[0] as usize]
            .iter()
            .any(|&t| f[1..].iter().all(|v| k.kept[t as usize].contains(v)))
    };
    let mut open = vec![false; regions.count];
    faces.for_each_face(|codes| {
        let first = (codes[0] >> 2) as usize;
        let r = regions.of[first] as usize;
        if open[r] {
            return;
        }
        let face = key3(super::complex::outward_face(
            &unkept[first],
            (codes[0] & 3) as usize,
        ));
        open[r] = match codes.len() {
            // a face with two unkept sides: witnessed when it lies on a plane outside its section
            2 => on_a_plane(k.planes, &face) && !k.internal.contains(&face),
            // a face of one unkept tetrahedron: enclosed only when a kept one is on its other side
            1 => !kept_on(&face),
            // overlapping tetrahedra where two cells triangulate a face differently
            _ => true,
        };
    });
    let mut stats = VoidStats::default();
    let mut counted = vec![false; regions.count];
    let mut fill = vec![false; unkept.len()];
    for (t, &r) in regions.of.iter().enumerate() {
        if !open[r as usize] {
            fill[t] = true;
            stats.tets_filled += 1;
            if !counted[r as usize] {
                counted[r as usize] = true;
                stats.voids_filled += 1;
            }
        }
    }
    if stats.tets_filled == 0 {
        return stats;
    }
    let n_fillable = k.fillable.len();
    let (mut keep_fillable, mut keep_external) = (Vec::new(), Vec::new());
    for (t, tet) in unkept.into_iter().enumerate() {
        if fill[t] {
            k.kept.push(tet);
        } else if t < n_fillable {
            keep_fillable.push(tet);
        } else {
            keep_external.push(tet);
        }
    }
    *k.fillable = keep_fillable;
    *k.external = keep_external;
    stats
}

/// Connected components of `tets` across shared faces.
struct Regions {
    of: Vec<u32>,
    count: usize,
}

fn regions(tets: &[[u32; 4]], faces: &FaceTable) -> Regions {
    let mut parent: Vec<u32> = (0..tets.len() as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    faces.for_each_face(|codes| {
        if let [a, b] = codes {
            let (ra, rb) = (find(&mut parent, a >> 2), find(&mut parent, b >> 2));
            if ra != rb {
                parent[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    });
    let mut id = vec![u32::MAX; tets.len()];
    let mut count = 0;
    let of = (0..tets.len() as u32)
        .map(|t| {
            let r = find(&mut parent, t) as usize;
            if id[r] == u32::MAX {
                id[r] = count;
                count += 1;
            }
            id[r]
        })
        .collect();
    Regions {
        of,
        count: count as usize,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bm::refine::test_support::Owned;
    use crate::bm::refine::Planes;
    use smallvec::smallvec;

    /// A tetrahedron (0,1,2,3) split at an interior vertex 4 into four.
    fn star() -> Vec<[u32; 4]> {
        // big positive tet (0,1,2,3) split at interior vertex 4 into four positive tets
        vec![[4, 1, 2, 3], [0, 4, 2, 3], [0, 1, 4, 3], [0, 1, 2, 4]]
    }

    fn run(
        kept: Vec<[u32; 4]>,
        unkept: Vec<[u32; 4]>,
        planes: Vec<Planes>,
        internal: &[[u32; 3]],
    ) -> (VoidStats, usize) {
        let mut o = Owned {
            positions: vec![[0.0; 3]; planes.len()],
            planes,
            kept,
            fillable: unkept,
            internal: internal.iter().map(|&t| key3(t)).collect(),
            ..Default::default()
        };
        let s = fill(&mut o.view());
        (s, o.kept.len())
    }

    #[test]
    fn an_enclosed_bubble_is_filled_and_an_open_one_is_not() {
        // one of the four tets unkept: its faces are its three kept neighbours' and the big
        // tet's hull face (0,1,2 side): open
        let t = star();
        let none: Vec<Planes> = vec![smallvec![]; 5];
        let (s, _) = run(t[..3].to_vec(), vec![t[3]], none.clone(), &[]);
        assert_eq!(s, VoidStats::default());
        // surround the big tet by kept caps on all four hull faces (apexes 5..8): enclosed
        let caps = vec![[5, 3, 2, 1], [0, 2, 3, 6], [0, 3, 1, 7], [0, 1, 2, 8]];
        let mut kept = t[..2].to_vec();
        kept.extend(&caps);
        let (s, n) = run(kept, t[2..].to_vec(), vec![smallvec![]; 9], &[]);
        assert_eq!(
            s,
            VoidStats {
                voids_filled: 1,
                tets_filled: 2
            }
        );
        assert_eq!(n, 8);
    }

    #[test]
    fn a_bubble_through_a_section_hole_is_witnessed() {
        // the unkept tets [0,1,4,3] and [0,1,2,4] share the face (0,1,4); put 0, 1 and 4 on plane 7
        let t = star();
        let caps = vec![[5, 3, 2, 1], [0, 2, 3, 6], [0, 3, 1, 7], [0, 1, 2, 8]];
        let mut kept = t[..2].to_vec();
        kept.extend(&caps);
        let mut planes: Vec<Planes> = vec![smallvec![]; 9];
        for v in [0, 1, 4] {
            planes[v] = smallvec![7];
        }
        // outside the section: witnessed, left open
        let (s, _) = run(kept.clone(), t[2..].to_vec(), planes.clone(), &[]);
        assert_eq!(s.tets_filled, 0);
        // inside the section (a flat zone between two unkept sides): filled
        let (s, _) = run(kept, t[2..].to_vec(), planes, &[[0, 1, 4]]);
        assert_eq!(s.tets_filled, 2);
    }
}
