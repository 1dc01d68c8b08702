//! The solid as one tetrahedral complex K: the kept tetrahedra of every cell in global vertex ids,
//! and its surface ∂K, the triangles with exactly one kept side, oriented outward.
//!
//! When the two cells of every face triangulate it alike (tagged kernel + shared diagram samples:
//! `nonconforming_faces == 0`), K is a conforming tetrahedralization and ∂K is closed and embedded
//! by construction: a section triangle kept from both sides is interior, from one side is surface,
//! from neither is a flat zone (not in ∂K, counted with its area). What ∂K can still have are
//! singularities (an edge with four surface triangles, a vertex whose surface link is several
//! cycles, paper Fig. 12a), counted here; resolving them inside K is the next step of
//! `docs/design/conforming-complex.md`. This replaces `glue` when `Assembly::Complex` is chosen.
use super::cell::CellResult;
use crate::arrangement::VertexPool;
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::mesh::{TetMesh, TriMesh};

/// K and what its boundary looks like.
#[derive(Clone, Debug, Default)]
pub struct Assembled {
    pub surface: TriMesh,
    pub tets: TetMesh,
    /// Faces with two cells whose section triangulations differ (K is then not conforming there).
    pub nonconforming_faces: u64,
    /// Section triangles that no kept tetrahedron stands on, on faces with a cell on each side or
    /// on a cap (the paper's flat zones): left out of ∂K.
    pub flat_triangles: u64,
    pub flat_area: f64,
    /// Edges of ∂K with more than two surface triangles.
    pub singular_edges: u64,
    /// Vertices of ∂K whose surface triangles form more than one fan (pinched), counted once each.
    pub singular_vertices: u64,
    /// Singular edges and vertices before filling, and the tetrahedra filling added.
    pub singular_edges_found: u64,
    pub singular_vertices_found: u64,
    pub tets_filled: u64,
}

/// Global ids per cell: pool ids, and fresh ids (appended to `positions`) for cell-local vertices.
pub(super) fn global_maps(
    results: &[Option<CellResult>],
    positions: &mut Vec<[f64; 3]>,
) -> Vec<Vec<u32>> {
    results
        .iter()
        .map(|r| match r.as_ref().and_then(|r| r.input.as_ref()) {
            Some(inp) => inp
                .global
                .iter()
                .enumerate()
                .map(|(l, &g)| {
                    if g == u32::MAX {
                        positions.push(inp.points[l]);
                        (positions.len() - 1) as u32
                    } else {
                        g
                    }
                })
                .collect(),
            None => Vec::new(),
        })
        .collect()
}

/// Most rounds of filling (each may expose new singularities at the filled tets).
const FILL_ROUNDS: usize = 8;

fn sorted3(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

/// Assemble K from the cells' kept tetrahedra (positively oriented, `robust::orient3d > 0`).
pub fn assemble(pool: &VertexPool, results: &[Option<CellResult>]) -> Assembled {
    let mut positions = pool.positions.clone();
    let maps = global_maps(results, &mut positions);
    let mut out = Assembled::default();
    let mut tets: Vec<[u32; 4]> = Vec::new();
    let mut fillable: Vec<[u32; 4]> = Vec::new();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r else { continue };
        let m = &maps[c];
        tets.extend(r.kept.iter().map(|t| t.map(|v| m[v as usize])));
        fillable.extend(r.fillable.iter().map(|t| t.map(|v| m[v as usize])));
    }
    count_faces(results, &maps, &positions, &mut out);
    let (edges, vertices) = singularities(&boundary_of(&tets));
    out.singular_edges_found = edges;
    out.singular_vertices_found = vertices;
    out.tets_filled = super::fill::fill_singularities(&mut tets, &fillable, FILL_ROUNDS);
    let boundary = boundary_of(&tets);
    let (edges, vertices) = singularities(&boundary);
    out.singular_edges = edges;
    out.singular_vertices = vertices;
    out.surface = compact_surface(&positions, &boundary);
    // TetMesh wants positive volume (orient3d < 0): swap two vertices
    out.tets = TetMesh {
        vertices: positions,
        tets: tets.iter().map(|t| [t[0], t[1], t[3], t[2]]).collect(),
    };
    out
}

