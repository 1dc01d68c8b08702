//! Repair of self-intersecting and self-touching contours (bow-ties, keyholes), not in strict mode.
//!
//! Fill rule: **nonzero winding**. A point is material when the region's outer contour winds around
//! it a nonzero number of times (minus its holes, each also by nonzero winding). Nonzero rather than
//! even-odd because a segmentation outline that runs over itself (a loop traced twice, a lobe
//! wrapped around) still encloses material there; even-odd would punch a hole wherever the outline
//! overlaps itself. Both agree on bow-ties (each lobe winds ±1) and keyholes (the hole is walked the
//! other way round, winding 0; the zero-width channel encloses no area and disappears).
//!
//! The Boolean operation is `i_overlay` (integer engine `i64`) on the plane-frame coordinates. Where
//! the resulting contours meet at a vertex (a bow-tie's two lobes at the crossing), each contour's
//! copy of that vertex is moved into its own material by `NUDGE_RELATIVE` × the model's diagonal, so
//! the pieces no longer touch; the exact validator then checks the result like any input.
use super::{
    check_intersections, check_nesting, orientation, winding_number, ContourId, Locator, Role,
};
use crate::sections::{Contour, Region, Section};
use i_overlay::core::{fill_rule::FillRule, overlay_rule::OverlayRule};
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::float::single::SingleFloatOverlay;
use std::collections::HashMap;

/// How far a vertex shared by two repaired contours is moved apart, relative to the model diagonal:
/// a hundredth of the off-plane tolerance, below the precision of real files (Horsers prints two
/// decimals, 4.9e-5 of its diagonal). Not smaller: the Delaunay engine thickens a piece that no
/// cell attaches into a slab up to 2e-5 of the diagonal thick, whose walls cross a neighbouring
/// piece much closer than that (a bow-tie's lobes 2e-9 apart lost one lobe; 2e-5 apart both are
/// kept, `tests/io_repair.rs`).
pub const NUDGE_RELATIVE: f64 = 1e-5;

/// Locations after repairs: a region made by a repair is named by the component it came from.
pub(super) struct RemapLocator<'a> {
    pub inner: &'a dyn Locator,
    /// Per section, per region: (region index in the input, made by a repair).
    pub map: Vec<Vec<(usize, bool)>>,
}

impl Locator for RemapLocator<'_> {
    fn plane(&self, s: usize) -> String {
        self.inner.plane(s)
    }
    fn contour(&self, id: ContourId) -> String {
        remapped(self.inner, &self.map[id.section], id)
    }
}

/// The location of contour `id` of a section whose regions came from the input by `map`.
pub(super) fn remapped(inner: &dyn Locator, map: &[(usize, bool)], id: ContourId) -> String {
    let (orig, repaired) = map[id.region];
    if repaired {
        let outer = ContourId {
            section: id.section,
            region: orig,
            role: Role::Outer,
        };
        format!("{} (as repaired)", inner.contour(outer))
    } else {
        inner.contour(ContourId { region: orig, ..id })
    }
}

/// Repair every region of section `s` that has a self-intersecting or self-touching contour.
/// Returns the region map for `RemapLocator`; warnings name the input component.
pub(super) fn repair_self_intersections(
    sec: &mut Section,
    s: usize,
    loc: &dyn Locator,
    nudge: f64,
    warnings: &mut Vec<String>,
) -> Vec<(usize, bool)> {
    let mut map: Vec<(usize, bool)> = (0..sec.regions.len()).map(|r| (r, false)).collect();
    let mut extra = Vec::new();
    for r in 0..sec.regions.len() {
        let region = &sec.regions[r];
        let contours = std::iter::once((Role::Outer, &region.outer)).chain(
            region
                .holes
                .iter()
                .enumerate()
                .map(|(h, c)| (Role::Hole(h), c)),
        );
        let mut bad = None;
        for (role, c) in contours {
            let id = ContourId {
                section: s,
                region: r,
                role,
            };
            if check_intersections(&[(id, c)], loc).is_err() {
                bad = Some(id);
                break;
            }
        }
        let Some(bad) = bad else { continue };
        let Some(pieces) = resolve(region, nudge) else {
            continue; // nothing left (zero area): the validator reports the contour
        };
        let n = pieces.len();
        let holes: usize = pieces.iter().map(|p| p.len() - 1).sum();
        let what = if n == 1 && holes > region.holes.len() {
            format!("keyhole: 1 outer + {holes} hole(s)")
        } else if n > 1 {
            format!("split into {n} regions with {holes} hole(s)")
        } else {
            format!("became 1 region with {holes} hole(s)")
        };
        let role = match bad.role {
            Role::Outer => "outer contour".to_string(),
            Role::Hole(h) => format!("hole {h}"),
        };
        warnings.push(format!(
            "{}: repaired self-intersecting or self-touching contour ({role}): {what} (nonzero winding)",
            loc.contour(bad)
        ));
        let label = region.label;
        let mut new = pieces
            .into_iter()
            .map(|p| region_of_piece(label, &sec.plane, p));
        sec.regions[r] = new.next().expect("at least one piece");
        map[r].1 = true;
        for region in new {
            extra.push(region);
            map.push((r, true));
        }
    }
    sec.regions.extend(extra);
    map
}

