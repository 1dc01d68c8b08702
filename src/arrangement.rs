//! The arrangement of the cutting planes inside a padded bounding box, and the sections on its faces.
//!
//! Contract used by the engines (`bm`, `implicit`):
//! * `planes[..n_input]` are the input planes in the order of `Sections::sections`
//!   (`section == Some(i)`); the box walls follow (`section == None`). Every face lies on one plane.
//! * The global `pool` holds every point the engines use on planes: arrangement vertices (3+ tags),
//!   contour vertices (1 tag), points where a contour edge crosses another plane (2 tags). A vertex shared
//!   by several faces or cells is one pool entry. Plane membership is the tag set, never a coordinate test.
//! * For every tag of a vertex, `pool.uv[v]` holds its (u,v) coordinates in that plane's frame (same order
//!   as `pool.tags[v]`): the exact input coordinates for an input contour vertex on its own plane.
//! * A face polygon is convex and counter-clockwise seen from its plane's normal; section pieces are
//!   counter-clockwise outer loops with clockwise holes, in pool vertex ids, and lie inside their face.
//! * `Face::positive_cell` is the cell on the side the plane normal points to.
//!
//! How it is built (see the submodules):
//! * `reach` (with `CellScope::Sections`, the default): a cell of the construction whose closure no
//!   section region can meet is not cut further and not kept; `empty_cells` drops the cells that
//!   end without a piece. The cells built are exactly the cells of the full arrangement that carry
//!   pieces, so the work grows with what the sections touch, not with the k³ cells of k planes.
//! * `cells`: the box (bbox of the sections padded by `margin × diagonal`, six walls with normals
//!   pointing out) is cut by every input plane in turn. Each vertex is the intersection of three
//!   planes; its side of another plane is the exact sign of a 4×4 determinant of plane equations
//!   (`exact`: floating filter, then expansion arithmetic), so three planes through a line, four
//!   through a point and nearly parallel planes give one consistent subdivision: a vertex exactly on
//!   a plane gets its tag, and coinciding vertices are one vertex. Duplicate input planes (equal up
//!   to scale, either orientation) are rejected with `Error::Input` naming both.
//! * `merge`: vertices closer than `merge_tolerance × diagonal` are only apart by rounding (four
//!   planes meeting in one point up to the rounding of their equations): they become one vertex
//!   (mean position, union of tags), faces left with fewer than three vertices and cells left
//!   with no face are dropped, before the pieces are built.
//! * `pieces`: contour vertices are classified by the exact sign of `n·p + d` at their 3D point;
//!   planes that share their line with another plane on the section's plane (exactly, or after the
//!   merge: two arrangement vertices on all three, a fan's axis) are decided through one
//!   representative, planes that do not cut the section's plane inside the box have a constant side.
//!   A contour edge crossing a plane gets one pool vertex tagged with both planes; a crossing or a
//!   contour vertex lying on two planes of different lines is the arrangement vertex (same id).
//!   Each contour stretch belongs to the face with its sign vector (a stretch lying on a line goes
//!   to the face on its left); pieces are traced per face, joining contour runs along the face
//!   boundary counter-clockwise, through every corner and every section point on it.
//! * `reconcile` (DESIGN invariant 5): crossings of two sections on their common line closer than
//!   `snap_tolerance × diagonal` and on the same arrangement edge are snapped to one vertex (midpoint
//!   in 3D, each frame keeps its section's own (u,v)); the other points stay with their section and
//!   are inserted into the other plane's piece edges along the line, so pieces of both planes share
//!   all vertices on the line. `max_disagreement` is the largest Hausdorff distance, along a line,
//!   between the two sections' points on it (or the longest interval when only one reaches it);
//!   lines beyond the tolerance are listed in `warnings`.
mod build;
mod cells;
mod empty_cells;
pub(crate) mod exact;
mod merge;
mod pieces;
mod reach;
mod reconcile;
mod signs;

use crate::error::Result;
use crate::sections::{Plane, Sections};
use serde::{Deserialize, Serialize};
use smallvec::SmallVec;

