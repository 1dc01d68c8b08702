//! Helpers for the arrangement integration tests.
#![allow(dead_code)]
use slice2solid::arrangement::Arrangement;
use slice2solid::sections::Sections;

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
