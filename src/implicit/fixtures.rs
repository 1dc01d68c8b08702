//! Hand-built arrangements of horizontal planes in a box (`z = const`), for tests and examples that
//! must not depend on the general arrangement builder. Follows the `arrangement` contract: input planes
//! first, then the six walls; faces convex and counter-clockwise seen from their plane normal; pieces
//! counter-clockwise (holes clockwise) in the plane frame. Vertices are not shared between faces here
//! (each face gets its own pool entries with one tag), which the implicit method does not need.
use crate::arrangement::{
    ArrPlane, Arrangement, Cell, CellFace, Face, PlaneTags, SectionPiece, VertexPool,
};
use crate::sections::Plane;
use smallvec::{smallvec, SmallVec};

struct Builder {
    planes: Vec<ArrPlane>,
    pool: VertexPool,
    faces: Vec<Face>,
}

impl Builder {
    fn vertex(&mut self, plane: u32, p: [f64; 3]) -> u32 {
        let uv = self.planes[plane as usize].plane.to_2d(p);
        let tags: PlaneTags = smallvec![plane];
        let uvs: SmallVec<[[f64; 2]; 3]> = smallvec![uv];
        self.pool.positions.push(p);
        self.pool.tags.push(tags);
        self.pool.uv.push(uvs);
        (self.pool.positions.len() - 1) as u32
    }

    /// A loop of 3D points on `plane` as pool ids, reordered counter-clockwise (or clockwise when
    /// `ccw` is false) in the plane frame.
    fn polygon(&mut self, plane: u32, pts: &[[f64; 3]], ccw: bool) -> Vec<u32> {
        let pl = self.planes[plane as usize].plane;
        let uv: Vec<[f64; 2]> = pts.iter().map(|&p| pl.to_2d(p)).collect();
        let mut area = 0.0;
        for i in 0..uv.len() {
            let (a, b) = (uv[i], uv[(i + 1) % uv.len()]);
            area += a[0] * b[1] - a[1] * b[0];
        }
        let mut ids: Vec<u32> = pts.iter().map(|&p| self.vertex(plane, p)).collect();
        if (area > 0.0) != ccw {
            ids.reverse();
        }
        ids
    }

    fn convex_face(&mut self, plane: u32, pts: &[[f64; 3]]) -> Vec<u32> {
        // Sort corners by angle around their centroid in the plane frame.
        let pl = self.planes[plane as usize].plane;
        let uv: Vec<[f64; 2]> = pts.iter().map(|&p| pl.to_2d(p)).collect();
        let cx = uv.iter().map(|q| q[0]).sum::<f64>() / uv.len() as f64;
        let cy = uv.iter().map(|q| q[1]).sum::<f64>() / uv.len() as f64;
        let mut order: Vec<usize> = (0..pts.len()).collect();
        order.sort_by(|&a, &b| {
            let ta = (uv[a][1] - cy).atan2(uv[a][0] - cx);
            let tb = (uv[b][1] - cy).atan2(uv[b][0] - cx);
            ta.partial_cmp(&tb).unwrap()
        });
        order.iter().map(|&i| self.vertex(plane, pts[i])).collect()
    }
}

/// A piece of a section: outer loop and holes, as (x, y) loops.
pub type Piece = (Vec<[f64; 2]>, Vec<Vec<[f64; 2]>>);

/// A section on the plane `z`: outer loops and holes given as (x, y) loops (any orientation).
#[derive(Clone, Debug, Default)]
pub struct Level {
    pub z: f64,
    /// Each piece: outer loop, then its holes.
    pub pieces: Vec<Piece>,
}

/// The arrangement of the planes `levels[i].z` (strictly increasing, inside the box) in the box
/// `lo..hi`: one slab cell between consecutive planes.
pub fn horizontal_slabs(lo: [f64; 3], hi: [f64; 3], levels: &[Level]) -> Arrangement {
    let mut b = Builder::with_planes(lo, hi, levels);
    let n_input = levels.len();
    let mut zs = vec![lo[2]];
    zs.extend(levels.iter().map(|l| l.z));
    zs.push(hi[2]);
    let n_cells = zs.len() - 1;
    let mut cells: Vec<Cell> = (0..n_cells)
        .map(|k| Cell {
            faces: Vec::new(),
            volume: (hi[0] - lo[0]) * (hi[1] - lo[1]) * (zs[k + 1] - zs[k]),
        })
        .collect();
    // Horizontal faces: bottom wall, input planes, top wall.
    for (k, &z) in zs.iter().enumerate() {
        let (plane, level) = if k == 0 {
            (wall(n_input, 4), None)
        } else if k == zs.len() - 1 {
            (wall(n_input, 5), None)
        } else {
            ((k - 1) as u32, Some(&levels[k - 1]))
        };
        b.horizontal_face(&mut cells, k, plane, level, [lo, hi], z);
    }
    // Side walls of every slab.
    for (k, cell) in cells.iter_mut().enumerate() {
        for w in 0..4 {
            let pts = side_wall(lo, hi, w, zs[k], zs[k + 1]);
            let polygon = b.convex_face(wall(n_input, w), &pts);
            let fid = b.faces.len() as u32;
            b.faces.push(Face {
                plane: wall(n_input, w),
                positive_cell: None,
                negative_cell: Some(k as u32),
                polygon,
                pieces: Vec::new(),
            });
            cell.faces.push(CellFace {
                face: fid,
                outward_is_plane_normal: true,
            });
        }
    }
    Arrangement {
        planes: b.planes,
        n_input,
        pool: b.pool,
        faces: b.faces,
        cells,
        bbox: (lo, hi),
        scope: crate::arrangement::CellScope::All,
        max_disagreement: 0.0,
        warnings: Vec::new(),
    }
}

