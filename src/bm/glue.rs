//! Gluing the cells' complexes into one solid.
//!
//! Choice (see DESIGN "Gluing without overlays"): two cells may triangulate a shared face differently
//! (their Delaunay triangulations break the massive cocircularity of a section independently), so
//! section triangles are never matched across cells. Instead, per face with a section, with cells A
//! and B on its two sides and X_A, X_B the section triangles each attaches to (a kept tet stands on
//! them):
//! * both attach somewhere: each side outputs the section triangles of its *own* triangulation that
//!   it leaves unattached, oriented into its own cell. As chains this is ∂R_A − S_A + ∂R_B − S_B on
//!   the face, whose boundary cancels because contour edges and their Steiner points are shared, so
//!   the surface is closed; where both attach the section is interior; where only A attaches the
//!   boundary is B's triangles over that region. Where neither attaches (a flat zone) the two sides'
//!   sheets coincide with opposite orientations: identical triangles cancel, the rest is reported.
//! * only A attaches: A's attached triangles are output, oriented outward from A (no double sheet).
//! * neither attaches: the whole section is a flat zone, not output, reported with its area.
//!
//! All vertices are global (pool ids, Steiner points, then branching samples), so the pieces weld.
//! The tetrahedral mesh is the union of the kept tets; it is non-conforming across a face where the
//! two cells' section triangulations differ (counted in the report).
use super::cell::CellResult;
use crate::arrangement::{Arrangement, VertexPool};
use crate::mesh::{TetMesh, TriMesh};
use std::collections::HashMap;

#[derive(Clone, Debug, Default)]
pub struct Glued {
    pub surface: TriMesh,
    pub tets: TetMesh,
    pub warnings: Vec<String>,
    pub flat_zone_faces: u64,
    pub flat_zone_area: f64,
    pub double_sheet_triangles: u64,
    pub nonconforming_faces: u64,
}

