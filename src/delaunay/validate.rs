//! `Delaunay::is_valid`: every invariant checked exactly. Together, (1) symmetric adjacency with
//! matching facets, (2) positive finite tetrahedra, (3) a locally convex hull closed by infinite
//! tetrahedra and (4) locally Delaunay facets imply a Delaunay triangulation of the vertices
//! (Delaunay's lemma), and (5) every vertex is used.
//!
//! Tagged triangulations: (4) and the convexity in (3) are decided by the tag rules where they
//! apply (for four points of one plane the float signs are rounding noise), no tetrahedron is
//! degenerate by its tags (four vertices on one plane, three on one line), and (6) for every plane
//! with a hull facet, the hull facets on it are exactly the reference 2D Delaunay triangulation of
//! its points ([`super::plane2d`], brute force: independent of the kernel's incremental state).
#![allow(clippy::needless_range_loop)]
use super::tags::{self, PointTags};
use super::tds::{facet_key, INFINITE, NONE};
use super::{plane2d, pred, Delaunay};
use std::collections::{BTreeMap, BTreeSet};

pub(super) fn check(dt: &Delaunay) -> Result<(), String> {
    if dt.dim < 3 {
        if dt.all_tets().next().is_some() {
            return Err(format!("dimension {} but tetrahedra exist", dt.dim));
        }
        return Ok(());
    }
    let tets = &dt.tds.tets;
    let mut nfinite = 0;
    for t in dt.all_tets() {
        let v = tets[t as usize].v;
        let ninf = v.iter().filter(|&&w| w == INFINITE).count();
        if ninf > 1 {
            return Err(format!("tet {t} has {ninf} infinite vertices"));
        }
        check_vertices_and_neighbours(dt, t)?;
        if ninf == 0 {
            nfinite += 1;
            check_finite_tet(dt, t)?;
        } else {
            check_infinite_tet(dt, t)?;
        }
    }
    if nfinite != dt.nfinite {
        return Err(format!(
            "finite tet count {nfinite} != tracked {}",
            dt.nfinite
        ));
    }
    check_vertex_records(dt)?;
    if dt.tagged {
        check_planes(dt)?;
    }
    Ok(())
}

/// The positions of tet `t`'s vertices (the origin for the infinite one).
fn tet_points(dt: &Delaunay, t: u32) -> [[f64; 3]; 4] {
    let v = dt.tds.tets[t as usize].v;
    v.map(|w| {
        if w == INFINITE {
            [0.0; 3]
        } else {
            dt.pts[w as usize]
        }
    })
}

/// The vertex of neighbour `m` of tet `t` opposite their common facet.
fn apex_id(dt: &Delaunay, t: u32, m: u32) -> u32 {
    let tets = &dt.tds.tets;
    tets[m as usize].v[tets[m as usize].index_of_neighbor(t)]
}

/// (1): known, distinct vertices; four live neighbours, each pointing back once across the same
/// facet.
fn check_vertices_and_neighbours(dt: &Delaunay, t: u32) -> Result<(), String> {
    let tets = &dt.tds.tets;
    let v = tets[t as usize].v;
    let n = tets[t as usize].n;
    for i in 0..4 {
        if v[i] != INFINITE && v[i] as usize >= dt.pts.len() {
            return Err(format!("tet {t} has an unknown vertex"));
        }
        for j in i + 1..4 {
            if v[i] == v[j] {
                return Err(format!("tet {t} repeats vertex {}", v[i]));
            }
        }
    }
    for i in 0..4 {
        let m = n[i];
        if m == NONE || m as usize >= tets.len() || tets[m as usize].is_dead() {
            return Err(format!("tet {t}: neighbour {i} is missing or dead"));
        }
        let back: Vec<usize> = (0..4).filter(|&j| tets[m as usize].n[j] == t).collect();
        if back.len() != 1 {
            return Err(format!("tet {t}: neighbour {m} does not point back once"));
        }
        if facet_key(v, i) != facet_key(tets[m as usize].v, back[0]) {
            return Err(format!(
                "tet {t} and {m} do not share facet {i}/{}",
                back[0]
            ));
        }
    }
    Ok(())
}

/// (2) and (4) for finite tet `t`: positively oriented, not flat by its tags, and locally Delaunay
/// across each facet with a finite neighbour.
fn check_finite_tet(dt: &Delaunay, t: u32) -> Result<(), String> {
    let tets = &dt.tds.tets;
    let v = tets[t as usize].v;
    let n = tets[t as usize].n;
    let [a, b, c, d] = tet_points(dt, t);
    if pred::orient(a, b, c, d) <= 0.0 {
        return Err(format!(
            "tet {t} is not positively oriented ({}){}",
            pred::orient(a, b, c, d),
            if dt.tagged {
                format!(": {:?}", v.map(|w| &dt.tags[w as usize]))
            } else {
                String::new()
            }
        ));
    }
    if dt.tagged && tags::degenerate(v.map(|w| &dt.tags[w as usize])) {
        return Err(format!("tet {t} is flat by its tags {:?}", ext_of(dt, v)));
    }
    // local Delaunay: no neighbour apex strictly inside, exactly; perturbed, none inside either.
    for i in 0..4 {
        let m = n[i];
        if tets[m as usize].is_infinite() {
            continue;
        }
        let e = dt.pts[apex_id(dt, t, m) as usize];
        if let Some(inside) = tag_rule(dt, v, apex_id(dt, t, m)) {
            if inside {
                return Err(format!(
                    "facet {i} of tet {t} is not locally Delaunay by the tag rules"
                ));
            }
            continue;
        }
        if pred::insphere(a, b, c, d, e) > 0.0 {
            return Err(format!("facet {i} of tet {t} is not locally Delaunay"));
        }
        if pred::conflict_finite([a, b, c, d], e, &pred::Bounds::NONE) {
            return Err(format!(
                "facet {i} of tet {t} is not locally Delaunay under the perturbation"
            ));
        }
    }
    Ok(())
}

