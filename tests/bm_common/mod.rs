//! Helpers of the bm integration tests: parallel-plane arrangements built by hand, section checks.
#![allow(dead_code)]
use slice2solid::arrangement::{
    ArrPlane, Arrangement, Cell, CellFace, Face, SectionPiece, VertexPool,
};
use slice2solid::{Contour, Plane, Region, Section, Sections};
use smallvec::smallvec;

/// A polygon with holes in the xy plane: outer counter-clockwise, holes clockwise.
pub type Poly = (Vec<[f64; 2]>, Vec<Vec<[f64; 2]>>);

pub fn circle(cx: f64, cy: f64, r: f64, n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [cx + r * a.cos(), cy + r * a.sin()]
        })
        .collect()
}

/// A surface check's verdict on a solid's surface: a closed, oriented manifold with no crossing
/// and no near-coplanar overlapping triangle pair; fails naming `name`.
pub fn assert_closed_embedded(name: &str, c: &slice2solid::eval::check::CheckReport) {
    assert!(
        c.closed && c.manifold && c.oriented,
        "{name}: not a closed oriented manifold"
    );
    assert!(
        c.self_intersection_free,
        "{name}: {} crossing pairs, {} overlapping near-coplanar pairs",
        c.self_intersections, c.overlapping_coplanar_pairs
    );
}

/// One region (label 1) bounded by `pts` (in the plane's frame) on `plane`.
pub fn polygon_section(plane: Plane, pts: Vec<[f64; 2]>, index: usize) -> Section {
    Section {
        plane,
        regions: vec![Region {
            label: 1,
            outer: Contour::from_2d(&plane, pts),
            holes: vec![],
        }],
        source_index: index,
        max_off_plane: 0.0,
    }
}

pub fn reversed(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p.reverse();
    p
}

/// Sections on horizontal planes z = z_i, and the arrangement of those parallel planes built by hand
/// (cells i = slab between plane i-1 and plane i; the box walls carry no section and are omitted).
pub fn parallel_case(layers: &[(f64, Vec<Poly>)]) -> (Sections, Arrangement) {
    let mut sections = Sections {
        n_labels: 1,
        ..Default::default()
    };
    let mut arr = Arrangement {
        planes: Vec::new(),
        n_input: layers.len(),
        pool: VertexPool::default(),
        faces: Vec::new(),
        cells: Vec::new(),
        bbox: ([-10.0; 3], [10.0; 3]),
        scope: slice2solid::arrangement::CellScope::Sections,
        max_disagreement: 0.0,
        warnings: Vec::new(),
    };
    for (i, (z, polys)) in layers.iter().enumerate() {
        let plane = Plane::from_equation([0.0, 0.0, 1.0], -z).unwrap();
        let mut regions = Vec::new();
        let mut pieces = Vec::new();
        let pool = &mut arr.pool;
        let add_loop = |xy: &Vec<[f64; 2]>, pool: &mut VertexPool| -> (Contour, Vec<u32>) {
            let uv: Vec<[f64; 2]> = xy.iter().map(|p| plane.to_2d([p[0], p[1], *z])).collect();
            let c = Contour::from_2d(&plane, uv);
            let ids = (0..xy.len())
                .map(|k| {
                    pool.positions.push(c.points3[k]);
                    pool.tags.push(smallvec![i as u32]);
                    pool.uv.push(smallvec![c.points2[k]]);
                    (pool.positions.len() - 1) as u32
                })
                .collect();
            (c, ids)
        };
        for (outer, holes) in polys {
            let (oc, oid) = add_loop(outer, pool);
            let mut hcs = Vec::new();
            let mut hids = Vec::new();
            for h in holes {
                let (hc, hid) = add_loop(h, pool);
                hcs.push(hc);
                hids.push(hid);
            }
            regions.push(Region {
                label: 1,
                outer: oc,
                holes: hcs,
            });
            pieces.push(SectionPiece {
                label: 1,
                outer: oid,
                holes: hids,
            });
        }
        sections.sections.push(Section {
            plane,
            regions,
            source_index: i,
            max_off_plane: 0.0,
        });
        arr.planes.push(ArrPlane {
            plane,
            section: Some(i),
        });
        arr.faces.push(Face {
            plane: i as u32,
            positive_cell: Some(i as u32 + 1),
            negative_cell: Some(i as u32),
            polygon: Vec::new(),
            pieces,
        });
    }
    for c in 0..=layers.len() {
        let mut faces = Vec::new();
        if c > 0 {
            faces.push(CellFace {
                face: c as u32 - 1,
                outward_is_plane_normal: false,
            });
        }
        if c < layers.len() {
            faces.push(CellFace {
                face: c as u32,
                outward_is_plane_normal: true,
            });
        }
        arr.cells.push(Cell { faces, volume: 1.0 });
    }
    (sections, arr)
}