/// The region's material by nonzero winding, as simple pieces: per piece, outer (counter-clockwise)
/// then holes (clockwise). None if nothing has area.
fn resolve(region: &Region, nudge: f64) -> Option<Vec<Vec<Vec<[f64; 2]>>>> {
    let subject = vec![region.outer.points2.clone()];
    let clip: Vec<Vec<[f64; 2]>> = region.holes.iter().map(|h| h.points2.clone()).collect();
    let shapes = subject.overlay_as::<i64>(&clip, OverlayRule::Difference, FillRule::NonZero);
    pieces_of(shapes, nudge)
}

/// i_overlay's shapes as pieces (outer counter-clockwise, then holes clockwise), without repeated
/// vertices, vertices shared by two contours moved apart. None if nothing has area.
pub(crate) fn pieces_of(
    shapes: Vec<Vec<Vec<[f64; 2]>>>,
    nudge: f64,
) -> Option<Vec<Vec<Vec<[f64; 2]>>>> {
    let mut pieces: Vec<Vec<Vec<[f64; 2]>>> = Vec::new();
    for shape in shapes {
        let mut piece = Vec::new();
        for (k, mut c) in shape.into_iter().enumerate() {
            c.dedup();
            while c.len() > 1 && c.first() == c.last() {
                c.pop();
            }
            if c.len() < 3 {
                continue;
            }
            if (orientation(&c) > 0.0) != (k == 0) {
                c.reverse();
            }
            if k == 0 || !piece.is_empty() {
                piece.push(c);
            }
        }
        if !piece.is_empty() {
            pieces.push(piece);
        }
    }
    if pieces.is_empty() {
        return None;
    }
    separate_shared_vertices(&mut pieces, nudge);
    Some(pieces)
}

/// Move every copy of a vertex that occurs more than once (in two contours, or twice in one) into
/// the material beside it (left of the contour: outer counter-clockwise, holes clockwise).
fn separate_shared_vertices(pieces: &mut [Vec<Vec<[f64; 2]>>], nudge: f64) {
    let key = |q: [f64; 2]| (q[0].to_bits(), q[1].to_bits());
    let mut count: HashMap<(u64, u64), usize> = HashMap::new();
    for c in pieces.iter().flatten() {
        for &q in c {
            *count.entry(key(q)).or_default() += 1;
        }
    }
    for c in pieces.iter_mut().flatten() {
        let n = c.len();
        let old = c.clone();
        for i in 0..n {
            if count[&key(old[i])] < 2 {
                continue;
            }
            let (a, v, b) = (old[(i + n - 1) % n], old[i], old[(i + 1) % n]);
            let unit = |d: [f64; 2]| {
                let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
                [d[0] / l, d[1] / l]
            };
            let e1 = unit([v[0] - a[0], v[1] - a[1]]);
            let e2 = unit([b[0] - v[0], b[1] - v[1]]);
            // Left normals of both edges; their sum points into the material on the left.
            let d = [-e1[1] - e2[1], e1[0] + e2[0]];
            let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
            if l.is_finite() && l > 1e-6 {
                c[i] = [v[0] + nudge * d[0] / l, v[1] + nudge * d[1] / l];
            }
        }
    }
}

