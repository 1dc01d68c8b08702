mod common;
#[test]
#[ignore]
fn one_file() {
    let name = std::env::var("BM_FILE").unwrap();
    let path = common::shared_dir()
        .join("data/csl")
        .join(format!("{name}.csl"));
    let sections = slice2solid::io::read_sections(&path).unwrap();
    let solid = slice2solid::reconstruct(&sections, &slice2solid::Options::default()).unwrap();
    let c = slice2solid::eval::check::check_mesh(&solid.surface, None);
    eprintln!(
        "{name}: closed {} manifold {} nm-edges {} nm-verts {} boundary {} self-int {}",
        c.closed,
        c.manifold,
        c.nonmanifold_edges,
        c.nonmanifold_vertices,
        c.boundary_edges,
        c.self_intersections_vertex_disjoint
    );
    eprintln!("{:?}", solid.report.counts);
    if let Some([i, j]) = c.self_intersection_example {
        let m = &solid.surface;
        for t in [i, j] {
            let tr = m.triangles[t];
            eprintln!("  tri {t}: {:?}", tr.map(|v| m.vertices[v as usize]));
        }
    }
    for w in solid.report.warnings.iter().take(10) {
        eprintln!("  w: {w}");
    }
}
