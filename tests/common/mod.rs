//! Shared helpers for integration tests.
#![allow(dead_code)]
use slice2solid::arrangement::Arrangement;
use slice2solid::sections::{Contour, Plane, Region, Section, Sections};
use std::path::PathBuf;

/// The shared data directory: `SLICE2SOLID_SHARED`, else `$CARGO_MANIFEST_DIR/../shared`, else `/work/shared`.
pub fn shared_dir() -> PathBuf {
    if let Ok(d) = std::env::var("SLICE2SOLID_SHARED") {
        return PathBuf::from(d);
    }
    let local = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared"));
    if local.exists() {
        return local;
    }
    PathBuf::from("/work/shared")
}

fn point_in(p: [f64; 2], q: &[[f64; 2]]) -> bool {
    let mut inside = false;
    for k in 0..q.len() {
        let (a, b) = (q[k], q[(k + 1) % q.len()]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            inside = !inside;
        }
    }
    inside
}

/// A minimal CSL reader for tests of modules that run before the real reader lands: components are
/// projected on their plane; nesting depth decides outer (even, made CCW) or hole (odd, made CW).
/// Labels are ignored (every region gets label 1).
pub fn read_csl_simple(path: &std::path::Path) -> Sections {
    let text = std::fs::read_to_string(path).unwrap();
    let mut tok = text.split_whitespace();
    assert_eq!(tok.next(), Some("CSLC"));
    let n_planes: usize = tok.next().unwrap().parse().unwrap();
    let _n_labels: usize = tok.next().unwrap().parse().unwrap();
    let mut out = Sections {
        sections: Vec::new(),
        n_labels: 1,
        warnings: Vec::new(),
    };
    for k in 0..n_planes {
        let _idx: usize = tok.next().unwrap().parse().unwrap();
        let nv: usize = tok.next().unwrap().parse().unwrap();
        let nc: usize = tok.next().unwrap().parse().unwrap();
        let mut e = [0.0; 4];
        for x in &mut e {
            *x = tok.next().unwrap().parse().unwrap();
        }
        let plane = Plane::from_equation([e[0], e[1], e[2]], e[3]).unwrap();
        let mut pts = Vec::with_capacity(nv);
        for _ in 0..nv {
            let p: Vec<f64> = (0..3)
                .map(|_| tok.next().unwrap().parse().unwrap())
                .collect();
            pts.push(plane.to_2d([p[0], p[1], p[2]]));
        }
        let mut comps: Vec<Vec<[f64; 2]>> = Vec::new();
        for _ in 0..nc {
            // "20" or "20h5" (20 vertices, a hole of component 5): nesting is recomputed below.
            let n: usize = tok
                .next()
                .unwrap()
                .split('h')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            let _label: i64 = tok.next().unwrap().parse().unwrap();
            let mut c: Vec<[f64; 2]> = (0..n)
                .map(|_| pts[tok.next().unwrap().parse::<usize>().unwrap()])
                .collect();
            c.dedup();
            while c.len() > 1 && c.first() == c.last() {
                c.pop();
            }
            comps.push(c);
        }
        let depth: Vec<usize> = (0..comps.len())
            .map(|a| {
                (0..comps.len())
                    .filter(|&b| b != a && point_in(comps[a][0], &comps[b]))
                    .count()
            })
            .collect();
        let mut regions: Vec<(usize, Region)> = Vec::new();
        for (a, c) in comps.iter().enumerate() {
            if depth[a] % 2 == 0 {
                let mut ct = Contour::from_2d(&plane, c.clone());
                if ct.signed_area() < 0.0 {
                    ct.points2.reverse();
                    ct.points3.reverse();
                }
                regions.push((
                    a,
                    Region {
                        label: 1,
                        outer: ct,
                        holes: Vec::new(),
                    },
                ));
            }
        }
        for (a, c) in comps.iter().enumerate() {
            if depth[a] % 2 == 1 {
                let mut ct = Contour::from_2d(&plane, c.clone());
                if ct.signed_area() > 0.0 {
                    ct.points2.reverse();
                    ct.points3.reverse();
                }
                // Parent: the containing outer of depth one less.
                let parent = regions
                    .iter_mut()
                    .filter(|(b, _)| depth[*b] + 1 == depth[a] && point_in(c[0], &comps[*b]))
                    .map(|(_, r)| r)
                    .next();
                if let Some(r) = parent {
                    r.holes.push(ct);
                }
            }
        }
        out.sections.push(Section {
            plane,
            regions: regions.into_iter().map(|x| x.1).collect(),
            source_index: k,
            max_off_plane: 0.0,
        });
    }
    out
}

