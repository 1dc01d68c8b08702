//! Several closed meshes, one label each, cut into labelled sections that partition every plane:
//! inputs with a known answer for multi-label reconstruction.
//!
//! * **Priority.** The meshes are given in priority order: where two overlap, the region inside both
//!   belongs to the one given first (the label of mesh k in a plane is its section minus the sections of
//!   meshes 0..k, `i_overlay` difference on its 64-bit grid). So label k's domain is
//!   `M_k \ (M_0 ∪ … ∪ M_{k-1})`, and the labels never overlap. Meshes that only touch (their
//!   sections' intersection at most [`LABEL_OVERLAP_RELATIVE_AREA`] × diagonal², as the reader
//!   counts touching) are kept as they were sliced, vertex for vertex.
//! * **Shared vertices.** Where the outlines of two labels run together, both carry the same vertices
//!   (bit for bit), so the reader's label logic sees them touch, not overlap or gap: a vertex of any
//!   label within [`SHARED_VERTEX_RELATIVE_TOLERANCE`] × diagonal of a vertex met before it (labels
//!   in priority order) takes that vertex's coordinates, then every vertex of one label within that
//!   tolerance of a contour edge of another label (strictly inside the edge) is inserted into that
//!   edge. Meshes that share an interface vertex for vertex already give identical crossing points
//!   (one per 3D edge); the insertion is what conforms interfaces triangulated differently, and the
//!   crossings the priority difference creates. Each move is within the tolerance (in practice a few
//!   ulps of the coordinates).
//!
//! Every mesh is sliced exactly as [`super::slice_mesh`] slices one; the result goes through the
//! shared validator (which warns that touching labels touch).
use super::{bounding_box, check_closed_manifold, clean_loop, has_area, section_regions};
use crate::error::{Error, Result};
use crate::mesh::TriMesh;
use crate::sections::{polygon_signed_area, Contour, Plane, Region, Section, Sections};
use crate::validate::{material_of, pieces_of, LABEL_OVERLAP_RELATIVE_AREA, NUDGE_RELATIVE};
use i_overlay::core::{fill_rule::FillRule, overlay_rule::OverlayRule};
use i_overlay::float::single::SingleFloatOverlay;
use rayon::prelude::*;
use std::collections::HashMap;

/// Vertices of two labels closer than this (relative to the bounding-box diagonal of all meshes) are
/// one shared vertex; a vertex this close to another label's contour edge is inserted into it.
pub const SHARED_VERTEX_RELATIVE_TOLERANCE: f64 = 1e-10;

/// A closed mesh, the label its material gets, and a name for messages (the file).
#[derive(Clone, Debug)]
pub struct LabelledMesh {
    pub name: String,
    pub mesh: TriMesh,
    pub label: i32,
}

/// All vertices of all meshes as one mesh (for [`super::make_planes`], which places planes by the
/// vertices' bounding box and keeps them clear of every vertex).
pub fn union_mesh(meshes: &[LabelledMesh]) -> TriMesh {
    let mut out = TriMesh::default();
    for m in meshes {
        let off = out.vertices.len() as u32;
        out.vertices.extend(&m.mesh.vertices);
        out.triangles
            .extend(m.mesh.triangles.iter().map(|t| t.map(|v| v + off)));
    }
    out
}

