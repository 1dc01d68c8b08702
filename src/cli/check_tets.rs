//! `slice2solid check TETS.vtk|TETS.mesh [--surface OUT] [--json]`: exit status 1 unless the
//! tetrahedral mesh is valid (see [`slice2solid::eval::tets`]). `--sections` is refused here: the
//! section comparison is a property of a surface, so check the surface file with it instead.
use crate::CheckArgs;
use slice2solid::eval::tets::{check_tets, TetCheck};
use slice2solid::io::mesh::{read_tetmesh, read_trimesh};
use slice2solid::{Error, Result};
use std::path::Path;
use std::process::ExitCode;

/// Tetrahedral meshes are told by their extension (the formats `read_tetmesh` reads).
pub fn is_tet_mesh(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    ext.eq_ignore_ascii_case("vtk") || ext.eq_ignore_ascii_case("mesh")
}

pub fn run(args: CheckArgs, mesh: &Path) -> Result<ExitCode> {
    if args.sections.is_some() {
        return Err(Error::input(
            mesh.display().to_string(),
            "--sections applies to a triangle surface, not to a tetrahedral mesh: check the surface \
             (e.g. the reconstruction's -o file) with --sections, and the tetrahedra with --surface",
        ));
    }
    let tets = read_tetmesh(mesh)?;
    let surface = match &args.surface {
        Some(p) => Some(read_trimesh(p)?),
        None => None,
    };
    let report = check_tets(&tets, surface.as_ref());
    if args.json {
        super::print_json(&report)?;
    } else {
        print_table(&mesh.display().to_string(), &report);
    }
    Ok(if report.valid {
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

/// A count that must be zero: "0", or the count flagged.
fn zero(n: usize) -> String {
    if n == 0 {
        "0".into()
    } else {
        format!("{n}  <- defect")
    }
}

fn print_table(name: &str, r: &TetCheck) {
    println!("{name}: {} points, {} tetrahedra", r.points, r.tets);
    if r.index_out_of_range > 0 {
        println!("  index out of range   {}", zero(r.index_out_of_range));
    }
    println!("  coincident vertices  {}", zero(r.coincident_vertices));
    println!("  inverted tets        {}", zero(r.inverted));
    if r.inverted == r.tets && r.tets > 0 {
        println!("    (all of them: the file orients tetrahedra the other way, orient3d > 0)");
    }
    println!("  flat tets            {}", zero(r.flat));
    println!(
        "  faces in 3+ tets     {}",
        zero(r.faces_used_more_than_twice)
    );
    println!(
        "  interior faces       {}  ({} with both tets on one side)",
        r.interior_faces, r.interior_faces_same_side
    );
    print_boundary(r);
    if let Some(s) = &r.surface {
        println!("  surface triangles    {}", s.surface_triangles);
        println!(
            "    missing from boundary {}",
            zero(s.surface_triangles_missing)
        );
        println!(
            "    extra in boundary     {}",
            zero(s.boundary_triangles_extra)
        );
        println!(
            "    orientation flipped   {}",
            zero(s.orientation_mismatches)
        );
        println!("  boundary = surface   {}", yes(s.boundary_equals_surface));
    }
    println!("  conforming           {}", yes(r.conforming));
    println!(
        "  => {}",
        if r.valid {
            "valid tetrahedral mesh"
        } else {
            "NOT a valid tetrahedral mesh"
        }
    );
}

fn print_boundary(r: &TetCheck) {
    println!("  boundary triangles   {}", r.boundary_triangles);
    println!(
        "    closed             {}  ({} boundary edges)",
        yes(r.boundary_closed),
        r.boundary_edges
    );
    println!(
        "    manifold           {}  ({} non-manifold edges, {} non-manifold vertices)",
        yes(r.boundary_manifold),
        r.boundary_nonmanifold_edges,
        r.boundary_nonmanifold_vertices
    );
    println!("    oriented outward   {}", yes(r.boundary_oriented));
    println!(
        "    self-intersections {}",
        zero(r.boundary_self_intersections)
    );
    println!(
        "  volume               {:.9e}  (boundary encloses {:.9e}: {})",
        r.volume,
        r.boundary_volume,
        if r.volume_matches {
            "same"
        } else {
            "DIFFERENT"
        }
    );
}