/// Every structural invariant of an arrangement and the area bookkeeping of its pieces.
pub fn check_arrangement(arr: &Arrangement, sections: &Sections) {
    let (lo, hi) = arr.bbox;
    let box_vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    let sum: f64 = arr.cells.iter().map(|c| c.volume).sum();
    assert!(
        ((sum - box_vol) / box_vol).abs() < 1e-12,
        "volumes {sum} vs box {box_vol}"
    );
    for (f, face) in arr.faces.iter().enumerate() {
        if arr.planes[face.plane as usize].section.is_some() {
            let (p, n) = (
                face.positive_cell.expect("positive"),
                face.negative_cell.expect("negative"),
            );
            assert_ne!(p, n);
            let fp = arr.cells[p as usize]
                .faces
                .iter()
                .find(|cf| cf.face as usize == f)
                .unwrap();
            let fn_ = arr.cells[n as usize]
                .faces
                .iter()
                .find(|cf| cf.face as usize == f)
                .unwrap();
            assert!(!fp.outward_is_plane_normal && fn_.outward_is_plane_normal);
        } else {
            assert!(face.positive_cell.is_none() && face.negative_cell.is_some());
        }
        for &v in &face.polygon {
            assert!(arr.pool.tags[v as usize].contains(&face.plane));
        }
        // Each face vertex has at least three tags (it is an arrangement vertex).
        for &v in &face.polygon {
            assert!(arr.pool.tags[v as usize].len() >= 3);
        }
    }
    // Every cell is closed: each (directed) edge of its faces appears once in each direction.
    for c in &arr.cells {
        let mut edges = std::collections::HashMap::new();
        for cf in &c.faces {
            let f = &arr.faces[cf.face as usize];
            let mut poly = f.polygon.clone();
            if !cf.outward_is_plane_normal {
                poly.reverse();
            }
            for k in 0..poly.len() {
                *edges
                    .entry((poly[k], poly[(k + 1) % poly.len()]))
                    .or_insert(0) += 1;
            }
        }
        for (&(a, b), &n) in &edges {
            assert_eq!(n, 1);
            assert_eq!(
                edges.get(&(b, a)),
                Some(&1),
                "cell not closed at edge {a}-{b}"
            );
        }
    }
    let nv = arr.pool.positions.len();
    assert_eq!(arr.pool.tags.len(), nv);
    assert_eq!(arr.pool.uv.len(), nv);
    for v in 0..nv {
        assert_eq!(arr.pool.tags[v].len(), arr.pool.uv[v].len());
        assert!(
            arr.pool.tags[v].windows(2).all(|w| w[0] < w[1]),
            "tags sorted and unique"
        );
    }
    for (i, s) in sections.sections.iter().enumerate() {
        let mut total = 0.0;
        for face in arr.faces.iter().filter(|f| f.plane as usize == i) {
            for piece in &face.pieces {
                for &v in piece.outer.iter().chain(piece.holes.iter().flatten()) {
                    assert!((v as usize) < nv);
                    assert!(arr.pool.tags[v as usize].contains(&(i as u32)));
                }
                total += arr.piece_area(i as u32, piece);
            }
        }
        let a = s.area();
        assert!(
            (total - a).abs() <= 1e-9 * a.max(1e-12),
            "plane {i}: pieces {total} vs section {a}"
        );
    }
}
