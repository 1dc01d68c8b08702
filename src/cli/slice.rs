//! `slice MESH -o OUT.csl --planes N [--seed S] [--mode random|parallel|axes|fan|sweep|tilt]`: cut
//! a closed triangle mesh with planes and write the cross-sections (CSL or JSON by the output's
//! extension). The modes are described at `slice2solid::slice::SliceMode`.
use crate::{SliceArgs, SliceMode as CliMode};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::slice::{make_planes, slice_mesh, SliceMode};
use slice2solid::Result;
use std::process::ExitCode;

pub fn run(args: SliceArgs) -> Result<ExitCode> {
    let mesh = read_trimesh(&args.mesh)?;
    let mode = match args.mode {
        CliMode::Random => SliceMode::Random,
        CliMode::Parallel => SliceMode::Parallel,
        CliMode::Axes => SliceMode::Axes,
        CliMode::Fan => SliceMode::Fan,
        CliMode::Sweep => SliceMode::Sweep,
        CliMode::Tilt => SliceMode::Tilt,
    };
    let planes = make_planes(&mesh, args.planes, args.seed, mode);
    let sections =
        slice_mesh(&mesh, &planes).map_err(|e| with_file(e, &args.mesh.display().to_string()))?;
    slice2solid::io::write_sections(&args.output, &sections)?;
    let regions: usize = sections.sections.iter().map(|s| s.regions.len()).sum();
    let holes: usize = sections
        .sections
        .iter()
        .flat_map(|s| &s.regions)
        .map(|r| r.holes.len())
        .sum();
    println!(
        "{}: {} vertices, {} triangles; {} of {} planes cut it ({} skipped); {} regions, {} holes, {} contour vertices -> {}",
        args.mesh.display(),
        mesh.vertices.len(),
        mesh.triangles.len(),
        sections.sections.len(),
        planes.len(),
        planes.len() - sections.sections.len(),
        regions,
        holes,
        sections.vertex_count(),
        args.output.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// Slicing errors locate problems in "mesh" (or "mesh: section i"); name the file instead.
fn with_file(e: slice2solid::Error, file: &str) -> slice2solid::Error {
    match e {
        slice2solid::Error::Input { location, reason } if location.starts_with("mesh") => {
            slice2solid::Error::Input {
                location: location.replacen("mesh", file, 1),
                reason,
            }
        }
        other => other,
    }
}
