//! The mean-value indicator on hand-built cells: constant precision and the interpolation property.
use slice2solid::implicit::fixtures::{circle, horizontal_slabs, Level};
use slice2solid::implicit::indicator::{FaceKind, Indicator};

fn full_square(lo: f64, hi: f64) -> Vec<[f64; 2]> {
    vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]]
}

/// Points spread over the inside of the cube [-1,1]² × [z0,z1], some very close to faces.
fn probe_points(z0: f64, z1: f64) -> Vec<[f64; 3]> {
    let mut pts = Vec::new();
    for &x in &[-0.999_999, -0.7, -0.1, 0.0, 0.33, 0.9, 0.999_999] {
        for &y in &[-0.95, -0.2, 0.0, 0.5, 0.999] {
            for &t in &[1e-9, 0.01, 0.3, 0.5, 0.77, 0.999_999] {
                pts.push([x, y, z0 + t * (z1 - z0)]);
            }
        }
    }
    pts
}

#[test]
fn cell_entirely_inside_is_exactly_one() {
    // The slab between z = -0.5 and z = 0.5 with both planes fully inside the section, and (by hand)
    // its four side walls covered by a full piece too: every face of the cell is inside.
    let lo = [-1.0, -1.0, -1.0];
    let hi = [1.0, 1.0, 1.0];
    let levels = [
        Level {
            z: -0.5,
            pieces: vec![(full_square(-1.0, 1.0), vec![])],
        },
        Level {
            z: 0.5,
            pieces: vec![(full_square(-1.0, 1.0), vec![])],
        },
    ];
    let mut arr = horizontal_slabs(lo, hi, &levels);
    // Cover the side walls of the middle cell (cell 1) with full pieces too: piece = face polygon,
    // started at a different vertex so the general formula sums the edges in another order.
    let cell = arr.cells[1].clone();
    for cf in &cell.faces {
        let f = &mut arr.faces[cf.face as usize];
        if f.pieces.is_empty() {
            let mut outer = f.polygon.clone();
            outer.rotate_left(1);
            f.pieces.push(slice2solid::arrangement::SectionPiece {
                label: 1,
                outer,
                holes: vec![],
            });
        }
    }
    let ind = Indicator::new(&arr).unwrap();
    assert!(cell
        .faces
        .iter()
        .all(|cf| ind.faces[cf.face as usize].kind == FaceKind::Full));
    assert_eq!(ind.cells[1].constant, Some(1.0));
    let mut worst: f64 = 0.0;
    for p in probe_points(-0.5, 0.5) {
        // The shortcut path: exactly 1.
        assert_eq!(ind.locate(p), Some(1), "{p:?}");
        assert_eq!(ind.eval(p), 1.0, "{p:?}");
        // The general formula (every face treated as inside/outside parts): 1 within 1e-12.
        let g = ind.eval_in_cell_general(1, p);
        worst = worst.max((g - 1.0).abs());
    }
    assert!(worst <= 1e-12, "general formula deviates by {worst}");
}

#[test]
fn mixed_cell_with_full_faces_is_bit_exact_one() {
    // Force the Full faces through the summation path: a cell whose faces are all Full but which is
    // not flagged constant evaluates num == den bit for bit.
    let levels = [
        Level {
            z: -0.5,
            pieces: vec![(full_square(-1.0, 1.0), vec![])],
        },
        Level {
            z: 0.5,
            pieces: vec![(full_square(-1.0, 1.0), vec![])],
        },
    ];
    let mut arr = horizontal_slabs([-1.0; 3], [1.0; 3], &levels);
    let cell = arr.cells[1].clone();
    for cf in &cell.faces {
        let f = &mut arr.faces[cf.face as usize];
        if f.pieces.is_empty() {
            let outer = f.polygon.clone();
            f.pieces.push(slice2solid::arrangement::SectionPiece {
                label: 1,
                outer,
                holes: vec![],
            });
        }
    }
    let mut ind = Indicator::new(&arr).unwrap();
    ind.cells[1].constant = None;
    for p in probe_points(-0.5, 0.5) {
        assert_eq!(ind.eval_in_cell(1, p), 1.0, "{p:?}");
    }
}

#[test]
fn empty_cells_are_minus_one_and_values_interpolate_the_section() {
    let levels = [Level {
        z: 0.0,
        pieces: vec![(circle([0.0, 0.0], 0.5, 64), vec![])],
    }];
    let ind = Indicator::new(&horizontal_slabs([-1.0; 3], [1.0; 3], &levels)).unwrap();
    // Close above/below the disc: → +1; close to the plane outside the disc: → −1.
    for s in [1e-4, -1e-4] {
        let inside = ind.eval([0.1, -0.2, s]);
        assert!(inside > 0.99, "{inside}");
        let outside = ind.eval([0.8, 0.7, s]);
        assert!(outside < -0.99, "{outside}");
    }
    // On the plane exactly: the section value.
    assert_eq!(ind.eval([0.1, 0.1, 0.0]), 1.0);
    assert_eq!(ind.eval([0.9, 0.1, 0.0]), -1.0);
    // Close to the contour: the two back-to-back copies cancel → near 0.
    let half = std::f64::consts::PI / 64.0;
    let r = 0.5 * half.cos(); // midpoint of the first contour edge
    let near = ind.eval([r * half.cos(), r * half.sin(), 1e-6]);
    assert!(near.abs() < 0.05, "{near}");
    // Far from the section, near the walls: negative.
    assert!(ind.eval([0.0, 0.0, 0.95]) < 0.0);
    assert!(ind.eval([0.99, 0.99, 0.5]) < 0.0);
    // Outside the box.
    assert_eq!(ind.eval([0.0, 0.0, 1.5]), -1.0);
    // Symmetric above and below (same geometry both sides).
    let a = ind.eval([0.2, 0.1, 0.3]);
    let b = ind.eval([0.2, 0.1, -0.3]);
    assert!((a - b).abs() < 1e-12, "{a} vs {b}");
    assert!(a > -1.0 && a < 1.0);
}