/// The plane of wall `w` (x-, x+, y-, y+, z-, z+) after `n_input` input planes.
fn wall(n_input: usize, w: usize) -> u32 {
    (n_input + w) as u32
}

/// The corners of side wall `w` (x-, x+, y-, y+) of the slab from `z0` to `z1`.
fn side_wall(lo: [f64; 3], hi: [f64; 3], w: usize, z0: f64, z1: f64) -> Vec<[f64; 3]> {
    if w < 2 {
        let x = if w == 0 { lo[0] } else { hi[0] };
        vec![
            [x, lo[1], z0],
            [x, hi[1], z0],
            [x, hi[1], z1],
            [x, lo[1], z1],
        ]
    } else {
        let y = if w == 2 { lo[1] } else { hi[1] };
        vec![
            [lo[0], y, z0],
            [hi[0], y, z0],
            [hi[0], y, z1],
            [lo[0], y, z1],
        ]
    }
}

impl Builder {
    /// The input planes `z = levels[i].z`, then the six walls with outward normals.
    fn with_planes(lo: [f64; 3], hi: [f64; 3], levels: &[Level]) -> Builder {
        let mut planes: Vec<ArrPlane> = (levels.iter().enumerate())
            .map(|(i, l)| ArrPlane {
                plane: Plane::from_equation([0.0, 0.0, 1.0], -l.z).unwrap(),
                section: Some(i),
            })
            .collect();
        let walls = [
            (lo, [-1.0, 0.0, 0.0]),
            (hi, [1.0, 0.0, 0.0]),
            (lo, [0.0, -1.0, 0.0]),
            (hi, [0.0, 1.0, 0.0]),
            (lo, [0.0, 0.0, -1.0]),
            (hi, [0.0, 0.0, 1.0]),
        ];
        planes.extend(walls.map(|(p, n)| ArrPlane {
            plane: Plane::from_point_normal(p, n).unwrap(),
            section: None,
        }));
        Builder {
            planes,
            pool: VertexPool::default(),
            faces: Vec::new(),
        }
    }

    /// The horizontal face `k` (0: the bottom wall) at height `z` on `plane`, the box's
    /// rectangle with `level`'s pieces on it, bounding the slabs below and above it.
    fn horizontal_face(
        &mut self,
        cells: &mut [Cell],
        k: usize,
        plane: u32,
        level: Option<&Level>,
        [lo, hi]: [[f64; 3]; 2],
        z: f64,
    ) {
        let rect = [
            [lo[0], lo[1], z],
            [hi[0], lo[1], z],
            [hi[0], hi[1], z],
            [lo[0], hi[1], z],
        ];
        let polygon = self.convex_face(plane, &rect);
        let mut pieces = Vec::new();
        for (outer, holes) in level.iter().flat_map(|l| &l.pieces) {
            let o3: Vec<[f64; 3]> = outer.iter().map(|q| [q[0], q[1], z]).collect();
            let outer = self.polygon(plane, &o3, true);
            let holes = holes
                .iter()
                .map(|h| {
                    let h3: Vec<[f64; 3]> = h.iter().map(|q| [q[0], q[1], z]).collect();
                    self.polygon(plane, &h3, false)
                })
                .collect();
            pieces.push(SectionPiece {
                label: 1,
                outer,
                holes,
            });
        }
        let normal_up = self.planes[plane as usize].plane.normal[2] > 0.0;
        let below = (k > 0).then(|| (k - 1) as u32);
        let above = (k < cells.len()).then_some(k as u32);
        let (positive_cell, negative_cell) = if normal_up {
            (above, below)
        } else {
            (below, above)
        };
        let fid = self.faces.len() as u32;
        self.faces.push(Face {
            plane,
            positive_cell,
            negative_cell,
            polygon,
            pieces,
        });
        if let Some(c) = above {
            // The face is the bottom of `above`: outward is −z.
            cells[c as usize].faces.push(CellFace {
                face: fid,
                outward_is_plane_normal: !normal_up,
            });
        }
        if let Some(c) = below {
            cells[c as usize].faces.push(CellFace {
                face: fid,
                outward_is_plane_normal: normal_up,
            });
        }
    }
}

/// A regular polygon with `n` vertices approximating a circle.
pub fn circle(centre: [f64; 2], r: f64, n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            [centre[0] + r * t.cos(), centre[1] + r * t.sin()]
        })
        .collect()
}