/// Same-label conflicts of section `s` (after `repair_self_intersections`, whose `map` this
/// extends): when the contours of one label's regions touch or cross (two components, or a hole and
/// its outer contour), or a region lies inside the material of another of its label, that label's
/// regions are replaced by the union of their material (outer contours counted +1, holes -1, kept
/// where the count is positive: a hole touching its outer contour is subtracted from it). A hole
/// outside its parent, not touching it, stays an error. Different labels are left to `labels`.
pub(super) fn repair_label_conflicts(
    sec: &mut Section,
    s: usize,
    loc: &dyn Locator,
    nudge: f64,
    map: &mut Vec<(usize, bool)>,
    warnings: &mut Vec<String>,
) {
    let mut labels: Vec<i32> = sec.regions.iter().map(|r| r.label).collect();
    labels.sort_unstable();
    labels.dedup();
    for label in labels {
        let members: Vec<usize> = (0..sec.regions.len())
            .filter(|&r| sec.regions[r].label == label)
            .collect();
        let contours = super::section_contours(s, sec, members.iter().copied());
        // Decisions only: the regions may be repaired pieces the input's locator does not know.
        let touching = check_intersections(&contours, &super::NoLocation).is_err();
        if !touching {
            let holes_inside = members.iter().all(|&r| {
                let region = &sec.regions[r];
                region
                    .holes
                    .iter()
                    .all(|h| winding_number(h.points2[0], &region.outer.points2) != 0)
            });
            if !holes_inside || check_nesting(&contours, &super::NoLocation).is_ok() {
                continue;
            }
        }
        let mut material: Vec<Vec<[f64; 2]>> = Vec::new();
        for &r in &members {
            material_of(&sec.regions[r], &mut material);
        }
        let shapes = material.simplify_shape_as::<i64>(FillRule::Positive);
        let Some(pieces) = pieces_of(shapes, nudge) else {
            continue;
        };
        let n = pieces.len();
        let holes: usize = pieces.iter().map(|p| p.len() - 1).sum();
        let names: Vec<String> = members
            .iter()
            .take(3)
            .map(|&r| {
                remapped(
                    loc,
                    map,
                    ContourId {
                        section: s,
                        region: r,
                        role: Role::Outer,
                    },
                )
            })
            .collect();
        let more = if members.len() > 3 {
            format!(" and {} more", members.len() - 3)
        } else {
            String::new()
        };
        let what = if members.len() == 1 {
            "a hole touching or crossing its outer contour".to_string()
        } else {
            format!(
                "{} touching or overlapping components of label {label}",
                members.len()
            )
        };
        let with = if members.len() > 1 {
            format!(" (with {}{more})", names[1..].join("; "))
        } else {
            String::new()
        };
        warnings.push(format!(
            "{}: repaired {what}{with}: merged into {n} region(s) with {holes} hole(s) (union of their material)",
            names[0]
        ));
        let origin = map[members[0]].0;
        let new: Vec<Region> = pieces
            .into_iter()
            .map(|p| region_of_piece(label, &sec.plane, p))
            .collect();
        // Replace the members by the pieces, in place of the first member.
        let mut regions = Vec::new();
        let mut new_map = Vec::new();
        let mut new = Some(new);
        for (r, region) in std::mem::take(&mut sec.regions).into_iter().enumerate() {
            if r == members[0] {
                for piece in new.take().expect("inserted once") {
                    regions.push(piece);
                    new_map.push((origin, true));
                }
            } else if region.label != label {
                regions.push(region);
                new_map.push(map[r]);
            }
        }
        sec.regions = regions;
        *map = new_map;
    }
}

/// Append the contours of `region` to `out` as material for the booleans: the outer contour
/// counter-clockwise, the holes clockwise (so `FillRule::Positive` counts outer +1, holes -1).
pub(crate) fn material_of(region: &Region, out: &mut Vec<Vec<[f64; 2]>>) {
    for (k, c) in std::iter::once(&region.outer)
        .chain(&region.holes)
        .enumerate()
    {
        let mut p = c.points2.clone();
        if (orientation(&p) > 0.0) != (k == 0) {
            p.reverse();
        }
        out.push(p);
    }
}

/// A region of `label` from a boolean result's piece (its outer loop first, then its holes).
pub(super) fn region_of_piece(
    label: i32,
    plane: &crate::sections::Plane,
    mut piece: Vec<Vec<[f64; 2]>>,
) -> Region {
    let outer = piece.remove(0);
    Region {
        label,
        outer: Contour::from_2d(plane, outer),
        holes: piece
            .into_iter()
            .map(|h| Contour::from_2d(plane, h))
            .collect(),
    }
}
