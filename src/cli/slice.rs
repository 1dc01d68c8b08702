//! `slice MESH[:LABEL]... -o OUT.csl --planes N [--seed S] [--mode random|parallel|axes|fan|sweep|tilt]`:
//! cut closed triangle meshes with planes and write the cross-sections (CSL or JSON by the output's
//! extension). One mesh without a label goes through `slice_mesh` (label 1); several (or a label)
//! through `slice_partition`, the planes placed for the union of the meshes. The modes are described
//! at `slice2solid::slice::SliceMode`.
use crate::{SliceArgs, SliceMode as CliMode};
use slice2solid::io::mesh::read_trimesh;
use slice2solid::slice::{
    make_planes, slice_mesh, slice_partition, union_mesh, LabelledMesh, SliceMode,
};
use slice2solid::{Error, Result};
use std::path::PathBuf;
use std::process::ExitCode;

/// `MESH:LABEL` → (MESH, Some(LABEL)); anything else (no colon, or no integer after the last
/// one) is a path without a label.
pub fn parse_mesh_arg(s: &str) -> (PathBuf, Option<i32>) {
    if let Some((path, label)) = s.rsplit_once(':') {
        if let Ok(l) = label.parse::<i32>() {
            if !path.is_empty() {
                return (PathBuf::from(path), Some(l));
            }
        }
    }
    (PathBuf::from(s), None)
}

pub fn run(args: SliceArgs) -> Result<ExitCode> {
    let mode = match args.mode {
        CliMode::Random => SliceMode::Random,
        CliMode::Parallel => SliceMode::Parallel,
        CliMode::Axes => SliceMode::Axes,
        CliMode::Fan => SliceMode::Fan,
        CliMode::Sweep => SliceMode::Sweep,
        CliMode::Tilt => SliceMode::Tilt,
    };
    let parsed: Vec<(PathBuf, Option<i32>)> =
        args.meshes.iter().map(|s| parse_mesh_arg(s)).collect();
    let mut meshes = Vec::with_capacity(parsed.len());
    for (i, (path, label)) in parsed.iter().enumerate() {
        meshes.push(LabelledMesh {
            name: path.display().to_string(),
            mesh: read_trimesh(path)?,
            label: label.unwrap_or(i as i32 + 1),
        });
    }
    let single = parsed.len() == 1 && parsed[0].1.is_none();
    let union = union_mesh(&meshes);
    let planes = make_planes(&union, args.planes, args.seed, mode);
    let sections = if single {
        slice_mesh(&meshes[0].mesh, &planes).map_err(|e| with_file(e, &meshes[0].name))?
    } else {
        slice_partition(&meshes, &planes)?
    };
    slice2solid::io::write_sections(&args.output, &sections)?;
    let regions: usize = sections.sections.iter().map(|s| s.regions.len()).sum();
    let holes: usize = sections
        .sections
        .iter()
        .flat_map(|s| &s.regions)
        .map(|r| r.holes.len())
        .sum();
    let names: Vec<String> = meshes.iter().map(|m| m.name.clone()).collect();
    println!(
        "{}: {} vertices, {} triangles; {} of {} planes cut it ({} skipped); {} regions, {} holes, {} contour vertices -> {}",
        names.join(" + "),
        union.vertices.len(),
        union.triangles.len(),
        sections.sections.len(),
        planes.len(),
        planes.len() - sections.sections.len(),
        regions,
        holes,
        sections.vertex_count(),
        args.output.display()
    );
    if !single {
        let per_label = sections.regions_per_label();
        for m in &meshes {
            println!(
                "  label {}: {} regions ({})",
                m.label,
                per_label.get(&m.label).copied().unwrap_or(0),
                m.name
            );
        }
        let touching = sections
            .warnings
            .iter()
            .filter(|w| w.contains("touching components of different labels"))
            .count();
        println!("  {touching} touching pairs of regions of different labels (shared vertices)");
    }
    Ok(ExitCode::SUCCESS)
}

/// Slicing errors locate problems in "mesh" (or "mesh: section i"); name the file instead.
fn with_file(e: Error, file: &str) -> Error {
    match e {
        Error::Input { location, reason } if location.starts_with("mesh") => Error::Input {
            location: location.replacen("mesh", file, 1),
            reason,
        },
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_arguments_with_and_without_labels() {
        assert_eq!(parse_mesh_arg("a.stl:3"), ("a.stl".into(), Some(3)));
        assert_eq!(
            parse_mesh_arg("dir:x/a.stl:12"),
            ("dir:x/a.stl".into(), Some(12))
        );
        assert_eq!(parse_mesh_arg("a.stl"), ("a.stl".into(), None));
        assert_eq!(parse_mesh_arg("C:/a.stl"), ("C:/a.stl".into(), None));
        assert_eq!(parse_mesh_arg(":3"), (":3".into(), None));
    }
}
