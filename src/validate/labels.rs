//! Components of different labels in one plane that touch or overlap (not in strict mode), and
//! the one-material view of all labels.
//!
//! Two regions of different labels are in *contact* when their contours touch or cross, or one
//! lies in the other's material (exact predicates, as the validator). A contact is
//! * **touching** when their materials meet only along their outlines (intersection area at most
//!   `LABEL_OVERLAP_RELATIVE_AREA` × the model's squared diagonal; the intersection is computed by
//!   `i_overlay`): both regions are kept as they are, shared boundary included. Each label alone is
//!   then a valid set of regions (`--label L`); the one-material view ([`one_material`], used when
//!   all labels are reconstructed together) merges them into the union of their material.
//! * **overlapping** otherwise, a real conflict, resolved by the rule **the lower label number keeps
//!   the overlap**: the material of every region of a lower label that overlaps it is subtracted
//!   from the region of the higher label (`i_overlay`, difference; the region may split, get holes,
//!   or vanish). The rule does not depend on the order of the file; renumber the labels to give
//!   another one priority. The warning gives the overlap's area.
//!
//! After the repair the validator checks each label on its own (exactly, as for one label) and that
//! no two regions of different labels overlap in area.
use super::repair::{material_of, pieces_of, region_of_piece, remapped};
use super::{
    check_intersections, check_nesting, model_diagonal, section_contours, ContourId, Locator,
    MemoryLocator, NoLocation, Role, NUDGE_RELATIVE,
};
use crate::error::{Error, Result};
use crate::sections::{polygon_signed_area, Region, Section, Sections};
use i_overlay::core::{fill_rule::FillRule, overlay_rule::OverlayRule};
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::float::single::SingleFloatOverlay;

/// Two regions of different labels whose materials intersect in at most this area, relative to the
/// model's squared diagonal, touch rather than overlap: the intersection of outlines that coincide
/// is empty up to the rounding of `i_overlay`'s integer grid (2^-60 of the extent) and of the
/// coordinates (about 1e-16), far below this; a real overlap of a segmentation is far above it.
pub const LABEL_OVERLAP_RELATIVE_AREA: f64 = 1e-12;

