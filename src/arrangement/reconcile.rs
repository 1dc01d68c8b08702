//! Agreement of two sections along their planes' common line (DESIGN invariant 5).
//!
//! Section i crosses the line L = P_i ∩ P_j at points (its pool vertices tagged {i, j}), and so does
//! section j. Rule: each section keeps its own crossings (its pieces stay exactly its input); the
//! disagreement on L is the Hausdorff distance between the two crossing sets measured along L (or the
//! longest interval of one section when the other does not reach L). The largest one is reported
//! as `max_disagreement`, and every line beyond `snap_tolerance × diagonal` gets a warning.
use super::{Arrangement, ArrangementOptions, VertexId};
use crate::sections::{cross, dot};
use std::collections::HashMap;

/// `line_points`: (section plane that made the point, pool id) for every section point on another plane.
pub(super) fn measure_disagreement(
    arr: &mut Arrangement,
    line_points: &[(u32, VertexId)],
    diag: f64,
    options: &ArrangementOptions,
) {
    let n = arr.n_input as u32;
    // (i, j) with i < j -> (points of i, points of j) as positions along the line.
    let mut per_line: HashMap<(u32, u32), (Vec<f64>, Vec<f64>)> = HashMap::new();
    for &(owner, v) in line_points {
        for &t in &arr.pool.tags[v as usize] {
            if t == owner || t >= n {
                continue;
            }
            let (a, b) = (owner.min(t), owner.max(t));
            let d = cross(
                arr.planes[a as usize].plane.normal,
                arr.planes[b as usize].plane.normal,
            );
            let s = dot(d, arr.pool.positions[v as usize]) / dot(d, d).sqrt();
            let e = per_line.entry((a, b)).or_default();
            if owner == a {
                e.0.push(s);
            } else {
                e.1.push(s);
            }
        }
    }
    let tol = options.snap_tolerance * diag;
    let mut keys: Vec<_> = per_line.keys().copied().collect();
    keys.sort_unstable();
    let mut worst = 0.0f64;
    for key in keys {
        let (mut a, mut b) = per_line.remove(&key).unwrap();
        let (sa, sb) = (
            arr.planes[key.0 as usize].section,
            arr.planes[key.1 as usize].section,
        );
        a.sort_by(f64::total_cmp);
        b.sort_by(f64::total_cmp);
        let d = set_disagreement(&a, &b);
        worst = worst.max(d);
        if d > tol {
            arr.warnings.push(format!(
                "sections {} and {} disagree along their common line by {:.3e} ({} vs {} crossings)",
                sa.unwrap_or(usize::MAX),
                sb.unwrap_or(usize::MAX),
                d,
                a.len(),
                b.len()
            ));
        }
    }
    arr.max_disagreement = worst;
}

fn set_disagreement(a: &[f64], b: &[f64]) -> f64 {
    let span = |x: &[f64]| -> f64 {
        x.chunks(2)
            .map(|c| if c.len() == 2 { c[1] - c[0] } else { 0.0 })
            .fold(0.0, f64::max)
    };
    if a.is_empty() {
        return span(b);
    }
    if b.is_empty() {
        return span(a);
    }
    let near = |x: f64, set: &[f64]| {
        set.iter()
            .map(|y| (x - y).abs())
            .fold(f64::INFINITY, f64::min)
    };
    let h1 = a.iter().map(|&x| near(x, b)).fold(0.0, f64::max);
    let h2 = b.iter().map(|&x| near(x, a)).fold(0.0, f64::max);
    h1.max(h2)
}
