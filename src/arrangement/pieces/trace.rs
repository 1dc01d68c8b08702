//! Inside one face: the section's pieces traced from the contour runs and the face boundary, then
//! grouped into outer loops and the holes they contain.
use super::super::{polygon_area, SectionPiece, VertexId};
use super::{Ctx, FaceWork};
use crate::fxhash::FxHashMap as HashMap;
use crate::geom::segment_distance_2d;
use crate::sections::Region;

/// Even-odd point-in-region test in the plane's (u,v) frame.
fn inside_region(region: &Region, p: [f64; 2]) -> bool {
    // crossing parity over all loops: the parities of the single loops combined
    std::iter::once(&region.outer)
        .chain(region.holes.iter())
        .fold(false, |inside, c| inside != point_in_loop(p, &c.points2))
}

pub(super) fn trace_face(
    ctx: &mut Ctx,
    i: u32,
    f: u32,
    w: &FaceWork,
    region: &Region,
) -> Vec<Vec<VertexId>> {
    let poly = ctx.arr.faces[f as usize].polygon.clone();
    let mut loops: Vec<Vec<VertexId>> = w.closed.clone();
    if w.runs.is_empty() && w.closed.is_empty() && w.bpoints.is_empty() {
        if background_inside(ctx, i, &poly, w, region) {
            loops.push(poly);
        }
        return loops;
    }
    let ring = boundary_ring(ctx, i, f, &poly, w);
    if w.runs.is_empty() {
        // No contour crosses the boundary: the boundary is wholly inside or outside the region.
        if background_inside(ctx, i, &poly, w, region) {
            loops.push(ring);
        }
        return loops;
    }
    join_runs_along_ring(ctx, i, f, &ring, w, &mut loops);
    loops
}

/// Whether the face's boundary lies in the region when no contour crosses it: test the face's
/// centroid (strictly inside the face, so on no contour that stays out of the face) and discount
/// the contours wholly inside the face that surround it.
fn background_inside(ctx: &Ctx, i: u32, poly: &[VertexId], w: &FaceWork, region: &Region) -> bool {
    let c: Vec<[f64; 2]> = poly.iter().map(|&v| ctx.uv(v, i)).collect();
    let n = c.len() as f64;
    let g = [
        c.iter().map(|p| p[0]).sum::<f64>() / n,
        c.iter().map(|p| p[1]).sum::<f64>() / n,
    ];
    let mut inside = inside_region(region, g);
    for l in &w.closed {
        let q: Vec<[f64; 2]> = l.iter().map(|&v| ctx.uv(v, i)).collect();
        if point_in_loop(g, &q) {
            inside = !inside;
        }
    }
    inside
}

