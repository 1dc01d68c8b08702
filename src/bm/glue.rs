//! Gluing the cells' complexes into one solid.
//!
//! Two cells may triangulate a shared face differently (their Delaunay triangulations break the
//! massive cocircularity of a section independently, and each has its own branching samples), so
//! section triangles are never matched across cells. Per face with a section, with cells A and B on
//! its two sides and X_A, X_B the section triangles each attaches to (a kept tet stands on them):
//! * both attach somewhere: the output is the oriented symmetric difference of X_A and X_B, from a
//!   2D overlay in the plane's (u,v) frame (`face_overlay`): where only A attaches, that region
//!   oriented outward from A; only B: outward from B; both: interior; neither: a flat zone, reported
//!   with its area. Vertices created where the two sides' edges cross are new global vertices (the
//!   plane frame applied to their (u,v)), and every output triangle on an edge that received vertices
//!   is split (`split_at_edges`), so the surface has no T-junctions. When the overlay is
//!   inconsistent (a triangle folded in (u,v), two vertices at one (u,v), …) the face falls back to
//!   each side's own unattached triangles oriented into its cell (closed as a chain, but two sheets
//!   may remain where neither attaches), with a warning.
//! * only A attaches: A's attached triangles are output, oriented outward from A.
//! * neither attaches: the whole section is a flat zone, not output, reported with its area.
//!
//! Where pieces touch along edges or at vertices (singularities), `unpinch` splits vertices with one
//! sheet pairing decided per edge; branching samples on the surface are lifted off the plane
//! (`lift_samples`), except where their star lies in one face's section (a cap, or where only one
//! side attaches: no other diagram can cross them there).
//!
//! All vertices are global (pool ids, Steiner points, then branching samples), so the pieces weld.
//! The tetrahedral mesh is the union of the kept tets; it is non-conforming across a face where the
//! two cells' section triangulations differ (counted in the report).
use super::cell::CellResult;
use super::face_overlay::{overlay, overlay_with_section, Overlay};
use super::thicken::{thicken, Zone};
use crate::arrangement::{Arrangement, VertexPool};
use crate::fxhash::{FxHashMap, FxHashSet};
use crate::mesh::{Stars, TetMesh, TriMesh};
use rayon::prelude::*;
use std::collections::HashMap;

/// First id of the vertices an overlay creates while the faces are overlaid in parallel (above every
/// global id; renumbered from the current vertex count when the face is assembled).
const OVERLAY_BASE: u32 = 1 << 31;

/// A face's overlay, and the one with the section layer when the first shows a flat zone.
type OverlayOutcome = (
    Result<(Overlay, f64), String>,
    Option<Result<(Overlay, f64), String>>,
);

#[derive(Clone, Debug, Default)]
pub struct Glued {
    pub surface: TriMesh,
    pub tets: TetMesh,
    pub warnings: Vec<String>,
    pub flat_zone_faces: u64,
    pub flat_zone_area: f64,
    pub double_sheet_triangles: u64,
    pub nonconforming_faces: u64,
    pub pinched_vertices: u64,
    /// Faces whose output is the overlay of the two sides' attached regions.
    pub overlay_faces: u64,
    /// Vertices created where the two sides' triangle edges cross.
    pub overlay_vertices: u64,
    /// Faces where the overlay failed and each side's unattached triangles were kept.
    pub overlay_fallbacks: u64,
    /// Displaced vertices moved to another candidate position because the first one crossed the surface.
    pub lifts_redirected: u64,
    /// Diagram samples not lifted off their plane: their star lies in one face's section.
    pub samples_kept_on_plane: u64,
    /// Connected flat zones thickened into a thin slab (`thicken`), and their total area.
    pub flat_zones_thickened: u64,
    pub flat_zone_area_thickened: f64,
    /// Connected flat zones that could not be thickened (left out of the solid).
    pub flat_zones_left: u64,
    /// Wall time of each gluing step, in the order run (reported as `glue_seconds.<step>`).
    pub timings: Vec<(&'static str, f64)>,
}

/// Wall time of consecutive steps: `lap(name)` records the time since the previous lap.
struct Laps {
    last: std::time::Instant,
}

impl Laps {
    fn new() -> Self {
        Laps {
            last: std::time::Instant::now(),
        }
    }
    fn lap(&mut self, name: &'static str, out: &mut Vec<(&'static str, f64)>) {
        let now = std::time::Instant::now();
        out.push((name, (now - self.last).as_secs_f64()));
        self.last = now;
    }
}

