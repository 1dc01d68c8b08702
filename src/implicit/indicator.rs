//! The indicator function: per arrangement cell, the mean-value transfinite interpolation of the
//! face sections (+1 inside the section pieces, −1 outside).
//!
//! Back-to-back contours (paper §4.3): every section contour is used twice, once as the boundary of
//! the inside region (value +1, the piece's own orientation) and once, reversed, as the boundary of
//! the outside region (value −1, together with the face polygon). The corner weights of the two copies
//! are equal and opposite in sign, so the value converges to 0 on the contours. With `I_F` the
//! mean-value integral of the whole face polygon and `I_A` that of its section pieces, a face contributes
//!
//! ```text
//!   numerator   += (+1)·I_A + (−1)·(I_F − I_A) = 2 I_A − I_F
//!   denominator += I_F
//! ```
//!
//! and `f(x) = Σ numerator / Σ denominator` over the faces of the cell containing x (the sum of the
//! weights over the closed cell boundary normalises). Faces entirely inside (one piece covering the
//! face) or without pieces contribute `±I_F` with the same bits as the denominator, so a cell whose
//! faces are all inside evaluates to exactly 1.0 (constant precision, bit-exact).
//!
//! Points are located by plane sides: every cell is one sign vector over the input planes.
use super::mvc::{self, Edge};
use crate::arrangement::Arrangement;
use crate::error::{Error, Result};
use crate::sections::{polygon_signed_area, Plane};
use smallvec::SmallVec;
use std::collections::HashMap;

/// What the section of a face looks like.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceKind {
    /// No section piece: −1 everywhere on the face.
    Empty,
    /// One piece covering the whole face: +1 everywhere.
    Full,
    /// Inside and outside parts.
    Mixed,
}

#[derive(Clone, Debug)]
pub struct FaceEval {
    pub plane: Plane,
    pub kind: FaceKind,
    /// The face polygon (convex, counter-clockwise) in the plane frame.
    pub polygon: Vec<[f64; 2]>,
    pub face_edges: Vec<Edge>,
    /// All loops of the section pieces (outer ccw, holes cw) in the plane frame.
    pub piece_loops: Vec<Vec<[f64; 2]>>,
    pub piece_edges: Vec<Edge>,
}

#[derive(Clone, Debug)]
pub struct CellEval {
    pub faces: Vec<u32>,
    /// The value when every face of the cell has the same constant section value.
    pub constant: Option<f64>,
}

/// The planes bounding a cell, each with the side (±1) the cell is on.
type HalfSpaces = Vec<(Plane, f64)>;

/// The indicator function of the whole box: `eval(x)` in [−1, 1], positive inside.
#[derive(Clone, Debug)]
pub struct Indicator {
    pub faces: Vec<FaceEval>,
    pub cells: Vec<CellEval>,
    input_planes: Vec<Plane>,
    locator: HashMap<Box<[u64]>, u32>,
    pub bbox: ([f64; 3], [f64; 3]),
    /// Distance below which a point counts as lying on a face's plane.
    on_plane_eps: f64,
    /// Interior point per cell (fallback location).
    cell_halfspaces: Vec<HalfSpaces>,
}

