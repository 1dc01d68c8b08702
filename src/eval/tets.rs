//! `check` for a tetrahedral mesh: is it a valid, conforming tetrahedrisation of a solid, and (with
//! a surface) is its boundary exactly that surface?
//!
//! Every decision is exact or combinatorial:
//! * orientation of each tetrahedron by the exact `orient3d` (the crate's convention, see
//!   [`TetMesh`]: positive volume is `orient3d(a, b, c, d) < 0`);
//! * vertices are welded by exact position first, because duplicated vertices make a cracked mesh
//!   look conforming to index-based tests (the count is reported as a defect);
//! * faces are counted over the welded indices; the faces used once form the boundary, which must be
//!   a closed, manifold, outward-oriented surface (`topology::analyze`) without self-intersections
//!   (exact). A non-conforming interface (a hanging vertex, a face against two faces) leaves boundary
//!   triangles inside the solid that meet others along a shared edge or overlap them coplanarly, so
//!   the boundary test sees what the face count alone cannot;
//! * each interior face must separate its two tetrahedra (the two apexes strictly on opposite sides).
//!
//! Why that suffices for "no overlap": with every tetrahedron positive and every face used at most
//! twice by tetrahedra on opposite sides, the faces used once are the boundary of the tetrahedra as a
//! chain; when that boundary is an embedded, outward-oriented closed surface its winding number is 0
//! or 1 everywhere, and it equals the number of tetrahedra covering a point, so none overlap.
//! The volume test (sum of tetrahedron volumes against the volume the boundary encloses, floating
//! point, relative [`VOLUME_RELATIVE_TOLERANCE`]) is a cross-check of that bookkeeping.
use super::check::self_intersections;
use super::topology::analyze;
use crate::fxhash::FxHashMap;
use crate::geom::predicates::orient3d;
use crate::mesh::{TetMesh, TriMesh};
use serde::Serialize;

/// Sum of tetrahedron volumes and enclosed boundary volume must agree to this fraction.
pub const VOLUME_RELATIVE_TOLERANCE: f64 = 1e-9;

/// The faces of tetrahedron (v0, v1, v2, v3), face k opposite v_k, oriented outward when the
/// tetrahedron has positive volume (same table as `shared/eval/tet_check.py`).
const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// What `check` measures on a tetrahedral mesh. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct TetCheck {
    pub points: usize,
    pub tets: usize,
    /// Tetrahedra naming a vertex past the vertex array (left out of every other count). The readers
    /// refuse such files; a mesh built in memory may still have them.
    pub index_out_of_range: usize,
    /// Vertices used by a tetrahedron at exactly the position of another used vertex (beyond the
    /// first at each position). A defect: a crack that index-based tests see as a shared face.
    pub coincident_vertices: usize,
    /// Negative volume (exact `orient3d(a, b, c, d) > 0` in the `robust` sign convention).
    pub inverted: usize,
    /// Zero volume (exact `orient3d == 0`, including a vertex repeated after welding).
    pub flat: usize,
    /// Distinct triangles (welded indices) that belong to three or more tetrahedra.
    pub faces_used_more_than_twice: usize,
    /// Triangles shared by exactly two tetrahedra.
    pub interior_faces: usize,
    /// Interior faces whose two tetrahedra lie on the same side (exact): they overlap.
    pub interior_faces_same_side: usize,
    /// Triangles used by exactly one tetrahedron, oriented outward from it.
    pub boundary_triangles: usize,
    pub boundary_closed: bool,
    pub boundary_manifold: bool,
    /// Consistent orientation and every closed shell facing out of the material.
    pub boundary_oriented: bool,
    pub boundary_edges: usize,
    pub boundary_nonmanifold_edges: usize,
    pub boundary_nonmanifold_vertices: usize,
    /// Intersecting boundary triangle pairs (exact; pairs sharing vertices only when they overlap
    /// beyond what they share).
    pub boundary_self_intersections: usize,
    /// Sum of the signed tetrahedron volumes.
    pub volume: f64,
    /// The volume the boundary encloses (divergence theorem).
    pub boundary_volume: f64,
    /// `volume` and `boundary_volume` agree within [`VOLUME_RELATIVE_TOLERANCE`].
    pub volume_matches: bool,
    /// No coincident vertices, no face used more than twice, and a closed, manifold boundary
    /// without self-intersections enclosing the tetrahedra's volume: every two tetrahedra that touch
    /// share a whole face, edge or vertex.
    pub conforming: bool,
    /// Only with a surface to compare with.
    #[serde(flatten)]
    pub surface: Option<SurfaceMatch>,
    /// Conforming, no inverted, flat or overlapping tetrahedra, outward boundary, and (with a
    /// surface) the boundary is exactly that surface.
    pub valid: bool,
}

