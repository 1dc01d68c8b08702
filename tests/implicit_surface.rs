//! Zero-set extraction on hand-built arrangements: closed, oriented 2-manifolds through the contours.
use slice2solid::implicit::fixtures::{circle, horizontal_slabs, Level};
use slice2solid::implicit::surface;
use slice2solid::{Report, TriMesh};
use std::collections::HashMap;

/// Every directed edge once and its reverse once: closed, consistently oriented, edge-manifold.
/// Returns the Euler characteristic V − E + F.
fn check_closed_oriented(m: &TriMesh) -> i64 {
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "degenerate {t:?}"
        );
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "directed edge {a}->{b} used {n} times");
        assert_eq!(directed.get(&(b, a)), Some(&1), "edge {a}-{b} is a border");
    }
    // Vertex manifoldness: the triangles around each vertex form one fan (one cycle).
    let mut next: HashMap<u32, HashMap<u32, u32>> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            next.entry(t[k])
                .or_default()
                .insert(t[(k + 1) % 3], t[(k + 2) % 3]);
        }
    }
    for (v, ring) in &next {
        let start = *ring.keys().next().unwrap();
        let mut cur = start;
        let mut len = 0;
        loop {
            cur = ring[&cur];
            len += 1;
            if cur == start {
                break;
            }
            assert!(len <= ring.len(), "vertex {v}: broken fan");
        }
        assert_eq!(len, ring.len(), "vertex {v} is not manifold");
    }
    let used: std::collections::HashSet<u32> = m.triangles.iter().flatten().copied().collect();
    used.len() as i64 - (directed.len() / 2) as i64 + m.triangles.len() as i64
}

fn signed_volume(m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let (a, b, c) = (
                m.vertices[t[0] as usize],
                m.vertices[t[1] as usize],
                m.vertices[t[2] as usize],
            );
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum()
}

fn point_triangle_distance(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    // Dense barycentric sampling is enough at the test's tolerance (a fraction of a grid step).
    let mut best = f64::INFINITY;
    let n = 8;
    for i in 0..=n {
        for j in 0..=(n - i) {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            let w = 1.0 - u - v;
            let q = [
                w * a[0] + u * b[0] + v * c[0],
                w * a[1] + u * b[1] + v * c[1],
                w * a[2] + u * b[2] + v * c[2],
            ];
            let d = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2)).sqrt();
            best = best.min(d);
        }
    }
    best
}

fn distance_to_mesh(p: [f64; 3], m: &TriMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            point_triangle_distance(
                p,
                m.vertices[t[0] as usize],
                m.vertices[t[1] as usize],
                m.vertices[t[2] as usize],
            )
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn single_circle_between_two_parallel_planes_gives_a_closed_surface_through_it() {
    let levels = [
        Level {
            z: -0.5,
            pieces: vec![],
        },
        Level {
            z: 0.0,
            pieces: vec![(circle([0.1, -0.1], 0.4, 48), vec![])],
        },
        Level {
            z: 0.5,
            pieces: vec![],
        },
    ];
    let arr = horizontal_slabs([-1.0; 3], [1.0; 3], &levels);
    let depth = 6;
    let mut report = Report::default();
    let mesh = surface(&arr, depth, false, &mut report).unwrap();
    assert!(!mesh.triangles.is_empty());
    let chi = check_closed_oriented(&mesh);
    assert_eq!(chi, 2, "one sphere-like component expected");
    assert!(signed_volume(&mesh) > 0.0, "outward orientation");
    // Between the two empty planes: the surface stays strictly between them.
    for p in &mesh.vertices {
        assert!(p[2] > -0.5 && p[2] < 0.5, "{p:?}");
    }
    // Through the circle: every contour vertex lies within one grid step of the surface.
    let h = 2.0 / (1u32 << depth) as f64;
    for q in circle([0.1, -0.1], 0.4, 48) {
        let d = distance_to_mesh([q[0], q[1], 0.0], &mesh);
        assert!(
            d <= h,
            "contour point {q:?} is {d} from the surface (h = {h})"
        );
    }
    assert!(report.counts["implicit_evaluations"] > 0);
}

#[test]
fn annulus_between_two_empty_planes_gives_a_torus() {
    // An annulus (disc with a hole) on one plane between two empty planes: a torus (χ = 0).
    let mut hole = circle([0.0, 0.0], 0.25, 40);
    hole.reverse();
    let levels = [
        Level {
            z: -0.4,
            pieces: vec![],
        },
        Level {
            z: 0.0,
            pieces: vec![(circle([0.0, 0.0], 0.6, 64), vec![hole])],
        },
        Level {
            z: 0.4,
            pieces: vec![],
        },
    ];
    let arr = horizontal_slabs([-1.0; 3], [1.0; 3], &levels);
    let mut report = Report::default();
    let mesh = surface(&arr, 6, false, &mut report).unwrap();
    let chi = check_closed_oriented(&mesh);
    assert_eq!(chi, 0, "a torus expected");
    assert!(signed_volume(&mesh) > 0.0);
}
