//! Boissonnat–Memari through the general arrangement: the paper's configurations with non-parallel
//! planes (sphere cut by the six faces of a cube; two non-parallel planes).
mod bm_common;
use bm_common::{polygon_section, worst_section};
use slice2solid::eval::check::check_mesh;
use slice2solid::{DelaunayOptions, Options, Plane, Section, Sections};

fn circle_section(plane: Plane, center: [f64; 3], r: f64, n: usize, index: usize) -> Section {
    let c = plane.to_2d(center);
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect();
    polygon_section(plane, pts, index)
}

/// Reconstruct, check (a closed oriented manifold free of self-intersections and degenerate
/// triangles, every section exact), return (components, genus, volume).
/// The raw Boissonnat–Memari solid (no collar) gives the numbers; the default one (with the
/// collar) must be as clean, with a volume within what its layers can change: 2 h × the summed
/// section areas, plus the largest move of its cells' maps (10 h) × the surface area.
fn run(name: &str, sections: &Sections) -> (usize, i64, f64) {
    let raw = Options {
        delaunay: DelaunayOptions {
            collar: 0.0,
            ..Default::default()
        },
        ..Default::default()
    };
    let (comps, genus, vol, _) = run_with(name, sections, &raw);
    let (_, _, collared, surface) = run_with(name, sections, &Options::default());
    let area = bm_common::section_area(sections);
    // the collar's height is relative to the padded box's diagonal: at most twice the model's
    let h = 2.0 * slice2solid::COLLAR_HEIGHT * slice2solid::validate::model_diagonal(sections);
    let bound = 2.0 * h * area + 10.0 * h * surface;
    assert!(
        (collared - vol).abs() <= bound,
        "{name}: volume with the collar {collared}, without {vol}, bound {bound}"
    );
    (comps, genus, vol)
}

fn run_with(name: &str, sections: &Sections, options: &Options) -> (usize, i64, f64, f64) {
    let solid =
        slice2solid::reconstruct(sections, options).unwrap_or_else(|e| panic!("{name}: {e}"));
    let c = check_mesh(&solid.surface, Some(sections));
    let worst = worst_section(&solid.surface, sections);
    for (x, y) in slice2solid::eval::section::section_agreement(
        &solid.surface,
        &bm_common::shifted(sections, -1e-7),
    )
    .iter()
    .zip(slice2solid::eval::section::section_agreement(
        &solid.surface,
        &bm_common::shifted(sections, 1e-7),
    )) {
        eprintln!(
            "  plane {}: input {:.4} mesh {:.4}/{:.4} rel {:.4}/{:.4}",
            x.plane, x.area_input, x.area_mesh, y.area_mesh, x.relative, y.relative
        );
    }
    eprintln!(
        "{name}: {} tris, closed {} manifold {} oriented {} comps {} genus {} vol {:.4} self-int {} worst section {:.4}\n  counts {:?}\n  warnings {:?}",
        c.triangles, c.closed, c.manifold, c.oriented, c.components, c.genus, c.volume,
        c.self_intersections_vertex_disjoint, worst, solid.report.counts, solid.report.warnings
    );
    bm_common::assert_closed_embedded(name, &c);
    assert_eq!(c.degenerate_triangles, 0, "{name}: degenerate triangles");
    let exact = c.worst_section.as_ref().map_or(0.0, |w| w.relative);
    eprintln!(
        "{name}: volume {:.12e} exact {exact:.3e} shifted {worst:.3e}",
        c.volume
    );
    assert!(exact < 1e-9, "{name}: section disagreement (exact) {exact}");
    assert!(
        worst < 1e-5,
        "{name}: section disagreement (shifted) {worst}"
    );
    (c.components, c.genus, c.volume, c.area)
}

