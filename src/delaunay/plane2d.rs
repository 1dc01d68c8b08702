//! A small reference 2D Delaunay triangulation of the points of one plane with the tagged kernel's
//! rules: circles through the plane's apex on the 3D positions (or in the plane's uv without one),
//! exact, ties by the 2D symbolic perturbation in the lexicographic order of the 3D positions, the
//! line rule for points sharing a second plane. Brute force on purpose: a triangle is kept iff it is not
//! degenerate and no other point conflicts with it, which is the definition, with no incremental
//! state that could share a bug with the 3D kernel. O(n⁴): for checks on up to a few hundred points.
use super::pred;
use super::tags::{line_plane, on_one_line, plane_conflict, PlaneApexes, PointTags, TaggedPoint};

/// Whether `q` conflicts with triangle `f` of `plane`: the line rule when two of `f`'s vertices
/// and `q` lie on one line (share a second plane), else the perturbed in-circle test (through the
/// apex, or in uv).
fn conflicts(plane: u32, f: [TaggedPoint; 3], q: TaggedPoint, apexes: &PlaneApexes) -> bool {
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if let Some(pl) = line_plane(f[i].0, f[j].0, q.0) {
            let uv = |t: &PointTags| t.uv(pl).unwrap();
            return pred::line_between(uv(f[i].0), uv(f[j].0), uv(q.0));
        }
    }
    plane_conflict(plane, f, q, apexes).unwrap_or(false)
}

/// The Delaunay triangles of `pts` (every one must lie on `plane`), as index triples counter-
/// clockwise in uv, sorted. Collinear triples (in uv, or by sharing a second plane) are never
/// triangles. Where the plane has an apex in `apexes`, circles and collinearity are decided
/// through it on the 3D positions, as the kernel does.
pub fn delaunay(plane: u32, pts: &[TaggedPoint], apexes: &PlaneApexes) -> Vec<[usize; 3]> {
    assert!(
        pts.iter().all(|p| p.0.on(plane)),
        "a point is not on the plane"
    );
    let uv = |i: usize| pts[i].0.uv(plane).unwrap();
    let n = pts.len();
    let mut out = Vec::new();
    let mut witness = 0;
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let o = match apexes.get(plane) {
                    // counter-clockwise in uv is positive against an apex above the plane
                    Some(a) => pred::orient(pts[i].1, pts[j].1, pts[k].1, a),
                    None => crate::geom::predicates::orient2d(uv(i), uv(j), uv(k)),
                };
                if o == 0.0 || on_one_line(pts[i].0, pts[j].0, pts[k].0) {
                    continue;
                }
                let f = [pts[i], pts[j], pts[k]];
                // the last witness first: a point that spoiled a neighbouring triple usually
                // spoils this one (the search stays brute force, only faster to refute)
                let others = |m: &usize| *m != i && *m != j && *m != k;
                let empty = !(others(&witness) && conflicts(plane, f, pts[witness], apexes))
                    && match (0..n)
                        .filter(others)
                        .find(|&m| conflicts(plane, f, pts[m], apexes))
                    {
                        Some(m) => {
                            witness = m;
                            false
                        }
                        None => true,
                    };
                if empty {
                    out.push(if o > 0.0 { [i, j, k] } else { [i, k, j] });
                }
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_is_triangulated_once() {
        // a 4×3 grid: massively cocircular; 2·(3·2) triangles covering area 6
        let pts: Vec<PointTags> = (0..12)
            .map(|k| PointTags::new(100 - k, &[(4, [(k % 4) as f64, (k / 4) as f64])]))
            .collect();
        let refs: Vec<TaggedPoint> = pts
            .iter()
            .enumerate()
            .map(|(k, t)| (t, [k as f64, 0.0, 0.0]))
            .collect();
        let tris = delaunay(4, &refs, &PlaneApexes::default());
        assert_eq!(tris.len(), 12);
        let area: f64 = tris
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| pts[i].uv(4).unwrap());
                crate::geom::predicates::orient2d(a, b, c) / 2.0
            })
            .sum();
        assert_eq!(area, 6.0);
    }
}