/// Unit normal of face `f`'s plane pointing into cell `c` (zero when `c` is not on the face).
fn into_cell(arr: &Arrangement, f: u32, c: u32) -> [f64; 3] {
    let face = &arr.faces[f as usize];
    let n = arr.planes[face.plane as usize].plane.normal;
    if face.positive_cell == Some(c) {
        n
    } else if face.negative_cell == Some(c) {
        [-n[0], -n[1], -n[2]]
    } else {
        [0.0; 3]
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Kind {
    /// Boundary triangle inside this cell.
    Cell(u32),
    /// Section triangle on this face.
    Face(u32),
}

/// The cell-local vertices (diagram samples) on a face: (global id, unit direction into their
/// cell, face).
fn cell_local_samples(
    results: &[Option<CellResult>],
    maps: &[Vec<u32>],
) -> Vec<(u32, [f64; 3], u32)> {
    let mut samples = Vec::new();
    for (c, r) in results.iter().enumerate() {
        let Some(inp) = r.as_ref().and_then(|r| r.input.as_ref()) else {
            continue;
        };
        for (l, &gid) in inp.global.iter().enumerate() {
            if gid != u32::MAX {
                continue;
            }
            if let Some(s) = (0..inp.slots.len()).find(|&s| inp.mask[l] >> s & 1 == 1) {
                let slot = &inp.slots[s];
                let n = slot.geom.normal;
                let d = if slot.outward_is_plane_normal {
                    -1.0
                } else {
                    1.0
                };
                samples.push((maps[c][l], [d * n[0], d * n[1], d * n[2]], slot.face));
            }
        }
    }
    samples
}

pub(super) fn tri_area(p: &[[f64; 3]], t: [u32; 3]) -> f64 {
    let (a, b, c) = (p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]);
    let u = crate::sections::sub(b, a);
    let v = crate::sections::sub(c, a);
    let w = crate::sections::cross(u, v);
    0.5 * crate::sections::dot(w, w).sqrt()
}

/// Glue the cells' results into one surface and tetrahedral mesh; `thicken_flat_zones` thickens flat zones
/// (else they are left out and warned).
pub fn glue(
    arr: &Arrangement,
    pool: &VertexPool,
    results: &[Option<CellResult>],
    thicken_flat_zones: bool,
) -> Glued {
    let mut g = Glued::default();
    let mut laps = Laps::new();
    let mut positions = pool.positions.clone();
    // global id per cell-local vertex (branching samples get new ids)
    let maps = super::assembly::global_maps(results, &mut positions);
    // branching samples: (global id, unit direction into their cell, face)
    let samples = cell_local_samples(results, &maps);
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let mut kind: Vec<Kind> = Vec::new();
    let mut tets: Vec<[u32; 4]> = Vec::new();
    let map3 = |m: &[u32], t: [u32; 3]| [m[t[0] as usize], m[t[1] as usize], m[t[2] as usize]];
    // per face: (cell, side data)
    let mut sides: HashMap<u32, Vec<(usize, usize)>> = HashMap::new();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r else { continue };
        let m = &maps[c];
        tris.extend(r.nonplanar.iter().map(|&t| map3(m, t)));
        kind.resize(tris.len(), Kind::Cell(c as u32));
        tets.extend(r.kept.iter().map(|t| {
            [
                m[t[0] as usize],
                m[t[1] as usize],
                m[t[2] as usize],
                m[t[3] as usize],
            ]
        }));
        if !r.flat_only {
            for (s, fs) in r.faces.iter().enumerate() {
                sides.entry(fs.face).or_default().push((c, s));
            }
        }
    }
    // A cell without volume contributes its sections only to faces no cell with volume has: there
    // they are flat zones (e.g. a single section, or one between empty planes), thickened like any.
    let mut flat_sides: HashMap<u32, Vec<(usize, usize)>> = HashMap::new();
    for (c, r) in results.iter().enumerate() {
        let Some(r) = r.as_ref().filter(|r| r.flat_only) else {
            continue;
        };
        for (s, fs) in r.faces.iter().enumerate() {
            if !sides.contains_key(&fs.face) && !fs.triangles.is_empty() {
                flat_sides.entry(fs.face).or_default().push((c, s));
            }
        }
    }
    sides.extend(flat_sides);
    laps.lap("collect", &mut g.timings);
    // original edge (min, max) → vertices the face overlays put inside it, from min to max
    let mut edge_splits: FxHashMap<(u32, u32), Vec<u32>> = FxHashMap::default();
    // flat zones attached from neither side, thickened after the faces are assembled
    let mut zones: Vec<Zone> = Vec::new();
    let mut face_ids: Vec<u32> = sides.keys().copied().collect();
    face_ids.sort_unstable();
    // The overlays of faces attached from both sides are independent: computed in parallel with
    // new vertices numbered from OVERLAY_BASE, renumbered in face order below (same ids as a
    // sequential run).
    let attached = |&(c, s): &(usize, usize)| {
        results[c].as_ref().unwrap().faces[s]
            .triangles
            .iter()
            .any(|t| t.1)
    };
    // largest first (by triangles on both sides), so that a big face does not start last and
    // leave the other threads idle; the results are keyed by face, whatever the order
    let mut to_overlay: Vec<(usize, u32)> = face_ids
        .iter()
        .filter(|f| sides[f].iter().filter(|cs| attached(cs)).count() >= 2)
        .map(|&f| {
            let size = sides[&f]
                .iter()
                .map(|&(c, s)| results[c].as_ref().unwrap().faces[s].triangles.len())
                .sum::<usize>();
            (size, f)
        })
        .collect();
    to_overlay.sort_unstable_by(|x, y| y.cmp(x));
    let mut overlays: HashMap<u32, OverlayOutcome> = to_overlay
        .par_iter()
        .map(|&(_, f)| {
            let list = &sides[&f];
            let first = overlay_face(pool, results, &maps, list, OVERLAY_BASE, false);
            // a flat zone: again with the whole section as a third layer, to get its triangles
            let with_zone = match &first {
                Ok((o, section_area)) if section_area - o.attached_area > 1e-9 * section_area => {
                    Some(overlay_face(pool, results, &maps, list, OVERLAY_BASE, true))
                }
                _ => None,
            };
            (f, (first, with_zone))
        })
        .collect();
    laps.lap("overlay", &mut g.timings);
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
                    zones.push(Zone {
                        face: f,
                        plane: arr.faces[f as usize].plane,
                        area,
                        cells: list
                            .iter()
                            .map(|&(c, _)| (c as u32, into_cell(arr, f, c as u32)))
                            .collect(),
                        tris: list
                            .iter()
                            .map(|cs| {
                                side(cs)
                                    .triangles
                                    .iter()
                                    .map(|t| map3(&maps[cs.0], t.0))
                                    .collect()
                            })
                            .collect(),
                    });
                }
            }
            1 => {
                let (c, s) = *attaching[0];
                let mut flat = 0.0;
                let mut zone = Vec::new();
                for &(t, att) in &results[c].as_ref().unwrap().faces[s].triangles {
                    if att {
                        tris.push(map3(&maps[c], t));
                        kind.push(Kind::Face(f));
                    } else {
                        flat += tri_area(&positions, map3(&maps[c], t));
                        zone.push(map3(&maps[c], t));
                    }
                }
                if flat > 0.0 {
                    g.flat_zone_faces += 1;
                    g.flat_zone_area += flat;
                    zones.push(Zone {
                        face: f,
                        plane: arr.faces[f as usize].plane,
                        area: flat,
                        cells: vec![(c as u32, into_cell(arr, f, c as u32))],
                        tris: vec![zone],
                    });
                }
            }
            _ => {
                let face = &arr.faces[f as usize];
                let plane = &arr.planes[face.plane as usize].plane;
                let (first, second) = overlays.remove(&f).expect("overlay computed");
                let renumber = |r: Result<(Overlay, f64), String>| {
                    r.map(|(o, a)| (o.renumbered(OVERLAY_BASE, positions.len() as u32), a))
                };
                let first = renumber(first);
                let with_zone = match second {
                    None => None,
                    Some(r) => match renumber(r) {
                        Ok(r) => Some(r),
                        Err(why) => {
                            g.warnings.push(format!(
                                    "face {f} (plane {}): overlay with the section layer failed ({why}); its flat zone is not thickened",
                                    face.plane
                                ));
                            None
                        }
                    },
                };
                let zone_found = with_zone.is_some();
                match with_zone.map(Ok).unwrap_or(first) {
                    Ok((o, section_area)) => {
                        g.overlay_faces += 1;
                        g.overlay_vertices += o.new_vertices.len() as u64;
                        positions.extend(o.new_vertices.iter().map(|&q| plane.to_3d(q)));
                        tris.extend(o.triangles.iter().copied());
                        kind.resize(tris.len(), Kind::Face(f));
                        for (e, chain) in o.splits {
                            edge_splits.entry(e).or_insert(chain);
                        }
                        let flat = section_area - o.attached_area;
                        if flat > 1e-9 * section_area {
                            g.flat_zone_faces += 1;
                            g.flat_zone_area += flat;
                            if zone_found && !o.flat.is_empty() {
                                zones.push(Zone {
                                    face: f,
                                    plane: face.plane,
                                    area: flat,
                                    cells: list
                                        .iter()
                                        .map(|&(c, _)| (c as u32, into_cell(arr, f, c as u32)))
                                        .collect(),
                                    tris: vec![o.flat.clone()],
                                });
                            } else {
                                g.flat_zones_left += 1;
                                g.warnings.push(format!(
                                    "face {f} (plane {}): flat zone of area {flat:.4e} attached from neither side (not in the solid)",
                                    face.plane
                                ));
                            }
                        }
                    }
                    Err(why) => {
                        // each side's own unattached triangles (closed as a chain; may leave two
                        // sheets where neither side attaches)
                        g.overlay_fallbacks += 1;
                        g.warnings.push(format!(
                            "face {f} (plane {}): overlay of the two sides failed ({why}); each side's unattached triangles kept",
                            face.plane
                        ));
                        for &(c, s) in list {
                            for &(t, att) in &results[c].as_ref().unwrap().faces[s].triangles {
                                if !att {
                                    let t = map3(&maps[c], t);
                                    tris.push([t[0], t[2], t[1]]);
                                    kind.push(Kind::Face(f));
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    laps.lap("faces", &mut g.timings);
    split_at_edges(&mut tris, &mut kind, &mut positions, &edge_splits);
    // Cancel coincident opposite triangles (flat-zone sheets triangulated alike on both sides).
    // (sorted triple, index), sorted: the triangles of each triple together, ascending
    let mut by_key: Vec<([u32; 3], usize)> = tris
        .iter()
        .enumerate()
        .map(|(i, &t)| (sorted(t), i))
        .collect();
    by_key.par_sort_unstable();
    let mut drop = vec![false; tris.len()];
    for g in by_key.chunk_by(|x, y| x.0 == y.0) {
        if g.len() < 2 {
            continue;
        }
        let (mut pos, mut neg): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
        for &(_, i) in g {
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
    let (mut tris, kind): (Vec<[u32; 3]>, Vec<Kind>) = tris
        .into_iter()
        .zip(kind)
        .zip(drop)
        .filter(|(_, d)| !d)
        .map(|(t, _)| t)
        .unzip();
    let mut kind = kind;
    laps.lap("split_cancel", &mut g.timings);
    let mut slab_vertices = 0..0u32;
    if !thicken_flat_zones {
        for z in &zones {
            g.flat_zones_left += 1;
            g.warnings.push(format!(
                "face {} (plane {}): flat zone of area {:.4e} attached from neither side (not in the solid; thickening disabled)",
                z.face, z.plane, z.area
            ));
        }
    } else if !zones.is_empty() {
        // the zones' triangles get the same splits as the faces' output
        for z in &mut zones {
            for l in &mut z.tris {
                let mut k = vec![Kind::Face(z.face); l.len()];
                split_at_edges(l, &mut k, &mut positions, &edge_splits);
            }
        }
        let diag = bbox_diagonal(&positions);
        slab_vertices = positions.len() as u32..u32::MAX;
        for o in thicken(
            arr,
            pool,
            &mut positions,
            &mut tris,
            &mut kind,
            &zones,
            diag,
        ) {
            for &(c, area, lo, hi) in &o.thickened {
                g.flat_zones_thickened += 1;
                g.flat_zone_area_thickened += area;
                g.warnings.push(format!(
                    "face {} (plane {}): flat zone of area {area:.4e} attached from neither side, thickened into cell {c} (paper Fig. 12c; slab {lo:.2e}..{hi:.2e} thick)",
                    o.face, o.plane
                ));
            }
            for (area, why) in &o.left {
                g.flat_zones_left += 1;
                g.warnings.push(format!(
                    "face {} (plane {}): flat zone of area {area:.4e} attached from neither side, not thickened ({why}): not in the solid",
                    o.face, o.plane
                ));
            }
        }
    }
    laps.lap("thicken", &mut g.timings);
    slab_vertices.end = slab_vertices.end.min(positions.len() as u32);
    let after_thicken = positions.len() as u32;
    let before_lift = positions.clone();
    let mut copies = Vec::new();
    let split = unpinch(arr, &mut positions, &mut tris, &kind, &mut copies);
    g.pinched_vertices = split.len() as u64;
    laps.lap("unpinch", &mut g.timings);
    // vertices from here on (slab copies, pinch copies) may be off their plane
    let first_off_plane = if slab_vertices.start < slab_vertices.end {
        slab_vertices.start
    } else {
        after_thicken
    };
    g.samples_kept_on_plane = lift_samples(
        &mut positions,
        &tris,
        &kind,
        &samples,
        &split,
        first_off_plane,
    );
    let mut crease_mids = Vec::new();
    let n_split_edges = split_mixed_edges(&mut positions, &mut tris, &mut kind, &mut crease_mids);
    if n_split_edges > 0 {
        g.warnings.push(format!(
            "{n_split_edges} edges where a crease met a section were split, the crease's side displaced into its cell"
        ));
    }
    laps.lap("lift_split_mixed", &mut g.timings);
    // every displaced vertex with the position it was displaced from
    let moved: Vec<(u32, [f64; 3])> = (0..before_lift.len())
        .filter(|&v| positions[v] != before_lift[v])
        .map(|v| (v as u32, before_lift[v]))
        .chain(copies.iter().map(|&(c, v)| (c, before_lift[v as usize])))
        .chain(crease_mids.iter().copied())
        .collect();
    let untangled = super::untangle::untangle(&mut positions, &tris, &moved);
    laps.lap("untangle", &mut g.timings);
    g.lifts_redirected = untangled.redirected;
    if untangled.unresolved > 0 {
        g.warnings.push(format!(
            "{} displaced vertices still make their triangles cross others (no candidate position was free)",
            untangled.unresolved
        ));
    }
    if g.pinched_vertices > 0 {
        g.warnings.push(format!(
            "{} vertices where the solid touched a section from above only (branching on an unattached side) were lifted off the plane (paper Fig. 12b)",
            g.pinched_vertices
        ));
    }
    g.double_sheet_triangles = count_double_sheet(positions.len(), &tris);
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
    laps.lap("double_sheet", &mut g.timings);
    let collapsed = collapse_micro_edges(
        pool,
        &positions,
        &mut tris,
        &mut tets,
        MICRO_EDGE * bbox_diagonal(&positions),
    );
    if collapsed > 0 {
        g.warnings.push(format!(
            "{collapsed} surface edges shorter than {MICRO_EDGE:e} of the diagonal collapsed (vertices the arrangement put apart by rounding where several planes nearly meet in one point)"
        ));
    }
    laps.lap("collapse", &mut g.timings);
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
    // the cells' tets have robust::orient3d > 0; TetMesh (and VTK, MEDIT) want positive volume,
    // orient3d < 0: swap the last two vertices
    let tets: Vec<[u32; 4]> = tets
        .iter()
        .map(|t| {
            [
                id(t[0], &mut verts),
                id(t[1], &mut verts),
                id(t[3], &mut verts),
                id(t[2], &mut verts),
            ]
        })
        .collect();
    g.tets = TetMesh {
        vertices: verts,
        tets,
    };
    laps.lap("compact", &mut g.timings);
    g
}

/// The overlay of a face attached from both sides (`list`: its two (cell, slot) sides), plus the
/// section's area (the larger of the two sides' triangulated areas).
fn overlay_face(
    pool: &VertexPool,
    results: &[Option<CellResult>],
    maps: &[Vec<u32>],
    list: &[(usize, usize)],
    first_new: u32,
    with_section: bool,
) -> Result<(Overlay, f64), String> {
    if list.len() != 2 {
        return Err(format!("{} sides", list.len()));
    }
    let mut uv: FxHashMap<u32, [f64; 2]> = FxHashMap::default();
    let mut x: [Vec<[u32; 3]>; 2] = [Vec::new(), Vec::new()];
    // A's whole triangulation of the section (the third layer, when asked)
    let mut whole: Vec<[u32; 3]> = Vec::new();
    let mut section_area = 0.0f64;
    let mut ccw_a = true;
    // every triangle of each side (global ids, attached, area)
    let mut all: [Vec<([u32; 3], bool, f64)>; 2] = [Vec::new(), Vec::new()];
    for (k, &(c, s)) in list.iter().enumerate() {
        let r = results[c].as_ref().ok_or("cell without result")?;
        let inp = r.input.as_ref().ok_or("cell without input")?;
        let slot = &inp.slots[s];
        if k == 0 {
            ccw_a = slot.outward_is_plane_normal;
        }
        // A vertex on several planes takes the (u,v) of its 3D point (which the cells triangulated),
        // not the pool's (u,v) in this plane: a crossing snapped between two sections (arrangement
        // `reconcile`) sits at their 3D midpoint while each frame keeps its own section's (u,v), so
        // the pool's (u,v) fold the triangles around it. Others keep the pool's (u,v), the exact
        // input coordinates (projecting them would turn exact collinearities into near ones).
        let proj = |l: u32| {
            let g = inp.global[l as usize];
            if g != u32::MAX && pool.tags[g as usize].len() > 1 {
                slot.geom.to_2d(inp.points[l as usize])
            } else {
                slot.uv[l as usize]
            }
        };
        let mut area = 0.0;
        for &(t, att) in &r.faces[s].triangles {
            let q = t.map(proj);
            let a = 0.5
                * ((q[1][0] - q[0][0]) * (q[2][1] - q[0][1])
                    - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]))
                    .abs();
            area += a;
            all[k].push((t.map(|l| maps[c][l as usize]), att, a));
            if k == 0 && with_section {
                for (l, p) in t.into_iter().zip(q) {
                    if !(p[0].is_finite() && p[1].is_finite()) {
                        return Err(format!("local vertex {l} of cell {c} has no (u,v)"));
                    }
                    uv.insert(maps[c][l as usize], p);
                }
                whole.push(t.map(|l| maps[c][l as usize]));
            }
            if !att {
                continue;
            }
            for (l, p) in t.into_iter().zip(q) {
                if !(p[0].is_finite() && p[1].is_finite()) {
                    return Err(format!("local vertex {l} of cell {c} has no position"));
                }
                uv.insert(maps[c][l as usize], p);
            }
            x[k].push(t.map(|l| maps[c][l as usize]));
        }
        section_area = section_area.max(area);
    }
    if let Some(o) = same_triangulation_overlay(&all, with_section) {
        return Ok((o, section_area));
    }
    let o = if with_section {
        overlay_with_section(&uv, &x[0], &x[1], &whole, ccw_a, first_new)?
    } else {
        overlay(&uv, &x[0], &x[1], ccw_a, first_new)?
    };
    Ok((o, section_area))
}

/// The overlay when both sides triangulated the section with the same triangles (about half the
/// overlaid faces of the shared files): triangle by triangle, the symmetric difference of the two
/// attached sets, each kept as its own side stored it (outward from that side), and the triangles
/// attached from neither side as A's (the flat zones, with the section layer). No new vertices, no
/// split edges. `None` when the triangulations differ.
fn same_triangulation_overlay(
    all: &[Vec<([u32; 3], bool, f64)>; 2],
    with_section: bool,
) -> Option<Overlay> {
    if all[0].len() != all[1].len() {
        return None;
    }
    let keyed = |k: usize| {
        let mut v: Vec<([u32; 3], usize)> = all[k]
            .iter()
            .enumerate()
            .map(|(i, (t, _, _))| (sorted(*t), i))
            .collect();
        v.sort_unstable();
        v
    };
    let (ka, kb) = (keyed(0), keyed(1));
    if ka.iter().zip(&kb).any(|(x, y)| x.0 != y.0) {
        return None;
    }
    let mut o = Overlay {
        new_vertices: Vec::new(),
        triangles: Vec::new(),
        splits: Vec::new(),
        attached_area: 0.0,
        output_area: 0.0,
        flat: Vec::new(),
    };
    // in A's order, so the output does not depend on hashing
    let mut b_of_a = vec![0usize; ka.len()];
    for (x, y) in ka.iter().zip(&kb) {
        b_of_a[x.1] = y.1;
    }
    for (i, &(ta, att_a, area)) in all[0].iter().enumerate() {
        let (tb, att_b, _) = all[1][b_of_a[i]];
        match (att_a, att_b) {
            (true, true) => o.attached_area += area,
            (true, false) | (false, true) => {
                o.attached_area += area;
                o.output_area += area;
                o.triangles.push(if att_a { ta } else { tb });
            }
            (false, false) => {
                if with_section {
                    o.flat.push(ta);
                }
            }
        }
    }
    Some(o)
}

/// Splits every triangle that has an edge with vertices inserted on it (by a face overlay), so the
/// surface has no T-junctions: a fan from the opposite corner when one edge is split, else a fan
/// from a new vertex at the triangle's centroid.
fn split_at_edges(
    tris: &mut Vec<[u32; 3]>,
    kind: &mut Vec<Kind>,
    positions: &mut Vec<[f64; 3]>,
    splits: &FxHashMap<(u32, u32), Vec<u32>>,
) {
    if splits.is_empty() {
        return;
    }
    let n = tris.len();
    for i in 0..n {
        let t = tris[i];
        let mut on: [Vec<u32>; 3] = Default::default();
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if let Some(ch) = splits.get(&(a.min(b), a.max(b))) {
                on[k] = ch.clone();
                if a > b {
                    on[k].reverse();
                }
            }
        }
        let split: Vec<usize> = (0..3).filter(|&k| !on[k].is_empty()).collect();
        if split.is_empty() {
            continue;
        }
        let mut pieces: Vec<[u32; 3]> = Vec::new();
        if split.len() == 1 {
            let k = split[0];
            let apex = t[(k + 2) % 3];
            let mut run = vec![t[k]];
            run.extend(on[k].iter().copied());
            run.push(t[(k + 1) % 3]);
            for w in run.windows(2) {
                pieces.push([w[0], w[1], apex]);
            }
        } else {
            let mut ring = Vec::new();
            for k in 0..3 {
                ring.push(t[k]);
                ring.extend(on[k].iter().copied());
            }
            let (a, b, c) = (
                positions[t[0] as usize],
                positions[t[1] as usize],
                positions[t[2] as usize],
            );
            positions.push([
                (a[0] + b[0] + c[0]) / 3.0,
                (a[1] + b[1] + c[1]) / 3.0,
                (a[2] + b[2] + c[2]) / 3.0,
            ]);
            let m = (positions.len() - 1) as u32;
            for j in 0..ring.len() {
                pieces.push([ring[j], ring[(j + 1) % ring.len()], m]);
            }
        }
        tris[i] = pieces[0];
        for p in &pieces[1..] {
            tris.push(*p);
            kind.push(kind[i]);
        }
    }
}

/// Diagonal of the bounding box of `positions`.
fn bbox_diagonal(positions: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let d = crate::sections::sub(hi, lo);
    crate::sections::dot(d, d).sqrt()
}

/// The triangles (indices, ascending) on each undirected edge, keyed `(min, max)`.
/// Surface edges shorter than this fraction of the bounding-box diagonal are collapsed.
const MICRO_EDGE: f64 = 1e-12;

/// Collapses surface edges shorter than `tol`: where several planes nearly meet in one point the
/// arrangement can make vertices 1e-15 apart, and the triangles between them have no area a float
/// consumer can resolve (they showed up as overlapping near-coplanar pairs). An edge a–b is
/// collapsed (b onto a, keeping the vertex on more planes) only when it has two triangles and the
/// link condition holds (the common neighbours of a and b are the two apexes), so the surface
/// stays a closed 2-manifold; tets using b use a, and tets that degenerate are dropped.
fn collapse_micro_edges(
    pool: &VertexPool,
    positions: &[[f64; 3]],
    tris: &mut Vec<[u32; 3]>,
    tets: &mut Vec<[u32; 4]>,
    tol: f64,
) -> usize {
    let len2 = |a: u32, b: u32| {
        let (p, q) = (positions[a as usize], positions[b as usize]);
        (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
    };
    let tags = |v: u32| pool.tags.get(v as usize).map_or(0, |t| t.len());
    let mut done = 0;
    let mut refused: std::collections::HashSet<(u32, u32)> = Default::default();
    loop {
        let short = tris
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .map(|(a, b)| (a.min(b), a.max(b)))
            .filter(|&(a, b)| a != b && len2(a, b) < tol * tol && !refused.contains(&(a, b)))
            .min();
        let Some((x, y)) = short else {
            return done;
        };
        let on_edge: Vec<usize> = (0..tris.len())
            .filter(|&i| tris[i].contains(&x) && tris[i].contains(&y))
            .collect();
        let neighbours = |v: u32| -> std::collections::BTreeSet<u32> {
            tris.iter()
                .filter(|t| t.contains(&v))
                .flat_map(|t| t.iter().copied())
                .filter(|&w| w != v)
                .collect()
        };
        let common: Vec<u32> = neighbours(x)
            .intersection(&neighbours(y))
            .copied()
            .collect();
        let mut apexes: Vec<u32> = on_edge
            .iter()
            .map(|&i| *tris[i].iter().find(|&&w| w != x && w != y).unwrap())
            .collect();
        apexes.sort_unstable();
        if on_edge.len() != 2 || common != apexes {
            refused.insert((x, y));
            continue;
        }
        let (keep, gone) = if tags(y) > tags(x) { (y, x) } else { (x, y) };
        let mut i = 0;
        tris.retain(|_| {
            i += 1;
            !on_edge.contains(&(i - 1))
        });
        for t in tris.iter_mut().flat_map(|t| t.iter_mut()) {
            if *t == gone {
                *t = keep;
            }
        }
        for t in tets.iter_mut().flat_map(|t| t.iter_mut()) {
            if *t == gone {
                *t = keep;
            }
        }
        tets.retain(|t| (0..4).all(|i| (i + 1..4).all(|j| t[i] != t[j])));
        done += 1;
    }
}

pub(super) fn sorted(mut t: [u32; 3]) -> [u32; 3] {
    t.sort_unstable();
    t
}

/// Even permutation of the sorted triple.
pub(super) fn parity(t: [u32; 3]) -> bool {
    let inv = (t[0] > t[1]) as u8 + (t[0] > t[2]) as u8 + (t[1] > t[2]) as u8;
    inv.is_multiple_of(2)
}

/// Triangles on an edge used by more than two triangles (a sign of overlapping sheets).
fn count_double_sheet(n_vertices: usize, tris: &[[u32; 3]]) -> u64 {
    let mut on = vec![false; tris.len()];
    for (_, l) in crowded_edges(&Stars::new(n_vertices, tris), tris) {
        for (i, _) in l {
            on[i] = true;
        }
    }
    on.iter().filter(|&&x| x).count() as u64
}

/// Where the solid touches a section plane from one side only (branching on a side the other cell
/// does not attach to, paper Fig. 12), or two pieces meet along an edge, the surface is pinched: the
/// triangles around a vertex form several fans. Every edge used by more than two triangles first gets
/// one pairing of its triangles into sheets, decided once for the edge so that both its endpoints
/// agree (otherwise the two endpoints split the edge's triangles differently and open the surface):
/// by kind when every kind (planar on one face, non-planar of one cell) holds exactly two of them,
/// else by angular order around the edge, each triangle with its neighbour across the solid's wedge
/// (`pair_around_edges` pass 0) or, where that leaves the edge's sheets in one fan at both endpoints,
/// across the void's (pass 1); an edge with no usable pairing keeps its triangles together. Fans are
/// then the classes of the triangles around a vertex joined through two-triangle edges and paired
/// triangles. Every fan but the one with the most planar triangles gets its own copy of the vertex,
/// lifted by a millionth of the shortest incident edge into its cell when the fan is non-planar (the
/// paper's remedy: displace slightly into the cell). Returns the split vertices.
fn unpinch(
    arr: &Arrangement,
    positions: &mut Vec<[f64; 3]>,
    tris: &mut [[u32; 3]],
    kind: &[Kind],
    copies: &mut Vec<(u32, u32)>,
) -> FxHashSet<u32> {
    let at: Stars<usize> = Stars::new(positions.len(), tris);
    let crowded = crowded_edges(&at, tris);
    let partners = pair_around_edges(positions, tris, &crowded);
    // the triangles of each edge used by more than two (ascending; a triangle using the edge twice
    // is listed twice)
    let edges: FxHashMap<(u32, u32), Vec<usize>> = crowded
        .iter()
        .map(|(e, l)| (*e, l.iter().map(|u| u.0).collect()))
        .collect();
    let forward = |i: usize, a: u32, b: u32| {
        let t = tris[i];
        (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b)
    };
    let mut choice: FxHashMap<(u32, u32), Pairing> = FxHashMap::default();
    for (&(a, b), l) in &edges {
        let mut by_kind: FxHashMap<Kind, Vec<usize>> = FxHashMap::default();
        for &i in l {
            by_kind.entry(kind_key(kind[i])).or_default().push(i);
        }
        let kind_ok = by_kind
            .values()
            .all(|g| g.len() == 2 && forward(g[0], a, b) != forward(g[1], a, b));
        let angle_ok = l.iter().all(|&i| {
            let k = slot_of(&tris[i], a, b);
            partners[0].contains_key(&(i, k)) && partners[1].contains_key(&(i, k))
        });
        let c = if kind_ok && by_kind.len() > 1 {
            Pairing::Kind
        } else if angle_ok {
            Pairing::Angle(0)
        } else if kind_ok {
            Pairing::Kind
        } else {
            Pairing::Together
        };
        choice.insert((a, b), c);
    }
    let fans = Fans {
        at: &at,
        tris,
        kind,
        partners: &partners,
    };
    // an angular pairing that separates nothing at either endpoint: try the other side's wedges
    let mut keys: Vec<(u32, u32)> = choice.keys().copied().collect();
    keys.sort_unstable();
    for _ in 0..2 {
        let mut changed = false;
        for &e in &keys {
            if choice[&e] != Pairing::Angle(0) {
                continue;
            }
            let l = &edges[&e];
            let separated = [e.0, e.1].iter().any(|&v| {
                let fans = fans.of(v, &choice);
                let f0 = fans.iter().position(|f| f.contains(&l[0]));
                l.iter()
                    .any(|&i| fans.iter().position(|f| f.contains(&i)) != f0)
            });
            if !separated {
                choice.insert(e, Pairing::Angle(1));
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let diag = bbox_diagonal(positions);
    // all fans from the original ids, before any vertex is split (independent: in parallel)
    let vs: Vec<u32> = (0..positions.len() as u32)
        .filter(|&v| !at[v as usize].is_empty())
        .collect();
    let all_fans: Vec<(u32, Vec<Vec<usize>>)> = vs
        .par_iter()
        .map(|&v| (v, fans.of(v, &choice)))
        .filter(|(_, f)| f.len() >= 2)
        .collect();
    let mut split = FxHashSet::default();
    for (v, mut fans) in all_fans {
        let list = at[v as usize].to_vec();
        let planar = |f: &Vec<usize>| {
            f.iter()
                .filter(|&&i| matches!(kind[i], Kind::Face(_)))
                .count()
        };
        fans.sort_by_key(|f| (std::cmp::Reverse(planar(f)), f[0]));
        let p = positions[v as usize];
        let mut min_len = f64::INFINITY;
        for &i in &list {
            for &w in &tris[i] {
                if w != v {
                    let d = crate::sections::sub(positions[w as usize], p);
                    let l = crate::sections::dot(d, d).sqrt();
                    // edges to coincident vertices (duplicates within rounding) do not count
                    if l > 1e-9 * diag {
                        min_len = min_len.min(l);
                    }
                }
            }
        }
        // a millionth of the model's size (so that welding equal positions to ~1e-8 keeps the copies
        // apart), but never more than a hundredth of the shortest incident edge
        let delta = if min_len.is_finite() {
            (1e-6 * diag).min(1e-2 * min_len).max(1e-6 * min_len)
        } else {
            1e-6 * diag
        };
        for fan in &fans[1..] {
            // lift direction: into the cell of a purely non-planar fan, when the vertex lies on a
            // face of that cell with planar output here; otherwise the copy stays in place
            let mut dir = [0.0; 3];
            let cells: Vec<u32> = fan
                .iter()
                .filter_map(|&i| match kind[i] {
                    Kind::Cell(c) => Some(c),
                    _ => None,
                })
                .collect();
            if planar(fan) == 0 && cells.iter().all(|&c| c == cells[0]) {
                let c = cells[0];
                if let Some(f) = list.iter().find_map(|&i| match kind[i] {
                    Kind::Face(f) => Some(f),
                    _ => None,
                }) {
                    let face = &arr.faces[f as usize];
                    let n = arr.planes[face.plane as usize].plane.normal;
                    if face.positive_cell == Some(c) {
                        dir = n;
                    } else if face.negative_cell == Some(c) {
                        dir = [-n[0], -n[1], -n[2]];
                    }
                }
            }
            if dir == [0.0; 3] {
                // elsewhere towards the fan's own triangles, so that the copies do not coincide
                // (a consumer welding equal positions would pinch the surface again)
                dir = fan_direction(positions, tris, fan, v);
            }
            positions.push([
                p[0] + delta * dir[0],
                p[1] + delta * dir[1],
                p[2] + delta * dir[2],
            ]);
            let id = (positions.len() - 1) as u32;
            copies.push((id, v));
            for &i in fan {
                for w in tris[i].iter_mut() {
                    if *w == v {
                        *w = id;
                    }
                }
            }
        }
        split.insert(v);
    }
    split
}

/// How the triangles of an edge used by more than two triangles are paired into sheets.
#[derive(Clone, Copy, PartialEq)]
enum Pairing {
    /// Triangles of one kind together.
    Kind,
    /// Angular neighbours (`pair_around_edges` pass).
    Angle(usize),
    /// All in one sheet.
    Together,
}

/// An edge (min, max) used by more than two triangles, with its uses (triangle, slot k of the edge
/// t[k]–t[k+1]).
type CrowdedEdge = ((u32, u32), Vec<(usize, u8)>);

/// Every edge (min, max) used by more than two triangles, ascending, with its uses (triangle, slot
/// k of the edge t[k]–t[k+1]) ascending: found around each edge's smaller endpoint, in parallel.
fn crowded_edges(at: &Stars<usize>, tris: &[[u32; 3]]) -> Vec<CrowdedEdge> {
    let n = at.len();
    let chunks: Vec<Vec<CrowdedEdge>> = (0..n.div_ceil(4096))
        .into_par_iter()
        .map(|c| {
            let mut out = Vec::new();
            let mut uses: Vec<(u32, usize, u8)> = Vec::new();
            for v in (c * 4096) as u32..((c + 1) * 4096).min(n) as u32 {
                uses.clear();
                let mut prev = usize::MAX;
                for &i in &at[v as usize] {
                    if i == prev {
                        continue;
                    }
                    prev = i;
                    let t = tris[i];
                    for k in 0..3 {
                        let (a, b) = (t[k], t[(k + 1) % 3]);
                        if a.min(b) == v {
                            uses.push((a.max(b), i, k as u8));
                        }
                    }
                }
                uses.sort_unstable();
                for g in uses.chunk_by(|x, y| x.0 == y.0) {
                    if g.len() > 2 {
                        out.push(((v, g[0].0), g.iter().map(|u| (u.1, u.2)).collect()));
                    }
                }
            }
            out
        })
        .collect();
    chunks.concat()
}

/// What the fans of a vertex are computed from (`unpinch`).
struct Fans<'a> {
    at: &'a Stars<usize>,
    tris: &'a [[u32; 3]],
    kind: &'a [Kind],
    partners: &'a [FxHashMap<(usize, u8), usize>; 2],
}

impl Fans<'_> {
    /// The sheets of crowded edge `e` (triangles `l`, ascending), as pairs of triangles to join.
    fn sheet_links(&self, e: (u32, u32), l: &[usize], c: Pairing) -> Vec<(usize, usize)> {
        match c {
            Pairing::Together => l.windows(2).map(|w| (w[0], w[1])).collect(),
            Pairing::Kind => {
                let mut out = Vec::new();
                for x in 0..l.len() {
                    for y in x + 1..l.len() {
                        if kind_key(self.kind[l[x]]) == kind_key(self.kind[l[y]]) {
                            out.push((l[x], l[y]));
                        }
                    }
                }
                out
            }
            Pairing::Angle(pass) => l
                .iter()
                .map(|&i| {
                    (
                        i,
                        self.partners[pass][&(i, slot_of(&self.tris[i], e.0, e.1))],
                    )
                })
                .collect(),
        }
    }

    /// Fans of `v`: classes of its star's triangles (indices into tris, each class ascending, the
    /// classes sorted) joined through two-triangle edges and the sheets of crowded edges.
    fn of(&self, v: u32, choice: &FxHashMap<(u32, u32), Pairing>) -> Vec<Vec<usize>> {
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        let list = &self.at[v as usize];
        // first position of triangle i in the (ascending) star
        let pos = |i: usize| {
            let p = list.partition_point(|&j| j < i);
            (list.get(p) == Some(&i)).then_some(p)
        };
        let mut parent: Vec<usize> = (0..list.len()).collect();
        // (other endpoint, triangle) per use of an edge at v: grouped, each group is the edge's
        // triangle list
        let mut uses: Vec<(u32, usize)> = Vec::new();
        let mut prev = usize::MAX;
        for &i in list {
            if i == prev {
                continue;
            }
            prev = i;
            let t = self.tris[i];
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if a == v && b != v {
                    uses.push((b, i));
                } else if b == v && a != v {
                    uses.push((a, i));
                }
            }
        }
        uses.sort_unstable();
        let mut l: Vec<usize> = Vec::new();
        for g in uses.chunk_by(|x, y| x.0 == y.0) {
            let w = g[0].0;
            let e = (v.min(w), v.max(w));
            l.clear();
            l.extend(g.iter().map(|u| u.1));
            let links = match choice.get(&e) {
                Some(&c) => self.sheet_links(e, &l, c),
                None if l.len() == 2 => vec![(l[0], l[1])],
                None => Vec::new(),
            };
            for (x, y) in links {
                if let (Some(x), Some(y)) = (pos(x), pos(y)) {
                    let (x, y) = (find(&mut parent, x), find(&mut parent, y));
                    parent[x] = y;
                }
            }
        }
        let mut slot = vec![usize::MAX; list.len()];
        let mut fans: Vec<Vec<usize>> = Vec::new();
        for (k, &i) in list.iter().enumerate() {
            let r = find(&mut parent, k);
            if slot[r] == usize::MAX {
                slot[r] = fans.len();
                fans.push(Vec::new());
            }
            fans[slot[r]].push(i);
        }
        fans.sort();
        fans
    }
}

/// An edge still used by four triangles after `unpinch` — two non-planar ones of one cell (a crease)
/// and two section triangles of one face — keeps both sheets in one fan at both endpoints, so no
/// vertex split separates them. The edge is split at its midpoint instead, with a separate midpoint for
/// the crease displaced a thousandth of the edge towards the crease's other vertices (into its cell):
/// the two sheets then share only the edge's endpoints. Returns the number of edges split; the crease
/// midpoints are added to `moved` (with the midpoint they came from) so that `untangle` checks them.
fn split_mixed_edges(
    positions: &mut Vec<[f64; 3]>,
    tris: &mut Vec<[u32; 3]>,
    kind: &mut Vec<Kind>,
    moved: &mut Vec<(u32, [f64; 3])>,
) -> usize {
    let crowded = crowded_edges(&Stars::new(positions.len(), tris), tris);
    let mut todo: Vec<((u32, u32), Vec<usize>)> = crowded
        .into_iter()
        .map(|(e, l)| (e, l.into_iter().map(|u| u.0).collect::<Vec<usize>>()))
        .filter(|(_, l)| {
            l.len() == 4 && {
                let cells: Vec<&usize> = l
                    .iter()
                    .filter(|&&i| matches!(kind[i], Kind::Cell(_)))
                    .collect();
                let faces: Vec<&usize> = l
                    .iter()
                    .filter(|&&i| matches!(kind[i], Kind::Face(_)))
                    .collect();
                cells.len() == 2
                    && faces.len() == 2
                    && kind[*cells[0]] == kind[*cells[1]]
                    && kind[*faces[0]] == kind[*faces[1]]
            }
        })
        .collect();
    todo.sort_unstable();
    let mut touched = std::collections::HashSet::new();
    let mut n = 0;
    for ((a, b), l) in todo {
        // one split per triangle (a triangle on two such edges waits for another run)
        if l.iter().any(|i| touched.contains(i)) {
            continue;
        }
        let (pa, pb) = (positions[a as usize], positions[b as usize]);
        let mid = [0, 1, 2].map(|k| 0.5 * (pa[k] + pb[k]));
        positions.push(mid);
        let m_face = (positions.len() - 1) as u32;
        // crease midpoint: towards the crease triangles' apexes
        let apexes: Vec<[f64; 3]> = l
            .iter()
            .filter(|&&i| matches!(kind[i], Kind::Cell(_)))
            .map(|&i| {
                let w = tris[i]
                    .iter()
                    .copied()
                    .find(|&w| w != a && w != b)
                    .unwrap_or(a);
                positions[w as usize]
            })
            .collect();
        let towards = [0, 1, 2].map(|k| 0.5 * (apexes[0][k] + apexes[1][k]) - mid[k]);
        let tl = crate::sections::dot(towards, towards).sqrt();
        let e = crate::sections::sub(pb, pa);
        let len = crate::sections::dot(e, e).sqrt();
        let m_cell_pos = if tl > 0.0 {
            [0, 1, 2].map(|k| mid[k] + 1e-3 * len * towards[k] / tl)
        } else {
            mid
        };
        positions.push(m_cell_pos);
        let m_cell = (positions.len() - 1) as u32;
        moved.push((m_cell, mid));
        for &i in &l {
            touched.insert(i);
            let m = if matches!(kind[i], Kind::Cell(_)) {
                m_cell
            } else {
                m_face
            };
            let t = tris[i];
            // t = (a, b, w) up to rotation: (a, m, w) and (m, b, w) keep the orientation
            let k = (0..3)
                .find(|&k| (t[k] == a && t[(k + 1) % 3] == b) || (t[k] == b && t[(k + 1) % 3] == a))
                .unwrap_or(0);
            let (p, q, w) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            tris[i] = [p, m, w];
            tris.push([m, q, w]);
            kind.push(kind[i]);
        }
        n += 1;
    }
    n
}

/// Unit direction from `v` into its fan: the mean of the unit vectors to the fan's other vertices
/// (zero when they cancel).
fn fan_direction(positions: &[[f64; 3]], tris: &[[u32; 3]], fan: &[usize], v: u32) -> [f64; 3] {
    use crate::sections::{dot, sub};
    let p = positions[v as usize];
    let mut d = [0.0; 3];
    for &i in fan {
        for &w in &tris[i] {
            if w != v {
                let e = sub(positions[w as usize], p);
                let l = dot(e, e).sqrt();
                if l > 0.0 {
                    for k in 0..3 {
                        d[k] += e[k] / l;
                    }
                }
            }
        }
    }
    let l = dot(d, d).sqrt();
    if l > 0.0 {
        [d[0] / l, d[1] / l, d[2] / l]
    } else {
        [0.0; 3]
    }
}

/// Kinds compared for pairing (identity; a hook should kinds grow fields).
fn kind_key(k: Kind) -> Kind {
    k
}

/// Slot k of the edge {v, w} in a triangle (the edge t[k], t[k+1]).
fn slot_of(t: &[u32; 3], v: u32, w: u32) -> u8 {
    (0..3)
        .find(|&k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            (a == v && b == w) || (a == w && b == v)
        })
        .unwrap_or(3) as u8
}

/// At every edge used by more than two triangles, pairs each triangle with its angular neighbour on
/// the side of the solid (its inner side): sorted by angle around the edge, a triangle using the
/// edge as a→b has its outward normal towards increasing angle, so the solid wedge lies between it
/// and its predecessor, which must use the edge as b→a ([0]: pairs across the solid's wedges; [1]:
/// across the voids', with the successor). Edges whose order does not alternate (flat sheets, ties)
/// are left out. Key: (triangle, edge slot) → partner triangle.
fn pair_around_edges(
    positions: &[[f64; 3]],
    tris: &[[u32; 3]],
    crowded: &[CrowdedEdge],
) -> [FxHashMap<(usize, u8), usize>; 2] {
    use crate::sections::{cross, dot, sub};
    let mut out = [FxHashMap::default(), FxHashMap::default()];
    for ((a, b), l) in crowded {
        let (a, b) = (*a, *b);
        if l.len() <= 2 || l.len() % 2 == 1 {
            continue;
        }
        let pa = positions[a as usize];
        let e = sub(positions[b as usize], pa);
        let ee = dot(e, e);
        if ee <= 0.0 {
            continue;
        }
        let perp = |i: usize, k: u8| {
            let c = tris[i][(k as usize + 2) % 3];
            let d = sub(positions[c as usize], pa);
            let s = dot(d, e) / ee;
            [d[0] - s * e[0], d[1] - s * e[1], d[2] - s * e[2]]
        };
        let u = perp(l[0].0, l[0].1);
        let w = cross(e, u);
        let mut ang: Vec<(f64, usize, u8, bool)> = l
            .iter()
            .map(|&(i, k)| {
                let p = perp(i, k);
                let forward = tris[i][k as usize] == a; // uses the edge as a→b
                (dot(p, w).atan2(dot(p, u)), i, k, forward)
            })
            .collect();
        ang.sort_by(|x, y| x.0.total_cmp(&y.0));
        let n = ang.len();
        let ties = (0..n).any(|j| ang[j].0 == ang[(j + 1) % n].0);
        let alternates = (0..n).all(|j| ang[j].3 != ang[(j + 1) % n].3);
        if ties || !alternates {
            continue;
        }
        for j in 0..n {
            if ang[j].3 {
                for (pass, p) in [&ang[(j + n - 1) % n], &ang[(j + 1) % n]]
                    .into_iter()
                    .enumerate()
                {
                    out[pass].insert((ang[j].1, ang[j].2), p.1);
                    out[pass].insert((p.1, p.2), ang[j].1);
                }
            }
        }
    }
    out
}

/// The paper's remedy for singular points where the branching diagrams of the two cells of a face
/// cross (Fig. 12a-b): every branching sample (a vertex of one cell only) is displaced into its cell
/// by a millionth of its shortest incident edge, so the two cells' crotch ridges no longer meet on the
/// plane. Vertices already split by `unpinch` stay.
fn lift_samples(
    positions: &mut [[f64; 3]],
    tris: &[[u32; 3]],
    kind: &[Kind],
    samples: &[(u32, [f64; 3], u32)],
    split: &FxHashSet<u32>,
    first_off_plane: u32,
) -> u64 {
    // shortest incident edge per vertex (None: on no triangle)
    let mut shortest: Vec<Option<f64>> = vec![None; positions.len()];
    // the sample's star lies in its own face's section: every incident triangle is a section
    // triangle of that face whose vertices are all on the plane by construction (pool, overlay and
    // sample vertices; not slab or pinch copies, not split vertices)
    let face_of: FxHashMap<u32, u32> = samples.iter().map(|s| (s.0, s.2)).collect();
    let mut planar_star: FxHashMap<u32, bool> = FxHashMap::default();
    for (t, k) in tris.iter().zip(kind) {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            let d = crate::sections::sub(positions[a as usize], positions[b as usize]);
            let l = crate::sections::dot(d, d).sqrt();
            for v in [a, b] {
                let e = shortest[v as usize].get_or_insert(f64::INFINITY);
                *e = e.min(l);
            }
            if let Some(&f) = face_of.get(&t[i]) {
                let on_plane = *k == Kind::Face(f)
                    && t.iter()
                        .all(|&w| w < first_off_plane && !split.contains(&w));
                let e = planar_star.entry(t[i]).or_insert(true);
                *e &= on_plane;
            }
        }
    }
    let mut kept = 0;
    for &(v, d, _) in samples {
        if split.contains(&v) {
            continue;
        }
        let Some(l) = shortest[v as usize] else {
            continue;
        };
        // Inside a region of one face's output (a cap, or where only one side attaches) the sample
        // is an interior point of a flat disk: no diagram of the other cell crosses it there, so
        // there is no singularity to avoid (Fig. 12a/b), and lifting would only dent the section.
        if planar_star.get(&v).copied().unwrap_or(false) {
            kept += 1;
            continue;
        }
        let delta = 1e-6 * l;
        let p = &mut positions[v as usize];
        for k in 0..3 {
            p[k] += delta * d[k];
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge_triangles(tris: &[[u32; 3]]) -> HashMap<(u32, u32), Vec<usize>> {
        let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
        for (i, t) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges.entry((a.min(b), a.max(b))).or_default().push(i);
            }
        }
        edges
    }

    #[test]
    fn micro_edge_is_collapsed_and_the_surface_stays_closed() {
        // a tetrahedron whose edge 0–1 got a vertex 4 at 1e-15 from vertex 0 (the two triangles
        // on that edge split in two): the micro edge 0–4 goes, the tetrahedron comes back
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1e-15, 0.0, 0.0],
        ];
        let mut tris = vec![
            [0, 2, 4],
            [4, 2, 1],
            [0, 4, 3],
            [4, 1, 3],
            [1, 2, 3],
            [0, 3, 2],
        ];
        let mut tets = vec![[0, 4, 2, 3], [4, 1, 2, 3]];
        let pool = VertexPool::default();
        let n = collapse_micro_edges(&pool, &positions, &mut tris, &mut tets, 1e-12 * 3f64.sqrt());
        assert_eq!(n, 1);
        let mut got: Vec<[u32; 3]> = tris.iter().map(|&t| sorted(t)).collect();
        got.sort_unstable();
        assert_eq!(got, vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
        assert!(edge_triangles(&tris).values().all(|l| l.len() == 2));
        // the tet on the micro edge degenerated and is dropped
        assert_eq!(tets, vec![[0, 1, 2, 3]]);
        // nothing shorter than the tolerance: nothing changes
        let before = tris.clone();
        assert_eq!(
            collapse_micro_edges(&pool, &positions, &mut tris, &mut tets, 1e-12),
            0
        );
        assert_eq!(tris, before);
    }

    /// hand.csl: a crease (two triangles of one cell) on an edge shared with two section triangles
    /// kept both sheets in one fan at both endpoints, so the edge stayed non-manifold.
    #[test]
    fn crease_meeting_a_section_edge_is_split_apart() {
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -1.0, 0.0],
            [0.5, 0.5, 1.0],
            [0.5, -0.5, 1.0],
        ];
        let mut tris = vec![[0, 1, 2], [1, 0, 3], [1, 0, 4], [0, 1, 5]];
        let mut kind = vec![Kind::Face(0), Kind::Face(0), Kind::Cell(0), Kind::Cell(0)];
        let mut moved = Vec::new();
        assert_eq!(
            split_mixed_edges(&mut pos, &mut tris, &mut kind, &mut moved),
            1
        );
        assert_eq!((tris.len(), kind.len()), (8, 8));
        let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
        for t in &tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        assert!(uses.values().all(|&c| c <= 2), "{uses:?}");
        // the section keeps the exact midpoint, the crease's copy moved up into its cell
        assert_eq!(pos[6], [0.5, 0.0, 0.0]);
        assert!(pos[7][2] > 0.0 && moved == vec![(7, [0.5, 0.0, 0.0])]);
        // the split triangles cover the same area as before
        let area: f64 = tris[..].iter().map(|&t| tri_area(&pos, t)).sum();
        assert!(
            (area - (0.5 + 0.5 + 2.0 * 0.5 * (1.25f64).sqrt())).abs() < 1e-3,
            "{area}"
        );
    }

    /// The four faces of tetrahedron `t`, oriented outward.
    fn tet_surface(p: &[[f64; 3]], t: [u32; 4]) -> Vec<[u32; 3]> {
        use crate::sections::{cross, dot, sub};
        let vol = |a: u32, b: u32, c: u32, d: u32| {
            let (a, b, c, d) = (p[a as usize], p[b as usize], p[c as usize], p[d as usize]);
            dot(cross(sub(b, a), sub(c, a)), sub(d, a))
        };
        (0..4)
            .map(|i| {
                let f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| t[k]).collect();
                // outward: the opposite vertex is behind the face
                if vol(f[0], f[1], f[2], t[i]) < 0.0 {
                    [f[0], f[1], f[2]]
                } else {
                    [f[0], f[2], f[1]]
                }
            })
            .collect()
    }

    fn edge_uses(tris: &[[u32; 3]]) -> HashMap<(u32, u32), usize> {
        let mut m = HashMap::new();
        for t in tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *m.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        m
    }

    /// Two tetrahedra meeting along the edge 0–1 only: unpinching makes every edge two-sided.
    fn two_tets(kinds: [Kind; 2]) {
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.5, 0.5],
            [1.0, -0.5, 0.5],
            [-1.0, 0.5, 0.5],
            [-1.0, -0.5, 0.5],
        ];
        let mut tris = tet_surface(&pos, [0, 1, 2, 3]);
        let mut kind = vec![kinds[0]; 4];
        tris.extend(tet_surface(&pos, [0, 1, 4, 5]));
        kind.extend([kinds[1]; 4]);
        assert_eq!(edge_uses(&tris)[&(0, 1)], 4);
        let split = unpinch(
            &super::super::empty_arrangement(),
            &mut pos,
            &mut tris,
            &kind,
            &mut Vec::new(),
        );
        assert!(!split.is_empty());
        let uses = edge_uses(&tris);
        assert!(uses.values().all(|&c| c == 2), "{uses:?}");
        // the copies do not coincide with the originals
        for v in 6..pos.len() {
            assert!((0..6).all(|w| pos[w] != pos[v]));
        }
    }

    #[test]
    fn tets_of_two_cells_touching_along_an_edge() {
        two_tets([Kind::Cell(0), Kind::Cell(1)]);
    }

    #[test]
    fn tets_of_one_cell_touching_along_an_edge() {
        two_tets([Kind::Cell(0), Kind::Cell(0)]);
    }

    #[test]
    fn splitting_an_edge_splits_its_triangles() {
        let mut pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
        ];
        let mut tris = vec![[0, 1, 2]];
        let mut kind = vec![Kind::Cell(0)];
        let mut splits = FxHashMap::default();
        splits.insert((0, 1), vec![3]);
        split_at_edges(&mut tris, &mut kind, &mut pos, &splits);
        assert_eq!(tris, vec![[0, 3, 2], [3, 1, 2]]);
        // edges on two sides: fan from a centroid
        pos.push([0.0, 0.5, 0.0]);
        let mut tris = vec![[0, 1, 2]];
        let mut kind = vec![Kind::Cell(0)];
        splits.insert((0, 2), vec![4]);
        split_at_edges(&mut tris, &mut kind, &mut pos, &splits);
        assert_eq!(tris.len(), 5);
        assert_eq!(kind.len(), 5);
        let uses = edge_uses(&tris);
        assert!(!uses.contains_key(&(0, 1)) && !uses.contains_key(&(0, 2)));
        assert_eq!(uses[&(0, 3)], 1);
        assert_eq!(uses[&(0, 4)], 1);
    }
}