/// (3) for infinite tet `t`: its hull facet faces outwards and the hull is locally convex there
/// (by the tag rules for two hull facets on one plane).
fn check_infinite_tet(dt: &Delaunay, t: u32) -> Result<(), String> {
    let tets = &dt.tds.tets;
    let v = tets[t as usize].v;
    let n = tets[t as usize].n;
    let k = v.iter().position(|&w| w == INFINITE).unwrap();
    let f = n[k];
    if tets[f as usize].is_infinite() {
        return Err(format!("infinite tet {t}: facet neighbour {f} is infinite"));
    }
    let mut s = tet_points(dt, t);
    s[k] = dt.pts[apex_id(dt, t, f) as usize];
    if pred::orient(s[0], s[1], s[2], s[3]) >= 0.0 {
        return Err(format!("infinite tet {t}: hull facet faces inwards"));
    }
    // hull convexity: the apex of each adjacent hull facet is not beyond this facet
    for i in 0..4 {
        if i == k {
            continue;
        }
        let mut s = tet_points(dt, t);
        s[k] = dt.pts[apex_id(dt, t, n[i]) as usize];
        let x = apex_id(dt, t, n[i]);
        let mut w = v;
        w[k] = x;
        if dt.tagged && tags::degenerate(w.map(|w| &dt.tags[w as usize])) {
            // two hull facets on one plane: locally Delaunay in its uv
            if tag_rule(dt, v, x) != Some(false) {
                return Err(format!(
                    "hull facets of infinite tet {t} not Delaunay in their plane: {:?} and {:?}",
                    v.map(|w| (w != INFINITE).then(|| &dt.tags[w as usize])),
                    dt.tags[x as usize]
                ));
            }
            continue;
        }
        if pred::orient(s[0], s[1], s[2], s[3]) > 0.0 {
            return Err(format!("hull not convex at infinite tet {t}"));
        }
    }
    Ok(())
}

/// (5): every vertex has a live incident tet and consistent numbering; duplicates point to their
/// canonical vertex.
fn check_vertex_records(dt: &Delaunay) -> Result<(), String> {
    let tets = &dt.tds.tets;
    for w in 0..dt.pts.len() as u32 {
        let t = dt.vtet[w as usize];
        if t == NONE || tets[t as usize].is_dead() || !tets[t as usize].v.contains(&w) {
            return Err(format!(
                "vertex {} has no valid incident tetrahedron",
                dt.ext[w as usize]
            ));
        }
        if dt.int[dt.ext[w as usize] as usize] != w {
            return Err(format!("vertex numbering broken at {w}"));
        }
    }
    for &(a, b) in &dt.dups {
        if dt.point(a) != dt.point(b) || dt.canonical(b) != b || dt.canonical(a) != b {
            return Err(format!("bad duplicate pair ({a}, {b})"));
        }
    }
    Ok(())
}

/// The tag rule's answer for tetrahedron `v` (internal ids) and internal vertex `q`.
fn tag_rule(dt: &Delaunay, v: [u32; 4], q: u32) -> Option<bool> {
    if !dt.tagged {
        return None;
    }
    let tv = v.map(|w| (w != INFINITE).then(|| (&dt.tags[w as usize], dt.pts[w as usize])));
    tags::conflict(tv, (&dt.tags[q as usize], dt.pts[q as usize]), &dt.apexes)
}

fn ext_of(dt: &Delaunay, v: [u32; 4]) -> [u32; 4] {
    v.map(|w| dt.external(w))
}

/// (6): on every plane with a hull facet, the hull facets are the reference 2D Delaunay of its points.
fn check_planes(dt: &Delaunay) -> Result<(), String> {
    let tets = &dt.tds.tets;
    let mut hull: BTreeMap<u32, BTreeSet<[u32; 3]>> = BTreeMap::new();
    for t in dt.all_tets() {
        let v = tets[t as usize].v;
        let Some(k) = v.iter().position(|&w| w == INFINITE) else {
            continue;
        };
        let mut f: Vec<u32> = (0..4).filter(|&i| i != k).map(|i| v[i]).collect();
        f.sort_unstable();
        let ts: Vec<&PointTags> = f.iter().map(|&w| &dt.tags[w as usize]).collect();
        for &(pl, _) in &ts[0].planes {
            if ts[1].on(pl) && ts[2].on(pl) {
                hull.entry(pl).or_default().insert([f[0], f[1], f[2]]);
            }
        }
    }
    for (pl, got) in hull {
        let ids: Vec<u32> = (0..dt.pts.len() as u32)
            .filter(|&w| dt.tags[w as usize].on(pl))
            .collect();
        let refs: Vec<(&PointTags, [f64; 3])> = ids
            .iter()
            .map(|&w| (&dt.tags[w as usize], dt.pts[w as usize]))
            .collect();
        let want: BTreeSet<[u32; 3]> = plane2d::delaunay(pl, &refs, &dt.apexes)
            .into_iter()
            .map(|t| {
                let mut f = t.map(|i| ids[i]);
                f.sort_unstable();
                f
            })
            .collect();
        if got != want {
            let ext = |s: &BTreeSet<[u32; 3]>| -> Vec<[u32; 3]> {
                s.iter().map(|f| f.map(|w| dt.external(w))).collect()
            };
            return Err(format!(
                "plane {pl}: hull facets differ from its 2D Delaunay: only in 3D {:?}, only in 2D {:?}",
                ext(&got.difference(&want).copied().collect()),
                ext(&want.difference(&got).copied().collect())
            ));
        }
    }
    Ok(())
}
