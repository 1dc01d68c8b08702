//! Sections that disagree along their planes' common line (DESIGN invariant 5), reconciled before
//! the arrangement by one rule: **material only where both sections have it**.
//!
//! A solid R with R ∩ P_i = A_i for every plane meets the line L = P_i ∩ P_j in A_i ∩ L and in
//! A_j ∩ L, so two sections can only both be kept when these agree. Real sections rarely do
//! exactly: the crossings of the two contours with L are a rounding or a sampling step apart
//! (the arrangement snaps those, `arrangement::reconcile`, within `snap_tolerance`), and sometimes
//! one section has material over a stretch of L where the other has none (a missed or dropped
//! contour, a segmentation that disagrees with its neighbour). Kept as it is, such a stretch
//! forces the solid to touch P_j along a segment without crossing it: a singular edge, which no
//! closed manifold has. The rule here: where A_i has material on L and A_j does not, the material
//! of A_i within `strip` (relative to the model diagonal) of L is removed there, from where A_j's
//! material ends on L to where A_i's ends (a rectangle of half-width `strip` along L, subtracted
//! with `i_overlay`). Then A_i ∩ L = A_j ∩ L = (A_i ∩ A_j) ∩ L. Stretches shorter than the snap
//! tolerance that continue one of A_j's intervals are left to the snapping. Each trim is warned
//! with both planes, the length of L concerned and the area removed.
//!
//! The intervals are constructions in floating point (where a contour edge crosses the other
//! plane), not decisions of the engine: the arrangement computes the crossings it uses itself.
use super::{material_of, model_diagonal, pieces_of, repair::region_of_piece, NUDGE_RELATIVE};
use crate::error::Result;
use crate::geom::three_planes_point;
use crate::sections::{cross, dot, polygon_signed_area, Plane, Section, Sections};
use i_overlay::core::{fill_rule::FillRule, overlay_rule::OverlayRule};
use i_overlay::float::single::SingleFloatOverlay;
use rayon::prelude::*;
use std::collections::HashMap;

/// Half-width of the strip removed along a common line where one section has material and the
/// other none, relative to the model diagonal: ten times the repairs' vertex nudge, a tenth of the
/// snap tolerance (so the small mismatches a trim leaves where two lines meet are snapped).
pub const LINE_STRIP_RELATIVE: f64 = 1e-4;

/// Planes whose normals' cross product is shorter than this are parallel (no common line).
const PARALLEL: f64 = 1e-12;

/// What `reconcile_common_lines` changed.
#[derive(Clone, Debug, Default)]
pub struct LineTrims {
    pub warnings: Vec<String>,
    /// Number of (section, line) pairs trimmed.
    pub trimmed: usize,
    /// Longest stretch of a common line on which one section had material and the other none.
    pub max_length: f64,
}

/// A stretch [s0, s1] of line (i, j) to clear of section `owner`'s material, in arc length
/// `dir · x` along the line's direction `dir` (n_i × n_j, normalised, for i < j: the same for
/// both owners of a line).
struct Trim {
    owner: usize,
    other: usize,
    dir: [f64; 3],
    s0: f64,
    s1: f64,
    /// Length of the owner's material on L inside the stretch.
    material: f64,
}