/// The tetrahedra's boundary against a given surface, triangles matched by exact vertex positions.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SurfaceMatch {
    pub surface_triangles: usize,
    /// Surface triangles without a boundary triangle on the same three positions (multisets).
    pub surface_triangles_missing: usize,
    /// Boundary triangles without a surface triangle on the same three positions.
    pub boundary_triangles_extra: usize,
    /// Triangles on the same three positions in both, but in opposite orientation.
    pub orientation_mismatches: usize,
    /// Nothing missing, nothing extra, no orientation mismatch.
    pub boundary_equals_surface: bool,
}

/// Check `tets`; with `surface`, also compare the tetrahedra's boundary with it.
pub fn check_tets(tets: &TetMesh, surface: Option<&TriMesh>) -> TetCheck {
    let (in_range, index_out_of_range) = in_range(tets);
    let tets = &in_range;
    let (welded, coincident_vertices) = weld(tets);
    let (inverted, flat) = orientation_counts(tets);
    let faces = face_counts(&welded);
    let boundary = TriMesh {
        vertices: welded.vertices.clone(),
        triangles: faces.boundary.clone(),
    };
    let topo = analyze(&boundary);
    let boundary_self_intersections = self_intersections(&boundary).count;
    let volume = tet_volume(tets);
    let boundary_volume = topo.components.iter().map(|c| c.volume).sum();
    let volume_matches = volumes_agree(volume, boundary_volume);
    let conforming = index_out_of_range == 0
        && coincident_vertices == 0
        && faces.more_than_twice == 0
        && topo.closed
        && topo.manifold
        && boundary_self_intersections == 0
        && volume_matches;
    let surface = surface.map(|s| match_surface(&boundary, s));
    let valid = conforming
        && inverted == 0
        && flat == 0
        && faces.same_side == 0
        && topo.oriented
        && surface.as_ref().is_none_or(|s| s.boundary_equals_surface);
    TetCheck {
        points: tets.vertices.len(),
        tets: tets.tets.len() + index_out_of_range,
        index_out_of_range,
        coincident_vertices,
        inverted,
        flat,
        faces_used_more_than_twice: faces.more_than_twice,
        interior_faces: faces.interior,
        interior_faces_same_side: faces.same_side,
        boundary_triangles: faces.boundary.len(),
        boundary_closed: topo.closed,
        boundary_manifold: topo.manifold,
        boundary_oriented: topo.oriented,
        boundary_edges: topo.boundary_edges,
        boundary_nonmanifold_edges: topo.nonmanifold_edges,
        boundary_nonmanifold_vertices: topo.nonmanifold_vertices,
        boundary_self_intersections,
        volume,
        boundary_volume,
        volume_matches,
        conforming,
        surface,
        valid,
    }
}

/// The tetrahedra whose four vertex ids are in range, and how many were not.
fn in_range(tets: &TetMesh) -> (TetMesh, usize) {
    let n = tets.vertices.len();
    let ok = |t: &&[u32; 4]| t.iter().all(|&v| (v as usize) < n);
    let kept: Vec<[u32; 4]> = tets.tets.iter().filter(ok).copied().collect();
    let dropped = tets.tets.len() - kept.len();
    let mesh = TetMesh {
        vertices: tets.vertices.clone(),
        tets: kept,
    };
    (mesh, dropped)
}

/// A position as a hashable key; `-0.0` and `0.0` are the same position.
fn position_key(p: [f64; 3]) -> [u64; 3] {
    p.map(|x| (x + 0.0).to_bits())
}

