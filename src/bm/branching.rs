//! Samples of the branching diagram on the cell's faces, the pragmatic iterative route of DESIGN.md.
//!
//! For a point a on face f (plane P, unit normal n into the cell) the maximal empty sphere tangent to
//! P at a touches first the site b minimising r_b(a) = |a − b|² / (2 h_b), h_b = n·(b − a) (a Moebius
//! diagram of the sites). The Delaunay triangulation carries it: the apex of the `Vf` tet standing on
//! a grounded triangle is that triangle's minimiser. Two neighbouring internal grounded triangles
//! whose apexes b1, b2 are *discontinuous* sites (no common plane, or a common plane on which the edge
//! b1b2 is external: different contours or far-apart parts of one) straddle the branching diagram;
//! we place a sample on their shared edge where r_b1 = r_b2 (a quadratic in the edge parameter).
//! The caller inserts the samples and re-triangulates, a few rounds, until none is found.
//! Samples are thinned: none closer than half the face's median contour edge to another sample or to
//! the edge's endpoints.
use super::cell_input::CellInput;
use super::classify::{Classifier, TetType};
use super::complex::{outward_face, Complex};
use crate::sections::{dot, sub};
use std::collections::HashMap;

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d)
}

/// Branching samples: (slot, (u,v) in the slot's plane, 3D position).
pub fn samples(
    input: &CellInput,
    cx: &Complex,
    ty: &[TetType],
) -> Vec<(usize, [f64; 2], [f64; 3])> {
    let mut cl = Classifier::new(input);
    let mut out = Vec::new();
    for (s, slot) in input.slots.iter().enumerate() {
        let bit = 1u128 << s;
        // grounded internal triangles on s with their Vf apex
        let mut tri_apex: Vec<([u32; 3], u32)> = Vec::new();
        for (t, tv) in cx.tets.iter().enumerate() {
            if ty[t] != TetType::Vf {
                continue;
            }
            for i in 0..4 {
                let f = outward_face(tv, i);
                if f.iter().all(|&v| input.mask[v as usize] & bit != 0)
                    && input.mask[tv[i] as usize] & bit == 0
                    && !cl.triangle_external(f[0], f[1], f[2])
                {
                    tri_apex.push((f, tv[i]));
                }
            }
        }
        if tri_apex.is_empty() {
            continue;
        }
        // spacing of the contour
        let mut lens: Vec<f64> = slot
            .contour_edges
            .iter()
            .map(|&(a, b)| dist2(input.points[a as usize], input.points[b as usize]).sqrt())
            .collect();
        lens.sort_by(f64::total_cmp);
        let h = if lens.is_empty() {
            0.0
        } else {
            lens[lens.len() / 2]
        };
        let plane = slot.geom;
        let n = if slot.outward_is_plane_normal {
            [-plane.normal[0], -plane.normal[1], -plane.normal[2]]
        } else {
            plane.normal
        };
        // edges → (triangle apexes)
        let mut by_edge: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        for &(f, apex) in &tri_apex {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                by_edge.entry((a.min(b), a.max(b))).or_default().push(apex);
            }
        }
        // Does the Delaunay triangulation show a discontinuity of the apex map on this face?
        let mut discontinuous = false;
        for (&(p, q), apexes) in &by_edge {
            if apexes.len() != 2 || slot.contour_edges.contains(&(p, q)) {
                continue;
            }
            let (b1, b2) = (apexes[0], apexes[1]);
            if b1 == b2 {
                continue;
            }
            let common = input.mask[b1 as usize] & input.mask[b2 as usize];
            if common == 0 || cl.edge_external(b1, b2) {
                discontinuous = true;
                break;
            }
        }
        if !discontinuous || h <= 0.0 {
            continue;
        }
        out.extend(
            grid_samples(input, &mut cl, s, n, h)
                .into_iter()
                .map(|(uv, p3)| (s, uv, p3)),
        );
    }
    out
}

