//! Cells without a section piece on any face, dropped under `CellScope::Sections`.
//!
//! The culling during the construction (`reach`) is conservative: it keeps every cell a region may
//! reach, so some cells next to the sections end with no piece. They are dropped here, after the
//! pieces are built (the pieces of a plane are traced in the faces of all cells kept so far, so
//! that a contour point exactly on another plane finds the faces on both sides): faces of no kept
//! cell go, a face keeps `None` on the side of a dropped cell, and the pool keeps the vertices the
//! remaining faces and pieces use (in their order, so the relative order of ids is unchanged).
use super::{Arrangement, CellId, FaceId, VertexId};

/// What was dropped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Dropped {
    pub cells: usize,
    pub faces: usize,
    pub vertices: usize,
}

pub(crate) fn drop_cells_without_pieces(arr: &mut Arrangement) -> Dropped {
    let has_piece = |arr: &Arrangement, c: &super::Cell| {
        c.faces
            .iter()
            .any(|cf| !arr.faces[cf.face as usize].pieces.is_empty())
    };
    let keep_cell: Vec<bool> = arr.cells.iter().map(|c| has_piece(arr, c)).collect();
    if keep_cell.iter().all(|&k| k) {
        return Dropped::default();
    }
    let mut cell_new: Vec<Option<CellId>> = vec![None; arr.cells.len()];
    let mut next = 0;
    for (c, &k) in keep_cell.iter().enumerate() {
        if k {
            cell_new[c] = Some(next);
            next += 1;
        }
    }
    let mut face_used = vec![false; arr.faces.len()];
    for (c, cell) in arr.cells.iter().enumerate() {
        if keep_cell[c] {
            for cf in &cell.faces {
                face_used[cf.face as usize] = true;
            }
        }
    }
    let mut face_new: Vec<Option<FaceId>> = vec![None; arr.faces.len()];
    let mut nf = 0;
    for (f, &u) in face_used.iter().enumerate() {
        if u {
            face_new[f] = Some(nf);
            nf += 1;
        }
    }
    let before = (arr.cells.len(), arr.faces.len(), arr.pool.positions.len());
    let mut k = 0;
    arr.cells.retain(|_| {
        k += 1;
        keep_cell[k - 1]
    });
    for cell in &mut arr.cells {
        for cf in &mut cell.faces {
            cf.face = face_new[cf.face as usize].expect("a kept cell's face is kept");
        }
    }
    k = 0;
    arr.faces.retain(|_| {
        k += 1;
        face_used[k - 1]
    });
    for face in &mut arr.faces {
        face.positive_cell = face.positive_cell.and_then(|c| cell_new[c as usize]);
        face.negative_cell = face.negative_cell.and_then(|c| cell_new[c as usize]);
    }
    let vertices = drop_unused_vertices(arr);
    Dropped {
        cells: before.0 - arr.cells.len(),
        faces: before.1 - arr.faces.len(),
        vertices: vertices.min(before.2),
    }
}

/// Remove the pool vertices no face polygon or piece uses; returns how many.
pub(crate) fn drop_unused_vertices(arr: &mut Arrangement) -> usize {
    let nv = arr.pool.positions.len();
    let mut used = vec![false; nv];
    for face in &arr.faces {
        for &v in &face.polygon {
            used[v as usize] = true;
        }
        for p in &face.pieces {
            for l in std::iter::once(&p.outer).chain(&p.holes) {
                for &v in l {
                    used[v as usize] = true;
                }
            }
        }
    }
    let mut new_id = vec![VertexId::MAX; nv];
    let mut next: VertexId = 0;
    for v in 0..nv {
        if used[v] {
            new_id[v] = next;
            next += 1;
        }
    }
    if next as usize == nv {
        return 0;
    }
    let pool = &mut arr.pool;
    for list in [
        &mut pool.positions as &mut dyn Retain,
        &mut pool.tags,
        &mut pool.uv,
    ] {
        list.retain_mask(&used);
    }
    for face in &mut arr.faces {
        for v in face.polygon.iter_mut() {
            *v = new_id[*v as usize];
        }
        for p in &mut face.pieces {
            for l in std::iter::once(&mut p.outer).chain(p.holes.iter_mut()) {
                for v in l.iter_mut() {
                    *v = new_id[*v as usize];
                }
            }
        }
    }
    nv - next as usize
}

trait Retain {
    fn retain_mask(&mut self, keep: &[bool]);
}

impl<T> Retain for Vec<T> {
    fn retain_mask(&mut self, keep: &[bool]) {
        let mut k = 0;
        self.retain(|_| {
            k += 1;
            keep[k - 1]
        });
    }
}