pub type PlaneId = u32;
pub type VertexId = u32;
pub type FaceId = u32;
pub type CellId = u32;
pub type PlaneTags = SmallVec<[PlaneId; 3]>;

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArrPlane {
    pub plane: Plane,
    /// Index into `Sections::sections`, `None` for a wall of the box.
    pub section: Option<usize>,
}

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct VertexPool {
    pub positions: Vec<[f64; 3]>,
    /// Sorted plane ids the vertex lies on.
    pub tags: Vec<PlaneTags>,
    /// Per tag (same order as `tags[v]`): the vertex in that plane's (u,v) frame.
    pub uv: Vec<SmallVec<[[f64; 2]; 3]>>,
    /// Vertices known to lie on a segment between two others (a contour edge's conformity
    /// Steiner points, `bm::conform`): the segment's ends. Its position and uv are rounded
    /// midpoints, collinear with the ends only up to rounding; the Delaunay kernel's line rule
    /// reads this instead.
    #[serde(default)]
    pub on_segment: std::collections::BTreeMap<VertexId, [VertexId; 2]>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SectionPiece {
    pub label: i32,
    pub outer: Vec<VertexId>,
    pub holes: Vec<Vec<VertexId>>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Face {
    pub plane: PlaneId,
    /// Cell on the side the plane normal points to; `None` outside the box (or, with
    /// `CellScope::Sections`, in a part of the box not built).
    pub positive_cell: Option<CellId>,
    pub negative_cell: Option<CellId>,
    /// Convex polygon, counter-clockwise seen from the plane normal, in pool vertex ids.
    pub polygon: Vec<VertexId>,
    /// The section of this face: pieces of the plane's regions clipped to the face.
    pub pieces: Vec<SectionPiece>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CellFace {
    pub face: FaceId,
    /// True when the cell's outward normal on this face is the plane normal (the cell is on the negative side).
    pub outward_is_plane_normal: bool,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Cell {
    pub faces: Vec<CellFace>,
    pub volume: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArrangementOptions {
    /// Box padding, relative to the sections' bounding-box diagonal.
    pub margin: f64,
    /// Where the sections of two planes cross their common line at points closer than this
    /// (relative to the bounding-box diagonal), the crossings are snapped to one shared vertex.
    pub snap_tolerance: f64,
    /// Where one section has material on its common line with another plane and that plane's
    /// section has none, the material within this distance of the line (relative to the
    /// bounding-box diagonal) is removed before the arrangement is built
    /// (`validate::reconcile_common_lines`; 0: sections are taken as they are).
    #[serde(default = "default_line_strip")]
    pub line_strip: f64,
    /// Arrangement vertices closer than this (relative to the bounding-box diagonal) are one vertex:
    /// where several planes meet in one point up to the rounding of their equations, the rounded
    /// vertices of their triples and the sliver faces and cells between them are merged away.
    #[serde(default = "default_merge_tolerance")]
    pub merge_tolerance: f64,
    /// Which cells are built (see `CellScope`).
    #[serde(default)]
    pub scope: CellScope,
}

/// Which cells of the arrangement are built.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CellScope {
    /// Every cell of the box: the cells tile it (the implicit method interpolates in all of them).
    All,
    /// Only the cells with a section piece on a face, each with its faces, vertices and pieces
    /// exactly as in `All`. No other cell is built: the construction does not cut further the cells
    /// no section reaches (`reach`), and the cells that end without a piece are dropped
    /// (`empty_cells`). A face whose other side was not built has `None` there, as a wall face.
    #[default]
    Sections,
}

fn default_line_strip() -> f64 {
    crate::validate::LINE_STRIP_RELATIVE
}

fn default_merge_tolerance() -> f64 {
    1e-10
}

impl Default for ArrangementOptions {
    fn default() -> Self {
        ArrangementOptions {
            margin: 0.1,
            snap_tolerance: 1e-3,
            line_strip: default_line_strip(),
            merge_tolerance: default_merge_tolerance(),
            scope: CellScope::default(),
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Arrangement {
    pub planes: Vec<ArrPlane>,
    pub n_input: usize,
    pub pool: VertexPool,
    pub faces: Vec<Face>,
    pub cells: Vec<Cell>,
    pub bbox: ([f64; 3], [f64; 3]),
    /// Which cells were built: with `CellScope::Sections` the cells do not tile the box.
    #[serde(default)]
    pub scope: CellScope,
    /// Largest disagreement found between two sections along their planes' common line.
    pub max_disagreement: f64,
    pub warnings: Vec<String>,
}

impl Arrangement {
    /// Build the arrangement of the sections' planes in the padded box, the global vertex pool and
    /// the section pieces of every face. Duplicate planes (equal up to scale) are rejected.
    pub fn build(sections: &Sections, options: &ArrangementOptions) -> Result<Arrangement> {
        build::build(sections, options)
    }

    /// Cell adjacency: one node per cell (weight = cell id), one edge per interior face (weight = face id).
    pub fn adjacency_graph(&self) -> petgraph::graph::UnGraph<CellId, FaceId> {
        let mut g = petgraph::graph::UnGraph::with_capacity(self.cells.len(), self.faces.len());
        for c in 0..self.cells.len() {
            g.add_node(c as CellId);
        }
        for (f, face) in self.faces.iter().enumerate() {
            if let (Some(a), Some(b)) = (face.positive_cell, face.negative_cell) {
                g.add_edge(
                    petgraph::graph::NodeIndex::new(a as usize),
                    petgraph::graph::NodeIndex::new(b as usize),
                    f as FaceId,
                );
            }
        }
        g
    }

    /// (u,v) coordinates of pool vertex `v` in the frame of `plane`, if the vertex carries that tag.
    pub fn uv(&self, v: VertexId, plane: PlaneId) -> Option<[f64; 2]> {
        let tags = &self.pool.tags[v as usize];
        tags.iter()
            .position(|&t| t == plane)
            .map(|k| self.pool.uv[v as usize][k])
    }

    /// Cells with at least one face carrying a section piece.
    pub fn cells_with_sections(&self) -> usize {
        self.cells
            .iter()
            .filter(|c| {
                c.faces
                    .iter()
                    .any(|cf| !self.faces[cf.face as usize].pieces.is_empty())
            })
            .count()
    }

    /// Outward unit normal of a cell on one of its faces.
    pub fn outward_normal(&self, cf: &CellFace) -> [f64; 3] {
        let n = self.planes[self.faces[cf.face as usize].plane as usize]
            .plane
            .normal;
        if cf.outward_is_plane_normal {
            n
        } else {
            [-n[0], -n[1], -n[2]]
        }
    }

    /// Every pool vertex on the boundary of a cell (face corners and piece vertices), sorted, unique.
    pub fn cell_vertices(&self, c: CellId) -> Vec<VertexId> {
        let mut out = Vec::new();
        for cf in &self.cells[c as usize].faces {
            let f = &self.faces[cf.face as usize];
            out.extend_from_slice(&f.polygon);
            for p in &f.pieces {
                out.extend_from_slice(&p.outer);
                for h in &p.holes {
                    out.extend_from_slice(h);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The faces of a cell that carry section pieces.
    pub fn cell_section_faces(&self, c: CellId) -> impl Iterator<Item = &CellFace> + '_ {
        self.cells[c as usize]
            .faces
            .iter()
            .filter(move |cf| !self.faces[cf.face as usize].pieces.is_empty())
    }

    /// Every face's boundary refined with the pool vertices lying on its edges (crossings of any
    /// section with the edge's line, shared by the faces around that edge), counter-clockwise seen
    /// from the plane normal, starting at `polygon[0]`. Conforming cell boundaries for the engines.
    pub fn face_boundaries(&self) -> Vec<Vec<VertexId>> {
        // Non-arrangement vertices on two or more planes, by plane pair.
        let mut corner = vec![false; self.pool.positions.len()];
        for f in &self.faces {
            for &v in &f.polygon {
                corner[v as usize] = true;
            }
        }
        let mut on_line: crate::fxhash::FxHashMap<(PlaneId, PlaneId), Vec<VertexId>> =
            Default::default();
        for (v, tags) in self.pool.tags.iter().enumerate() {
            if tags.len() < 2 || corner[v] {
                continue;
            }
            for (k, &a) in tags.iter().enumerate() {
                for &b in &tags[k + 1..] {
                    on_line.entry((a, b)).or_default().push(v as VertexId);
                }
            }
        }
        let mut out = Vec::with_capacity(self.faces.len());
        for face in &self.faces {
            let p = face.plane;
            let poly = &face.polygon;
            let n = poly.len();
            let mut b = Vec::with_capacity(n);
            for e in 0..n {
                let (a, c) = (poly[e], poly[(e + 1) % n]);
                b.push(a);
                let (pa, pc) = (
                    self.pool.positions[a as usize],
                    self.pool.positions[c as usize],
                );
                let d = [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]];
                let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                let mut extra: Vec<(f64, VertexId)> = Vec::new();
                for &t in self.pool.tags[a as usize].iter() {
                    if t == p || !self.pool.tags[c as usize].contains(&t) {
                        continue;
                    }
                    let Some(list) = on_line.get(&(p.min(t), p.max(t))) else {
                        continue;
                    };
                    for &v in list {
                        let x = self.pool.positions[v as usize];
                        let s =
                            ((x[0] - pa[0]) * d[0] + (x[1] - pa[1]) * d[1] + (x[2] - pa[2]) * d[2])
                                / len2;
                        if s > 0.0 && s < 1.0 {
                            extra.push((s, v));
                        }
                    }
                }
                extra.sort_by(|x, y| x.0.total_cmp(&y.0));
                extra.dedup_by_key(|x| x.1);
                b.extend(extra.into_iter().map(|x| x.1));
            }
            out.push(b);
        }
        out
    }

    /// Signed area (in the plane's frame) of a loop of pool vertices on `plane`.
    pub fn loop_area(&self, plane: PlaneId, ids: &[VertexId]) -> f64 {
        let pts: Vec<[f64; 2]> = ids
            .iter()
            .map(|&v| self.uv(v, plane).unwrap_or([0.0, 0.0]))
            .collect();
        polygon_area(&pts)
    }

    /// Area of a section piece (outer minus holes).
    pub fn piece_area(&self, plane: PlaneId, piece: &SectionPiece) -> f64 {
        self.loop_area(plane, &piece.outer)
            + piece
                .holes
                .iter()
                .map(|h| self.loop_area(plane, h))
                .sum::<f64>()
    }
}

pub(crate) fn polygon_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    if n < 3 {
        return 0.0;
    }
    let o = p[0];
    let mut a = 0.0;
    for i in 1..n - 1 {
        let (b, c) = (p[i], p[i + 1]);
        a += (b[0] - o[0]) * (c[1] - o[1]) - (b[1] - o[1]) * (c[0] - o[0]);
    }
    0.5 * a
}