/// Apply the rule of the module docs to every pair of non-parallel planes. `snap_relative` is the
/// arrangement's snap tolerance, `strip_relative` the strip's half-width (0: nothing is changed).
pub fn reconcile_common_lines(
    mut sections: Sections,
    snap_relative: f64,
    strip_relative: f64,
) -> Result<(Sections, LineTrims)> {
    let mut log = LineTrims::default();
    let diag = model_diagonal(&sections);
    if strip_relative <= 0.0 || diag <= 0.0 {
        return Ok((sections, log));
    }
    let (tol, strip) = (snap_relative * diag, strip_relative * diag);
    let boxes: Vec<Option<([f64; 3], [f64; 3])>> =
        sections.sections.iter().map(section_box).collect();
    let n = sections.sections.len();
    let input = &sections;
    let trims: Vec<Trim> = (0..n)
        .into_par_iter()
        .flat_map_iter(|i| {
            let boxes = &boxes;
            (i + 1..n).flat_map(move |j| pair_trims(input, boxes, i, j, tol))
        })
        .collect();
    // planes and file indices stay as they are; only regions are trimmed
    let planes: Vec<Plane> = sections.sections.iter().map(|s| s.plane).collect();
    let index: Vec<usize> = sections.sections.iter().map(|s| s.source_index).collect();
    let mut per_section: Vec<Vec<&Trim>> = (0..n).map(|_| Vec::new()).collect();
    for t in &trims {
        per_section[t.owner].push(t);
        log.max_length = log.max_length.max(t.material);
    }
    for (i, list) in per_section.iter().enumerate() {
        if list.is_empty() {
            continue;
        }
        let sec = &mut sections.sections[i];
        let rects: Vec<Vec<[f64; 2]>> = list
            .iter()
            .map(|t| strip_rectangle(&sec.plane, &planes[t.other], t.dir, t.s0, t.s1, strip))
            .collect();
        let before = sec.area();
        trim_section(sec, &rects, strip, NUDGE_RELATIVE * diag);
        let removed = before - sec.area();
        log.trimmed += list.len();
        for t in list {
            log.warnings.push(format!(
                "planes {} and {} disagree along their common line: plane {} has material over {:.3e} of it where plane {} has none; plane {}'s material within {strip:.1e} of the line removed there (material only where both sections have it)",
                index[t.owner].min(index[t.other]),
                index[t.owner].max(index[t.other]),
                index[t.owner],
                t.material,
                index[t.other],
                index[t.owner],
            ));
        }
        log.warnings.push(format!(
            "plane {}: {removed:.3e} of its area {before:.3e} removed along {} common line(s) where another section has no material",
            sec.source_index,
            list.len()
        ));
    }
    Ok((sections, log))
}

