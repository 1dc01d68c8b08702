//! `Delaunay::is_valid`: every invariant checked exactly. Together, (1) symmetric adjacency with
//! matching facets, (2) positive finite tetrahedra, (3) a locally convex hull closed by infinite
//! tetrahedra and (4) locally Delaunay facets imply a Delaunay triangulation of the vertices
//! (Delaunay's lemma), and (5) every non-merged vertex is used.
#![allow(clippy::needless_range_loop)]
use super::{pred, Delaunay, DEAD, INFINITE, NONE};

pub(super) fn check(dt: &Delaunay) -> Result<(), String> {
    if dt.dim < 3 {
        if dt.all_tets().next().is_some() {
            return Err(format!("dimension {} but tetrahedra exist", dt.dim));
        }
        return Ok(());
    }
    let p = |w: u32| dt.pts[w as usize];
    let mut nfinite = 0;
    for t in dt.all_tets() {
        let v = dt.tv[t as usize];
        let n = dt.tn[t as usize];
        let ninf = v.iter().filter(|&&w| w == INFINITE).count();
        if ninf > 1 {
            return Err(format!("tet {t} has {ninf} infinite vertices"));
        }
        for i in 0..4 {
            for j in i + 1..4 {
                if v[i] == v[j] {
                    return Err(format!("tet {t} repeats vertex {}", v[i]));
                }
            }
        }
        for i in 0..4 {
            let m = n[i];
            if m == NONE || m as usize >= dt.tv.len() || dt.tv[m as usize][0] == DEAD {
                return Err(format!("tet {t}: neighbour {i} is missing or dead"));
            }
            let back: Vec<usize> = (0..4).filter(|&j| dt.tn[m as usize][j] == t).collect();
            if back.len() != 1 {
                return Err(format!("tet {t}: neighbour {m} does not point back once"));
            }
            let j = back[0];
            if super::facet_key(v, i) != super::facet_key(dt.tv[m as usize], j) {
                return Err(format!("tet {t} and {m} do not share facet {i}/{j}"));
            }
        }
        if ninf == 0 {
            nfinite += 1;
            let [a, b, c, d] = dt.tet_points(t);
            if pred::orient(a, b, c, d) <= 0.0 {
                return Err(format!("tet {t} {v:?} is not positively oriented"));
            }
            // local Delaunay: no neighbour apex strictly inside, exactly; perturbed, none inside either.
            for i in 0..4 {
                let m = n[i];
                if dt.is_infinite(m) {
                    continue;
                }
                let j = (0..4).find(|&j| dt.tn[m as usize][j] == t).unwrap();
                let e = p(dt.tv[m as usize][j]);
                if pred::insphere(a, b, c, d, e) > 0.0 {
                    return Err(format!("facet {i} of tet {t} is not locally Delaunay"));
                }
                if pred::conflict_finite([a, b, c, d], e) {
                    return Err(format!(
                        "facet {i} of tet {t} is not locally Delaunay under the perturbation"
                    ));
                }
            }
        } else {
            let k = v.iter().position(|&w| w == INFINITE).unwrap();
            let f = dt.tn[t as usize][k];
            if dt.is_infinite(f) {
                return Err(format!("infinite tet {t}: facet neighbour {f} is infinite"));
            }
            let j = (0..4).find(|&j| dt.tn[f as usize][j] == t).unwrap();
            let d = p(dt.tv[f as usize][j]);
            let mut s = dt.tet_points(t);
            s[k] = d;
            if pred::orient(s[0], s[1], s[2], s[3]) >= 0.0 {
                return Err(format!("infinite tet {t}: hull facet faces inwards"));
            }
            // hull convexity: the apex of each adjacent hull facet is not beyond this facet
            for i in 0..4 {
                if i == k {
                    continue;
                }
                let m = n[i];
                let jm = (0..4).find(|&j| dt.tn[m as usize][j] == t).unwrap();
                let e = p(dt.tv[m as usize][jm]);
                let mut s = dt.tet_points(t);
                s[k] = e;
                if pred::orient(s[0], s[1], s[2], s[3]) > 0.0 {
                    return Err(format!("hull not convex at infinite tet {t}"));
                }
            }
        }
    }
    if nfinite != dt.nfinite {
        return Err(format!(
            "finite tet count {} != tracked {}",
            nfinite, dt.nfinite
        ));
    }
    let merged: std::collections::HashSet<u32> = dt.dups.iter().map(|d| d.0).collect();
    for v in 0..dt.pts.len() as u32 {
        if merged.contains(&v) {
            continue;
        }
        let t = dt.vtet[v as usize];
        if t == NONE || dt.tv[t as usize][0] == DEAD || !dt.tv[t as usize].contains(&v) {
            return Err(format!("vertex {v} has no valid incident tetrahedron"));
        }
    }
    for &(a, b) in &dt.dups {
        if dt.pts[a as usize] != dt.pts[b as usize] || merged.contains(&b) {
            return Err(format!("bad duplicate pair ({a}, {b})"));
        }
    }
    Ok(())
}
