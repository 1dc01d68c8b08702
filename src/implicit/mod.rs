//! The implicit method of Bermano, Vaxman & Gotsman (2011): mean-value interpolation of the sections
//! per arrangement cell (`indicator`, with the closed-form weights of `mvc`), zero set found on an
//! octree (`octree`) and extracted by marching tetrahedra (`extract`).
pub mod extract;
pub mod fixtures;
pub mod indicator;
pub mod labels;
pub mod mvc;
pub mod octree;

use crate::arrangement::Arrangement;
use crate::error::Result;
use crate::mesh::TriMesh;
use crate::sections::Sections;
use crate::solid::{Options, Report, Solid};
use indicator::{FaceKind, Indicator};
use octree::{Field, Grid, Refinement};

/// Section contour vertices in 3D: the vertices of the section pieces on faces that are partly inside.
pub fn contour_points(ind: &Indicator) -> Vec<[f64; 3]> {
    ind.faces
        .iter()
        .filter(|f| f.kind == FaceKind::Mixed)
        .flat_map(|f| {
            f.piece_loops
                .iter()
                .flatten()
                .map(move |&q| f.plane.to_3d(q))
        })
        .collect()
}

/// The zero set of the indicator of `arrangement` on a grid of depth `depth`, with statistics in `report`.
pub fn surface(
    arrangement: &Arrangement,
    depth: u32,
    progress: bool,
    report: &mut Report,
) -> Result<TriMesh> {
    let refinement = Refinement::default();
    let ind = report.time("indicator", || Indicator::new(arrangement))?;
    let grid = Grid::new(arrangement.bbox.0, arrangement.bbox.1, depth);
    let points = contour_points(&ind);
    let bar = if progress {
        let b = indicatif::ProgressBar::new_spinner();
        b.enable_steady_tick(std::time::Duration::from_millis(200));
        Some(b)
    } else {
        None
    };
    let on_progress = |stage: &str, n: u64| {
        if let Some(b) = &bar {
            b.set_message(format!("implicit: {stage}, {n} evaluations"));
        }
    };
    let field = report.time("octree", || {
        Field::build(&ind, grid, &points, refinement, &on_progress)
    });
    if let Some(b) = &bar {
        b.set_message("implicit: extracting the zero set");
    }
    let mesh = report.time("extract", || extract::extract(&field));
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    report.count("implicit_depth", field.grid.depth as u64);
    report.count("implicit_evaluations", field.evaluations);
    report.count("implicit_interpolated_nodes", field.interpolated);
    report.count(
        "implicit_coarse_surface_leaves",
        field.coarse_surface_leaves,
    );
    report.count("implicit_surface_cubes", field.surface_cubes.len() as u64);
    report.count("implicit_closure_waves", field.flood_waves);
    report.count(
        "implicit_constant_cells",
        ind.cells.iter().filter(|c| c.constant.is_some()).count() as u64,
    );
    report.count("implicit_contour_vertices", points.len() as u64);
    for (i, n) in field.cubes_per_level.iter().enumerate() {
        report.count(
            &format!(
                "implicit_cubes_level_{:02}",
                refinement.coarse.min(field.grid.depth) as usize + i
            ),
            *n,
        );
    }
    report.count("triangles", mesh.triangles.len() as u64);
    report
        .values
        .insert("implicit_grid_step".into(), field.grid.h);
    Ok(mesh)
}

/// Reconstruct with the implicit mean-value method. Fills `report` (phases, counts, warnings).
pub fn reconstruct(
    _sections: &Sections,
    arrangement: &Arrangement,
    options: &Options,
    report: &mut Report,
) -> Result<Solid> {
    let surface = surface(arrangement, options.depth, options.progress, report)?;
    Ok(Solid {
        surface,
        tets: None,
        report: Report::default(),
    })
}