#[test]
fn sphere_cut_by_cube_faces_gives_the_hull_of_the_contours() {
    let (a, r_sphere): (f64, f64) = (1.0, 1.3);
    let r = (r_sphere * r_sphere - a * a).sqrt();
    let mut sections = Sections {
        n_labels: 1,
        ..Default::default()
    };
    for (k, axis) in [0usize, 1, 2].iter().enumerate() {
        for (j, s) in [-1.0, 1.0].iter().enumerate() {
            let mut n = [0.0; 3];
            n[*axis] = *s;
            let plane = Plane::from_equation(n, -a).unwrap();
            let mut c = [0.0; 3];
            c[*axis] = s * a;
            sections
                .sections
                .push(circle_section(plane, c, r, 32, 2 * k + j));
        }
    }
    let (comps, genus, vol) = run("sphere-cube", &sections);
    {
        assert_eq!((comps, genus), (1, 0));
        // One cell holds every contour, nothing is pruned: the solid is the convex hull of the
        // contour vertices, whose volume is that of any tetrahedralisation of them (our kernel's).
        let pts: Vec<[f64; 3]> = sections
            .sections
            .iter()
            .flat_map(|s| s.regions[0].outer.points3.clone())
            .collect();
        let dt = slice2solid::delaunay::Delaunay::new(&pts);
        let hull: f64 = dt
            .tets()
            .map(|t| {
                let [a, b, c, d] = dt.tet_vertices(t).map(|v| dt.point(v));
                let (u, v, w) = (sub(b, a), sub(c, a), sub(d, a));
                (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                    + u[2] * (v[0] * w[1] - v[1] * w[0]))
                    .abs()
                    / 6.0
            })
            .sum();
        assert!(
            (vol - hull).abs() <= 1e-9 * hull,
            "volume {vol} is not the hull's {hull}"
        );
    }
}

/// Today's volumes (relative 1e-9): no closed form (the join between non-parallel circles; slabs
/// whose thickness the thickening chooses).
const TWO_PLANES_VOLUME: f64 = 4.792340527294353;
const ISLAND_VOLUME: f64 = 6.215034900771671;
/// The square (area 4) as a slab of tetrahedra 3.6e-3 thick (1e-3 of the padded box's diagonal,
/// `bm::slab`).
const SINGLE_VOLUME: f64 = 1.431090890340885e-2;
/// Two such slabs, thicker (the thickness follows the model's size).
const EMPTY_MIDDLE_VOLUME: f64 = 3.664144922515024e-2;

fn assert_volume(name: &str, vol: f64, expected: f64) {
    assert!(
        (vol - expected).abs() <= 1e-9 * expected.abs(),
        "{name}: volume {vol:.15e}, expected {expected:.15e}"
    );
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[test]
fn two_non_parallel_planes() {
    let pa = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
    let t = 30f64.to_radians();
    let nb = [t.sin(), 0.0, t.cos()];
    let pb = Plane::from_point_normal([0.0, 0.0, 2.0], nb).unwrap();
    let sections = Sections {
        sections: vec![
            circle_section(pa, [0.0, 0.0, 0.0], 1.0, 32, 0),
            circle_section(pb, [0.0, 0.0, 2.0], 0.8, 28, 1),
        ],
        n_labels: 1,
        warnings: vec![],
        label_names: Default::default(),
    };
    let (comps, genus, vol) = run("two-planes", &sections);
    assert_eq!((comps, genus), (1, 0));
    assert_volume("two-planes", vol, TWO_PLANES_VOLUME);
}

/// Sections with several regions (each a counter-clockwise circle) on one plane.
fn circles_section(plane: Plane, circles: &[([f64; 3], f64, usize)], index: usize) -> Section {
    let mut s = circle_section(plane, circles[0].0, circles[0].1, circles[0].2, index);
    for &(c, r, n) in &circles[1..] {
        s.regions
            .extend(circle_section(plane, c, r, n, index).regions);
    }
    s
}

/// The paper's Fig. 13: on sparse planes a region of a section can be attached from neither side (a
/// flat zone on both). Here the middle of three parallel planes carries, besides the disk that
/// continues above and below, an island that nothing above or below faces. The island must still be
/// in the solid's section (thickened into a thin slab, Fig. 12c), and the surface stay a closed
/// oriented manifold without crossings.
#[test]
fn island_attached_from_neither_side_is_thickened() {
    let planes: Vec<Plane> = (0..3)
        .map(|k| Plane::from_equation([0.0, 0.0, 1.0], -(k as f64)).unwrap())
        .collect();
    let sections = Sections {
        sections: vec![
            circle_section(planes[0], [0.0, 0.0, 0.0], 1.0, 24, 0),
            circles_section(
                planes[1],
                &[([0.0, 0.0, 1.0], 1.0, 24), ([3.0, 0.0, 1.0], 0.4, 16)],
                1,
            ),
            circle_section(planes[2], [0.0, 0.0, 2.0], 1.0, 24, 2),
        ],
        n_labels: 1,
        warnings: vec![],
        label_names: Default::default(),
    };
    let solid = slice2solid::reconstruct(&sections, &Options::default()).expect("reconstruct");
    eprintln!("island: {:?}", solid.report.warnings);
    let thickened = solid
        .report
        .counts
        .get("flat_zone_triangles_thickened")
        .copied()
        .unwrap_or(0);
    assert!(thickened >= 1, "{:?}", solid.report.counts);
    let (comps, genus, vol) = run("island", &sections);
    // the column of disks, and the island's slab (nothing above or below it to merge with)
    assert_eq!((comps, genus), (2, 0));
    assert_volume("island", vol, ISLAND_VOLUME);
}

/// A square on z = `z` (counter-clockwise seen from +z).
fn square_section(plane: Plane, z: f64, index: usize) -> Section {
    let pts: Vec<[f64; 2]> = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]
        .iter()
        .map(|&[x, y]| plane.to_2d([x, y, z]))
        .collect();
    polygon_section(plane, pts, index)
}