/// The triangles of `tets` with exactly one tetrahedron, oriented outward from it.
pub fn boundary_of(tets: &[[u32; 4]]) -> Vec<[u32; 3]> {
    let mut open: FxHashMap<[u32; 3], Option<[u32; 3]>> = FxHashMap::default();
    for t in tets {
        for i in 0..4 {
            let f = super::complex::outward_face(t, i);
            open.entry(sorted3(f))
                .and_modify(|e| *e = None)
                .or_insert(Some(f));
        }
    }
    let mut out: Vec<[u32; 3]> = open.into_values().flatten().collect();
    out.sort_unstable();
    out
}

/// Non-conforming faces and flat-zone triangles, from the cells' own face triangles.
fn count_faces(
    results: &[Option<CellResult>],
    maps: &[Vec<u32>],
    positions: &[[f64; 3]],
    out: &mut Assembled,
) {
    // face → per side: (all triangle keys, attached keys)
    type Side = (Vec<[u32; 3]>, FxHashSet<[u32; 3]>);
    let mut sides: FxHashMap<u32, Vec<Side>> = FxHashMap::default();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r.as_ref().filter(|r| !r.flat_only) else {
            continue;
        };
        for fs in &r.faces {
            let m = &maps[c];
            let mut all = Vec::with_capacity(fs.triangles.len());
            let mut attached = FxHashSet::default();
            for &(t, a) in &fs.triangles {
                let k = sorted3(t.map(|v| m[v as usize]));
                all.push(k);
                if a {
                    attached.insert(k);
                }
            }
            all.sort_unstable();
            sides.entry(fs.face).or_default().push((all, attached));
        }
    }
    for list in sides.values() {
        if list.len() == 2 && list[0].0 != list[1].0 {
            out.nonconforming_faces += 1;
        }
        // a triangle of any side that no side attaches to (by key; sides that differ count
        // what the first side has)
        for k in &list[0].0 {
            if list.iter().all(|s| !s.1.contains(k)) {
                out.flat_triangles += 1;
                out.flat_area += super::glue::tri_area(positions, *k);
            }
        }
    }
}

/// (edges with more than two triangles, vertices whose triangles form more than one fan).
pub fn singularities(tris: &[[u32; 3]]) -> (u64, u64) {
    let (edges, vertices) = super::fill::singular_simplices(tris);
    (edges.len() as u64, vertices.len() as u64)
}

/// The surface with only the vertices it uses, in increasing global id.
fn compact_surface(positions: &[[f64; 3]], tris: &[[u32; 3]]) -> TriMesh {
    let mut used: Vec<u32> = tris.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let index: FxHashMap<u32, u32> = used
        .iter()
        .enumerate()
        .map(|(i, &g)| (g, i as u32))
        .collect();
    TriMesh {
        vertices: used.iter().map(|&g| positions[g as usize]).collect(),
        triangles: tris.iter().map(|t| t.map(|v| index[&v])).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_tets_share_an_interior_face() {
        // two positive tets on either side of the triangle (0,1,2): 6 boundary triangles
        let tets = vec![[0, 1, 2, 3], [0, 2, 1, 4]];
        let b = boundary_of(&tets);
        assert_eq!(b.len(), 6);
        assert!(!b.iter().any(|t| sorted3(*t) == [0, 1, 2]));
        assert_eq!(singularities(&b), (0, 0));
    }

    #[test]
    fn tets_meeting_at_an_edge_or_a_vertex_are_singular() {
        // two tets sharing only the edge (0,1): that edge has four surface triangles
        let edge = boundary_of(&[[0, 1, 2, 3], [0, 1, 4, 5]]);
        assert_eq!(singularities(&edge).0, 1);
        // sharing only vertex 0: one pinched vertex, no singular edge
        let vertex = boundary_of(&[[0, 1, 2, 3], [0, 4, 5, 6]]);
        assert_eq!(singularities(&vertex), (0, 1));
    }
}