impl Indicator {
    /// The indicator of an arrangement of all cells (`CellScope::All`: it locates points in the
    /// cells that tile the box).
    pub fn new(arr: &Arrangement) -> Result<Indicator> {
        if arr.scope != crate::arrangement::CellScope::All {
            return Err(Error::Geometry(
                "the implicit method needs the arrangement of all cells (CellScope::All)".into(),
            ));
        }
        let (lo, hi) = arr.bbox;
        let diag = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2))
            .sqrt()
            .max(f64::MIN_POSITIVE);
        let mut faces = Vec::with_capacity(arr.faces.len());
        for (fi, f) in arr.faces.iter().enumerate() {
            faces.push(face_eval(arr, fi, f)?);
        }

        let input_planes: Vec<Plane> = arr.planes[..arr.n_input].iter().map(|p| p.plane).collect();
        let mut locator = HashMap::with_capacity(arr.cells.len());
        let mut cells = Vec::with_capacity(arr.cells.len());
        let mut cell_halfspaces = Vec::with_capacity(arr.cells.len());
        for (ci, c) in arr.cells.iter().enumerate() {
            let (key, halfspaces) = cell_key_and_halfspaces(arr, ci, c, &input_planes)?;
            locator.insert(key.into_boxed_slice(), ci as u32);
            cells.push(CellEval {
                faces: c.faces.iter().map(|cf| cf.face).collect(),
                constant: constant_value(c, &faces),
            });
            cell_halfspaces.push(halfspaces);
        }
        Ok(Indicator {
            faces,
            cells,
            input_planes,
            locator,
            bbox: arr.bbox,
            on_plane_eps: 1e-12 * diag,
            cell_halfspaces,
        })
    }

    /// The cell whose closure contains `x` (points on a plane go to the positive side).
    pub fn locate(&self, x: [f64; 3]) -> Option<u32> {
        let words = self.input_planes.len().div_ceil(64).max(1);
        let mut key: SmallVec<[u64; 4]> = SmallVec::from_elem(0, words);
        for (p, plane) in self.input_planes.iter().enumerate() {
            if plane.signed_distance(x) >= 0.0 {
                key[p / 64] |= 1 << (p % 64);
            }
        }
        if let Some(&c) = self.locator.get(key.as_slice()) {
            return Some(c);
        }
        // Rounding near a plane crossing: take the cell whose half-spaces x violates least.
        let mut best = None;
        let mut best_violation = f64::INFINITY;
        for (ci, hs) in self.cell_halfspaces.iter().enumerate() {
            let v = hs
                .iter()
                .map(|(pl, s)| (-s * pl.signed_distance(x)).max(0.0))
                .fold(0.0, f64::max);
            if v < best_violation {
                best_violation = v;
                best = Some(ci as u32);
            }
        }
        best
    }

    pub fn inside_box(&self, x: [f64; 3]) -> bool {
        let (lo, hi) = self.bbox;
        (0..3).all(|k| x[k] >= lo[k] && x[k] <= hi[k])
    }

    /// The indicator at `x`: −1 outside the box.
    pub fn eval(&self, x: [f64; 3]) -> f64 {
        if !self.inside_box(x) {
            return -1.0;
        }
        match self.locate(x) {
            Some(c) => self.eval_in_cell(c, x),
            None => -1.0,
        }
    }

    /// The section value on a face at a point of its plane (inside the polygon).
    fn face_value(&self, f: &FaceEval, q: [f64; 2]) -> f64 {
        match f.kind {
            FaceKind::Empty => -1.0,
            FaceKind::Full => 1.0,
            FaceKind::Mixed => {
                if mvc::point_in_loops(q, f.piece_loops.iter().map(|l| l.as_slice())) {
                    1.0
                } else {
                    -1.0
                }
            }
        }
    }

    /// Mean-value interpolation of the face values of `cell` at `x` (x in the cell's closure).
    pub fn eval_in_cell(&self, cell: u32, x: [f64; 3]) -> f64 {
        let c = &self.cells[cell as usize];
        if let Some(v) = c.constant {
            return v;
        }
        let mut num = 0.0;
        let mut den = 0.0;
        for &fi in &c.faces {
            let f = &self.faces[fi as usize];
            let gamma = f.plane.signed_distance(x);
            let q = f.plane.to_2d(x);
            if gamma.abs() <= self.on_plane_eps {
                if mvc::point_in_loops(q, [f.polygon.as_slice()]) {
                    return self.face_value(f, q);
                }
                continue; // on the plane outside this face: the face subtends no solid angle
            }
            let i_face = mvc::region_integral(&f.face_edges, q, gamma);
            match f.kind {
                FaceKind::Empty => num -= i_face,
                FaceKind::Full => num += i_face,
                FaceKind::Mixed => {
                    let i_pieces = mvc::region_integral(&f.piece_edges, q, gamma);
                    num += 2.0 * i_pieces - i_face;
                }
            }
            den += i_face;
        }
        if den > 0.0 && num.is_finite() {
            (num / den).clamp(-1.0, 1.0)
        } else {
            -1.0
        }
    }

    /// The same interpolation treating every face as `Mixed` (no shortcuts): used by tests to check
    /// the precision of the general formula.
    pub fn eval_in_cell_general(&self, cell: u32, x: [f64; 3]) -> f64 {
        let c = &self.cells[cell as usize];
        let mut num = 0.0;
        let mut den = 0.0;
        for &fi in &c.faces {
            let f = &self.faces[fi as usize];
            let gamma = f.plane.signed_distance(x);
            let q = f.plane.to_2d(x);
            let i_face = mvc::region_integral(&f.face_edges, q, gamma);
            let i_pieces = mvc::region_integral(&f.piece_edges, q, gamma);
            num += 2.0 * i_pieces - i_face;
            den += i_face;
        }
        num / den
    }
}

/// The (u, v) of pool vertex `v` in the frame of plane `plane_id`.
fn pool_uv(arr: &Arrangement, v: u32, plane_id: u32) -> Result<[f64; 2]> {
    let pool = &arr.pool;
    let v = v as usize;
    if v >= pool.positions.len() {
        return Err(Error::Geometry(format!(
            "arrangement: vertex {v} out of the pool"
        )));
    }
    if let Some(k) = pool
        .tags
        .get(v)
        .and_then(|t| t.iter().position(|&p| p == plane_id))
    {
        if let Some(q) = pool.uv.get(v).and_then(|u| u.get(k)) {
            return Ok(*q);
        }
    }
    // Contract says uv is there; fall back to projecting the position.
    Ok(arr.planes[plane_id as usize].plane.to_2d(pool.positions[v]))
}

