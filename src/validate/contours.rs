//! Exact checks of one plane's contours: no contour crosses or touches itself or another
//! (`check_intersections`), and holes, outer contours and regions nest as a section's must
//! (`check_nesting`).
use super::{winding_number, ContourId, Locator, Role};
use crate::error::{Error, Result};
use crate::geom::predicates::orient2d;
use crate::sections::Contour;

/// One contour edge, for the intersection search.
#[derive(Clone, Copy)]
struct Edge {
    contour: u32,
    index: u32,
    a: [f64; 2],
    b: [f64; 2],
}

/// The contours (outer, then holes) of regions `regions` of section `s`, with their ids.
pub(super) fn section_contours(
    s: usize,
    sec: &crate::sections::Section,
    regions: impl IntoIterator<Item = usize>,
) -> Vec<(ContourId, &Contour)> {
    regions
        .into_iter()
        .flat_map(|r| {
            let region = &sec.regions[r];
            std::iter::once((Role::Outer, &region.outer))
                .chain(
                    region
                        .holes
                        .iter()
                        .enumerate()
                        .map(|(h, c)| (Role::Hole(h), c)),
                )
                .map(move |(role, c)| {
                    (
                        ContourId {
                            section: s,
                            region: r,
                            role,
                        },
                        c,
                    )
                })
        })
        .collect()
}

