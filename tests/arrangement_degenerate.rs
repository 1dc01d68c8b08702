//! Degenerate plane configurations and contours through arrangement features.
mod arrangement_support;
use proptest::prelude::*;
use slice2solid::arrangement::{Arrangement, ArrangementOptions};
use slice2solid::sections::{Contour, Plane, Region, Section, Sections};
use slice2solid::Error;

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
            // An annulus every other plane, to exercise holes.
            let holes = if k % 2 == 1 {
                let h: Vec<[f64; 2]> = (0..n / 2)
                    .map(|a| {
                        let t = -(a as f64) / (n / 2) as f64 * std::f64::consts::TAU;
                        [0.4 * rr * t.cos() + 0.05, 0.4 * rr * t.sin()]
                    })
                    .collect();
                vec![Contour::from_2d(&plane, h)]
            } else {
                Vec::new()
            };
            regions.push(Region {
                label: 1,
                outer: Contour::from_2d(&plane, pts),
                holes,
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

/// Section on `plane` from 3D points lying exactly on it (axis planes: exact frames).
fn polygon_section(plane: Plane, polys: &[Vec<[f64; 3]>], k: usize) -> Section {
    let regions = polys
        .iter()
        .map(|p| {
            let pts: Vec<[f64; 2]> = p.iter().map(|&x| plane.to_2d(x)).collect();
            let mut c = Contour::from_2d(&plane, pts);
            if c.signed_area() < 0.0 {
                c.points2.reverse();
                c.points3.reverse();
            }
            Region {
                label: 1,
                outer: c,
                holes: Vec::new(),
            }
        })
        .collect();
    Section {
        plane,
        regions,
        source_index: k,
        max_off_plane: 0.0,
    }
}

#[test]
fn planes_through_a_common_line() {
    let planes: Vec<([f64; 3], f64)> = (0..5)
        .map(|k| {
            let a = k as f64 * 0.6;
            ([0.0, a.sin(), a.cos()], 0.0)
        })
        .chain([([1.0, 0.0, 0.0], 0.3)])
        .collect();
    let s = ball_sections(&planes, 1.0, 96);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    // 5 planes through one line: 10 wedges, each cut by x = 0.3.
    assert_eq!(arr.cells.len(), 20);
    // The two arrangement vertices on the common line carry all five tags.
    let five = arr
        .pool
        .tags
        .iter()
        .filter(|t| t.iter().filter(|&&p| p < 5).count() == 5)
        .count();
    assert!(five >= 2, "{five}");
}

#[test]
fn four_planes_through_one_point() {
    let planes = [
        ([1.0, 0.0, 0.0], 0.0),
        ([0.0, 1.0, 0.0], 0.0),
        ([0.0, 0.0, 1.0], 0.0),
        ([1.0, 1.0, 1.0], 0.0),
        ([0.3, -0.7, 0.2], 0.0),
    ];
    let s = ball_sections(&planes, 1.0, 128);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    let centre: Vec<_> = arr
        .pool
        .tags
        .iter()
        .filter(|t| t.iter().filter(|&&p| p < 5).count() == 5)
        .collect();
    assert_eq!(centre.len(), 1, "one vertex through all five planes");
}

#[test]
fn nearly_parallel_planes() {
    let e = 1e-9f64;
    let planes = [
        ([0.0, 0.0, 1.0], 0.0),
        ([0.0, e.sin(), e.cos()], 1e-10),
        ([1.0, 0.0, 0.0], 0.1),
        ([0.0, 1.0, 0.2], 0.05),
    ];
    let s = ball_sections(&planes, 1.0, 64);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
}

#[test]
fn duplicate_planes_are_rejected() {
    for dup in [([0.0, 0.0, 2.0], 0.2), ([0.0, 0.0, -1.0], -0.1)] {
        let s = ball_sections(
            &[([0.0, 0.0, 1.0], 0.1), ([1.0, 0.0, 0.0], 0.0), dup],
            1.0,
            32,
        );
        match Arrangement::build(&s, &ArrangementOptions::default()) {
            Err(Error::Input { location, reason }) => {
                assert!(
                    location.contains('0') && location.contains('2'),
                    "{location}"
                );
                assert!(reason.contains("duplicate"));
            }
            other => panic!(
                "expected an input error, got {:?}",
                other.map(|a| a.cells.len())
            ),
        }
    }
}

#[test]
fn contours_through_lines_and_vertices() {
    let pz = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
    let px = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
    let py = Plane::from_equation([0.0, 1.0, 0.0], -0.25).unwrap();
    // On z = 0: a square with an edge along x = 0, a triangle with a vertex at the arrangement
    // vertex (0, 0.25, 0), and a diamond touching x = 0 at one vertex.
    let z_polys = vec![
        vec![
            [0.0, -0.5, 0.0],
            [0.5, -0.5, 0.0],
            [0.5, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ],
        vec![[0.0, 0.25, 0.0], [-0.5, 0.5, 0.0], [-0.5, 0.3, 0.0]],
        vec![
            [-0.25, -0.25, 0.0],
            [0.0, -0.75, 0.0],
            [-0.25, -1.0, 0.0],
            [-0.5, -0.75, 0.0],
        ],
    ];
    // On x = 0: a square crossing both other planes' lines.
    let x_polys = vec![vec![
        [0.0, -0.5, -0.5],
        [0.0, 0.5, -0.5],
        [0.0, 0.5, 0.5],
        [0.0, -0.5, 0.5],
    ]];
    let y_polys = vec![vec![
        [-0.3, 0.25, -0.3],
        [0.3, 0.25, -0.3],
        [0.3, 0.25, 0.3],
        [-0.3, 0.25, 0.3],
    ]];
    let s = Sections {
        sections: vec![
            polygon_section(pz, &z_polys, 0),
            polygon_section(px, &x_polys, 1),
            polygon_section(py, &y_polys, 2),
        ],
        n_labels: 1,
        warnings: Vec::new(),
        label_names: Default::default(),
    };
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    // The three synthetic sections disagree along their lines on purpose; nothing else is reported.
    assert!(
        arr.warnings.iter().all(|w| w.starts_with("sections")),
        "{:?}",
        arr.warnings
    );
    assert!(arr.max_disagreement > 0.1);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]
    #[test]
    fn random_planes(planes in prop::collection::vec(
        ((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), -0.8f64..0.8), 1..=8)) {
        let planes: Vec<([f64; 3], f64)> = planes
            .into_iter()
            .filter(|((a, b, c), _)| a * a + b * b + c * c > 1e-3)
            .map(|((a, b, c), d)| {
                let l = (a * a + b * b + c * c).sqrt();
                ([a, b, c], d * l)
            })
            .collect();
        prop_assume!(!planes.is_empty());
        let s = ball_sections(&planes, 1.0, 48);
        prop_assume!(s.sections.iter().any(|x| !x.regions.is_empty()));
        let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
        arrangement_support::check_arrangement(&arr, &s);
        arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    }
}

/// Two perpendicular planes whose square sections cross their common line at points `gap` apart.
fn two_squares(gap: f64) -> Sections {
    let pz = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
    let py = Plane::from_equation([0.0, 1.0, 0.0], 0.0).unwrap();
    // Common line: the x-axis. z = 0 section spans x in [-0.5, 0.5]; y = 0 spans [-0.5 + gap, 0.5].
    let z_polys = vec![vec![
        [-0.5, -0.5, 0.0],
        [0.5, -0.5, 0.0],
        [0.5, 0.5, 0.0],
        [-0.5, 0.5, 0.0],
    ]];
    let y_polys = vec![vec![
        [-0.5 + gap, 0.0, -0.5],
        [0.5, 0.0, -0.5],
        [0.5, 0.0, 0.5],
        [-0.5 + gap, 0.0, 0.5],
    ]];
    Sections {
        sections: vec![
            polygon_section(pz, &z_polys, 0),
            polygon_section(py, &y_polys, 1),
        ],
        n_labels: 1,
        warnings: Vec::new(),
        label_names: Default::default(),
    }
}

fn line_vertices(arr: &Arrangement, plane: u32) -> Vec<u32> {
    let mut v: Vec<u32> = arr
        .faces
        .iter()
        .filter(|f| f.plane == plane)
        .flat_map(|f| f.pieces.iter().flat_map(|p| p.outer.iter().copied()))
        .filter(|&v| {
            let t = &arr.pool.tags[v as usize];
            t.contains(&0) && t.contains(&1) && t.len() == 2
        })
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

#[test]
fn close_crossings_are_snapped_to_one_shared_vertex() {
    let s = two_squares(1e-5);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    assert!(
        (arr.max_disagreement - 1e-5).abs() < 1e-12,
        "{}",
        arr.max_disagreement
    );
    // Both planes' pieces use the same two vertices on the x-axis.
    let (a, b) = (line_vertices(&arr, 0), line_vertices(&arr, 1));
    assert_eq!(a.len(), 2, "{a:?}");
    assert_eq!(a, b);
    // No orphan: every pool vertex is used by a face polygon or a piece.
    let mut used = vec![false; arr.pool.positions.len()];
    for f in &arr.faces {
        for &v in f.polygon.iter().chain(
            f.pieces
                .iter()
                .flat_map(|p| p.outer.iter().chain(p.holes.iter().flatten())),
        ) {
            used[v as usize] = true;
        }
    }
    assert!(used.iter().all(|&u| u));
}

#[test]
fn far_crossings_are_kept_and_shared_along_the_line() {
    let s = two_squares(0.1);
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    assert!(
        (arr.max_disagreement - 0.1).abs() < 1e-12,
        "{}",
        arr.max_disagreement
    );
    assert!(arr.warnings.iter().any(|w| w.contains("disagree")));
    // Plane 0's pieces pass through plane 1's crossing too (no T-junction along the line).
    let (a, b) = (line_vertices(&arr, 0), line_vertices(&arr, 1));
    assert_eq!(a.len(), 3, "{a:?}");
    assert!(b.iter().all(|v| a.contains(v)));
}

#[test]
fn contours_crossing_diagonally_through_an_arrangement_vertex() {
    let pz = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
    let px = Plane::from_equation([1.0, 0.0, 0.0], 0.0).unwrap();
    let py = Plane::from_equation([0.0, 1.0, 0.0], 0.0).unwrap();
    // First polygon: an edge from quadrant III to quadrant I through the origin (not a vertex);
    // second: a vertex exactly at (0, 0, 0.0) of another plane pair is avoided, but one at the
    // arrangement vertex of z = 0, x = 0, y = 0.5 is used.
    let py2 = Plane::from_equation([0.0, 1.0, 0.0], -0.5).unwrap();
    let z_polys = vec![
        vec![[-0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [0.6, -0.6, 0.0]],
        vec![
            [-0.3, 0.25, 0.0],
            [0.0, 0.5, 0.0],
            [0.3, 0.75, 0.0],
            [-0.3, 0.75, 0.0],
        ],
    ];
    let side = |k: usize| {
        vec![vec![[0.9, 0.9, 0.9], [0.9, 0.95, 0.9], [0.95, 0.95, 0.95]]]
            .into_iter()
            .map(|p: Vec<[f64; 3]>| {
                let pl = [px, py, py2][k];
                p.into_iter()
                    .map(|x| pl.to_3d(pl.to_2d(x)))
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
    };
    let s = Sections {
        sections: vec![
            polygon_section(pz, &z_polys, 0),
            polygon_section(px, &side(0), 1),
            polygon_section(py, &side(1), 2),
            polygon_section(py2, &side(2), 3),
        ],
        n_labels: 1,
        warnings: Vec::new(),
        label_names: Default::default(),
    };
    let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
    arrangement_support::check_arrangement(&arr, &s);
    arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
    assert!(
        arr.warnings.iter().all(|w| w.starts_with("sections")),
        "{:?}",
        arr.warnings
    );
    // The origin (z, x, y) is used by the pieces of the three faces the triangle covers there; the
    // vertex (0, 0.5, 0) is both a contour vertex and an arrangement vertex, used by the three
    // faces that the second polygon touches there.
    let origin = (0..arr.pool.tags.len() as u32)
        .find(|&v| {
            let t = &arr.pool.tags[v as usize];
            t.contains(&0) && t.contains(&1) && t.contains(&2)
        })
        .unwrap();
    let uses = arr
        .faces
        .iter()
        .filter(|f| f.plane == 0 && f.pieces.iter().any(|p| p.outer.contains(&origin)))
        .count();
    assert_eq!(uses, 3);
    let v05 = (0..arr.pool.tags.len() as u32)
        .find(|&v| {
            let t = &arr.pool.tags[v as usize];
            t.contains(&0) && t.contains(&1) && t.contains(&3)
        })
        .unwrap();
    let uses = arr
        .faces
        .iter()
        .filter(|f| f.plane == 0 && f.pieces.iter().any(|p| p.outer.contains(&v05)))
        .count();
    assert_eq!(uses, 3);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]
    /// Planes from a few normals with offsets on a grid: many planes through common lines and
    /// points, parallel planes, contours through arrangement features.
    #[test]
    fn random_degenerate_planes(choice in prop::collection::vec((0usize..7, -2i32..=2), 1..=8)) {
        const NORMALS: [[f64; 3]; 7] = [
            [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0],
            [1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, -1.0, 0.0],
        ];
        let mut seen = std::collections::HashSet::new();
        let planes: Vec<([f64; 3], f64)> = choice
            .into_iter()
            .filter(|c| seen.insert(*c))
            .map(|(n, o)| (NORMALS[n], 0.25 * o as f64))
            .collect();
        let s = ball_sections(&planes, 1.0, 40);
        prop_assume!(s.sections.iter().any(|x| !x.regions.is_empty()));
        let arr = Arrangement::build(&s, &ArrangementOptions::default()).unwrap();
        arrangement_support::check_arrangement(&arr, &s);
        arrangement_support::check_scopes_agree(&s, &ArrangementOptions::default());
        let other: Vec<_> = arr.warnings.iter().filter(|w| !w.starts_with("sections")).collect();
        prop_assert!(other.is_empty(), "{:?}", other);
    }
}