/// Flat-zone triangles thickened into slabs, when the warning says so and none is left out.
fn thickened(report: &slice2solid::Report) -> u64 {
    let warned = report
        .warnings
        .iter()
        .any(|w| w.starts_with("flat zones:") && w.contains("thickened into slabs"));
    assert_eq!(report.counts["flat_zone_triangles_left"], 0);
    if warned {
        report.counts["flat_zone_triangles_thickened"]
    } else {
        0
    }
}

/// One section alone bounds no volume in any cell: it is a flat zone attached from neither side,
/// and becomes a thin slab (it used to vanish, with an empty surface and no warning).
#[test]
fn a_single_section_is_a_thin_slab() {
    let plane = Plane::from_equation([0.0, 0.0, 1.0], 0.0).unwrap();
    let sections = Sections {
        sections: vec![square_section(plane, 0.0, 0)],
        n_labels: 1,
        warnings: vec![],
        label_names: Default::default(),
    };
    let solid = slice2solid::reconstruct(&sections, &Options::default()).unwrap();
    assert_eq!(thickened(&solid.report), 2, "{:?}", solid.report.warnings);
    let (comps, genus, vol) = run("single", &sections);
    assert_eq!((comps, genus), (1, 0));
    assert_volume("single", vol, SINGLE_VOLUME);
}

/// Two squares with an empty plane between them: the solid may not cross the empty plane, so each
/// square is a flat zone of its own (two slabs), and the empty plane's section stays empty.
#[test]
fn sections_apart_from_an_empty_plane_between_them_are_kept() {
    let planes: Vec<Plane> = (0..3)
        .map(|k| Plane::from_equation([0.0, 0.0, 1.0], -(k as f64)).unwrap())
        .collect();
    let mut empty = square_section(planes[1], 1.0, 1);
    empty.regions.clear();
    let sections = Sections {
        sections: vec![
            square_section(planes[0], 0.0, 0),
            empty,
            square_section(planes[2], 2.0, 2),
        ],
        n_labels: 1,
        warnings: vec![],
        label_names: Default::default(),
    };
    let solid = slice2solid::reconstruct(&sections, &Options::default()).unwrap();
    assert_eq!(thickened(&solid.report), 4, "{:?}", solid.report.warnings);
    let (comps, genus, vol) = run("empty-middle", &sections);
    assert_eq!((comps, genus), (2, 0));
    assert_volume("empty-middle", vol, EMPTY_MIDDLE_VOLUME);
}
