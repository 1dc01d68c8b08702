//! Displaced vertices must not make the surface cross itself.
//!
//! Gluing splits pinched vertices into copies and lifts branching samples off their plane (paper
//! Fig. 12b), each by a tiny step in a direction chosen from local combinatorics. Where that
//! direction points across a neighbouring sheet (a crease folding back onto the section, two fans
//! meeting at a narrow angle), the displaced vertex's triangles cross other triangles. Each
//! displaced vertex is therefore checked exactly (orient3d triangle tests) against the triangles
//! near it, and when its star crosses one, other candidate positions are tried in a fixed order:
//! a tenth of the step, the opposite step, a step (and a tenth of one) into the solid along the
//! star's inward normal, the same two out of it (into the void the star faces), a step and ten
//! steps towards the centroid of its star's link (into its own fan's cone, away from another sheet
//! that meets it only at the original point: two copies of one pinch point), and finally the
//! position it came from (a coincident copy: a pinch point, but no crossing). The first position
//! whose star crosses nothing is kept; if none is free, the one with fewest crossings.
//!
//! Which side is free depends on what touches the pinch: where two solids touch, each copy belongs
//! inside its own solid; where two voids touch (a pocket meeting the outer surface, a crack ending
//! on a section), each copy belongs in its own void, i.e. *outward*, so that solid fills the gap.
//! Elephant (a main surface crossing its plane at a contour vertex where a pocket above a section
//! wedge touches it) and Armadillo (a crack ending on a section under a wall rising from the same
//! contour vertex) both needed the outward step.
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::geom::bvh::{triangle_boxes, Aabb, Bvh};
use crate::geom::tri_tri::mesh_triangles_intersect;
use crate::sections::{cross, dot, sub};
use rayon::prelude::*;
use std::collections::HashMap;

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Untangled {
    /// Vertices moved to another candidate than their first position.
    pub redirected: u64,
    /// Vertices whose star still crosses the surface at the best candidate.
    pub unresolved: u64,
}