/// Face `fi` in its plane's frame: polygon, section loops and what its section looks like.
fn face_eval(arr: &Arrangement, fi: usize, f: &crate::arrangement::Face) -> Result<FaceEval> {
    let plane = arr
        .planes
        .get(f.plane as usize)
        .ok_or_else(|| Error::Geometry(format!("face {fi}: no plane {}", f.plane)))?
        .plane;
    let uv_loop = |l: &[u32]| -> Result<Vec<[f64; 2]>> {
        l.iter().map(|&v| pool_uv(arr, v, f.plane)).collect()
    };
    let polygon: Vec<[f64; 2]> = uv_loop(&f.polygon)?;
    let face_edges = mvc::loop_edges([polygon.as_slice()]);
    let mut piece_loops = Vec::new();
    let mut piece_area = 0.0;
    for p in &f.pieces {
        let outer: Vec<[f64; 2]> = uv_loop(&p.outer)?;
        piece_area += polygon_signed_area(&outer);
        piece_loops.push(outer);
        for h in &p.holes {
            let hole: Vec<[f64; 2]> = uv_loop(h)?;
            piece_area += polygon_signed_area(&hole);
            piece_loops.push(hole);
        }
    }
    let face_area = polygon_signed_area(&polygon);
    let kind = if piece_loops.is_empty() {
        FaceKind::Empty
    } else if f.pieces.len() == 1
        && f.pieces[0].holes.is_empty()
        && (piece_area - face_area).abs() <= 1e-12 * face_area.abs().max(f64::MIN_POSITIVE)
    {
        FaceKind::Full
    } else {
        FaceKind::Mixed
    };
    let piece_edges = mvc::loop_edges(piece_loops.iter().map(|l| l.as_slice()));
    Ok(FaceEval {
        plane,
        kind,
        polygon,
        face_edges,
        piece_loops,
        piece_edges,
    })
}

/// Cell `ci`'s locator key (one bit per input plane, set on the positive side: from its faces'
/// planes, for the other planes from the side of the mean of its face vertices) and its bounding
/// half-spaces (plane, side).
fn cell_key_and_halfspaces(
    arr: &Arrangement,
    ci: usize,
    c: &crate::arrangement::Cell,
    input_planes: &[Plane],
) -> Result<(Vec<u64>, HalfSpaces)> {
    let words = arr.n_input.div_ceil(64).max(1);
    let mut sum = [0.0; 3];
    let mut n = 0usize;
    let mut key = vec![0u64; words];
    let mut fixed = vec![false; arr.n_input];
    let mut halfspaces = Vec::new();
    for cf in &c.faces {
        let f = arr
            .faces
            .get(cf.face as usize)
            .ok_or_else(|| Error::Geometry(format!("cell {ci}: no face {}", cf.face)))?;
        for &v in &f.polygon {
            let p = arr.pool.positions[v as usize];
            for k in 0..3 {
                sum[k] += p[k];
            }
            n += 1;
        }
        let p = f.plane as usize;
        // outward = plane normal ⇒ the cell is on the negative side.
        let positive = !cf.outward_is_plane_normal;
        if p < arr.n_input {
            fixed[p] = true;
            if positive {
                key[p / 64] |= 1 << (p % 64);
            }
        }
        halfspaces.push((arr.planes[p].plane, if positive { 1.0 } else { -1.0 }));
    }
    if n == 0 {
        return Err(Error::Geometry(format!("cell {ci} has no faces")));
    }
    let centre = [sum[0] / n as f64, sum[1] / n as f64, sum[2] / n as f64];
    for (p, plane) in input_planes.iter().enumerate() {
        if !fixed[p] && plane.signed_distance(centre) > 0.0 {
            key[p / 64] |= 1 << (p % 64);
        }
    }
    Ok((key, halfspaces))
}

/// The cell's value when all its faces are full (1) or all empty (−1).
fn constant_value(c: &crate::arrangement::Cell, faces: &[FaceEval]) -> Option<f64> {
    let kinds: Vec<FaceKind> = c
        .faces
        .iter()
        .map(|cf| faces[cf.face as usize].kind)
        .collect();
    if kinds.iter().all(|&k| k == FaceKind::Full) {
        Some(1.0)
    } else if kinds.iter().all(|&k| k == FaceKind::Empty) {
        Some(-1.0)
    } else {
        None
    }
}
