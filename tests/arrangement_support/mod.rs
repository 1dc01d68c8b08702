//! Helpers for the arrangement integration tests.
#![allow(dead_code)]
use slice2solid::arrangement::{Arrangement, ArrangementOptions, CellScope};
use slice2solid::sections::Sections;

/// The cells with a section piece on a face, each as its sorted list of faces (plane, side, sorted
/// corners, sorted pieces), every vertex by its position and tags: comparable across arrangements.
pub fn section_cells(arr: &Arrangement) -> Vec<String> {
    let key = |v: u32| {
        format!(
            "{:?}{:?}",
            arr.pool.positions[v as usize], arr.pool.tags[v as usize]
        )
    };
    let mut cells: Vec<String> = Vec::new();
    for cell in &arr.cells {
        if !cell
            .faces
            .iter()
            .any(|cf| !arr.faces[cf.face as usize].pieces.is_empty())
        {
            continue;
        }
        let mut faces: Vec<String> = cell
            .faces
            .iter()
            .map(|cf| {
                let f = &arr.faces[cf.face as usize];
                let mut corners: Vec<String> = f.polygon.iter().map(|&v| key(v)).collect();
                corners.sort();
                let mut pieces: Vec<String> = f
                    .pieces
                    .iter()
                    .map(|p| {
                        let mut l: Vec<Vec<String>> = std::iter::once(&p.outer)
                            .chain(&p.holes)
                            .map(|l| {
                                let mut l: Vec<String> = l.iter().map(|&v| key(v)).collect();
                                l.sort();
                                l
                            })
                            .collect();
                        l[1..].sort();
                        format!("{} {:?}", p.label, l)
                    })
                    .collect();
                pieces.sort();
                format!(
                    "{} {} {:?} {:?}",
                    f.plane, cf.outward_is_plane_normal, corners, pieces
                )
            })
            .collect();
        faces.sort();
        cells.push(faces.join("\n"));
    }
    cells.sort();
    cells
}

/// The arrangement of the cells with sections (`CellScope::Sections`) is exactly the part of the
/// full arrangement (`CellScope::All`) made of its cells with sections: the same cells, faces,
/// vertices (positions and tags) and pieces, the same warnings and disagreement. Returns the cell
/// counts (all, with sections).
pub fn check_scopes_agree(sections: &Sections, options: &ArrangementOptions) -> (usize, usize) {
    let with = |scope| ArrangementOptions {
        scope,
        ..options.clone()
    };
    let full = Arrangement::build(sections, &with(CellScope::All)).unwrap();
    let sparse = Arrangement::build(sections, &with(CellScope::Sections)).unwrap();
    check_arrangement(&full, sections);
    check_arrangement(&sparse, sections);
    let (a, b) = (section_cells(&full), section_cells(&sparse));
    assert_eq!(
        sparse.cells.len(),
        a.len(),
        "the sparse arrangement has only the cells with sections"
    );
    let differing = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(
        differing,
        0,
        "{differing} of {} cells with sections differ",
        a.len()
    );
    assert_eq!(full.warnings, sparse.warnings);
    assert_eq!(full.max_disagreement, sparse.max_disagreement);
    (full.cells.len(), sparse.cells.len())
}

/// Every structural invariant of an arrangement and the area bookkeeping of its pieces. With
/// `CellScope::All` the cells tile the box; with `CellScope::Sections` every cell has a piece and
/// both cells of every face with a piece are there.
pub fn check_arrangement(arr: &Arrangement, sections: &Sections) {
    let (lo, hi) = arr.bbox;
    let box_vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    let sum: f64 = arr.cells.iter().map(|c| c.volume).sum();
    let all = arr.scope == CellScope::All;
    if all {
        assert!(
            ((sum - box_vol) / box_vol).abs() < 1e-12,
            "volumes {sum} vs box {box_vol}"
        );
    } else {
        assert!(
            sum <= box_vol * (1.0 + 1e-12),
            "volumes {sum} vs box {box_vol}"
        );
        for (c, cell) in arr.cells.iter().enumerate() {
            assert!(
                cell.faces
                    .iter()
                    .any(|cf| !arr.faces[cf.face as usize].pieces.is_empty()),
                "cell {c} has no piece"
            );
        }
    }
    for (f, face) in arr.faces.iter().enumerate() {
        let both = all || !face.pieces.is_empty();
        if arr.planes[face.plane as usize].section.is_some() && !both {
            assert!(face.positive_cell.is_some() || face.negative_cell.is_some());
            for (c, out) in [(face.positive_cell, false), (face.negative_cell, true)] {
                if let Some(c) = c {
                    let cf = arr.cells[c as usize]
                        .faces
                        .iter()
                        .find(|cf| cf.face as usize == f)
                        .unwrap();
                    assert_eq!(cf.outward_is_plane_normal, out);
                }
            }
        } else if arr.planes[face.plane as usize].section.is_some() {
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