/// Boundary list of face `f` (polygon `poly`): corners and every section point on the boundary,
/// counter-clockwise.
fn boundary_ring(ctx: &mut Ctx, i: u32, f: u32, poly: &[VertexId], w: &FaceWork) -> Vec<VertexId> {
    let nc = poly.len();
    let cuv: Vec<[f64; 2]> = poly.iter().map(|&v| ctx.uv(v, i)).collect();
    let mut entries: Vec<(usize, u8, f64, VertexId)> = Vec::new();
    for (e, &c) in poly.iter().enumerate() {
        entries.push((e, 0, 0.0, c));
    }
    let mut bp = w.bpoints.clone();
    bp.sort_unstable();
    bp.dedup();
    for &x in &bp {
        if poly.contains(&x) {
            continue;
        }
        let xuv = ctx.uv(x, i);
        let e = boundary_edge_of(ctx, i, f, poly, &cuv, x);
        let (a, b) = (cuv[e], cuv[(e + 1) % nc]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (((xuv[0] - a[0]) * d[0] + (xuv[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        entries.push((e, 1, t, x));
    }
    entries.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.total_cmp(&y.2)));
    entries.iter().map(|e| e.3).collect()
}

/// The edge of the face polygon that section point `x` lies on: the first whose two ends share a
/// plane with it, else (with a warning) the nearest.
fn boundary_edge_of(
    ctx: &mut Ctx,
    i: u32,
    f: u32,
    poly: &[VertexId],
    cuv: &[[f64; 2]],
    x: VertexId,
) -> usize {
    let nc = poly.len();
    let tags = ctx.arr.pool.tags[x as usize].clone();
    let xuv = ctx.uv(x, i);
    for e in 0..nc {
        let (a, b) = (poly[e], poly[(e + 1) % nc]);
        let ta = &ctx.arr.pool.tags[a as usize];
        let tb = &ctx.arr.pool.tags[b as usize];
        if tags
            .iter()
            .any(|&t| t != i && ta.contains(&t) && tb.contains(&t))
        {
            return e;
        }
    }
    ctx.warnings.push(format!(
        "plane {i}: section point {x} on the boundary of face {f} matches no edge; placed on the nearest"
    ));
    (0..nc)
        .min_by(|&a, &b| {
            segment_distance_2d(xuv, cuv[a], cuv[(a + 1) % nc]).total_cmp(&segment_distance_2d(
                xuv,
                cuv[b],
                cuv[(b + 1) % nc],
            ))
        })
        .unwrap_or(0)
}

/// Close the contour runs into loops: from where a run leaves the face, follow the boundary `ring`
/// to where the next run enters.
fn join_runs_along_ring(
    ctx: &mut Ctx,
    i: u32,
    f: u32,
    ring: &[VertexId],
    w: &FaceWork,
    loops: &mut Vec<Vec<VertexId>>,
) {
    let pos: HashMap<VertexId, usize> = ring.iter().enumerate().map(|(k, &v)| (v, k)).collect();
    let enter: HashMap<VertexId, usize> = w
        .runs
        .iter()
        .enumerate()
        .map(|(r, run)| (run[0], r))
        .collect();
    let nr = w.runs.len();
    let mut next = vec![usize::MAX; nr];
    let mut chain: Vec<Vec<VertexId>> = vec![Vec::new(); nr];
    for (r, run) in w.runs.iter().enumerate() {
        let leave = *run.last().unwrap();
        let Some(&p0) = pos.get(&leave) else {
            ctx.warnings.push(format!(
                "plane {i}: face {f}: a contour leaves the face at a point not on its boundary"
            ));
            continue;
        };
        let mut k = (p0 + 1) % ring.len();
        let mut steps = 0;
        while steps < ring.len() {
            let v = ring[k];
            if let Some(&r2) = enter.get(&v) {
                next[r] = r2;
                break;
            }
            chain[r].push(v);
            k = (k + 1) % ring.len();
            steps += 1;
        }
    }
    let mut used = vec![false; nr];
    for r0 in 0..nr {
        if used[r0] {
            continue;
        }
        let mut lp = Vec::new();
        let mut r = r0;
        let mut ok = true;
        while !used[r] {
            used[r] = true;
            let run = &w.runs[r];
            lp.extend_from_slice(&run[..run.len() - 1]);
            lp.push(*run.last().unwrap());
            lp.extend_from_slice(&chain[r]);
            if next[r] == usize::MAX {
                ok = false;
                break;
            }
            r = next[r];
        }
        if !ok || r != r0 {
            ctx.warnings.push(format!(
                "plane {i}: face {f}: inconsistent section boundary (contours touching or crossing); a loop was dropped"
            ));
            continue;
        }
        loops.push(lp);
    }
}

fn point_in_loop(p: [f64; 2], q: &[[f64; 2]]) -> bool {
    let mut inside = false;
    let n = q.len();
    for k in 0..n {
        let (a, b) = (q[k], q[(k + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Outer loops (positive area) with the holes (negative area) they contain.
pub(super) fn assemble(
    ctx: &mut Ctx,
    i: u32,
    loops: Vec<Vec<VertexId>>,
    label: i32,
) -> Vec<SectionPiece> {
    let mut outers: Vec<(Vec<VertexId>, Vec<[f64; 2]>, f64)> = Vec::new();
    let mut holes: Vec<(Vec<VertexId>, Vec<[f64; 2]>)> = Vec::new();
    for lp in loops {
        // Drop immediate repeats (a point that is both a run end and a chain start).
        let mut l: Vec<VertexId> = Vec::with_capacity(lp.len());
        for v in lp {
            if l.last() != Some(&v) {
                l.push(v);
            }
        }
        while l.len() > 1 && l.first() == l.last() {
            l.pop();
        }
        if l.len() < 3 {
            continue;
        }
        let uv: Vec<[f64; 2]> = l.iter().map(|&v| ctx.uv(v, i)).collect();
        let a = polygon_area(&uv);
        if a > 0.0 {
            outers.push((l, uv, a));
        } else if a < 0.0 {
            holes.push((l, uv));
        }
    }
    let mut pieces: Vec<SectionPiece> = outers
        .iter()
        .map(|(l, _, _)| SectionPiece {
            label,
            outer: l.clone(),
            holes: Vec::new(),
        })
        .collect();
    for (h, huv) in holes {
        let owner = if outers.len() == 1 {
            Some(0)
        } else {
            // Smallest outer containing a vertex of the hole that is not one of its own vertices.
            let mut best: Option<(usize, f64)> = None;
            for (k, (ol, ouv, a)) in outers.iter().enumerate() {
                let probe = h
                    .iter()
                    .zip(&huv)
                    .find(|(v, _)| !ol.contains(v))
                    .map(|(_, p)| *p);
                let Some(p) = probe else { continue };
                if point_in_loop(p, ouv) && best.is_none_or(|(_, ba)| *a < ba) {
                    best = Some((k, *a));
                }
            }
            best.map(|b| b.0)
        };
        match owner {
            Some(k) => pieces[k].holes.push(h),
            None => ctx.warnings.push(format!(
                "plane {i}: a hole of a section piece lies in no outer loop; dropped"
            )),
        }
    }
    pieces
}