/// No contour of one plane may touch itself (except consecutive edges at their shared vertex) or
/// another contour. Edges are bucketed in a uniform grid over the plane's bounding box; each pair
/// sharing cells is tested once, in the lowest cell both cover, with exact predicates.
pub(super) fn check_intersections(
    contours: &[(ContourId, &Contour)],
    loc: &dyn Locator,
) -> Result<()> {
    let mut edges = Vec::new();
    let mut lens = Vec::new();
    for (ci, (_, c)) in contours.iter().enumerate() {
        let n = c.points2.len();
        lens.push(n as u32);
        for i in 0..n {
            edges.push(Edge {
                contour: ci as u32,
                index: i as u32,
                a: c.points2[i],
                b: c.points2[(i + 1) % n],
            });
        }
    }
    if edges.len() < 2 {
        return Ok(());
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for e in &edges {
        for k in 0..2 {
            lo[k] = lo[k].min(e.a[k]);
            hi[k] = hi[k].max(e.a[k]);
        }
    }
    let g = ((edges.len() as f64).sqrt().ceil() as usize).clamp(1, 1024);
    // Monotone in x, so intersecting edges (overlapping boxes) get overlapping cell ranges.
    let cell = |x: f64, k: usize| -> usize {
        let w = hi[k] - lo[k];
        if w > 0.0 {
            (((x - lo[k]) / w * g as f64) as usize).min(g - 1)
        } else {
            0
        }
    };
    let ranges: Vec<[usize; 4]> = edges
        .iter()
        .map(|e| {
            [
                cell(e.a[0].min(e.b[0]), 0),
                cell(e.a[0].max(e.b[0]), 0),
                cell(e.a[1].min(e.b[1]), 1),
                cell(e.a[1].max(e.b[1]), 1),
            ]
        })
        .collect();
    // Compressed buckets: count, prefix sums, fill.
    let mut start = vec![0usize; g * g + 1];
    for r in &ranges {
        for y in r[2]..=r[3] {
            for x in r[0]..=r[1] {
                start[y * g + x + 1] += 1;
            }
        }
    }
    for i in 0..g * g {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut bucket = vec![0u32; start[g * g]];
    for (ei, r) in ranges.iter().enumerate() {
        for y in r[2]..=r[3] {
            for x in r[0]..=r[1] {
                bucket[fill[y * g + x]] = ei as u32;
                fill[y * g + x] += 1;
            }
        }
    }
    for y in 0..g {
        for x in 0..g {
            let items = &bucket[start[y * g + x]..start[y * g + x + 1]];
            for (k, &i) in items.iter().enumerate() {
                for &j in &items[k + 1..] {
                    let (ri, rj) = (&ranges[i as usize], &ranges[j as usize]);
                    if ri[0].max(rj[0]) != x || ri[2].max(rj[2]) != y {
                        continue; // tested in a lower cell
                    }
                    let (e, f) = (&edges[i as usize], &edges[j as usize]);
                    if let Some(reason) = edge_conflict(e, f, &lens) {
                        let (ce, cf) = (
                            contours[e.contour as usize].0,
                            contours[f.contour as usize].0,
                        );
                        let at = e.a;
                        return Err(if e.contour == f.contour {
                            Error::input(
                                loc.contour(ce),
                                format!(
                                    "self-intersecting contour: edges {} and {} {reason} (near {:?})",
                                    e.index.min(f.index),
                                    e.index.max(f.index),
                                    at
                                ),
                            )
                        } else {
                            Error::input(
                                loc.contour(ce),
                                format!(
                                    "contours of one plane cross: edge {} {reason} edge {} of {}",
                                    e.index,
                                    f.index,
                                    loc.contour(cf)
                                ),
                            )
                        });
                    }
                }
            }
        }
    }
    Ok(())
}

/// Why two edges conflict (`None` if they don't): they cross or touch, except two consecutive edges
/// of one contour, which may share their common vertex but must not overlap.
fn edge_conflict(e: &Edge, f: &Edge, lens: &[u32]) -> Option<&'static str> {
    if e.contour == f.contour {
        let n = lens[e.contour as usize];
        let (i, j) = (e.index, f.index);
        let consecutive_ef = (i + 1) % n == j; // e.b == f.a
        let consecutive_fe = (j + 1) % n == i; // f.b == e.a
        if consecutive_ef || consecutive_fe {
            if n == 3 {
                // Every pair of a triangle is consecutive; it only fails when degenerate.
                return (orient2d(e.a, e.b, if consecutive_ef { f.b } else { f.a }) == 0.0)
                    .then_some("overlap (degenerate triangle)");
            }
            let (a, shared, c) = if consecutive_ef {
                (e.a, e.b, f.b)
            } else {
                (f.a, f.b, e.b)
            };
            return (orient2d(a, shared, c) == 0.0 && same_direction(shared, a, c))
                .then_some("overlap (the contour turns back on itself)");
        }
    }
    segments_intersect(e.a, e.b, f.a, f.b).then_some("cross or touch")
}

/// For collinear a, b, c distinct from o: do a and c lie on the same side of o? Exact (comparisons).
fn same_direction(o: [f64; 2], a: [f64; 2], c: [f64; 2]) -> bool {
    let k = if a[0] != o[0] { 0 } else { 1 };
    (a[k] > o[k]) == (c[k] > o[k])
}

/// Closed segments pq and rs share a point. Exact.
pub fn segments_intersect(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let sign = |x: f64| (x > 0.0) as i8 - (x < 0.0) as i8;
    let d1 = sign(orient2d(r, s, p));
    let d2 = sign(orient2d(r, s, q));
    let d3 = sign(orient2d(p, q, r));
    let d4 = sign(orient2d(p, q, s));
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    (d1 == 0 && in_box(r, s, p))
        || (d2 == 0 && in_box(r, s, q))
        || (d3 == 0 && in_box(p, q, r))
        || (d4 == 0 && in_box(p, q, s))
}

/// For x collinear with ab: x lies on the closed segment ab.
fn in_box(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    (0..2).all(|k| a[k].min(b[k]) <= x[k] && x[k] <= a[k].max(b[k]))
}

/// Nesting (the contours are disjoint by now, so containment is a tree): a hole's innermost
/// container must be its own outer contour; an outer contour lies outside every contour or
/// directly inside a hole.
pub(super) fn check_nesting(contours: &[(ContourId, &Contour)], loc: &dyn Locator) -> Result<()> {
    let n = contours.len();
    if n < 2 {
        return Ok(());
    }
    let boxes: Vec<([f64; 2], [f64; 2])> = contours
        .iter()
        .map(|(_, c)| {
            let mut lo = c.points2[0];
            let mut hi = lo;
            for q in &c.points2 {
                for k in 0..2 {
                    lo[k] = lo[k].min(q[k]);
                    hi[k] = hi[k].max(q[k]);
                }
            }
            (lo, hi)
        })
        .collect();
    let containers: Vec<Vec<usize>> = (0..n)
        .map(|x| {
            let q = contours[x].1.points2[0];
            (0..n)
                .filter(|&y| {
                    let (lo, hi) = boxes[y];
                    y != x
                        && (0..2).all(|k| lo[k] <= q[k] && q[k] <= hi[k])
                        && winding_number(q, &contours[y].1.points2) != 0
                })
                .collect()
        })
        .collect();
    let parent = |x: usize| -> Option<usize> {
        let depth = containers[x].len();
        containers[x]
            .iter()
            .copied()
            .find(|&y| containers[y].len() + 1 == depth)
    };
    for x in 0..n {
        let (id, _) = contours[x];
        match id.role {
            Role::Hole(_) => {
                let own_outer = (0..n)
                    .find(|&y| {
                        contours[y].0.region == id.region && contours[y].0.role == Role::Outer
                    })
                    .expect("every region has an outer contour");
                if !containers[x].contains(&own_outer) {
                    return Err(Error::input(
                        loc.contour(id),
                        format!(
                            "hole is not inside its parent {}",
                            loc.contour(contours[own_outer].0)
                        ),
                    ));
                }
                if let Some(p) = parent(x) {
                    if p != own_outer {
                        return Err(Error::input(
                            loc.contour(id),
                            format!(
                                "hole lies inside {}, which is itself inside the hole's parent",
                                loc.contour(contours[p].0)
                            ),
                        ));
                    }
                }
            }
            Role::Outer => {
                if let Some(p) = parent(x) {
                    if contours[p].0.role == Role::Outer {
                        return Err(Error::input(
                            loc.contour(id),
                            format!(
                                "region lies inside the material of {} (regions overlap; a contour inside another must be inside one of its holes)",
                                loc.contour(contours[p].0)
                            ),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::segments_intersect;

    #[test]
    fn segment_predicate_cases() {
        assert!(segments_intersect(
            [0.0, 0.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [2.0, 0.0]
        ));
        assert!(segments_intersect(
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 0.0],
            [1.0, 5.0]
        )); // T touch
        assert!(!segments_intersect(
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0]
        )); // collinear apart
        assert!(segments_intersect(
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 0.0],
            [3.0, 0.0]
        )); // overlap
        assert!(!segments_intersect(
            [0.0, 0.0],
            [1.0, 1.0],
            [1.0, 0.0],
            [2.0, 0.5]
        ));
    }
}