fn tri_area(p: &[[f64; 3]], t: [u32; 3]) -> f64 {
    let (a, b, c) = (p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
    let u = crate::sections::sub(b, a);
    let v = crate::sections::sub(c, a);
    let w = crate::sections::cross(u, v);
    0.5 * crate::sections::dot(w, w).sqrt()
}

pub fn glue(arr: &Arrangement, pool: &VertexPool, results: &[Option<CellResult>]) -> Glued {
    let mut g = Glued::default();
    let mut positions = pool.positions.clone();
    // global id per cell-local vertex (branching samples get new ids)
    let maps: Vec<Vec<u32>> = results
        .iter()
        .map(|r| match r.as_ref().and_then(|r| r.input.as_ref()) {
            Some(inp) => inp
                .global
                .iter()
                .enumerate()
                .map(|(l, &gid)| {
                    if gid == u32::MAX {
                        positions.push(inp.points[l]);
                        (positions.len() - 1) as u32
                    } else {
                        gid
                    }
                })
                .collect(),
            None => Vec::new(),
        })
        .collect();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let mut tets: Vec<[u32; 4]> = Vec::new();
    let map3 = |m: &[u32], t: [u32; 3]| [m[t[0] as usize], m[t[1] as usize], m[t[2] as usize]];
    // per face: (cell, side data)
    let mut sides: HashMap<u32, Vec<(usize, usize)>> = HashMap::new();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r else { continue };
        let m = &maps[c];
        tris.extend(r.nonplanar.iter().map(|&t| map3(m, t)));
        tets.extend(r.kept.iter().map(|t| {
            [
                m[t[0] as usize],
                m[t[1] as usize],
                m[t[2] as usize],
                m[t[3] as usize],
            ]
        }));
        for (s, fs) in r.faces.iter().enumerate() {
            sides.entry(fs.face).or_default().push((c, s));
        }
    }
    let mut face_ids: Vec<u32> = sides.keys().copied().collect();
    face_ids.sort_unstable();
    for f in face_ids {
        let list = &sides[&f];
        let side = |&(c, s): &(usize, usize)| &results[c].as_ref().unwrap().faces[s];
        let attaching: Vec<&(usize, usize)> = list
            .iter()
            .filter(|cs| side(cs).triangles.iter().any(|t| t.1))
            .collect();
        if list.len() == 2 {
            let (a, b) = (side(&list[0]), side(&list[1]));
            let ka: Vec<[u32; 3]> = a
                .triangles
                .iter()
                .map(|t| sorted(map3(&maps[list[0].0], t.0)))
                .collect();
            let kb: Vec<[u32; 3]> = b
                .triangles
                .iter()
                .map(|t| sorted(map3(&maps[list[1].0], t.0)))
                .collect();
            let (mut ka, mut kb) = (ka, kb);
            ka.sort_unstable();
            kb.sort_unstable();
            if ka != kb {
                g.nonconforming_faces += 1;
            }
        }
        match attaching.len() {
            0 => {
                // whole section unattached: a flat zone
                let area: f64 = list
                    .iter()
                    .map(|cs| {
                        side(cs)
                            .triangles
                            .iter()
                            .map(|t| tri_area(&positions, map3(&maps[cs.0], t.0)))
                            .sum::<f64>()
                    })
                    .fold(0.0, f64::max);
                if area > 0.0 {
                    g.flat_zone_faces += 1;
                    g.flat_zone_area += area;
                    g.warnings.push(format!(
                        "face {f} (plane {}): section of area {area:.4e} attached from neither side (flat zone, not in the solid)",
                        arr.faces[f as usize].plane
                    ));
                }
            }
            1 => {
                let (c, s) = *attaching[0];
                let mut flat = 0.0;
                for &(t, att) in &results[c].as_ref().unwrap().faces[s].triangles {
                    if att {
                        tris.push(map3(&maps[c], t));
                    } else {
                        flat += tri_area(&positions, map3(&maps[c], t));
                    }
                }
                if flat > 0.0 {
                    g.flat_zone_faces += 1;
                    g.flat_zone_area += flat;
                    g.warnings.push(format!(
                        "face {f} (plane {}): flat zone of area {flat:.4e} attached from neither side (not in the solid)",
                        arr.faces[f as usize].plane
                    ));
                }
            }
            _ => {
                for &(c, s) in list {
                    for &(t, att) in &results[c].as_ref().unwrap().faces[s].triangles {
                        if !att {
                            let t = map3(&maps[c], t);
                            tris.push([t[0], t[2], t[1]]);
                        }
                    }
                }
            }
        }
    }
    // Cancel coincident opposite triangles (flat-zone sheets triangulated alike on both sides).
    let mut by_key: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    for (i, &t) in tris.iter().enumerate() {
        by_key.entry(sorted(t)).or_default().push(i);
    }
    let mut drop = vec![false; tris.len()];
    for idx in by_key.values() {
        if idx.len() < 2 {
            continue;
        }
        let (mut pos, mut neg): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
        for &i in idx {
            if parity(tris[i]) {
                pos.push(i)
            } else {
                neg.push(i)
            }
        }
        for (&i, &j) in pos.iter().zip(neg.iter()) {
            drop[i] = true;
            drop[j] = true;
        }
    }
    let tris: Vec<[u32; 3]> = tris
        .into_iter()
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(t, _)| t)
        .collect();
    g.double_sheet_triangles = count_double_sheet(&tris);
    if g.double_sheet_triangles > 0 {
        g.warnings.push(format!(
            "{} surface triangles touch non-manifold edges (singularities where pieces meet, or overlapping flat-zone sheets)",
            g.double_sheet_triangles
        ));
    }
    if g.nonconforming_faces > 0 {
        g.warnings.push(format!(
            "tetrahedral mesh is non-conforming across {} faces (the two cells triangulate the section differently)",
            g.nonconforming_faces
        ));
    }
    // compact vertices
    let mut remap = vec![u32::MAX; positions.len()];
    let mut verts = Vec::new();
    let mut id = |v: u32, verts: &mut Vec<[f64; 3]>| {
        if remap[v as usize] == u32::MAX {
            remap[v as usize] = verts.len() as u32;
            verts.push(positions[v as usize]);
        }
        remap[v as usize]
    };
    let triangles: Vec<[u32; 3]> = tris
        .iter()
        .map(|t| {
            [
                id(t[0], &mut verts),
                id(t[1], &mut verts),
                id(t[2], &mut verts),
            ]
        })
        .collect();
    g.surface = TriMesh {
        vertices: verts.clone(),
        triangles,
    };
    let tets: Vec<[u32; 4]> = tets
        .iter()
        .map(|t| {
            [
                id(t[0], &mut verts),
                id(t[1], &mut verts),
                id(t[2], &mut verts),
                id(t[3], &mut verts),
            ]
        })
        .collect();
    g.tets = TetMesh {
        vertices: verts,
        tets,
    };
    g
}

fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

/// Even permutation of the sorted triple.
fn parity(t: [u32; 3]) -> bool {
    let inv = (t[0] > t[1]) as u8 + (t[0] > t[2]) as u8 + (t[1] > t[2]) as u8;
    inv % 2 == 0
}

/// Triangles on an edge used by more than two triangles (a sign of overlapping sheets).
fn count_double_sheet(tris: &[[u32; 3]]) -> u64 {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for t in tris {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    tris.iter()
        .filter(|t| {
            (0..3).any(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges[&(a.min(b), a.max(b))] > 2
            })
        })
        .count() as u64
}