/// Cut every mesh by every plane and partition each plane among the labels (module docs). Labels
/// must be positive and distinct; each mesh a closed oriented 2-manifold (errors name the mesh).
/// Planes no mesh crosses are skipped; `source_index` is the position in the result.
pub fn slice_partition(meshes: &[LabelledMesh], planes: &[Plane]) -> Result<Sections> {
    check_labels(meshes)?;
    for m in meshes {
        check_closed_manifold(&m.mesh).map_err(|e| relocate(e, &m.name))?;
    }
    let all = union_mesh(meshes);
    let diag = bounding_box(&all.vertices).map_or(0.0, |(lo, hi)| {
        (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
    });
    let tol = Tolerances {
        shared: SHARED_VERTEX_RELATIVE_TOLERANCE * diag,
        area: LABEL_OVERLAP_RELATIVE_AREA * diag * diag,
        nudge: NUDGE_RELATIVE * diag,
    };
    let per_plane: Vec<Vec<Region>> = planes
        .par_iter()
        .map(|p| {
            let mut sliced = Vec::with_capacity(meshes.len());
            for m in meshes {
                let mut regions = section_regions(&m.mesh, p)
                    .map_err(|e| relocate(e, &m.name))?
                    .unwrap_or_default();
                regions.iter_mut().for_each(|r| r.label = m.label);
                sliced.push(regions);
            }
            Ok(partition_plane(p, sliced, &tol))
        })
        .collect::<Result<_>>()?;
    let mut sections = Vec::new();
    for (plane, regions) in planes.iter().zip(per_plane) {
        if !regions.is_empty() {
            sections.push(Section {
                plane: *plane,
                regions,
                source_index: sections.len(),
                max_off_plane: 0.0,
            });
        }
    }
    let n_labels = meshes.iter().map(|m| m.label).max().unwrap_or(1) as usize;
    crate::validate::validate(
        Sections {
            sections,
            n_labels,
            warnings: Vec::new(),
            label_names: Default::default(),
        },
        "mesh partition",
    )
}

fn check_labels(meshes: &[LabelledMesh]) -> Result<()> {
    if meshes.is_empty() {
        return Err(Error::input("meshes", "no mesh to slice"));
    }
    for (i, m) in meshes.iter().enumerate() {
        if m.label < 1 {
            return Err(Error::input(
                &m.name,
                format!("label {} is not positive", m.label),
            ));
        }
        if let Some(o) = meshes[..i].iter().find(|o| o.label == m.label) {
            return Err(Error::input(
                &m.name,
                format!(
                    "label {} is also the label of {} (one mesh per label: merge them into one closed mesh)",
                    m.label, o.name
                ),
            ));
        }
    }
    Ok(())
}

/// Errors of the one-mesh slicer are located as "mesh…": name the mesh instead.
fn relocate(e: Error, name: &str) -> Error {
    match e {
        Error::Input { location, reason } if location.starts_with("mesh") => Error::Input {
            location: location.replacen("mesh", name, 1),
            reason,
        },
        other => other,
    }
}

/// One label's material in a plane: its pieces, each an outer loop then its holes.
type LabelLoops = (i32, Vec<Vec<Vec<[f64; 2]>>>);

struct Tolerances {
    /// Distance within which vertices are shared and inserted into edges.
    shared: f64,
    /// Overlap area up to which two labels touch rather than overlap.
    area: f64,
    /// The move apart of pieces meeting at a vertex after a difference (as the validator's repairs).
    nudge: f64,
}

/// One plane: `sliced[k]` the regions of mesh k (priority order, labels set) → the partition's
/// regions, all labels together.
fn partition_plane(plane: &Plane, sliced: Vec<Vec<Region>>, tol: &Tolerances) -> Vec<Region> {
    let mut labels: Vec<LabelLoops> = Vec::with_capacity(sliced.len());
    for k in 0..sliced.len() {
        let Some(label) = sliced[k].first().map(|r| r.label) else {
            continue;
        };
        let loops = match without_higher(&sliced[k], &sliced[..k], tol) {
            Some(pieces) => pieces,
            None => sliced[k].iter().map(region_loops).collect(),
        };
        labels.push((label, loops));
    }
    snap_to_earlier_labels(&mut labels, tol.shared);
    insert_into_edges(&mut labels, tol.shared);
    let mut regions = Vec::new();
    for (label, pieces) in labels {
        for piece in pieces {
            let mut loops = piece
                .into_iter()
                .map(clean_loop)
                .filter(|l| l.len() >= 3 && has_area(l));
            let Some(outer) = loops.next() else { continue };
            regions.push(Region {
                label,
                outer: Contour::from_2d(plane, outer),
                holes: loops.map(|h| Contour::from_2d(plane, h)).collect(),
            });
        }
    }
    regions
}

fn region_loops(r: &Region) -> Vec<Vec<[f64; 2]>> {
    std::iter::once(&r.outer)
        .chain(&r.holes)
        .map(|c| c.points2.clone())
        .collect()
}

type Box2 = ([f64; 2], [f64; 2]);

fn box_of<'a>(pts: impl Iterator<Item = &'a [f64; 2]>) -> Box2 {
    pts.fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}

