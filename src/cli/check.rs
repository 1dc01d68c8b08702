//! `slice2solid check MESH [--sections INPUT] [--json]`: exit status 1 when the mesh is not a closed
//! manifold, so scripts can gate on it. A `.vtk` or `.mesh` file is a tetrahedral mesh and goes to
//! [`super::check_tets`].
use crate::CheckArgs;
use slice2solid::eval::check::{check_mesh, CheckReport};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::io::read_sections;
use slice2solid::{Error, Result};
use std::process::ExitCode;

pub fn run(args: CheckArgs) -> Result<ExitCode> {
    if !args.partition.is_empty() {
        return super::check_partition::run(&args);
    }
    let mesh_path = args
        .mesh
        .clone()
        .ok_or_else(|| Error::input("check", "a MESH or --partition is needed"))?;
    if super::check_tets::is_tet_mesh(&mesh_path) {
        return super::check_tets::run(args, &mesh_path);
    }
    if let Some(s) = &args.surface {
        return Err(Error::input(
            s.display().to_string(),
            format!(
                "--surface compares a tetrahedral mesh's boundary with a surface, but {} is not a tetrahedral mesh (.vtk or .mesh)",
                mesh_path.display()
            ),
        ));
    }
    let mesh = read_trimesh(&mesh_path)?;
    let sections = match &args.sections {
        Some(p) => Some(read_sections(p)?),
        None => None,
    };
    let report = check_mesh(&mesh, sections.as_ref());
    if args.json {
        super::print_json(&report)?;
    } else {
        print_table(&mesh_path.display().to_string(), &report);
    }
    Ok(if report.is_closed_manifold() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "NO"
    }
}

fn print_table(name: &str, r: &CheckReport) {
    println!("{name}: {} vertices, {} triangles", r.vertices, r.triangles);
    println!(
        "  closed              {}  ({} boundary edges)",
        yes(r.closed),
        r.boundary_edges
    );
    println!(
        "  manifold            {}  ({} non-manifold edges, {} non-manifold vertices)",
        yes(r.manifold),
        r.nonmanifold_edges,
        r.nonmanifold_vertices
    );
    println!(
        "  oriented outward    {}  ({} inconsistent edges)",
        yes(r.oriented),
        r.inconsistent_edges
    );
    match r.self_intersection_example {
        Some([i, j]) => println!(
            "  self-intersections  {}  (e.g. triangles {i} and {j})",
            r.self_intersections
        ),
        None => println!("  self-intersections  0"),
    }
    match r.overlapping_coplanar_example {
        Some([i, j]) => println!(
            "  overlapping coplanar {}  (double sheet within {:.1e}, e.g. triangles {i} and {j})",
            r.overlapping_coplanar_pairs, r.near_coplanar_tolerance
        ),
        None => println!("  overlapping coplanar 0"),
    }
    if r.edge_in_plane_pairs > 0 {
        println!(
            "    (info: {} disjoint pairs with an edge in the other's plane, where float tests may see crossings)",
            r.edge_in_plane_pairs
        );
    }
    if r.coincident_vertices > 0 {
        println!(
            "  coincident vertices {}  (distinct vertices at one position: pinch points)",
            r.coincident_vertices
        );
    }
    if r.degenerate_triangles > 0 {
        println!("  degenerate tris     {}", r.degenerate_triangles);
    }
    if r.self_intersections > 0 {
        println!(
            "    of which sharing no vertex: {}",
            r.self_intersections_vertex_disjoint
        );
    }
    println!("  components          {}", r.components);
    println!("  euler               {}", r.euler);
    println!("  genus (total)       {}", r.genus);
    println!("  volume              {:.6e}", r.volume);
    println!("  area                {:.6e}", r.area);
    if r.components > 1 {
        println!("  component  triangles  euler  genus  closed  volume");
        for (i, c) in r.component_details.iter().enumerate() {
            println!(
                "  {:>9}  {:>9}  {:>5}  {:>5}  {:>6}  {:.6e}",
                i,
                c.triangles,
                c.euler,
                c.genus.map_or("-".to_string(), |g| g.to_string()),
                yes(c.closed),
                c.volume
            );
        }
    }
    if !r.sections.is_empty() {
        let secs = &r.sections;
        println!("  plane  source  area_input    area_mesh     sym_diff      relative");
        for s in secs {
            println!(
                "  {:>5}  {:>6}  {:.6e}  {:.6e}  {:.6e}  {:.3e}",
                s.plane, s.source_index, s.area_input, s.area_mesh, s.sym_diff, s.relative
            );
        }
        if let Some(w) = &r.worst_section {
            println!(
                "  worst section: plane {} (input plane {}), relative symmetric difference {:.3e}",
                w.plane, w.source_index, w.relative
            );
        }
    }
    println!(
        "  => {}",
        if r.is_closed_manifold() {
            "closed manifold"
        } else {
            "NOT a closed manifold"
        }
    );
}