fn section_box(sec: &Section) -> Option<([f64; 3], [f64; 3])> {
    let mut pts = sec
        .regions
        .iter()
        .flat_map(|r| std::iter::once(&r.outer).chain(&r.holes))
        .flat_map(|c| c.points3.iter());
    let first = *pts.next()?;
    Some(pts.fold((first, first), |(lo, hi), p| {
        (
            [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
            [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
        )
    }))
}

/// Whether `plane` meets the box (some corner on each side, or on it).
fn plane_meets_box(plane: &Plane, b: &([f64; 3], [f64; 3])) -> bool {
    let (mut neg, mut pos) = (false, false);
    for k in 0..8 {
        let c = [
            if k & 1 == 0 { b.0[0] } else { b.1[0] },
            if k & 2 == 0 { b.0[1] } else { b.1[1] },
            if k & 4 == 0 { b.0[2] } else { b.1[2] },
        ];
        let d = plane.signed_distance(c);
        neg |= d <= 0.0;
        pos |= d >= 0.0;
    }
    neg && pos
}

/// The stretches of line (i, j) to clear from section i and from section j.
fn pair_trims(
    sections: &Sections,
    boxes: &[Option<([f64; 3], [f64; 3])>],
    i: usize,
    j: usize,
    tol: f64,
) -> Vec<Trim> {
    let (pi, pj) = (&sections.sections[i].plane, &sections.sections[j].plane);
    let d = cross(pi.normal, pj.normal);
    let l = dot(d, d).sqrt();
    if l < PARALLEL {
        return Vec::new();
    }
    // the common line, parametrised by arc length s = dir · x
    let dir = [d[0] / l, d[1] / l, d[2] / l];
    let meets = |a: usize, b: usize| {
        boxes[a]
            .as_ref()
            .is_some_and(|bx| plane_meets_box(&sections.sections[b].plane, bx))
    };
    let (mi, mj) = (meets(i, j), meets(j, i));
    if !mi && !mj {
        return Vec::new();
    }
    let on_line = |a: usize, b: usize, m: bool| {
        if m {
            material_on_line(&sections.sections[a], &sections.sections[b].plane, dir)
        } else {
            Vec::new()
        }
    };
    let (ii, ij) = (on_line(i, j, mi), on_line(j, i, mj));
    // where the other planes cross the line: the snapping merges two crossings only between the
    // same two of them (on one arrangement edge); needed only where both sections touch the line
    let breaks = if ii.is_empty() || ij.is_empty() {
        Vec::new()
    } else {
        line_breaks(sections, i, j, dir)
    };
    let mut out = Vec::new();
    for (owner, other, mine, theirs) in [(i, j, &ii, &ij), (j, i, &ij, &ii)] {
        for (s0, s1, material) in stretches_to_clear(mine, theirs, &breaks, tol) {
            out.push(Trim {
                owner,
                other,
                dir,
                s0,
                s1,
                material,
            });
        }
    }
    out
}

/// Where the planes of the sections other than `i` and `j` cross the line of `i` and `j` (arc
/// length `dir · x`, sorted): the arrangement's vertices on it.
fn line_breaks(sections: &Sections, i: usize, j: usize, dir: [f64; 3]) -> Vec<f64> {
    let (a, b) = (&sections.sections[i].plane, &sections.sections[j].plane);
    let mut out: Vec<f64> = (sections.sections.iter().enumerate())
        .filter(|&(k, _)| k != i && k != j)
        // a plane parallel to the line does not cross it
        .filter(|(_, s)| dot(a.normal, cross(b.normal, s.plane.normal)).abs() >= PARALLEL)
        .map(|(_, s)| {
            let x = three_planes_point(a.equation(), b.equation(), s.plane.equation());
            dot(dir, x)
        })
        .collect();
    out.sort_by(f64::total_cmp);
    out
}

/// The intervals of the line along `dir` (arc length `dir · x`; sorted, disjoint) where `sec` has
/// material: between consecutive crossings of its contours with `other` (validated contours are
/// disjoint and nested, so parity is material). A vertex on the other plane counts as on its positive side.
fn material_on_line(sec: &Section, other: &Plane, dir: [f64; 3]) -> Vec<(f64, f64)> {
    let mut s = Vec::new();
    for c in sec
        .regions
        .iter()
        .flat_map(|r| std::iter::once(&r.outer).chain(&r.holes))
    {
        let p = &c.points3;
        let m = p.len();
        for k in 0..m {
            let (a, b) = (p[k], p[(k + 1) % m]);
            let (fa, fb) = (other.signed_distance(a), other.signed_distance(b));
            if (fa >= 0.0) == (fb >= 0.0) {
                continue;
            }
            let t = fa / (fa - fb);
            let x = [
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            ];
            s.push(dot(dir, x));
        }
    }
    s.sort_by(f64::total_cmp);
    s.chunks_exact(2).map(|c| (c[0], c[1])).collect()
}

/// Stretches (s0, s1, material length) of the line to clear from `mine`: every gap of `theirs`
/// holding material of `mine`, except where `mine` overhangs one of `theirs`' intervals by less
/// than `tol` and the snapping will merge the two ends (the arrangement pairs the crossings of
/// the two sections closest first, one to one, within the snap tolerance: [`snap_partners`] pairs
/// the intervals' ends alike). An overhang whose end the snapping pairs with another crossing was
/// left as it was, and the solid met the other plane along it where that section has no material
/// (a singular edge on the line: 24 of 46 unclean generated odd inputs). A gap without end is
/// closed `tol` past `mine`'s material.
fn stretches_to_clear(
    mine: &[(f64, f64)],
    theirs: &[(f64, f64)],
    breaks: &[f64],
    tol: f64,
) -> Vec<(f64, f64, f64)> {
    let Some((first, last)) = mine.first().zip(mine.last()) else {
        return Vec::new();
    };
    let pad = 0.01 * (last.1 - first.0) + tol;
    let mut gaps = Vec::with_capacity(theirs.len() + 1);
    let mut start = f64::NEG_INFINITY;
    for &(a, b) in theirs {
        gaps.push((start, a));
        start = b;
    }
    gaps.push((start, f64::INFINITY));
    let partner = snap_partners(mine, theirs, breaks, tol);
    let snapped_to = |x: f64, y: f64| partner.get(&x.to_bits()) == Some(&y.to_bits());
    let mut out = Vec::new();
    for (g0, g1) in gaps {
        let mut material = 0.0;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(a, b) in mine {
            let (p0, p1) = (a.max(g0), b.min(g1));
            if p1 <= p0 {
                continue;
            }
            // mine ends inside the gap (at b) or starts inside it (at a), one end snapped
            let continues = p1 - p0 <= tol
                && ((p0 == g0 && p1 < g1 && snapped_to(b, g0))
                    || (p1 == g1 && p0 > g0 && snapped_to(a, g1)));
            if !continues {
                material += p1 - p0;
                lo = lo.min(p0);
                hi = hi.max(p1);
            }
        }
        if material > 0.0 {
            let s0 = if g0.is_finite() { g0 } else { lo - pad };
            let s1 = if g1.is_finite() { g1 } else { hi + pad };
            out.push((s0, s1, material));
        }
    }
    out
}

/// The crossings of the line (intervals' ends, as bits) of `mine` that the snapping merges with
/// one of `theirs`, with that one: pairs within `tol`, closest first, one to one (the snapping's
/// order, [`crate::geom::close_pairs`]; the intervals are sorted, so are their ends).
fn snap_partners(
    mine: &[(f64, f64)],
    theirs: &[(f64, f64)],
    breaks: &[f64],
    tol: f64,
) -> HashMap<u64, u64> {
    let ends = |x: &[(f64, f64)]| -> Vec<f64> { x.iter().flat_map(|&(a, b)| [a, b]).collect() };
    let (a, b) = (ends(mine), ends(theirs));
    let pairs = crate::geom::close_pairs(&a, &b, tol, breaks);
    let (mut used_a, mut used_b) = (vec![false; a.len()], vec![false; b.len()]);
    let mut out = HashMap::new();
    for (_, i, j) in pairs {
        if !used_a[i] && !used_b[j] {
            used_a[i] = true;
            used_b[j] = true;
            out.insert(a[i].to_bits(), b[j].to_bits());
        }
    }
    out
}

/// The rectangle of plane `p`'s (u,v) coordinates along its line with `other` from s0 to s1 (arc
/// length `dir · x`, `dir` the line's unit direction), `half_width` to either side (either
/// orientation: `trim_section` orients it).
fn strip_rectangle(
    p: &Plane,
    other: &Plane,
    dir: [f64; 3],
    s0: f64,
    s1: f64,
    half_width: f64,
) -> Vec<[f64; 2]> {
    // The other plane's signed distance restricted to p: a s + b t + c.
    let (a, b) = (dot(other.normal, p.u), dot(other.normal, p.v));
    let c = dot(other.normal, p.origin) + other.offset;
    let g = (a * a + b * b).sqrt();
    let normal = [a / g, b / g];
    // `dir` in (u,v): the caller's orientation of the line, which depends on the order of the
    // two planes, not on which of them owns the section being trimmed.
    let along = [dot(dir, p.u), dot(dir, p.v)];
    let foot = [-c * normal[0] / g, -c * normal[1] / g];
    let s_foot = dot(dir, p.to_3d(foot));
    let at = |s: f64, side: f64| {
        [
            foot[0] + (s - s_foot) * along[0] + side * half_width * normal[0],
            foot[1] + (s - s_foot) * along[1] + side * half_width * normal[1],
        ]
    };
    vec![at(s0, 1.0), at(s1, 1.0), at(s1, -1.0), at(s0, -1.0)]
}

/// Subtract the rectangles from every region of `sec`; pieces with less area than a square of
/// the strip's half-width are dropped (slivers a rectangle cut off).
fn trim_section(sec: &mut Section, rects: &[Vec<[f64; 2]>], strip: f64, nudge: f64) {
    let mut clip: Vec<Vec<[f64; 2]>> = rects.to_vec();
    for r in &mut clip {
        if polygon_signed_area(r) < 0.0 {
            r.reverse();
        }
    }
    // every region's pieces first: a row on a strip's edge may take vertices from several
    // regions (two contours cut by one strip), and all of them are collinear
    let mut labels = Vec::new();
    let mut pieces = Vec::new();
    for region in &sec.regions {
        let mut subject = Vec::new();
        material_of(region, &mut subject);
        let shapes = subject.overlay_as::<i64>(&clip, OverlayRule::Difference, FillRule::NonZero);
        for piece in pieces_of(shapes, nudge).unwrap_or_default() {
            labels.push(region.label);
            pieces.push(piece);
        }
    }
    break_rows(&mut pieces, rects, strip);
    sec.regions = labels
        .into_iter()
        .zip(pieces)
        .map(|(label, piece)| region_of_piece(label, &sec.plane, piece))
        .filter(|r| r.area() >= strip * strip)
        .collect();
}

/// How far `break_rows` moves a vertex off a strip's edge, relative to the strip's half-width
/// (times 1 to 2, per vertex).
const ROW_BREAK: f64 = 1e-5;

/// Where a wiggly contour crosses a strip's long edge, the boolean leaves a row of section vertices
/// on one straight line, collinear in the ideal but not exactly after its rounding. The engine's
/// tag rules decide collinear plane points combinatorially only when they are exactly collinear
/// (or on a line of two planes); a row that is collinear up to rounding is decided by the float
/// predicates in 3D and in uv differently, and the cell's Delaunay insertion meets a cavity that is
/// not star-shaped (odd040: every cell beside a trimmed row went untagged). So a row of three or
/// more vertices on the line of one edge is moved off it, away from the strip, by 1–2 ×
/// `ROW_BREAK` × the half-width (a different amount per vertex, deterministic): in general position
/// at the scale the predicates resolve, and still outside the strip. A row is taken along the whole
/// line, over every region of the section: two stretches of one common line (two rectangles) or
/// two contours cut by one strip leave two vertices each on the same line, as collinear as one
/// row of four.
fn break_rows(pieces: &mut [Vec<Vec<[f64; 2]>>], rects: &[Vec<[f64; 2]>], strip: f64) {
    let on_edge = strip * 1e-6;
    for r in rects {
        // the two long edges (corners 0→1 and 2→3, `strip_rectangle`), each with the unit normal
        // pointing away from the strip
        for (p, q, opposite) in [(r[0], r[1], r[3]), (r[2], r[3], r[0])] {
            let d = [q[0] - p[0], q[1] - p[1]];
            let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
            if len == 0.0 {
                continue;
            }
            let mut normal = [-d[1] / len, d[0] / len];
            if (opposite[0] - p[0]) * normal[0] + (opposite[1] - p[1]) * normal[1] > 0.0 {
                normal = [-normal[0], -normal[1]];
            }
            let mut row: Vec<(usize, usize, usize)> = Vec::new();
            for (a, piece) in pieces.iter().enumerate() {
                for (b, c) in piece.iter().enumerate() {
                    for (k, x) in c.iter().enumerate() {
                        let rel = [x[0] - p[0], x[1] - p[1]];
                        let h = rel[0] * normal[0] + rel[1] * normal[1];
                        if h.abs() <= on_edge {
                            row.push((a, b, k));
                        }
                    }
                }
            }
            if row.len() < 3 {
                continue;
            }
            for (m, &(a, b, k)) in row.iter().enumerate() {
                // a pseudo-random amount in [1, 2) (a hash of the index, not a linear sequence,
                // whose values at equally spaced points are themselves on one line)
                let amount = strip * ROW_BREAK * (1.0 + unit_hash(m as u64));
                let x = &mut pieces[a][b][k];
                x[0] += amount * normal[0];
                x[1] += amount * normal[1];
            }
        }
    }
}

/// A number in [0, 1) from `x` (splitmix64's finaliser): deterministic, without structure.
fn unit_hash(x: u64) -> f64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gap_of_the_other_section_is_cleared() {
        // Theirs covers [0,1] and [3,4]; mine [0.5, 3.5]: clear the gap (1, 3).
        let s = stretches_to_clear(&[(0.5, 3.5)], &[(0.0, 1.0), (3.0, 4.0)], &[], 1e-3);
        assert_eq!(s.len(), 1);
        assert_eq!((s[0].0, s[0].1), (1.0, 3.0));
        assert!((s[0].2 - 2.0).abs() < 1e-15);
    }

    #[test]
    fn a_short_overhang_is_left_to_snapping_but_an_island_is_not() {
        // Mine continues theirs by 1e-4 past 1.0: snapping's case.
        assert!(stretches_to_clear(&[(0.0, 1.0001)], &[(0.0, 1.0)], &[], 1e-3).is_empty());
        // A tiny island of mine inside their gap is cleared, however short.
        let s = stretches_to_clear(&[(0.0, 1.0), (2.0, 2.00001)], &[(0.0, 1.0)], &[], 1e-3);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].0, 1.0);
        assert!(s[0].1 > 2.00001);
    }

    #[test]
    fn an_overhang_whose_end_the_snapping_pairs_elsewhere_is_cleared() {
        // mine ends at 1.0004 past theirs' end at 1, but mine's crossing at 0.9999 is closer to
        // it: the snapping pairs those two, and the overhang would stay (g036 of the generated odd
        // inputs: a singular edge on the line)
        let s = stretches_to_clear(&[(0.0, 0.9998), (0.9999, 1.0004)], &[(0.0, 1.0)], &[], 1e-3);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].0, 1.0);
        assert!(s[0].1 > 1.0004);
        assert!((s[0].2 - 4e-4).abs() < 1e-12);
        // without the closer crossing the same overhang is the snapping's
        assert!(stretches_to_clear(&[(0.0, 1.0004)], &[(0.0, 1.0)], &[], 1e-3).is_empty());
        // mine across a short gap of theirs: no crossing of mine to snap, cleared
        let s = stretches_to_clear(&[(0.0, 2.0)], &[(0.0, 1.0), (1.0002, 2.0)], &[], 1e-3);
        assert_eq!(s.len(), 1);
        assert_eq!((s[0].0, s[0].1), (1.0, 1.0002));
    }

    #[test]
    fn an_overhang_across_another_planes_crossing_is_cleared() {
        // mine overhangs theirs' end at 1 by 4e-4, within the snap tolerance, but a third plane
        // crosses the line at 1.0002, between the two crossings: the arrangement snaps only on
        // one of its edges, the overhang would stay (generated odd input 117: a singular edge on
        // the line of planes 6 and 7, plane 0 crossing between their ends)
        let s = stretches_to_clear(&[(0.0, 1.0004)], &[(0.0, 1.0)], &[1.0002], 1e-3);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].0, 1.0);
        assert!((s[0].2 - 4e-4).abs() < 1e-12);
        // a crossing beyond both ends changes nothing
        assert!(stretches_to_clear(&[(0.0, 1.0004)], &[(0.0, 1.0)], &[0.5, 1.5], 1e-3).is_empty());
    }

    #[test]
    fn the_breaks_of_a_line_are_the_other_planes_crossings() {
        let sec = |n: [f64; 3], o: f64| crate::sections::Section {
            plane: Plane::from_equation(n, o).unwrap(),
            regions: Vec::new(),
            source_index: 0,
            max_off_plane: 0.0,
        };
        // z = 0 and y = 0 meet on the x axis; x = 0.25 and x = -2 cross it, z = 1 is parallel
        let sections = Sections {
            sections: vec![
                sec([0.0, 0.0, 1.0], 0.0),
                sec([0.0, 1.0, 0.0], 0.0),
                sec([1.0, 0.0, 0.0], -0.25),
                sec([0.0, 0.0, 1.0], -1.0),
                sec([2.0, 0.0, 0.0], 4.0),
            ],
            ..Default::default()
        };
        let b = line_breaks(&sections, 0, 1, [1.0, 0.0, 0.0]);
        assert_eq!(b.len(), 2);
        assert!((b[0] + 2.0).abs() < 1e-15 && (b[1] - 0.25).abs() < 1e-15);
    }

    #[test]
    fn nothing_on_their_side_clears_all_of_mine() {
        let s = stretches_to_clear(&[(0.0, 1.0), (2.0, 3.0)], &[], &[], 1e-3);
        assert_eq!(s.len(), 1);
        assert!(s[0].0 < 0.0 && s[0].1 > 3.0);
        assert!((s[0].2 - 2.0).abs() < 1e-15);
    }

    #[test]
    fn a_row_of_crossings_on_a_strip_edge_is_broken() {
        // a comb of five teeth crossing the line x = 0 of plane z = 0 (the other plane x = 0):
        // the strip's two long edges cut it in rows of ten vertices each
        let p = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let q = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let mut comb: Vec<[f64; 3]> = vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        for k in 0..5 {
            let y = 1.0 + 2.0 * (4 - k) as f64 * 0.1;
            comb.extend([
                [1.0, y + 0.1, 0.0],
                [-1.0, y + 0.1, 0.0],
                [-1.0, y, 0.0],
                [1.0, y, 0.0],
            ]);
        }
        comb.truncate(comb.len() - 2);
        comb.push([-1.0, 1.0, 0.0]);
        let points2: Vec<[f64; 2]> = comb.iter().map(|&x| p.to_2d(x)).collect();
        let mut sec = Section {
            plane: p,
            regions: vec![crate::sections::Region {
                label: 1,
                outer: crate::sections::Contour::from_2d(&p, points2),
                holes: Vec::new(),
            }],
            source_index: 0,
            max_off_plane: 0.0,
        };
        let d = cross(p.normal, q.normal);
        let dir = d.map(|x| x / dot(d, d).sqrt());
        let w = 0.01;
        let rect = strip_rectangle(&p, &q, dir, -10.0, 10.0, w);
        trim_section(&mut sec, &[rect], w, 1e-9);
        let n = assert_rows_broken(&sec, &q, w);
        assert!(n >= 2 * 10, "{n}");
    }

    /// The vertices of `sec` within 1e-6 of the long edges of strips of half-width `w` along
    /// the plane `q`, after `trim_section`: asserted to be off the edges by the row break and
    /// no three of them collinear by a margin far above rounding; their number.
    fn assert_rows_broken(sec: &Section, q: &Plane, w: f64) -> usize {
        let p = sec.plane;
        let near: Vec<[f64; 2]> = sec
            .regions
            .iter()
            .flat_map(|r| {
                r.outer
                    .points2
                    .iter()
                    .chain(r.holes.iter().flat_map(|h| &h.points2))
            })
            .copied()
            .filter(|&x| (q.signed_distance(p.to_3d(x)).abs() - w).abs() < 1e-6)
            .collect();
        for x in &near {
            let h = q.signed_distance(p.to_3d(*x)).abs();
            assert!(h >= w * (1.0 + 0.5 * ROW_BREAK) && h < w * (1.0 + 2.0 * ROW_BREAK));
        }
        for a in 0..near.len() {
            for b in a + 1..near.len() {
                for c in b + 1..near.len() {
                    let o = crate::geom::predicates::orient2d(near[a], near[b], near[c]);
                    assert!(o.abs() > 1e-12, "{:?}", (near[a], near[b], near[c]));
                }
            }
        }
        near.len()
    }

    /// A section of plane z = 0 with one region per polygon (given in 3D).
    fn section_of(p: Plane, polygons: &[&[[f64; 3]]]) -> Section {
        Section {
            plane: p,
            regions: polygons
                .iter()
                .map(|poly| crate::sections::Region {
                    label: 1,
                    outer: crate::sections::Contour::from_2d(
                        &p,
                        poly.iter().map(|&x| p.to_2d(x)).collect(),
                    ),
                    holes: Vec::new(),
                })
                .collect(),
            source_index: 0,
            max_off_plane: 0.0,
        }
    }

    #[test]
    fn a_row_across_two_regions_is_one_row() {
        // two squares crossing the line x = 0 (of the plane x = 0): each leaves two vertices on
        // each long edge of the strip, four on one line in all (g041 of a generator of odd files:
        // a cell beside such a row went untagged)
        let p = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let q = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let square = |y: f64| {
            [
                [-1.0, y, 0.0],
                [1.0, y, 0.0],
                [1.0, y + 1.0, 0.0],
                [-1.0, y + 1.0, 0.0],
            ]
        };
        let mut sec = section_of(p, &[&square(0.0), &square(2.0)]);
        let d = cross(p.normal, q.normal);
        let dir = d.map(|x| x / dot(d, d).sqrt());
        let w = 0.01;
        let rect = strip_rectangle(&p, &q, dir, -10.0, 10.0, w);
        trim_section(&mut sec, &[rect], w, 1e-9);
        assert_eq!(sec.regions.len(), 4);
        assert_eq!(assert_rows_broken(&sec, &q, w), 8);
    }

    #[test]
    fn a_row_across_two_stretches_of_one_line_is_one_row() {
        // one region, two stretches of the line cleared inside it (two rectangles, two holes):
        // two corners of each on each long edge's line, four on one line in all
        let p = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let q = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
        let mut sec = section_of(
            p,
            &[&[
                [-1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 3.0, 0.0],
                [-1.0, 3.0, 0.0],
            ]],
        );
        let d = cross(p.normal, q.normal);
        let dir = d.map(|x| x / dot(d, d).sqrt());
        let w = 0.01;
        let rects: Vec<_> = [(0.5, 1.0), (2.0, 2.5)]
            .iter()
            .map(|&(s0, s1)| strip_rectangle(&p, &q, dir, s0, s1, w))
            .collect();
        trim_section(&mut sec, &rects, w, 1e-9);
        assert_eq!(sec.regions.len(), 1);
        assert_eq!(assert_rows_broken(&sec, &q, w), 8);
    }

    #[test]
    fn the_strip_rectangle_lies_along_the_line() {
        let p = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
        let q = Plane::from_equation([1.0, 0.0, 1.0], -0.5).unwrap();
        let d = cross(p.normal, q.normal);
        let dir = d.map(|x| x / dot(d, d).sqrt());
        // the same stretch of the line on either plane (the second owner was the bug of odd026:
        // its rectangle lay at -s)
        for (a, b) in [(&p, &q), (&q, &p)] {
            let r = strip_rectangle(a, b, dir, -1.0, 2.0, 0.01);
            let mid =
                |x: [f64; 2], y: [f64; 2]| a.to_3d([(x[0] + y[0]) / 2.0, (x[1] + y[1]) / 2.0]);
            for (x, s) in [(mid(r[0], r[3]), -1.0), (mid(r[1], r[2]), 2.0)] {
                assert!(a.signed_distance(x).abs() < 1e-12);
                assert!(b.signed_distance(x).abs() < 1e-12);
                assert!((dot(dir, x) - s).abs() < 1e-12);
            }
            assert!((polygon_signed_area(&r).abs() - 3.0 * 0.02).abs() < 1e-12);
        }
    }
}