fn boxes_meet(a: Box2, b: Box2) -> bool {
    (0..2).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
}

fn shapes_area(shapes: &[Vec<Vec<[f64; 2]>>]) -> f64 {
    shapes
        .iter()
        .flatten()
        .map(|c| polygon_signed_area(c))
        .sum::<f64>()
        .abs()
}

/// The regions `mine` minus the material of the higher-priority `higher`, as pieces (outer loop
/// first); `None` when they overlap by at most the touching area (nothing to take away).
fn without_higher(
    mine: &[Region],
    higher: &[Vec<Region>],
    tol: &Tolerances,
) -> Option<Vec<Vec<Vec<[f64; 2]>>>> {
    let my_box = box_of(mine.iter().flat_map(|r| &r.outer.points2));
    let mut clip = Vec::new();
    for r in higher.iter().flatten() {
        if boxes_meet(my_box, box_of(r.outer.points2.iter())) {
            material_of(r, &mut clip);
        }
    }
    if clip.is_empty() {
        return None;
    }
    let mut subject = Vec::new();
    for r in mine {
        material_of(r, &mut subject);
    }
    let common = subject.overlay_as::<i64>(&clip, OverlayRule::Intersect, FillRule::Positive);
    if shapes_area(&common) <= tol.area {
        return None;
    }
    let rest = subject.overlay_as::<i64>(&clip, OverlayRule::Difference, FillRule::Positive);
    Some(pieces_of(rest, tol.nudge).unwrap_or_default())
}

/// Grid cell of a point for the shared-vertex search (cells of the tolerance's size).
fn cell(p: [f64; 2], size: f64) -> (i64, i64) {
    ((p[0] / size).floor() as i64, (p[1] / size).floor() as i64)
}

/// Every vertex within `tol` of a vertex met before it (labels in priority order, each label's
/// contours in order) takes that earlier vertex's coordinates (the nearest, if several): vertices
/// closer than `tol` become one, the earliest.
fn snap_to_earlier_labels(labels: &mut [LabelLoops], tol: f64) {
    if tol <= 0.0 {
        return;
    }
    let mut grid: HashMap<(i64, i64), Vec<[f64; 2]>> = HashMap::new();
    for p in labels
        .iter_mut()
        .flat_map(|(_, pieces)| pieces.iter_mut().flatten().flatten())
    {
        let (cx, cy) = cell(*p, tol);
        let mut best: Option<([f64; 2], f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &q in grid.get(&(cx + dx, cy + dy)).into_iter().flatten() {
                    let d = (q[0] - p[0]).hypot(q[1] - p[1]);
                    if d <= tol && best.is_none_or(|(_, bd)| d < bd) {
                        best = Some((q, d));
                    }
                }
            }
        }
        match best {
            Some((q, _)) => *p = q,
            None => grid.entry((cx, cy)).or_default().push(*p),
        }
    }
}

/// Insert into every contour edge the vertices of other labels within `tol` of it (strictly between
/// its ends, in order along it).
fn insert_into_edges(labels: &mut [LabelLoops], tol: f64) {
    if labels.len() < 2 || tol <= 0.0 {
        return;
    }
    // Every vertex with the index of its label, sorted by x for range queries.
    let mut verts: Vec<([f64; 2], usize)> = labels
        .iter()
        .enumerate()
        .flat_map(|(k, (_, pieces))| pieces.iter().flatten().flatten().map(move |&p| (p, k)))
        .collect();
    verts.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]).then(a.0[1].total_cmp(&b.0[1])));
    verts.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
    for (k, (_, pieces)) in labels.iter_mut().enumerate() {
        for lp in pieces.iter_mut().flatten() {
            let n = lp.len();
            let mut out = Vec::with_capacity(n);
            for i in 0..n {
                let (p, q) = (lp[i], lp[(i + 1) % n]);
                out.push(p);
                out.extend(on_edge(&verts, k, p, q, tol));
            }
            *lp = out;
        }
    }
}