/// The mesh with vertices of equal position merged (same vertex array order of first occurrence),
/// and how many used vertices were merged into another used one.
fn weld(tets: &TetMesh) -> (TetMesh, usize) {
    let mut first: FxHashMap<[u64; 3], u32> = FxHashMap::default();
    let mut remap = vec![u32::MAX; tets.vertices.len()];
    let mut out = TetMesh::default();
    let mut coincident = 0;
    for t in &tets.tets {
        for &v in t {
            let v = v as usize;
            if remap[v] != u32::MAX {
                continue;
            }
            let next = out.vertices.len() as u32;
            let id = *first.entry(position_key(tets.vertices[v])).or_insert(next);
            if id == next {
                out.vertices.push(tets.vertices[v]);
            } else {
                coincident += 1;
            }
            remap[v] = id;
        }
    }
    out.tets = tets
        .tets
        .iter()
        .map(|t| t.map(|v| remap[v as usize]))
        .collect();
    (out, coincident)
}

fn corners(m: &TetMesh, t: [u32; 4]) -> [[f64; 3]; 4] {
    t.map(|v| m.vertices[v as usize])
}

/// (inverted, flat) by the exact sign of `orient3d` (positive volume is a negative `orient3d`).
fn orientation_counts(m: &TetMesh) -> (usize, usize) {
    let mut inverted = 0;
    let mut flat = 0;
    for &t in &m.tets {
        let [a, b, c, d] = corners(m, t);
        let o = orient3d(a, b, c, d);
        if o > 0.0 {
            inverted += 1;
        } else if o == 0.0 {
            flat += 1;
        }
    }
    (inverted, flat)
}

/// Sum of (b−a)·((c−a)×(d−a))/6 (floating point; relative to a corner, so no far-origin loss).
fn tet_volume(m: &TetMesh) -> f64 {
    m.tets
        .iter()
        .map(|&t| {
            let [a, b, c, d] = corners(m, t);
            let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
            (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]))
                / 6.0
        })
        .sum()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn volumes_agree(a: f64, b: f64) -> bool {
    (a - b).abs() <= VOLUME_RELATIVE_TOLERANCE * a.abs().max(b.abs()) && a.abs().max(b.abs()) > 0.0
}

/// Face bookkeeping over welded indices.
struct FaceCounts {
    /// Faces used once, oriented outward from their tetrahedron.
    boundary: Vec<[u32; 3]>,
    interior: usize,
    same_side: usize,
    more_than_twice: usize,
}

/// One use of a face: its sorted vertex ids, the tetrahedron and the local face number.
struct FaceUse {
    key: [u32; 3],
    tet: u32,
    local: u8,
}

/// Count the uses of every face; tetrahedra with a repeated (welded) vertex have no proper faces and
/// are skipped here (they are counted as flat).
fn face_counts(m: &TetMesh) -> FaceCounts {
    let mut uses = face_uses(m);
    uses.sort_unstable_by_key(|u| (u.key, u.tet, u.local));
    let mut out = FaceCounts {
        boundary: Vec::new(),
        interior: 0,
        same_side: 0,
        more_than_twice: 0,
    };
    for group in uses.chunk_by(|x, y| x.key == y.key) {
        match group {
            [one] => out.boundary.push(oriented_face(m, one)),
            [x, y] => {
                out.interior += 1;
                if !separates(m, x, y) {
                    out.same_side += 1;
                }
            }
            _ => out.more_than_twice += 1,
        }
    }
    out
}

fn face_uses(m: &TetMesh) -> Vec<FaceUse> {
    let mut uses = Vec::with_capacity(4 * m.tets.len());
    for (i, t) in m.tets.iter().enumerate() {
        let repeated = (0..4).any(|a| (a + 1..4).any(|b| t[a] == t[b]));
        if repeated {
            continue;
        }
        for (k, f) in FACES.iter().enumerate() {
            let mut key = f.map(|j| t[j]);
            key.sort_unstable();
            uses.push(FaceUse {
                key,
                tet: i as u32,
                local: k as u8,
            });
        }
    }
    uses
}

fn oriented_face(m: &TetMesh, u: &FaceUse) -> [u32; 3] {
    FACES[u.local as usize].map(|j| m.tets[u.tet as usize][j])
}