/// Bounding box of a region's outer contour.
fn bbox(region: &Region) -> ([f64; 2], [f64; 2]) {
    let mut lo = region.outer.points2[0];
    let mut hi = lo;
    for q in &region.outer.points2 {
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    (lo, hi)
}

/// The pairs (lower label, higher label) of regions of section `s` in contact. Regions that are
/// not valid on their own are left out (the validator reports them). Empty, without pairwise
/// tests, when the section's contours are disjoint and properly nested.
fn contacts(sec: &Section, s: usize) -> Vec<(usize, usize)> {
    let loc = &NoLocation;
    let all = section_contours(s, sec, 0..sec.regions.len());
    if check_intersections(&all, loc).is_ok() && check_nesting(&all, loc).is_ok() {
        return Vec::new();
    }
    let valid = |r: usize| {
        let c = section_contours(s, sec, [r]);
        check_intersections(&c, loc).is_ok() && check_nesting(&c, loc).is_ok()
    };
    let ok: Vec<bool> = (0..sec.regions.len()).map(valid).collect();
    let boxes: Vec<_> = sec.regions.iter().map(bbox).collect();
    let mut pairs = Vec::new();
    for a in 0..sec.regions.len() {
        for b in a + 1..sec.regions.len() {
            let (ra, rb) = (&sec.regions[a], &sec.regions[b]);
            let ((la, ha), (lb, hb)) = (boxes[a], boxes[b]);
            let apart = (0..2).any(|k| ha[k] < lb[k] || hb[k] < la[k]);
            if ra.label == rb.label || !ok[a] || !ok[b] || apart {
                continue;
            }
            let c = section_contours(s, sec, [a, b]);
            if check_intersections(&c, loc).is_err() || check_nesting(&c, loc).is_err() {
                pairs.push(if ra.label < rb.label { (a, b) } else { (b, a) });
            }
        }
    }
    pairs
}

/// Area of the intersection of two regions' materials.
fn overlap_area(a: &Region, b: &Region) -> f64 {
    let (mut ma, mut mb) = (Vec::new(), Vec::new());
    material_of(a, &mut ma);
    material_of(b, &mut mb);
    let shapes = ma.overlay_as::<i64>(&mb, OverlayRule::Intersect, FillRule::Positive);
    shapes
        .iter()
        .map(|shape| {
            let mut loops = shape.iter().map(|c| polygon_signed_area(c).abs());
            let outer = loops.next().unwrap_or(0.0);
            outer - loops.sum::<f64>()
        })
        .sum::<f64>()
        .max(0.0)
}

/// The absolute overlap tolerance of `sections`.
pub(super) fn area_tolerance(sections: &Sections) -> f64 {
    LABEL_OVERLAP_RELATIVE_AREA * model_diagonal(sections).powi(2)
}

/// Touching and overlapping regions of different labels in section `s` (after the same-label
/// repairs, whose `map` this extends): touching ones are kept (with a warning), overlapping ones
/// resolved by the lower label keeping the overlap (module docs).
pub(super) fn repair_label_overlaps(
    sec: &mut Section,
    s: usize,
    loc: &dyn Locator,
    area_tol: f64,
    nudge: f64,
    map: &mut Vec<(usize, bool)>,
    warnings: &mut Vec<String>,
) {
    let pairs = contacts(sec, s);
    if pairs.is_empty() {
        return;
    }
    let name = |r: usize, map: &[(usize, bool)]| {
        let id = ContourId {
            section: s,
            region: r,
            role: Role::Outer,
        };
        remapped(loc, map, id)
    };
    // Per region of a higher label: the lower-label regions it overlaps.
    let mut cut: Vec<Vec<usize>> = vec![Vec::new(); sec.regions.len()];
    for &(lo, hi) in &pairs {
        let (l, h) = (sec.regions[lo].label, sec.regions[hi].label);
        let area = overlap_area(&sec.regions[lo], &sec.regions[hi]);
        let with = format!("(label {l}) and {} (label {h})", name(hi, map));
        if area <= area_tol {
            warnings.push(format!(
                "{} {with}: repaired touching components of different labels: they share part of their outline (overlap area {area:.3e}); both kept, separate regions with --label, merged when all labels are one material",
                name(lo, map)
            ));
        } else {
            warnings.push(format!(
                "{} {with}: repaired overlapping components of different labels: overlap area {area:.6e}; the lower label {l} keeps it, it is cut from the label {h} component",
                name(lo, map)
            ));
            cut[hi].push(lo);
        }
    }
    if cut.iter().all(Vec::is_empty) {
        return;
    }
    let mut regions = Vec::new();
    let mut new_map = Vec::new();
    for (r, region) in sec.regions.iter().enumerate() {
        if cut[r].is_empty() {
            regions.push(region.clone());
            new_map.push(map[r]);
            continue;
        }
        let (mut subject, mut clip) = (Vec::new(), Vec::new());
        material_of(region, &mut subject);
        for &lo in &cut[r] {
            material_of(&sec.regions[lo], &mut clip);
        }
        let shapes = subject.overlay_as::<i64>(&clip, OverlayRule::Difference, FillRule::Positive);
        let pieces = pieces_of(shapes, nudge).unwrap_or_default();
        let holes: usize = pieces.iter().map(|p| p.len() - 1).sum();
        let what = if pieces.is_empty() {
            "removed (all of its material belongs to lower labels)".to_string()
        } else {
            format!("became {} region(s) with {holes} hole(s)", pieces.len())
        };
        warnings.push(format!(
            "{}: repaired label {} component overlapped by lower labels: {what}",
            name(r, map),
            region.label
        ));
        for p in pieces {
            regions.push(region_of_piece(region.label, &sec.plane, p));
            new_map.push((map[r].0, true));
        }
    }
    sec.regions = regions;
    *map = new_map;
}

/// Regions of different labels in section `s` may touch but not overlap in area (the check after
/// the repairs; each label is checked on its own by the caller).
pub(super) fn check_labels_disjoint(
    sec: &Section,
    s: usize,
    loc: &dyn Locator,
    area_tol: f64,
) -> Result<()> {
    for (lo, hi) in contacts(sec, s) {
        let area = overlap_area(&sec.regions[lo], &sec.regions[hi]);
        if area > area_tol {
            let id = |r| ContourId {
                section: s,
                region: r,
                role: Role::Outer,
            };
            return Err(Error::input(
                loc.contour(id(lo)),
                format!(
                    "regions of labels {} and {} overlap (area {area:.3e}) with {}",
                    sec.regions[lo].label,
                    sec.regions[hi].label,
                    loc.contour(id(hi))
                ),
            ));
        }
    }
    Ok(())
}

/// All labels as one material: in every plane where regions of different labels touch, they are
/// replaced by the union of the plane's material (`i_overlay`, 32-bit grid, so that outlines
/// coinciding up to the rounding of earlier repairs merge; pieces meeting at a vertex moved apart
/// as in the other repairs), labelled with the plane's lowest label. Other planes are unchanged.
/// The result is validated exactly like input (an error says the union is not valid, which a
/// validated input does not give).
pub fn one_material(sections: &Sections) -> Result<Sections> {
    let source = "all labels as one material";
    let loc = MemoryLocator {
        source,
        source_index: sections.sections.iter().map(|s| s.source_index).collect(),
    };
    let nudge = NUDGE_RELATIVE * model_diagonal(sections);
    let mut out = sections.clone();
    for (s, sec) in out.sections.iter_mut().enumerate() {
        let all = section_contours(s, sec, 0..sec.regions.len());
        if check_intersections(&all, &loc).is_ok() && check_nesting(&all, &loc).is_ok() {
            continue;
        }
        let mut material = Vec::new();
        for region in &sec.regions {
            material_of(region, &mut material);
        }
        let label = sec.regions.iter().map(|r| r.label).min().unwrap_or(1);
        let shapes = material.simplify_shape_as::<i32>(FillRule::Positive);
        let pieces = pieces_of(shapes, nudge).unwrap_or_default();
        sec.regions = pieces
            .into_iter()
            .map(|p| region_of_piece(label, &sec.plane, p))
            .collect();
        let all = section_contours(s, sec, 0..sec.regions.len());
        check_intersections(&all, &loc)?;
        check_nesting(&all, &loc)?;
    }
    Ok(out)
}

/// How far (relative to the model's diagonal) a vertex of the union may be from a label's vertex
/// or edge and still be it or lie on it: above the union's rounding (`one_material` merges on an
/// i32 grid, about 5e-10 of the extent), far below any feature of a section.
pub const JUNCTION_RELATIVE_TOLERANCE: f64 = 1e-8;

/// [`one_material`] keeping the *junctions*: the vertices of the labels' contours that lie on the
/// outline of the union (where the outline two labels share meets the outside, or a label's
/// vertex on a straight run of the union that the union's simplification dropped) become vertices
/// of the union's contours again, at the labels' exact positions. What a partition of the labels
/// needs: the outlines they share end at vertices of the one-material solid.
pub fn one_material_with_junctions(sections: &Sections) -> Result<Sections> {
    let mut out = one_material(sections)?;
    let tol = JUNCTION_RELATIVE_TOLERANCE * model_diagonal(sections);
    for (sec, labelled) in out.sections.iter_mut().zip(&sections.sections) {
        if sec.regions == labelled.regions {
            continue;
        }
        let mut points: Vec<([f64; 2], [f64; 3])> = (labelled.regions.iter())
            .flat_map(|r| std::iter::once(&r.outer).chain(&r.holes))
            .flat_map(|c| c.points2.iter().copied().zip(c.points3.iter().copied()))
            .collect();
        points.sort_unstable_by(|a, b| a.0[0].total_cmp(&b.0[0]));
        for region in &mut sec.regions {
            for c in std::iter::once(&mut region.outer).chain(&mut region.holes) {
                insert_junctions(c, &points, tol);
            }
        }
    }
    Ok(out)
}

/// Put into contour `c` every point of `points` (sorted by u) within `tol` of one of its edges,
/// strictly between its ends, in order along the edge; and move its vertices within `tol` of a
/// point of `points` onto it.
fn insert_junctions(c: &mut crate::sections::Contour, points: &[([f64; 2], [f64; 3])], tol: f64) {
    let n = c.points2.len();
    let mut p2 = Vec::with_capacity(n);
    let mut p3 = Vec::with_capacity(n);
    // a union vertex within rounding of a label's vertex is that vertex, at its exact position
    let near = |q: [f64; 2]| {
        let first = points.partition_point(|p| p.0[0] < q[0] - tol);
        (points[first..].iter())
            .take_while(|p| p.0[0] <= q[0] + tol)
            .find(|p| (p.0[0] - q[0]).hypot(p.0[1] - q[1]) <= tol)
            .copied()
    };
    for i in 0..n {
        let (a, b) = (c.points2[i], c.points2[(i + 1) % n]);
        match near(a) {
            Some((q, q3)) => {
                p2.push(q);
                p3.push(q3);
            }
            None => {
                p2.push(a);
                p3.push(c.points3[i]);
            }
        }
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        if len2 == 0.0 {
            continue;
        }
        let (lo, hi) = (a[0].min(b[0]) - tol, a[0].max(b[0]) + tol);
        let first = points.partition_point(|p| p.0[0] < lo);
        let mut on: Vec<(f64, [f64; 2], [f64; 3])> = Vec::new();
        for &(q, q3) in points[first..].iter().take_while(|p| p.0[0] <= hi) {
            let t = ((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2;
            let off = ((q[0] - a[0]) * d[1] - (q[1] - a[1]) * d[0]).abs() / len2.sqrt();
            let ends = tol / len2.sqrt();
            if off <= tol && t > ends && t < 1.0 - ends {
                on.push((t, q, q3));
            }
        }
        on.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        on.dedup_by(|x, y| x.1 == y.1);
        for (_, q, q3) in on {
            p2.push(q);
            p3.push(q3);
        }
    }
    c.points2 = p2;
    c.points3 = p3;
}

#[cfg(test)]
mod junction_tests {
    use super::*;
    use crate::sections::{Contour, Plane};

    #[test]
    fn junctions_on_edges_are_inserted_and_near_vertices_snapped() {
        let plane = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let mut c = Contour::from_2d(&plane, vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]);
        let p = |q: [f64; 2]| (q, plane.to_3d(q));
        let mut points = vec![
            p([1.0, 1e-10]),       // on the first edge within the tolerance
            p([2.0, 1.0 + 1e-10]), // the corner, rounded
            p([0.5, 0.5]),         // inside: not a junction
            p([0.0, 1.0 + 1e-3]),  // too far
        ];
        points.sort_unstable_by(|a, b| a.0[0].total_cmp(&b.0[0]));
        insert_junctions(&mut c, &points, 1e-8);
        assert_eq!(
            c.points2,
            vec![
                [0.0, 0.0],
                [1.0, 1e-10],
                [2.0, 0.0],
                [2.0, 1.0 + 1e-10],
                [0.0, 1.0]
            ]
        );
        assert_eq!(c.points3[1], plane.to_3d([1.0, 1e-10]));
    }
}