/// `moved`: (vertex, position it was displaced from). Positions are updated in place.
pub fn untangle(
    positions: &mut [[f64; 3]],
    tris: &[[u32; 3]],
    moved: &[(u32, [f64; 3])],
) -> Untangled {
    let mut out = Untangled::default();
    if moved.is_empty() || tris.is_empty() {
        return out;
    }
    let mut star: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
    let moved_set: FxHashSet<u32> = moved.iter().map(|m| m.0).collect();
    for (i, t) in tris.iter().enumerate() {
        for &v in t {
            if moved_set.contains(&v) {
                star.entry(v).or_default().push(i as u32);
            }
        }
    }
    // Boxes padded by the largest displacement (times a margin) stay conservative while vertices move.
    let reach = moved
        .iter()
        .map(|&(v, o)| {
            let d = sub(positions[v as usize], o);
            dot(d, d).sqrt()
        })
        .fold(0.0f64, f64::max);
    let pad = 4.0 * reach;
    let boxes: Vec<Aabb> = triangle_boxes(positions, tris)
        .into_iter()
        .map(|b| Aabb {
            lo: b.lo.map(|x| x - pad),
            hi: b.hi.map(|x| x + pad),
        })
        .collect();
    let bvh = Bvh::build(boxes);
    let crossings = |positions: &[[f64; 3]], v: u32| -> usize {
        let Some(s) = star.get(&v) else { return 0 };
        let mut n = 0;
        for &i in s {
            let t = tris[i as usize];
            let bb = Aabb::of_points(&t.map(|w| positions[w as usize]));
            bvh.for_each_overlap(&bb, |j| {
                // a pair inside the star is seen from both sides; count (and test) it once
                if j != i
                    && !(j < i && s.contains(&j))
                    && mesh_triangles_intersect(t, tris[j as usize], positions)
                {
                    n += 1;
                }
            });
        }
        n
    };
    // Sweeps: a chain of displaced neighbours (samples along one crease) may only clear once its
    // neighbours have moved, so the vertices still crossing are revisited.
    let mut todo: Vec<(u32, [f64; 3])> = moved.to_vec();
    let first: HashMap<u32, [f64; 3]> = moved
        .iter()
        .map(|&(v, _)| (v, positions[v as usize]))
        .collect();
    let mut unresolved = 0;
    // The first sweep's crossing counts at the start, in parallel (most are 0). A vertex's count is
    // taken from there unless a vertex moved earlier in the sweep had a triangle (before or after
    // the move) whose box overlaps one of its star's: only then can its count have changed.
    let initial: Vec<usize> = {
        let p: &[[f64; 3]] = positions;
        todo.par_iter().map(|&(v, _)| crossings(p, v)).collect()
    };
    let tbox = |positions: &[[f64; 3]], i: u32| {
        Aabb::of_points(&tris[i as usize].map(|w| positions[w as usize]))
    };
    for sweep in 0..4 {
        let mut again = Vec::new();
        // boxes of the triangles of the vertices moved so far in this sweep, before and after
        let mut dirty: Vec<Aabb> = Vec::new();
        for (k, &(v, origin)) in todo.iter().enumerate() {
            let start = positions[v as usize];
            let fresh = sweep > 0
                || (!dirty.is_empty()
                    && star.get(&v).is_some_and(|s| {
                        s.iter().any(|&i| {
                            let b = tbox(positions, i);
                            dirty.iter().any(|d| d.overlaps(&b))
                        })
                    }));
            let now = if fresh {
                crossings(positions, v)
            } else {
                initial[k]
            };
            let mut best = (now, start);
            if best.0 == 0 {
                continue;
            }
            let star_boxes = |positions: &[[f64; 3]]| -> Vec<Aabb> {
                star.get(&v)
                    .map(|s| s.iter().map(|&i| tbox(positions, i)).collect())
                    .unwrap_or_default()
            };
            dirty.extend(star_boxes(positions));
            let step = sub(first[&v], origin);
            let len = dot(step, step).sqrt();
            let inward = star
                .get(&v)
                .map(|s| inward_normal(positions, tris, s))
                .unwrap_or([0.0; 3]);
            let to_link = star
                .get(&v)
                .map(|s| towards_link(positions, tris, s, v))
                .unwrap_or([0.0; 3]);
            let candidates = [
                first[&v],
                add(origin, scale(step, 0.1)),
                sub(origin, step),
                add(origin, scale(inward, len)),
                add(origin, scale(inward, 0.1 * len)),
                sub(origin, scale(inward, len)),
                sub(origin, scale(inward, 0.1 * len)),
                add(origin, scale(to_link, len)),
                add(origin, scale(to_link, 10.0 * len)),
                origin,
            ];
            for c in candidates {
                if c == start || !c.iter().all(|x| x.is_finite()) {
                    continue;
                }
                positions[v as usize] = c;
                let n = crossings(positions, v);
                if n < best.0 {
                    best = (n, c);
                    if n == 0 {
                        break;
                    }
                }
            }
            positions[v as usize] = best.1;
            dirty.extend(star_boxes(positions));
            if best.0 > 0 {
                again.push((v, origin));
            }
        }
        unresolved = again.len();
        if again.is_empty() {
            break;
        }
        todo = again;
    }
    // A crease of several lifted samples can only go back all together: its triangles between two
    // displaced vertices cross whichever of them stays lifted.
    if unresolved > 0 {
        let origin_of: HashMap<u32, [f64; 3]> = moved.iter().copied().collect();
        let mut left = 0;
        for &(v, _) in &todo {
            if crossings(positions, v) == 0 {
                continue;
            }
            let mut group: Vec<u32> = vec![v];
            for &i in &star[&v] {
                for &w in &tris[i as usize] {
                    if w != v && origin_of.contains_key(&w) && !group.contains(&w) {
                        group.push(w);
                    }
                }
            }
            let saved: Vec<[f64; 3]> = group.iter().map(|&w| positions[w as usize]).collect();
            let before: usize = group.iter().map(|&w| crossings(positions, w)).sum();
            for &w in &group {
                positions[w as usize] = origin_of[&w];
            }
            let after: usize = group.iter().map(|&w| crossings(positions, w)).sum();
            if after >= before {
                for (&w, &p) in group.iter().zip(&saved) {
                    positions[w as usize] = p;
                }
            }
            if crossings(positions, v) > 0 {
                left += 1;
            }
        }
        unresolved = left;
    }
    out.redirected = moved
        .iter()
        .filter(|&&(v, _)| positions[v as usize] != first[&v])
        .count() as u64;
    out.unresolved = unresolved as u64;
    out
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Unit direction from `v` to the centroid of its star's other vertices: a step along it pulls the
/// tip of `v`'s fan into the fan's own cone, away from another sheet that meets it only at `v`'s
/// original position (two copies of one pinch point, each fan crossing the other's sheet).
fn towards_link(positions: &[[f64; 3]], tris: &[[u32; 3]], star: &[u32], v: u32) -> [f64; 3] {
    let (mut c, mut n) = ([0.0; 3], 0.0);
    for &i in star {
        for &w in &tris[i as usize] {
            if w != v {
                c = add(c, positions[w as usize]);
                n += 1.0;
            }
        }
    }
    if n == 0.0 {
        return [0.0; 3];
    }
    let d = sub(scale(c, 1.0 / n), positions[v as usize]);
    let l = dot(d, d).sqrt();
    if l > 0.0 {
        scale(d, 1.0 / l)
    } else {
        [0.0; 3]
    }
}

/// Unit vector into the solid at `v`: minus the area-weighted sum of its star's outward normals.
fn inward_normal(positions: &[[f64; 3]], tris: &[[u32; 3]], star: &[u32]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for &i in star {
        let t = tris[i as usize].map(|w| positions[w as usize]);
        n = add(n, cross(sub(t[1], t[0]), sub(t[2], t[0])));
    }
    let l = dot(n, n).sqrt();
    if l > 0.0 {
        scale(n, -1.0 / l)
    } else {
        [0.0; 3]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square (two triangles, outward +z) and a pyramid apex displaced straight through it.
    #[test]
    fn a_vertex_pushed_through_a_sheet_is_moved_back() {
        // sheet: square at z = 0; tent: a triangle fan from v (index 4) above the sheet
        let mut pos = vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [0.0, 0.0, 0.1],
            [-0.5, 0.0, 0.5],
            [0.5, 0.0, 0.5],
        ];
        let tris = vec![[0, 1, 2], [0, 2, 3], [4, 6, 5]];
        let origin = pos[4];
        // displaced through the sheet: its triangle now crosses the square
        pos[4] = [0.0, 0.0, -0.1];
        assert!(
            mesh_triangles_intersect(tris[2], tris[0], &pos)
                || mesh_triangles_intersect(tris[2], tris[1], &pos)
        );
        let u = untangle(&mut pos, &tris, &[(4, origin)]);
        assert_eq!(
            u,
            Untangled {
                redirected: 1,
                unresolved: 0
            }
        );
        assert!(pos[4][2] > 0.0, "{:?}", pos[4]);
    }

    /// Every exactly crossing pair of `tris` (i < j).
    fn all_crossings(pos: &[[f64; 3]], tris: &[[u32; 3]]) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for i in 0..tris.len() {
            for j in i + 1..tris.len() {
                if mesh_triangles_intersect(tris[i], tris[j], pos) {
                    out.push((i, j));
                }
            }
        }
        out
    }

    /// Elephant.csl, plane 15 at contour vertex 9111 (the stars of 9111 and of its copy 87162, as
    /// glued, ids in the comments): the outer surface crosses the plane along the contour 9110-9111-9112
    /// (cell 389 above, cell 393 below), and a void pocket — a section wedge attached from below only,
    /// roofed by two cell-389 triangles — touches it at 9111. The surface's copy, stepped towards its
    /// fan's vertices (up, into cell 389), made the cell-393 triangle 6555-87162-9110 pierce the wedge;
    /// the opposite step and the step into the solid cross too. The free side is outward: two voids
    /// touch here, and the solid must fill between them.
    #[test]
    fn elephant_surface_touching_a_void_pocket_steps_outward() {
        let pos: Vec<[f64; 3]> = vec![
            [
                -0.23225595128277368,
                -0.22398609171052705,
                -0.4531602444733901,
            ], // 6555
            [
                -0.26107817331037675,
                -0.18214964409365872,
                -0.4179508945160292,
            ], // 6560
            [
                -0.2202805159934098,
                -0.2480798097018841,
                -0.40540491930793543,
            ], // 9110
            [
                -0.2338423133861267,
                -0.22569427650396628,
                -0.4219826958167052,
            ], // 9111
            [
                -0.23736855285312053,
                -0.21954820711340267,
                -0.4263704227564488,
            ], // 9112
            [
                -0.2821961993733619,
                -0.22144810739719933,
                -0.39209738739309996,
            ], // 11843
            [
                -0.2817974632977457,
                -0.22180305899976302,
                -0.393492669199416,
            ], // 11844
            [
                -0.28175268515836727,
                -0.22184023849562282,
                -0.39365044808921595,
            ], // 11845
            [
                -0.28173776762474145,
                -0.22180888489208742,
                -0.3937207648805059,
            ], // 11846
            [-0.281684850993032, -0.2218771183992674, -0.3938973583981951], // 11847
            [
                -0.2769717894698418,
                -0.22944936319682924,
                -0.4090189935921882,
            ], // 11849
            [
                -0.28650864504287227,
                -0.21796223864399367,
                -0.3768637161852023,
            ], // 12453
            [
                -0.23799568819965766,
                -0.24819924256053708,
                -0.42008861173582135,
            ], // 17109
            [
                -0.2863329595119132,
                -0.20730246399229418,
                -0.3818687242421545,
            ], // 17160
            [
                -0.2860373227250511,
                -0.20451762812294116,
                -0.38414041402852395,
            ], // 17161
            [
                -0.28615774220825496,
                -0.20122477373262262,
                -0.3850120845219769,
            ], // 17167
            [
                -0.2386956791224519,
                -0.25585216311189324,
                -0.41885291543825987,
            ], // 17444
            [
                -0.22998890465924635,
                -0.24819924437956137,
                -0.41343916771736156,
            ], // 17445
            [
                -0.22802811429490846,
                -0.248175121935667,
                -0.41181649864343534,
            ], // 50822
            [
                -0.2864376129007808,
                -0.2136522561109361,
                -0.3788873520146755,
            ], // 51096
            [
                -0.28643434449556854,
                -0.21345394068694443,
                -0.3789804656629209,
            ], // 51097
            [
                -0.23384481035972599,
                -0.2256935625226063,
                -0.42198129813340063,
            ], // 87162 copy of 9111
        ];
        let tris: Vec<[u32; 3]> = vec![
            [1, 21, 4],
            [21, 15, 14],
            [1, 15, 21],
            [2, 21, 9],
            [13, 20, 21],
            [21, 11, 5],
            [21, 5, 6],
            [21, 7, 8],
            [21, 6, 7],
            [21, 8, 9],
            [3, 18, 10],
            [3, 10, 12],
            [21, 14, 13],
            [0, 21, 2],
            [0, 4, 21],
            [17, 3, 16],
            [12, 16, 3],
            [3, 17, 18],
            [20, 19, 21],
            [19, 11, 21],
        ];
        let (v, c) = (3u32, 21u32);
        let mut pos = pos;
        assert!(!all_crossings(&pos, &tris).is_empty());
        let origin = pos[v as usize];
        let u = untangle(&mut pos, &tris, &[(c, origin)]);
        assert_eq!(u.unresolved, 0);
        assert_eq!(all_crossings(&pos, &tris), vec![]);
        assert_ne!(pos[c as usize], origin);
    }

    /// Armadillo-23-better.csl, plane 5 at contour vertex 1138 (the stars of 1138, 31903, 9415 and of
    /// their copies 39955, 40019, 40001): a void crack of cell 62 ends on the section along
    /// 31903-1138-9415, under the wall rising from the contour vertex 1138. Lifted along the plane's
    /// normal into the cell, the crack's apex copy pierced the wall triangles 1137-1138-5688 and
    /// 1138-1354-5688; it belongs in the crack (outward of its fan).
    #[test]
    fn armadillo_crack_under_a_wall_steps_into_the_crack() {
        let pos: Vec<[f64; 3]> = vec![
            [29906.1050486, -20513.0, 2749.1057713],  // 999
            [33735.8976389, -12877.0, 1333.2030268],  // 1137
            [32589.9147779, -12877.0, -519.5554656],  // 1138
            [32502.7455017, -12877.0, -584.6836227],  // 1139
            [30918.0618233, -12877.0, -1368.0243524], // 1140
            [31360.3596433, -5241.0, -597.426561],    // 1354
            [31310.1718811, -5241.0, -646.2353883],   // 1355
            [32835.27947010002, -6110.981523300146, 979.8940572996277], // 5688
            [32495.5777903, -9528.680418499855, 2322.001780100373], // 5690
            [32490.190136299654, -9562.731175383953, 2335.3560551407786], // 5691
            [32501.24356590037, -9580.350561916635, 2342.385219557733], // 5692
            [29037.07728681107, -12876.999403740287, 362.9466913189958], // 9411
            [29447.40019323254, -12876.999414801852, -69.67411062364744], // 9412
            [29884.38011127725, -12876.999414801852, -458.91108572066946], // 9413
            [30364.28960680603, -12876.999400221805, -818.6620556432176], // 9414
            [32198.06843395302, -12877.0, 114.85640955950623], // 9415
            [33114.95784752651, -12876.999680415009, 817.2489908538882], // 9416
            [29929.843603462134, -12877.000612014826, 362.9466913189958], // 9715
            [31913.301094540908, -12877.00073025042, 1184.8044683586609], // 9719
            [33114.95784752651, -12877.000137037048, 448.1647799025929], // 9720
            [30495.243071676676, -12877.0, 597.2234288726089], // 31897
            [32535.881109439102, -12877.0, 803.150433565355], // 31901
            [32847.327169525575, -12877.0, 612.2277527724004], // 31902
            [32998.125970722846, -12877.0, 519.7850634124711], // 31903
            [32589.9147779, -12876.698339205559, -519.5554656], // 39955 copy of 1138
            [32198.06843395302, -12876.698339205559, 114.85640955950623], // 40001 copy of 9415
            [32998.125970722846, -12876.698339205559, 519.7850634124711], // 40019 copy of 31903
        ];
        let tris: Vec<[u32; 3]> = vec![
            [1, 2, 7],
            [24, 26, 8],
            [2, 6, 5],
            [2, 3, 6],
            [24, 8, 25],
            [2, 5, 7],
            [24, 25, 10],
            [16, 26, 10],
            [8, 9, 25],
            [9, 10, 25],
            [15, 20, 17],
            [18, 20, 15],
            [14, 15, 13],
            [17, 11, 15],
            [2, 15, 3],
            [14, 4, 15],
            [3, 15, 4],
            [19, 2, 1],
            [11, 12, 15],
            [19, 23, 2],
            [13, 15, 12],
            [15, 22, 21],
            [2, 23, 15],
            [15, 21, 18],
            [22, 15, 23],
            [26, 16, 8],
            [26, 24, 10],
            [22, 23, 0],
            [23, 19, 0],
        ];
        let mut pos = pos;
        assert!(!all_crossings(&pos, &tris).is_empty());
        // the copies with the contour vertices they were split from (1138, 9415, 31903)
        let moved = [(24u32, pos[2]), (25, pos[15]), (26, pos[23])];
        let u = untangle(&mut pos, &tris, &moved);
        assert_eq!(u.unresolved, 0);
        assert_eq!(all_crossings(&pos, &tris), vec![]);
    }

    #[test]
    fn a_harmless_displacement_is_kept() {
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.8, 0.8, 0.001],
        ];
        let tris = vec![[0, 1, 2], [1, 3, 2]];
        let before = pos.clone();
        let u = untangle(&mut pos, &tris, &[(3, [0.8, 0.8, 0.0])]);
        assert_eq!(u, Untangled::default());
        assert_eq!(pos, before);
    }
}