/// The two apexes of an interior face lie strictly on opposite sides of it (exact). A flat
/// tetrahedron's apex on the face's plane does not count as overlap here (it is counted as flat).
fn separates(m: &TetMesh, x: &FaceUse, y: &FaceUse) -> bool {
    let [a, b, c] = x.key.map(|v| m.vertices[v as usize]);
    let apex = |u: &FaceUse| m.vertices[m.tets[u.tet as usize][u.local as usize] as usize];
    let (sx, sy) = (orient3d(a, b, c, apex(x)), orient3d(a, b, c, apex(y)));
    sx == 0.0 || sy == 0.0 || (sx > 0.0) != (sy > 0.0)
}

/// A triangle as its three position keys, in the given order.
type PosTri = [[u64; 3]; 3];

fn position_triangles(m: &TriMesh) -> Vec<PosTri> {
    m.triangles
        .iter()
        .map(|t| t.map(|v| position_key(m.vertices[v as usize])))
        .collect()
}

/// Orientation-insensitive key: the positions sorted.
fn unoriented(t: PosTri) -> PosTri {
    let mut s = t;
    s.sort_unstable();
    s
}

/// Orientation-sensitive key: the smallest of the three rotations.
fn oriented(t: PosTri) -> PosTri {
    let r = |k: usize| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
    r(0).min(r(1)).min(r(2))
}

/// Size of the multiset intersection of two sorted lists.
fn common<T: Ord>(a: &[T], b: &[T]) -> usize {
    let (mut i, mut j, mut n) = (0, 0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                n += 1;
                i += 1;
                j += 1;
            }
        }
    }
    n
}

fn sorted_keys(tris: &[PosTri], key: fn(PosTri) -> PosTri) -> Vec<PosTri> {
    let mut v: Vec<PosTri> = tris.iter().map(|&t| key(t)).collect();
    v.sort_unstable();
    v
}

