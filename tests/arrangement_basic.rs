//! Arrangement invariants on synthetic sections (balls and boxes cut by planes).
mod arrangement_support;
use slice2solid::arrangement::{Arrangement, ArrangementOptions, CellScope};

fn all_cells() -> ArrangementOptions {
    ArrangementOptions {
        scope: CellScope::All,
        ..Default::default()
    }
}
use slice2solid::sections::{Contour, Plane, Region, Section, Sections};

/// Sections of the ball of radius `r` centred at the origin by the given planes (n-gon contours).
fn ball_sections(planes: &[([f64; 3], f64)], r: f64, n: usize) -> Sections {
    let mut out = Sections {
        sections: Vec::new(),
        n_labels: 1,
        warnings: Vec::new(),
        label_names: Default::default(),
    };
    for (k, &(normal, offset)) in planes.iter().enumerate() {
        let plane = Plane::from_equation(normal, offset).unwrap();
        let d = plane.offset;
        let mut regions = Vec::new();
        if d.abs() < r {
            let rr = (r * r - d * d).sqrt();
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|a| {
                    let t = a as f64 / n as f64 * std::f64::consts::TAU + 0.1;
                    [rr * t.cos(), rr * t.sin()]
                })
                .collect();
            regions.push(Region {
                label: 1,
                outer: Contour::from_2d(&plane, pts),
                holes: Vec::new(),
            });
        }
        out.sections.push(Section {
            plane,
            regions,
            source_index: k,
            max_off_plane: 0.0,
        });
    }
    out
}

fn check_invariants(arr: &Arrangement, sections: &Sections) {
    assert_eq!(
        arr.scope,
        CellScope::All,
        "the invariants of the full arrangement"
    );
    let (lo, hi) = arr.bbox;
    let box_vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    let sum: f64 = arr.cells.iter().map(|c| c.volume).sum();
    assert!(
        ((sum - box_vol) / box_vol).abs() < 1e-12,
        "volumes {sum} vs box {box_vol}"
    );
    for c in &arr.cells {
        assert!(c.volume > 0.0, "cell volume {}", c.volume);
    }
    // Faces: interior faces have two cells, wall faces one, and cell face lists agree.
    for (f, face) in arr.faces.iter().enumerate() {
        let wall = arr.planes[face.plane as usize].section.is_none();
        if wall {
            assert!(face.positive_cell.is_none() && face.negative_cell.is_some());
        } else {
            let (p, n) = (face.positive_cell.unwrap(), face.negative_cell.unwrap());
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
        }
        // Polygon: every vertex carries the face plane tag; convex CCW seen from the normal.
        assert!(face.polygon.len() >= 3);
        let uv: Vec<[f64; 2]> = face
            .polygon
            .iter()
            .map(|&v| arr.uv(v, face.plane).expect("tag"))
            .collect();
        assert!(arr.loop_area(face.plane, &face.polygon) > 0.0);
        // convex: every corner turns left or goes straight (exact orient2d in the plane's frame)
        for k in 0..uv.len() {
            let (a, b, c) = (uv[k], uv[(k + 1) % uv.len()], uv[(k + 2) % uv.len()]);
            assert!(
                slice2solid::geom::predicates::orient2d(a, b, c) >= 0.0,
                "face {f}: reflex corner at polygon vertex {}",
                (k + 1) % uv.len()
            );
        }
    }
    // Pieces: tags include the plane; areas add up to the section area.
    for (i, s) in sections.sections.iter().enumerate() {
        let mut total = 0.0;
        for face in arr.faces.iter().filter(|f| f.plane as usize == i) {
            for piece in &face.pieces {
                for &v in piece.outer.iter().chain(piece.holes.iter().flatten()) {
                    assert!(arr.pool.tags[v as usize].contains(&(i as u32)));
                }
                assert!(arr.loop_area(i as u32, &piece.outer) > 0.0);
                for h in &piece.holes {
                    assert!(arr.loop_area(i as u32, h) < 0.0);
                }
                total += arr.piece_area(i as u32, piece);
            }
        }
        let a = s.area();
        assert!(
            (total - a).abs() <= 1e-9 * a.max(1e-300),
            "plane {i}: pieces {total} vs section {a}"
        );
    }
    // Cell adjacency graph: one edge per interior face.
    let g = arr.adjacency_graph();
    assert_eq!(g.node_count(), arr.cells.len());
    let interior = arr
        .faces
        .iter()
        .filter(|f| f.positive_cell.is_some() && f.negative_cell.is_some())
        .count();
    assert_eq!(g.edge_count(), interior);
}

#[test]
fn three_axis_planes_make_eight_cells() {
    let s = ball_sections(
        &[
            ([0.0, 0.0, 1.0], 0.0),
            ([1.0, 0.0, 0.0], 0.0),
            ([0.0, 1.0, 0.0], 0.0),
        ],
        1.0,
        64,
    );
    let arr = Arrangement::build(&s, &all_cells()).unwrap();
    assert_eq!(arr.cells.len(), 8);
    assert_eq!(
        arrangement_support::check_scopes_agree(&s, &Default::default()),
        (8, 8)
    );
    assert_eq!(arr.n_input, 3);
    assert_eq!(arr.planes.len(), 9);
    check_invariants(&arr, &s);
    // Every plane has 4 faces, each with one piece (a quarter disc).
    for i in 0..3u32 {
        let faces: Vec<_> = arr.faces.iter().filter(|f| f.plane == i).collect();
        assert_eq!(faces.len(), 4);
        for f in faces {
            assert_eq!(f.pieces.len(), 1, "{:?}", f.pieces);
        }
    }
    // The centre is one arrangement vertex with the three tags, shared by all 12 input faces.
    let centre: Vec<usize> = (0..arr.pool.tags.len())
        .filter(|&v| arr.pool.tags[v].iter().filter(|&&t| t < 3).count() == 3)
        .collect();
    assert_eq!(centre.len(), 1);
    let c = centre[0] as u32;
    assert_eq!(
        arr.faces.iter().filter(|f| f.polygon.contains(&c)).count(),
        12
    );
    assert_eq!(
        arr.faces
            .iter()
            .filter(|f| f.pieces.iter().any(|p| p.outer.contains(&c)))
            .count(),
        12
    );
}

#[test]
fn tilted_planes_ball() {
    let planes = [
        ([0.3, 0.1, 1.0], 0.1),
        ([1.0, -0.2, 0.05], -0.2),
        ([0.1, 1.0, 0.4], 0.3),
        ([0.7, 0.7, 0.1], 0.0),
        ([-0.2, 0.5, 0.9], -0.4),
    ];
    let s = ball_sections(&planes, 1.0, 200);
    let arr = Arrangement::build(&s, &all_cells()).unwrap();
    check_invariants(&arr, &s);
    let (all, sparse) = arrangement_support::check_scopes_agree(&s, &Default::default());
    assert!(sparse < all, "{sparse} of {all} cells");
    assert!(arr.max_disagreement < 0.01, "{}", arr.max_disagreement);
}
