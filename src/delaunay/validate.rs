//! `Delaunay::is_valid`: every invariant checked exactly. Together, (1) symmetric adjacency with
//! matching facets, (2) positive finite tetrahedra, (3) a locally convex hull closed by infinite
//! tetrahedra and (4) locally Delaunay facets imply a Delaunay triangulation of the vertices
//! (Delaunay's lemma), and (5) every vertex is used.
#![allow(clippy::needless_range_loop)]
use super::tds::{facet_key, INFINITE, NONE};
use super::{pred, Delaunay};

pub(super) fn check(dt: &Delaunay) -> Result<(), String> {
    let tets = &dt.tds.tets;
    if dt.dim < 3 {
        if dt.all_tets().next().is_some() {
            return Err(format!("dimension {} but tetrahedra exist", dt.dim));
        }
        return Ok(());
    }
    let p = |w: u32| dt.pts[w as usize];
    let pts_of = |t: u32| {
        let v = tets[t as usize].v;
        v.map(|w| if w == INFINITE { [0.0; 3] } else { p(w) })
    };
    let mut nfinite = 0;
    for t in dt.all_tets() {
        let v = tets[t as usize].v;
        let n = tets[t as usize].n;
        let ninf = v.iter().filter(|&&w| w == INFINITE).count();
        if ninf > 1 {
            return Err(format!("tet {t} has {ninf} infinite vertices"));
        }
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
        let apex = |m: u32| p(tets[m as usize].v[tets[m as usize].index_of_neighbor(t)]);
        if ninf == 0 {
            nfinite += 1;
            let [a, b, c, d] = pts_of(t);
            if pred::orient(a, b, c, d) <= 0.0 {
                return Err(format!("tet {t} is not positively oriented"));
            }
            // local Delaunay: no neighbour apex strictly inside, exactly; perturbed, none inside either.
            for i in 0..4 {
                let m = n[i];
                if tets[m as usize].is_infinite() {
                    continue;
                }
                let e = apex(m);
                if pred::insphere(a, b, c, d, e) > 0.0 {
                    return Err(format!("facet {i} of tet {t} is not locally Delaunay"));
                }
                if pred::conflict_finite([a, b, c, d], e, &pred::Bounds::NONE) {
                    return Err(format!(
                        "facet {i} of tet {t} is not locally Delaunay under the perturbation"
                    ));
                }
            }
        } else {
            let k = v.iter().position(|&w| w == INFINITE).unwrap();
            let f = n[k];
            if tets[f as usize].is_infinite() {
                return Err(format!("infinite tet {t}: facet neighbour {f} is infinite"));
            }
            let mut s = pts_of(t);
            s[k] = apex(f);
            if pred::orient(s[0], s[1], s[2], s[3]) >= 0.0 {
                return Err(format!("infinite tet {t}: hull facet faces inwards"));
            }
            // hull convexity: the apex of each adjacent hull facet is not beyond this facet
            for i in 0..4 {
                if i == k {
                    continue;
                }
                let mut s = pts_of(t);
                s[k] = apex(n[i]);
                if pred::orient(s[0], s[1], s[2], s[3]) > 0.0 {
                    return Err(format!("hull not convex at infinite tet {t}"));
                }
            }
        }
    }
    if nfinite != dt.nfinite {
        return Err(format!(
            "finite tet count {nfinite} != tracked {}",
            dt.nfinite
        ));
    }
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