/// Compare boundary and surface triangle multisets by exact positions, without and with orientation.
fn match_surface(boundary: &TriMesh, surface: &TriMesh) -> SurfaceMatch {
    let (b, s) = (position_triangles(boundary), position_triangles(surface));
    let same = common(&sorted_keys(&b, unoriented), &sorted_keys(&s, unoriented));
    let same_oriented = common(&sorted_keys(&b, oriented), &sorted_keys(&s, oriented));
    let missing = s.len() - same;
    let extra = b.len() - same;
    let flipped = same.saturating_sub(same_oriented);
    SurfaceMatch {
        surface_triangles: s.len(),
        surface_triangles_missing: missing,
        boundary_triangles_extra: extra,
        orientation_mismatches: flipped,
        boundary_equals_surface: missing == 0 && extra == 0 && flipped == 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [f64; 3] = [0.0, 0.0, 0.0];
    const B: [f64; 3] = [1.0, 0.0, 0.0];
    const C: [f64; 3] = [0.0, 1.0, 0.0];
    const D: [f64; 3] = [0.0, 0.0, 1.0];
    /// Beyond face BCD (plane x + y + z = 1), opposite A.
    const E: [f64; 3] = [1.0, 1.0, 1.0];

    fn mesh(vertices: &[[f64; 3]], tets: &[[u32; 4]]) -> TetMesh {
        TetMesh {
            vertices: vertices.to_vec(),
            tets: tets.to_vec(),
        }
    }

    /// The tetrahedron with its last two corners swapped when needed to give it positive volume.
    fn positive(m: &TetMesh, t: [u32; 4]) -> [u32; 4] {
        if orient3d(
            m.vertices[t[0] as usize],
            m.vertices[t[1] as usize],
            m.vertices[t[2] as usize],
            m.vertices[t[3] as usize],
        ) > 0.0
        {
            [t[0], t[1], t[3], t[2]]
        } else {
            t
        }
    }

    fn positive_mesh(vertices: &[[f64; 3]], tets: &[[u32; 4]]) -> TetMesh {
        let mut m = mesh(vertices, tets);
        m.tets = m.tets.iter().map(|&t| positive(&m, t)).collect();
        m
    }

    /// A, B, C, D and E; tetrahedra ABCD and BCDE share face BCD.
    fn two_tets() -> TetMesh {
        positive_mesh(&[A, B, C, D, E], &[[0, 1, 2, 3], [1, 2, 3, 4]])
    }

    /// The outward faces of the tetrahedra used once, built independently of `face_counts`.
    fn boundary_of(m: &TetMesh) -> TriMesh {
        let mut tris: Vec<[u32; 3]> = Vec::new();
        for t in &m.tets {
            for f in FACES {
                tris.push(f.map(|j| t[j]));
            }
        }
        let key = |t: &[u32; 3]| {
            let mut k = *t;
            k.sort_unstable();
            k
        };
        let keys: Vec<[u32; 3]> = tris.iter().map(key).collect();
        let once = |t: &[u32; 3]| keys.iter().filter(|&&k| k == key(t)).count() == 1;
        TriMesh {
            vertices: m.vertices.clone(),
            triangles: tris.iter().copied().filter(once).collect(),
        }
    }

    #[test]
    fn two_tets_sharing_a_face_are_valid() {
        let m = two_tets();
        let r = check_tets(&m, Some(&boundary_of(&m)));
        assert_eq!((r.points, r.tets), (5, 2));
        assert_eq!((r.inverted, r.flat, r.coincident_vertices), (0, 0, 0));
        assert_eq!((r.interior_faces, r.boundary_triangles), (1, 6));
        assert!(r.boundary_closed && r.boundary_manifold && r.boundary_oriented);
        assert_eq!(r.boundary_self_intersections, 0);
        assert!(r.volume_matches && (r.volume - (1.0 / 6.0 + 2.0 / 6.0)).abs() < 1e-15);
        let s = r.surface.as_ref().unwrap();
        assert!(s.boundary_equals_surface);
        assert!(r.conforming && r.valid);
    }

    #[test]
    fn the_six_tets_of_a_cube_are_valid() {
        // Kuhn triangulation: one tetrahedron per ordering of the axes along the main diagonal.
        let v: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64])
            .collect();
        let perms = [
            [1, 2, 4],
            [1, 4, 2],
            [2, 1, 4],
            [2, 4, 1],
            [4, 1, 2],
            [4, 2, 1],
        ];
        let tets: Vec<[u32; 4]> = perms.iter().map(|p| [0, p[0], p[0] + p[1], 7]).collect();
        let r = check_tets(&positive_mesh(&v, &tets), None);
        assert_eq!((r.boundary_triangles, r.interior_faces), (12, 6)); // 24 uses = 12 + 2·6
        assert!((r.volume - 1.0).abs() < 1e-15);
        assert!(r.conforming && r.valid, "{r:?}");
        assert!(r.surface.is_none());
    }

    #[test]
    fn an_inverted_tet_is_invalid() {
        let r = check_tets(&mesh(&[A, B, C, D], &[[0, 2, 1, 3]]), None);
        assert_eq!((r.inverted, r.flat), (1, 0));
        assert!(!r.boundary_oriented && !r.valid);
    }

    #[test]
    fn a_flat_tet_is_invalid() {
        let r = check_tets(&mesh(&[A, B, C, [1.0, 1.0, 0.0]], &[[0, 1, 2, 3]]), None);
        assert_eq!((r.inverted, r.flat), (0, 1));
        assert!(!r.valid);
    }

    #[test]
    fn a_face_used_three_times_is_not_conforming() {
        let f = [0.5, 0.5, 2.0];
        let m = positive_mesh(
            &[A, B, C, D, E, f],
            &[[0, 1, 2, 3], [1, 2, 3, 4], [1, 2, 3, 5]],
        );
        let r = check_tets(&m, None);
        assert_eq!(r.faces_used_more_than_twice, 1);
        assert!(!r.conforming && !r.valid);
    }

    #[test]
    fn tets_on_the_same_side_of_their_face_overlap() {
        let m = positive_mesh(
            &[A, B, C, D, [0.1, 0.1, 0.1]],
            &[[0, 1, 2, 3], [1, 2, 3, 4]],
        );
        let r = check_tets(&m, None);
        assert_eq!((r.interior_faces, r.interior_faces_same_side), (1, 1));
        assert!(!r.valid);
    }

    #[test]
    fn a_crack_of_duplicated_vertices_is_not_conforming() {
        // ABCD and B'C'D'E: the same positions, but the second tetrahedron has its own copies.
        let m = positive_mesh(&[A, B, C, D, B, C, D, E], &[[0, 1, 2, 3], [4, 5, 6, 7]]);
        let r = check_tets(&m, None);
        assert_eq!(r.coincident_vertices, 3);
        // welded, the faces pair up: only the duplicates tell the crack
        assert_eq!((r.interior_faces, r.boundary_triangles), (1, 6));
        assert!(r.boundary_closed && r.volume_matches);
        assert!(!r.conforming && !r.valid);
    }

    #[test]
    fn a_hanging_vertex_is_not_conforming() {
        // Big tetrahedron on face ABC (apex below), two small ones on ABM and AMC (apex above),
        // with M the midpoint of BC: M hangs on the big tetrahedron's edge BC.
        let m_ = [0.5, 0.5, 0.0];
        let below = [0.2, 0.2, -1.0];
        let above = [0.2, 0.2, 1.0];
        let m = positive_mesh(
            &[A, B, C, m_, below, above],
            &[[0, 1, 2, 4], [0, 1, 3, 5], [0, 3, 2, 5]],
        );
        let r = check_tets(&m, None);
        assert_eq!(
            (r.inverted, r.flat, r.faces_used_more_than_twice),
            (0, 0, 0)
        );
        assert_eq!(r.interior_faces, 1); // AM between the two small ones
        assert!(r.volume_matches); // the cracked sheet encloses nothing
                                   // ABC against ABM and AMC: edge AB in four boundary triangles, coplanar overlaps
        assert!(!r.boundary_manifold && r.boundary_nonmanifold_edges > 0);
        assert!(r.boundary_self_intersections > 0);
        assert!(!r.conforming && !r.valid);
    }

    #[test]
    fn a_surface_that_differs_is_reported() {
        let m = two_tets();
        let surface = boundary_of(&m);

        let mut one_less = surface.clone();
        one_less.triangles.pop();
        let r = check_tets(&m, Some(&one_less));
        let s = r.surface.as_ref().unwrap();
        assert_eq!(
            (s.surface_triangles_missing, s.boundary_triangles_extra),
            (0, 1)
        );
        assert!(!s.boundary_equals_surface && r.conforming && !r.valid);

        let mut other = surface.clone();
        other.vertices.push([2.0, 2.0, 2.0]);
        other.triangles[0][0] = 5;
        let s = check_tets(&m, Some(&other)).surface.unwrap();
        assert_eq!(
            (s.surface_triangles_missing, s.boundary_triangles_extra),
            (1, 1)
        );

        let mut flipped = surface.clone();
        flipped.triangles[2].swap(1, 2);
        let r = check_tets(&m, Some(&flipped));
        let s = r.surface.as_ref().unwrap();
        assert_eq!(
            (s.surface_triangles_missing, s.boundary_triangles_extra),
            (0, 0)
        );
        assert_eq!(s.orientation_mismatches, 1);
        assert!(!s.boundary_equals_surface && !r.valid);

        // matched by position, not index: the same surface with its own vertex numbering
        let mut renumbered = surface.clone();
        renumbered.vertices.reverse();
        let n = renumbered.vertices.len() as u32;
        for t in &mut renumbered.triangles {
            *t = t.map(|v| n - 1 - v);
        }
        assert!(check_tets(&m, Some(&renumbered)).valid);
    }

    #[test]
    fn an_index_out_of_range_is_counted_not_a_panic() {
        let mut m = two_tets();
        m.tets.push([0, 1, 2, 9]);
        let r = check_tets(&m, None);
        assert_eq!((r.tets, r.index_out_of_range), (3, 1));
        assert!(!r.conforming && !r.valid);
    }

    #[test]
    fn an_empty_mesh_is_invalid_without_panicking() {
        let r = check_tets(&TetMesh::default(), Some(&TriMesh::default()));
        assert_eq!((r.points, r.tets, r.boundary_triangles), (0, 0, 0));
        assert!(!r.valid);
    }
}