/// Sample the section on a grid of spacing `h`, find each grid point's minimiser of r_b, and on every
/// grid edge whose two minimisers are discontinuous place a point where r_b1 = r_b2 (bisection on the
/// segment). Points closer than h/2 to a contour vertex or to another sample are dropped.
fn grid_samples(
    input: &CellInput,
    cl: &mut Classifier,
    s: usize,
    n: [f64; 3],
    h: f64,
) -> Vec<([f64; 2], [f64; 3])> {
    let slot = &input.slots[s];
    let bit = 1u128 << s;
    let plane = slot.geom;
    let sites: Vec<(u32, [f64; 3], f64)> = (0..input.points.len() as u32)
        .filter(|&v| input.mask[v as usize] & bit == 0 && input.global[v as usize] != u32::MAX)
        .filter_map(|v| {
            let x = input.points[v as usize];
            let hb = dot(n, sub(x, plane.origin));
            (hb > 0.0).then_some((v, x, hb))
        })
        .collect();
    if sites.len() < 2 {
        return Vec::new();
    }
    let on_face: Vec<u32> = (0..input.points.len() as u32)
        .filter(|&v| input.mask[v as usize] & bit != 0)
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for &v in &on_face {
        let q = slot.uv[v as usize];
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let nx = (((hi[0] - lo[0]) / h).ceil() as usize).clamp(1, 400);
    let ny = (((hi[1] - lo[1]) / h).ceil() as usize).clamp(1, 400);
    let (sx, sy) = ((hi[0] - lo[0]) / nx as f64, (hi[1] - lo[1]) / ny as f64);
    let at = |i: usize, j: usize| [lo[0] + sx * i as f64, lo[1] + sy * j as f64];
    let r = |a3: [f64; 3], site: &(u32, [f64; 3], f64)| {
        // h_b measured from a (a is on the plane up to rounding)
        let hb = dot(n, sub(site.1, a3));
        if hb <= 0.0 {
            f64::INFINITY
        } else {
            dist2(a3, site.1) / (2.0 * hb)
        }
    };
    let argmin = |q: [f64; 2]| -> usize {
        let a3 = plane.to_3d(q);
        let mut best = (f64::INFINITY, 0);
        for (k, site) in sites.iter().enumerate() {
            let v = r(a3, site);
            if v < best.0 {
                best = (v, k);
            }
        }
        best.1
    };
    let w = nx + 1;
    let mut minimiser: Vec<Option<usize>> = vec![None; w * (ny + 1)];
    for j in 0..=ny {
        for i in 0..=nx {
            let q = at(i, j);
            if slot.locator.locate(q) == super::cell_input::Where::Inside {
                minimiser[j * w + i] = Some(argmin(q));
            }
        }
    }
    // thinning grid: cells of size h/2
    let cell = 0.5 * h;
    let key = |q: [f64; 2]| ((q[0] / cell).floor() as i64, (q[1] / cell).floor() as i64);
    let mut occupied: HashMap<(i64, i64), Vec<[f64; 2]>> = HashMap::new();
    for &v in &on_face {
        let q = slot.uv[v as usize];
        occupied.entry(key(q)).or_default().push(q);
    }
    let near = |occ: &HashMap<(i64, i64), Vec<[f64; 2]>>, q: [f64; 2]| {
        let (kx, ky) = key(q);
        (kx - 1..=kx + 1).any(|x| {
            (ky - 1..=ky + 1).any(|y| {
                occ.get(&(x, y)).is_some_and(|l| {
                    l.iter()
                        .any(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) < cell * cell)
                })
            })
        })
    };
    let mut out = Vec::new();
    let mut pairs_checked: HashMap<(usize, usize), bool> = HashMap::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let Some(m0) = minimiser[j * w + i] else {
                continue;
            };
            for (di, dj) in [(1usize, 0usize), (0, 1)] {
                let (i1, j1) = (i + di, j + dj);
                if i1 > nx || j1 > ny {
                    continue;
                }
                let Some(m1) = minimiser[j1 * w + i1] else {
                    continue;
                };
                if m0 == m1 {
                    continue;
                }
                let key_pair = (m0.min(m1), m0.max(m1));
                let disc = *pairs_checked.entry(key_pair).or_insert_with(|| {
                    let (b1, b2) = (sites[m0].0, sites[m1].0);
                    let common = input.mask[b1 as usize] & input.mask[b2 as usize];
                    common == 0 || cl.edge_external(b1, b2)
                });
                if !disc {
                    continue;
                }
                let (q0, q1) = (at(i, j), at(i1, j1));
                let f = |t: f64| {
                    let q = [q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1])];
                    let a3 = plane.to_3d(q);
                    r(a3, &sites[m0]) - r(a3, &sites[m1])
                };
                let (mut a, mut b) = (0.0, 1.0);
                let fa = f(a);
                if !(fa <= 0.0 && f(b) >= 0.0) {
                    continue;
                }
                for _ in 0..50 {
                    let mid = 0.5 * (a + b);
                    if f(mid) <= 0.0 {
                        a = mid;
                    } else {
                        b = mid;
                    }
                }
                let t = 0.5 * (a + b);
                let q = [q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1])];
                if slot.locator.locate(q) != super::cell_input::Where::Inside || near(&occupied, q)
                {
                    continue;
                }
                occupied.entry(key(q)).or_default().push(q);
                out.push((q, plane.to_3d(q)));
            }
        }
    }
    out
}