/// The vertices of labels other than `k` within `tol` of edge pq, strictly between p and q, ordered
/// from p to q.
fn on_edge(
    verts: &[([f64; 2], usize)],
    k: usize,
    p: [f64; 2],
    q: [f64; 2],
    tol: f64,
) -> Vec<[f64; 2]> {
    let (x0, x1) = (p[0].min(q[0]) - tol, p[0].max(q[0]) + tol);
    let (y0, y1) = (p[1].min(q[1]) - tol, p[1].max(q[1]) + tol);
    let start = verts.partition_point(|v| v.0[0] < x0);
    let d = [q[0] - p[0], q[1] - p[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    if len2 == 0.0 {
        return Vec::new();
    }
    let mut hits: Vec<(f64, [f64; 2])> = Vec::new();
    for &(v, l) in verts[start..].iter().take_while(|v| v.0[0] <= x1) {
        let near = |a: [f64; 2]| (v[0] - a[0]).hypot(v[1] - a[1]) <= tol;
        if l == k || v[1] < y0 || v[1] > y1 || near(p) || near(q) {
            continue;
        }
        let t = ((v[0] - p[0]) * d[0] + (v[1] - p[1]) * d[1]) / len2;
        if t <= 0.0 || t >= 1.0 {
            continue;
        }
        let c = [p[0] + t * d[0], p[1] + t * d[1]];
        if (v[0] - c[0]).hypot(v[1] - c[1]) <= tol {
            hits.push((t, v));
        }
    }
    hits.sort_by(|a, b| a.0.total_cmp(&b.0));
    hits.dedup_by(|a, b| a.1 == b.1);
    hits.into_iter().map(|(_, v)| v).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::shapes::grid_box;
    use crate::slice::{make_planes, slice_mesh, SliceMode};

    fn lm(name: &str, mesh: TriMesh, label: i32) -> LabelledMesh {
        LabelledMesh {
            name: name.into(),
            mesh,
            label,
        }
    }

    #[test]
    fn one_labelled_mesh_slices_as_slice_mesh_does() {
        let m = grid_box([0.0; 3], [1.0, 2.0, 3.0], [2, 3, 4]);
        let planes = make_planes(&m, 7, 2, SliceMode::Random);
        let one = slice_mesh(&m, &planes).unwrap();
        let part = slice_partition(&[lm("box", m, 4)], &planes).unwrap();
        assert_eq!(part.sections.len(), one.sections.len());
        for (a, b) in part.sections.iter().zip(&one.sections) {
            assert_eq!(a.regions.len(), b.regions.len());
            for (ra, rb) in a.regions.iter().zip(&b.regions) {
                assert_eq!(ra.label, 4);
                assert_eq!(ra.outer.points2, rb.outer.points2);
            }
        }
    }

    #[test]
    fn labels_must_be_positive_and_distinct_and_meshes_closed() {
        let b = grid_box([0.0; 3], [1.0; 3], [1, 1, 1]);
        let c = grid_box([2.0; 3], [3.0; 3], [1, 1, 1]);
        let planes = make_planes(&b, 3, 0, SliceMode::Parallel);
        let e = slice_partition(&[lm("b", b.clone(), 1), lm("c", c.clone(), 1)], &planes)
            .unwrap_err()
            .to_string();
        assert!(e.contains("c") && e.contains("also the label of b"), "{e}");
        let e = slice_partition(&[lm("b", b.clone(), 0)], &planes).unwrap_err();
        assert!(e.to_string().contains("not positive"), "{e}");
        let mut open = c;
        open.triangles.pop();
        let e = slice_partition(&[lm("b", b, 1), lm("open.stl", open, 2)], &planes).unwrap_err();
        assert!(e.to_string().starts_with("open.stl"), "{e}");
        assert!(e.to_string().contains("not closed"), "{e}");
    }
}
