//! Where the sections are: which cells of the arrangement under construction can still carry a
//! section piece on their boundary (`CellScope::Sections`).
//!
//! A final cell carries a piece on a face `F` of plane `P_i` when the region `A_i` meets `F` with
//! positive area, so it lies in the closure of every cell it descends from during the incremental
//! construction. A cell whose closure meets no region (closed, with a margin) has no descendant with
//! a piece and is not built further. The test is conservative (it may keep a cell that ends without a
//! piece, never drops one that would have one), in floats with error bounds:
//! * the cell's box (its vertices' rounded positions, grown by their error bound and the margin)
//!   overlaps the region's box (its contour vertices' 3D points, grown by the margin);
//! * the cell meets `P_i`: for a plane already cut, exactly, by a vertex carrying the tag `i` (the
//!   cell lies on one side of `P_i`, so its closure meets the plane only in such vertices); for a
//!   plane not cut yet, its vertices' signed distances to `P_i` are not all beyond the margin on one
//!   side;
//! * the 2D box (in `P_i`'s frame) of what of the cell can lie on `P_i` (its vertices tagged `i`, or
//!   the projection of all its vertices) overlaps the region's 2D box grown by the margin.
use super::cells::{BCell, CellBuilder};
use crate::geom::bvh::{Aabb, Bvh};
use crate::sections::{Plane, Sections};

struct RegionBox {
    plane: u32,
    lo2: [f64; 2],
    hi2: [f64; 2],
}

/// The regions of all sections, by box, for the culling test.
pub(crate) struct SectionReach {
    regions: Vec<RegionBox>,
    planes: Vec<Plane>,
    bvh: Bvh,
    margin: f64,
}

impl SectionReach {
    /// `margin`: an absolute distance (the build uses a tiny fraction of the diagonal).
    pub fn new(sections: &Sections, margin: f64) -> SectionReach {
        let mut regions = Vec::new();
        let mut boxes = Vec::new();
        for (i, s) in sections.sections.iter().enumerate() {
            for r in &s.regions {
                let mut b = Aabb::EMPTY;
                let (mut lo2, mut hi2) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for c in std::iter::once(&r.outer).chain(&r.holes) {
                    for &p in &c.points3 {
                        b.add_point(p);
                    }
                    for p in &c.points2 {
                        for k in 0..2 {
                            lo2[k] = lo2[k].min(p[k]);
                            hi2[k] = hi2[k].max(p[k]);
                        }
                    }
                }
                if b.lo[0] > b.hi[0] {
                    continue;
                }
                for k in 0..3 {
                    b.lo[k] -= margin;
                    b.hi[k] += margin;
                }
                for k in 0..2 {
                    lo2[k] -= margin;
                    hi2[k] += margin;
                }
                boxes.push(b);
                regions.push(RegionBox {
                    plane: i as u32,
                    lo2,
                    hi2,
                });
            }
        }
        SectionReach {
            regions,
            planes: sections.sections.iter().map(|s| s.plane).collect(),
            bvh: Bvh::build(boxes),
            margin,
        }
    }

    /// Whether the closure of `cell` may meet a region (false: no descendant carries a piece).
    pub fn may_touch(&self, b: &CellBuilder, cell: &BCell) -> bool {
        let grow = cell.err * 2.0 + self.margin;
        let bb = Aabb {
            lo: cell.lo.map(|x| x - grow),
            hi: cell.hi.map(|x| x + grow),
        };
        let mut verts: Vec<u32> = cell
            .faces
            .iter()
            .flat_map(|f| f.poly.iter().copied())
            .collect();
        verts.sort_unstable();
        verts.dedup();
        let hit = std::cell::Cell::new(false);
        self.bvh.visit(
            |x| !hit.get() && x.overlaps(&bb),
            |r| {
                if !hit.get() {
                    let r = &self.regions[r as usize];
                    hit.set(self.region_may_touch(b, &verts, r, grow));
                }
            },
        );
        hit.get()
    }

    fn region_may_touch(&self, b: &CellBuilder, verts: &[u32], r: &RegionBox, grow: f64) -> bool {
        let i = r.plane;
        let plane = &self.planes[i as usize];
        let cut = b.is_cut(i);
        let on_plane: Vec<u32> = if cut {
            // Exact: the closure meets P_i exactly in its vertices tagged i.
            verts
                .iter()
                .copied()
                .filter(|&v| b.tags[v as usize].contains(&i))
                .collect()
        } else {
            let n = plane.normal;
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for &v in verts {
                let p = b.pos[v as usize];
                let d = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + plane.offset;
                lo = lo.min(d);
                hi = hi.max(d);
            }
            let m = 2.0 * grow;
            if lo > m || hi < -m {
                return false;
            }
            verts.to_vec()
        };
        if on_plane.is_empty() {
            return false;
        }
        let (mut lo2, mut hi2) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &v in &on_plane {
            let q = plane.to_2d(b.pos[v as usize]);
            for k in 0..2 {
                lo2[k] = lo2[k].min(q[k]);
                hi2[k] = hi2[k].max(q[k]);
            }
        }
        let m = 2.0 * grow;
        (0..2).all(|k| lo2[k] - m <= r.hi2[k] && r.lo2[k] <= hi2[k] + m)
    }
}