/// The same sections with every plane's normal reversed (frames recomputed, contours re-expressed).
pub fn flipped(s: &Sections) -> Sections {
    let mut out = s.clone();
    for sec in &mut out.sections {
        let p = Plane::from_equation(
            [
                -sec.plane.normal[0],
                -sec.plane.normal[1],
                -sec.plane.normal[2],
            ],
            -sec.plane.offset,
        )
        .unwrap();
        let redo = |c: &Contour| {
            let mut pts: Vec<[f64; 3]> = c.points3.clone();
            pts.reverse();
            Contour {
                points2: pts.iter().map(|&q| p.to_2d(q)).collect(),
                points3: pts,
            }
        };
        for r in &mut sec.regions {
            r.outer = redo(&r.outer);
            r.holes = r.holes.iter().map(redo).collect();
        }
        sec.plane = p;
    }
    out
}

/// The same sections moved by `eps` along each plane's normal (frames keep u, v; (u,v) unchanged).
pub fn shifted(s: &Sections, eps: f64) -> Sections {
    let mut out = s.clone();
    for sec in &mut out.sections {
        let n = sec.plane.normal;
        let p = Plane::from_equation(n, sec.plane.offset - eps).unwrap();
        for r in &mut sec.regions {
            for c in std::iter::once(&mut r.outer).chain(r.holes.iter_mut()) {
                c.points3 = c.points2.iter().map(|&q| p.to_3d(q)).collect();
            }
        }
        sec.plane = p;
    }
    out
}

/// Largest per-plane relative symmetric difference between the mesh's section and the input, each
/// plane measured on a parallel plane moved by ±1e-7 of the model size to whichever side agrees
/// better: a solid's face lying in a section plane (rounded, not exactly coplanar) makes the section
/// exactly at the plane ill-defined, and a solid lying on one side of its extreme plane is seen from
/// that side only.
pub fn worst_section(mesh: &slice2solid::TriMesh, s: &Sections) -> f64 {
    use slice2solid::eval::section::section_agreement;
    let (lo, hi) = s.bounding_box().unwrap_or(([0.0; 3], [1.0; 3]));
    let diag = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    let eps = 1e-7 * diag;
    let a = section_agreement(mesh, &shifted(s, eps));
    let b = section_agreement(mesh, &shifted(s, -eps));
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| x.relative.min(y.relative))
        // NaN (a broken measurement) must not vanish in the max
        .fold(0.0_f64, |m, r| {
            if r.is_nan() || m.is_nan() {
                f64::NAN
            } else {
                m.max(r)
            }
        })
}

/// The summed area of every section's material (outer contours less holes).
#[allow(dead_code)]
pub fn section_area(sections: &Sections) -> f64 {
    let shoelace = |p: &[[f64; 2]]| {
        let n = p.len();
        (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum::<f64>()
            .abs()
            / 2.0
    };
    sections
        .sections
        .iter()
        .flat_map(|s| &s.regions)
        .map(|r| {
            shoelace(&r.outer.points2) - r.holes.iter().map(|h| shoelace(&h.points2)).sum::<f64>()
        })
        .sum()
}

/// The diagonal of the bounding box of `points`.
pub fn diagonal(points: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt()
}

/// The smallest distance between two vertices of `mesh`, relative to its bounding-box diagonal
/// (tools such as trimesh weld vertices closer than about 1e-8 and so break a surface there).
#[allow(dead_code)]
pub fn closest_vertex_gap(mesh: &slice2solid::TriMesh) -> f64 {
    let v = &mesh.vertices;
    let diag = diagonal(v);
    // sorted by x, each vertex against those after it within the best distance so far
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a][0].total_cmp(&v[b][0]));
    let mut best = f64::INFINITY;
    for (i, &a) in order.iter().enumerate() {
        for &b in &order[i + 1..] {
            if v[b][0] - v[a][0] >= best {
                break;
            }
            let d = (0..3)
                .map(|k| (v[a][k] - v[b][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            best = best.min(d);
        }
    }
    best / diag
}

/// How many pairs of vertices of `mesh` lie closer than `relative` of its diagonal (tools that
/// weld vertices, trimesh at about 1e-8, merge them).
pub fn close_vertex_pairs(mesh: &slice2solid::TriMesh, relative: f64) -> usize {
    let v = &mesh.vertices;
    let limit = relative * diagonal(v);
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a][0].total_cmp(&v[b][0]));
    let mut count = 0;
    for (i, &a) in order.iter().enumerate() {
        for &b in &order[i + 1..] {
            if v[b][0] - v[a][0] >= limit {
                break;
            }
            let d2: f64 = (0..3).map(|k| (v[a][k] - v[b][k]).powi(2)).sum();
            count += usize::from(d2 < limit * limit);
        }
    }
    count
}
